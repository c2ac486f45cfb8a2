"""The private scratch directories of the local Dask cluster, and what killed runs left.

Each run of the local cluster (:mod:`.cluster`) works in a fresh ``roughcontact-dask-*``
directory (mode 0700) of the temporary directory and holds an advisory lock
(``flock``) on :data:`SCRATCH_LOCK` in it while it lives. A run killed with ``kill -9``
cannot remove its directory; the next run does (:func:`remove_stale_scratch`): only
directories of that name, themselves (not links), owned by this user, unchanged for
:data:`STALE_SCRATCH_SECONDS` and whose lock no live process holds.
"""

from __future__ import annotations

import os
import shutil
import stat
import tempfile
import time

__all__ = [
    "SCRATCH_LOCK",
    "SCRATCH_PREFIX",
    "STALE_SCRATCH_SECONDS",
    "lock_scratch",
    "remove_scratch",
    "remove_stale_scratch",
]

SCRATCH_PREFIX = "roughcontact-dask-"  # the private scratch directories' names
SCRATCH_LOCK = ".roughcontact-scratch.lock"  # held (flock) by the run using the directory
STALE_SCRATCH_SECONDS = 3600.0  # a directory left this long, its lock free, is removed


def lock_scratch(scratch: str):
    """Hold an advisory lock on :data:`SCRATCH_LOCK` in ``scratch`` (the open file, or
    None where ``fcntl`` is missing): a later run leaves the directory alone meanwhile."""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows: the age alone decides
        return None
    fd = os.open(
        os.path.join(scratch, SCRATCH_LOCK),
        os.O_RDWR | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0) | os.O_CLOEXEC,
        0o600,
    )
    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    return fd


def remove_scratch(scratch: str, held) -> None:
    shutil.rmtree(scratch, ignore_errors=True)
    if held is not None:
        try:
            os.close(held)
        except OSError:
            pass


def _in_use(directory: str) -> bool:
    """Does a live process hold the lock of the scratch ``directory``?"""
    try:
        import fcntl
    except ImportError:  # pragma: no cover - Windows
        return False
    try:
        fd = os.open(
            os.path.join(directory, SCRATCH_LOCK),
            os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | os.O_CLOEXEC | os.O_NONBLOCK,
        )
    except OSError:
        return False  # no lock file (or not a plain one): nobody holds it
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        return False
    except OSError:
        return True
    finally:
        os.close(fd)


def remove_stale_scratch(base=None, older_than: float = STALE_SCRATCH_SECONDS) -> list[str]:
    """Remove the scratch directories that killed runs left in ``base`` (default: the
    temporary directory); return their paths.

    Only directories named ``roughcontact-dask-*``, themselves (not links), owned by this
    user, unchanged for ``older_than`` seconds and whose lock no live process holds.
    """
    base = tempfile.gettempdir() if base is None else os.fspath(base)
    removed = []
    try:
        names = [n for n in os.listdir(base) if n.startswith(SCRATCH_PREFIX)]
    except OSError:
        return removed
    now = time.time()
    for name in names:
        path = os.path.join(base, name)
        try:
            st = os.lstat(path)
        except OSError:
            continue
        if (
            not stat.S_ISDIR(st.st_mode)
            or st.st_uid != os.getuid()
            or now - st.st_mtime < older_than
            or _in_use(path)
        ):
            continue
        shutil.rmtree(path, ignore_errors=True)
        removed.append(path)
    return removed
