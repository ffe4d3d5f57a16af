"""Sub-commands of the ``smtmvt`` command line (one module each)."""
