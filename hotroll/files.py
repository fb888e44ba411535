"""Files written whole or not at all, and a clear error on a full disk (issue 18). The lowest
layer: every writer of hotroll (checkpoints, figures, tables, summaries) goes through
``atomic``."""
from __future__ import annotations

import errno
import os
import shutil
import tempfile
import threading
from contextlib import contextmanager
from pathlib import Path

#: the errors of a full device or an exhausted quota
FULL = (errno.ENOSPC, errno.EDQUOT)


class DiskFullError(OSError):
    """A write that found no space left; the message names the file and the free space."""


def disk_full(path: Path, err: OSError) -> DiskFullError:
    """The clear error for ``err`` (ENOSPC/EDQUOT) while writing ``path``."""
    path = Path(path)
    where = next((p for p in [path, *path.parents] if p.exists()), Path("."))
    try:
        free = f"{shutil.disk_usage(where).free / 1e6:.1f} MB free"
    except OSError:
        free = "free space unknown"
    return DiskFullError(err.errno, f"disk full: no space left writing {path} ({free} on the "
                         f"device of {where}); the files written before are intact (each is "
                         f"written whole or not at all). Free space or write elsewhere (--out), "
                         f"then run the command again: finished work is read back")


_UMASK_LOCK = threading.Lock()


def umask() -> int:
    """The process's file-creation mask, read without changing it where Linux shows it
    (/proc/self/status, since 4.7); else set and restored at once under a lock, the
    restrictive 0o077 in between, so that a file another thread creates then is private
    rather than open."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    with _UMASK_LOCK:
        mask = os.umask(0o077)
        os.umask(mask)
    return mask


@contextmanager
def atomic(path: Path):
    """Yields a temporary path beside ``path`` (``name.tmpXXXXXX.ext``, unique: two writers of
    one file never share it; the same extension); on success it replaces ``path`` in one
    step, on failure it is removed (``path`` untouched). A full disk raises
    ``DiskFullError``. The file gets the mode any new file gets, 0o666 less the umask (the
    temporary file is created 0o600: without the chmod no one else could read the results
    on a shared machine)."""
    path = Path(path)
    try:
        fd, name = tempfile.mkstemp(prefix=f"{path.stem}.tmp", suffix=path.suffix,
                                    dir=path.parent)
    except OSError as e:
        if e.errno in FULL:
            raise disk_full(path, e) from None
        raise
    os.close(fd)
    tmp = Path(name)
    try:
        yield tmp
        os.chmod(tmp, 0o666 & ~umask())
        os.replace(tmp, path)
    except BaseException as e:
        try:
            tmp.unlink()
        except OSError:
            pass
        if isinstance(e, OSError) and not isinstance(e, DiskFullError) and e.errno in FULL:
            raise disk_full(path, e) from None
        raise
