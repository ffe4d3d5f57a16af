"""Atomic file writes: a reader sees the old file whole or the new one whole, never a part.

Every file this package writes (result and times files, ``run.json``, ``errors.json``, the
report's tables, plots and pages) goes through :func:`write_bytes_atomic`.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

__all__ = ["write_bytes_atomic", "write_text_atomic"]


def write_bytes_atomic(path, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically; return ``Path(path)``.

    Missing parent folders are created. The bytes go to a temporary file in the same
    folder, are flushed and ``fsync``-ed, then renamed over ``path`` with ``os.replace``;
    an interrupted write leaves no temporary file behind. A symbolic link at ``path`` is
    replaced by the new file, never written through. A new file gets permissions
    ``0o644``; a replaced regular file keeps its permissions.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        st = os.lstat(path)
        mode = st.st_mode & 0o777 if not path.is_symlink() else 0o644
    except FileNotFoundError:
        mode = 0o644
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
    return path


def write_text_atomic(path, text: str, *, encoding: str = "utf-8") -> Path:
    """Write ``text`` (``\\n`` line ends) to ``path`` atomically, see :func:`write_bytes_atomic`."""
    return write_bytes_atomic(path, text.encode(encoding))
