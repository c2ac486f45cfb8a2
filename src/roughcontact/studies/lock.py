"""One writer per study directory: an OS-level advisory lock on a file inside it.

Two runs writing into the same directory would remove each other's temporary files
and partial results (every run starts by cleaning up after a killed one) and compute
the same tasks twice. A run therefore holds an exclusive ``flock`` on
``DIR/.roughcontact.lock`` for as long as it writes there. The kernel releases the lock
when the holder's file descriptor is closed, which includes the process dying by
``kill -9``, so a stale lock file never blocks ``--resume``: the file's content (the
holder's PID, host and start time) is only read to write a helpful message, never to
decide anything.

The lock file is opened without following a symbolic link (``O_NOFOLLOW``) and without
truncation, and used only if it is a regular file with no other hard link: a study
directory received from somebody else may hold a link named ``.roughcontact.lock`` to any
file of the user's, which the run must not overwrite (:class:`UnsafePath`, naming it).

Where ``fcntl`` is missing (Windows) or the file system refuses locks (some network
file systems), the run goes on unlocked after a :class:`RuntimeWarning`.
"""

from __future__ import annotations

import contextlib
import errno
import os
import socket
import stat
import time
import warnings
from pathlib import Path

from .._validate import ParameterError

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None

__all__ = ["LOCK_NAME", "DirectoryLocked", "UnsafePath", "directory_lock", "open_regular"]

LOCK_NAME = ".roughcontact.lock"
# errors of flock that mean "the file system cannot lock", not "somebody holds it"
_UNSUPPORTED = {errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS, errno.EINVAL}


class DirectoryLocked(ParameterError):
    """Another process is writing into the directory (it holds the lock)."""


class UnsafePath(ParameterError):
    """A file of the study directory is a symbolic link, a hard link or not a regular file."""


_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_CLOEXEC = getattr(os, "O_CLOEXEC", 0)
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)  # a FIFO planted under the name must not block


def open_regular(path, flags: int, mode: int = 0o644) -> int:
    """``os.open`` that never follows a symbolic link and accepts only a regular file.

    ``path``'s last component must not be a symbolic link (``O_NOFOLLOW``; checked with
    ``lstat`` too where the flag is missing); the opened file must be a regular file with
    one link (a hard link would let a write change a file elsewhere). Returns the file
    descriptor; raises :class:`UnsafePath` (one line, naming ``path``) otherwise.
    """
    path = Path(path)
    if not _NOFOLLOW and path.is_symlink():  # pragma: no cover - Windows
        raise _unsafe(path, "is a symbolic link")
    try:
        fd = os.open(path, flags | _NOFOLLOW | _CLOEXEC | _NONBLOCK, mode)
    except OSError as err:
        if err.errno == errno.ELOOP or path.is_symlink():
            raise _unsafe(path, "is a symbolic link") from None
        if err.errno in (errno.EISDIR, errno.ENXIO, errno.ENODEV):
            raise _unsafe(path, "is not a regular file") from None
        raise
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise _unsafe(path, "is not a regular file")
        if st.st_nlink > 1:
            raise _unsafe(path, f"has {st.st_nlink} hard links (it is another file too)")
        if _NONBLOCK:
            os.set_blocking(fd, True)
    except BaseException:
        os.close(fd)
        raise
    return fd


def _unsafe(path: Path, what: str) -> UnsafePath:
    return UnsafePath(
        f"{str(path)!r} {what}; refusing to use it (a study directory may contain only "
        "regular files written by roughcontact: remove it if the directory is yours, "
        "or choose another directory)"
    )


def _owner(fd: int) -> str:
    """The holder's record as written by :func:`_claim` (read from the open lock file)."""
    try:
        text = os.pread(fd, 4096, 0).decode("utf-8", "replace").strip()
    except OSError:
        text = ""
    text = " ".join(text.split())  # one line, whatever the file holds
    # empty while the holder is between taking the lock and writing its record
    return text or "PID unknown"


def _claim(fd: int) -> None:
    """Replace the lock file's content by this process's PID, host and start time."""
    record = (
        f"PID {os.getpid()} on {socket.gethostname()} since "
        f"{time.strftime('%Y-%m-%dT%H:%M:%SZ', time.gmtime())}\n"
    )
    os.ftruncate(fd, 0)
    os.pwrite(fd, record.encode("utf-8"), 0)


def _unlocked(directory: Path, why: str) -> None:
    warnings.warn(
        f"cannot lock {str(directory)!r} ({why}); make sure that no other roughcontact "
        "run writes into it at the same time",
        RuntimeWarning,
        stacklevel=2,
    )


def _acquire(fd: int, directory: Path, path: Path, hint: str) -> bool:
    """Take the lock without waiting; True if held, False if locking is unsupported.

    Raises :class:`DirectoryLocked` (naming the directory, the lock file and its
    holder) when another open file description holds it.
    """
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        raise DirectoryLocked(
            f"{str(directory)!r} is in use by another roughcontact run "
            f"({_owner(fd)}; lock file {path}); wait for it to finish or stop it, "
            f"then {hint}"
        ) from None
    except OSError as err:
        if err.errno not in _UNSUPPORTED:
            raise
        _unlocked(directory, f"the file system does not support locks: {err.strerror}")
        return False
    return True


@contextlib.contextmanager
def directory_lock(directory, *, hint="run again with --resume to continue"):
    """Hold the exclusive lock of ``directory`` (created if missing) for a ``with`` block.

    Parameters
    ----------
    directory : path-like
        The directory written to; the lock file is ``directory / LOCK_NAME``.
    hint : str
        How to proceed, appended to the error when the directory is locked.

    Yields
    ------
    pathlib.Path or None
        The lock file, or None where locking is not available (after a warning).

    Raises
    ------
    DirectoryLocked
        At once (no waiting) when another process, or another ``directory_lock`` of
        this process, holds the lock.
    UnsafePath
        The lock file is a symbolic link (never followed), has other hard links or is not
        a regular file: it is left as it is.
    """
    directory = Path(directory)
    created = not directory.exists()
    directory.mkdir(parents=True, exist_ok=True)
    if fcntl is None:  # Windows
        _unlocked(directory, "no fcntl on this platform")
        yield None
        return
    path = directory / LOCK_NAME
    # opened without truncation: the holder's record must survive a failed attempt, and
    # a link planted under the name is refused before anything is written; Python's
    # descriptors are not inherited by spawned worker processes (PEP 446)
    fd = open_regular(path, os.O_RDWR | os.O_CREAT, 0o644)
    try:
        held = _acquire(fd, directory, path, hint)
        if held:
            _claim(fd)
        try:
            yield path if held else None
        except BaseException:
            if created and held:
                _remove_if_unused(directory, path)
            raise
    finally:
        os.close(fd)  # releases the lock; the file stays (deleting it would race)


def _remove_if_unused(directory: Path, path: Path) -> None:
    """Remove a directory made for a run that failed before writing anything into it.

    Called with the lock still held, so no other run can be using the directory; a run
    that fails early (an unreachable scheduler, a directory that already holds results)
    leaves no trace behind.
    """
    try:
        if {p.name for p in directory.iterdir()} == {LOCK_NAME}:
            path.unlink()
            directory.rmdir()
    except OSError:
        pass  # somebody else's file appeared: keep the directory
