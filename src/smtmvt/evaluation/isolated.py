"""Child side of :func:`smtmvt.evaluation.workers.run_in_fresh_process`.

``python -m smtmvt.evaluation.isolated`` reads a pickled :class:`~.pairs.PairTask` on stdin,
runs it with one OpenCV/BLAS thread and writes the pickled :class:`~.pairs.PairOutcome` on
stdout. Anything the tracker prints goes to stderr, so stdout carries the outcome only. The
process ends when its parent dies (:func:`~.workers.exit_with_parent`).
"""

from __future__ import annotations

import dataclasses
import os
import pickle
import sys


def main() -> int:
    from .pairs import run_pair
    from .workers import exit_with_parent

    exit_with_parent(int(os.environ.get("SMTMVT_PARENT_PID") or os.getppid()))
    result_fd = os.dup(1)
    os.dup2(2, 1)  # prints of the tracker (Python or C) go to stderr
    task = pickle.loads(sys.stdin.buffer.read())
    outcome = run_pair(dataclasses.replace(task, single_thread=True, fresh_process=False))
    with os.fdopen(result_fd, "wb") as out:
        out.write(pickle.dumps(outcome))
    return 0


if __name__ == "__main__":
    sys.exit(main())
