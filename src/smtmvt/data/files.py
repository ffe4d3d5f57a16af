"""Reading whole small files (box files, tables, times, frames) without ever blocking.

A FIFO, socket or device in place of a file would make ``open().read()`` wait forever (a
FIFO blocks until a writer comes). :func:`read_regular_bytes` opens without blocking,
checks that it is a regular file (``stat.S_ISREG``) and only then reads.
"""

from __future__ import annotations

import errno
import os
import stat

__all__ = ["read_regular_bytes"]

_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a FIFO"),
    (stat.S_ISSOCK, "a socket"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
)


def read_regular_bytes(path) -> bytes:
    """The bytes of ``path`` when it is a regular file (a link to one is followed).

    Anything else (FIFO, socket, device, folder) raises ``OSError`` (``strerror``: ``not a
    regular file (a FIFO)``, ``filename``: ``path``) at once, without waiting; a missing
    file raises ``FileNotFoundError`` as ``open`` does.
    """
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            kind = next((name for test, name in _KINDS if test(mode)), "a special file")
            raise OSError(errno.EINVAL, f"not a regular file ({kind})", os.fspath(path))
    except BaseException:
        os.close(fd)
        raise
    with os.fdopen(fd, "rb") as fh:
        return fh.read()
