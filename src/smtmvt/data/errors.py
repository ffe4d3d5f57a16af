"""The one exception of :mod:`smtmvt.data`: bad input data, named precisely."""

from __future__ import annotations

__all__ = ["SequenceError", "SequenceWarning"]


class SequenceError(ValueError):
    """Bad or missing sequence data.

    The message always names the file at fault, and the line (1-based, as an
    editor shows it) or the frame (0-based index into the sequence) where that
    applies. The same facts are kept as attributes for programs:

    Attributes
    ----------
    path : str or None
        The file or folder at fault.
    line : int or None
        1-based line number in ``path``.
    frame : int or None
        0-based frame index in the sequence.
    sequence : str or None
        Name of the sequence concerned, where known.
    """

    def __init__(self, message: str, *, path=None, line=None, frame=None, sequence=None):
        super().__init__(message)
        self.path = None if path is None else str(path)
        self.line = line
        self.frame = frame
        self.sequence = sequence

    def __reduce__(self):
        # Keep the attributes when pickled (e.g. sent back from a worker process).
        return (_rebuild, (type(self), str(self), self.path, self.line, self.frame, self.sequence))


def _rebuild(cls, message, path, line, frame, sequence):
    return cls(message, path=path, line=line, frame=frame, sequence=sequence)


class SequenceWarning(UserWarning):
    """Data that is usable but not as expected (e.g. fewer ground-truth lines than frames).

    The message names the file and what was done about it. Filter it with
    ``warnings.simplefilter("ignore", SequenceWarning)`` once you have checked.
    """
