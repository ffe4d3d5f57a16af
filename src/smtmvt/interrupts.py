"""Ctrl-C and SIGTERM stop a command, even when they land inside compiled code.

The command line turns SIGTERM into :class:`Terminated`, a ``KeyboardInterrupt``, as Python
turns SIGINT into ``KeyboardInterrupt`` (:func:`signals_as_interrupts`). A signal's Python
handler runs between two bytecodes, which may be inside Python code that a numba kernel
calls (numba unpickles its constants and exceptions in Python). The kernel then returns
with the interrupt set and CPython raises ``SystemError: CPUDispatcher(...) returned a
result with an exception set``, the interrupt being only its cause. Code that catches
exceptions to record them (a pair's error, a report's failure) calls
:func:`reraise_interruption` first, so that a stop is never taken for a failure; loops call
:func:`check_stop`, for a signal whose exception compiled code dropped altogether.
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

__all__ = ["Terminated", "interruption", "reraise_interruption", "check_stop", "signals_as_interrupts"]


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised in the main thread so that a command stops as it does on Ctrl-C:
    ``finally`` blocks run, worker processes are ended, nothing partial is written."""

    signum = signal.SIGTERM


#: signals received while :func:`signals_as_interrupts` is active (main thread only)
_received: list[int] = []


def _exception_for(signum: int) -> KeyboardInterrupt:
    return Terminated() if signum == signal.SIGTERM else KeyboardInterrupt()


def interruption(exc: BaseException | None) -> KeyboardInterrupt | None:
    """The ``KeyboardInterrupt`` (or :class:`Terminated`) that ``exc`` is or hides in its
    chain (``__cause__``, ``__context__``), else a new one for a stop signal received under
    :func:`signals_as_interrupts`, else None."""
    todo, seen = [exc], set()
    while todo:
        e = todo.pop()
        if e is None or id(e) in seen:
            continue
        if isinstance(e, KeyboardInterrupt):
            return e
        seen.add(id(e))
        todo += [e.__cause__, e.__context__]
    return _exception_for(_received[-1]) if _received else None


def reraise_interruption(exc: BaseException) -> None:
    """Raise a fresh interrupt of the same kind when :func:`interruption` finds one for
    ``exc``; return otherwise (``exc`` is a failure to record)."""
    stop = interruption(exc)
    if stop is not None:
        raise type(stop)(*stop.args) from None


def check_stop() -> None:
    """Raise the interrupt of a stop signal received under :func:`signals_as_interrupts`
    (one whose exception was lost in compiled code); return otherwise."""
    if _received:
        raise _exception_for(_received[-1])


@contextlib.contextmanager
def signals_as_interrupts() -> Iterator[None]:
    """While active, SIGTERM raises :class:`Terminated` and SIGINT ``KeyboardInterrupt``
    (unless SIGINT was set to something else, say ignored), and both are remembered for
    :func:`interruption` and :func:`check_stop`. Main thread only; elsewhere it does nothing."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame):
        _received.append(signum)
        raise _exception_for(signum)

    _received.clear()
    previous = {signal.SIGTERM: signal.signal(signal.SIGTERM, handler)}
    if signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        previous[signal.SIGINT] = signal.signal(signal.SIGINT, handler)
    try:
        yield
    finally:
        for signum, old in previous.items():
            signal.signal(signum, old)
        _received.clear()
