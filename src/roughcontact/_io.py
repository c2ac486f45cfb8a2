"""Atomic file writes that survive a full disk: the old file or the new one, never half.

One writer for every NetCDF file the package produces as results (``roughcontact path
-o``, the task files of a study): :func:`write_netcdf_atomic` serialises the dataset to
bytes in memory first (HDF5 never touches the disk, so a full disk cannot crash it in
its ``close``: that used to end the process with a segfault, exit code 139), then
:func:`write_bytes_atomic` writes the bytes with plain ``os.write`` to a temporary file
in the target's directory, fsyncs it, renames it over the target (``os.replace``,
atomic on POSIX and Windows) and fsyncs the directory. A failure on the way removes the
temporary file and leaves the target as it was; the errors that mean the storage cannot
take the data (no space left, quota exceeded, I/O error, file too large) are raised as
one :class:`WriteError` whose message is a single line naming the file. SIGINT/SIGTERM
during the write are held back until it is done (:func:`._signals.deferred`).
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import uuid
from pathlib import Path

from . import _guard
from ._signals import deferred
from .errors import ParameterError

__all__ = [
    "STORAGE_ERRNOS",
    "WriteError",
    "as_write_error",
    "check_directory_writable",
    "claim_directory",
    "check_writable",
    "netcdf_bytes",
    "output_directory",
    "temporary_name",
    "write_bytes_atomic",
    "write_netcdf_atomic",
]

#: errno values that mean "the storage cannot take these bytes", with their wording
STORAGE_ERRNOS = {
    errno.ENOSPC: "no space left writing",
    errno.EDQUOT: "disk quota exceeded writing",
    errno.EIO: "I/O error writing",
    errno.EFBIG: "file too large writing",
}
TMP_SUFFIX = ".tmp"


class WriteError(OSError):
    """A result file could not be written: no space left, quota, I/O error, too large.

    The file named (``filename``) is unchanged and no temporary file is left; ``str()``
    is one line: ``no space left writing FILE ([Errno 28] No space left on device);
    FILE was left as it was``.
    """

    def __str__(self) -> str:
        return str(self.strerror)


def as_write_error(err: OSError, path) -> OSError:
    """``err`` as a :class:`WriteError` naming ``path`` when the storage could not take the
    data (an errno of :data:`STORAGE_ERRNOS`); any other error comes back as it is."""
    if isinstance(err, WriteError) or err.errno not in STORAGE_ERRNOS:
        return err
    what = STORAGE_ERRNOS[err.errno]
    cause = f"[Errno {err.errno}] {err.strerror or os.strerror(err.errno)}"
    message = f"{what} {path} ({cause}); {path} was left as it was, no temporary file remains"
    return WriteError(err.errno, message, str(path))


def temporary_name(path) -> Path:
    """A fresh temporary name next to ``path``: ``.NAME.<random>.tmp`` (hidden)."""
    path = Path(path)
    return path.with_name(f".{path.name}.{uuid.uuid4().hex[:12]}{TMP_SUFFIX}")


def _write_all(fd: int, data) -> None:
    view = memoryview(data).cast("B")
    while view.nbytes:
        written = os.write(fd, view)
        if written <= 0:  # pragma: no cover - os.write raises rather than write nothing
            raise OSError(errno.EIO, os.strerror(errno.EIO))
        view = view[written:]


def _fsync_dir(directory: Path) -> None:
    """Make a rename in ``directory`` durable (best effort: the file is in place already)."""
    if os.name == "nt":  # pragma: no cover - directories cannot be opened on Windows
        return
    try:
        fd = os.open(directory, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass
    finally:
        os.close(fd)


def write_bytes_atomic(path, data, *, opener=None) -> Path:
    """Write ``data`` (bytes-like) to ``path`` atomically and durably; return the path.

    The temporary file is new (``O_EXCL``, never through a symbolic link). Only a
    regular file at ``path`` is replaced (keeping its permission bits), never a device,
    FIFO, an input of the command or a write-protected file, nor a link at a name the
    user gave (a link planted under another name is replaced, not followed): the rules
    of :mod:`roughcontact._guard`, a one-line :class:`ParameterError` otherwise. A file
    written below a claimed report directory is recorded in its manifest first.
    ``opener(path, flags, mode) -> fd`` replaces ``os.open`` for the temporary file
    (e.g. :func:`roughcontact.studies.lock.open_regular`). Raises :class:`WriteError`
    when the storage cannot take the bytes (see the module docstring) and any other
    :class:`OSError` as it is (permission denied, missing directory, ...), in both cases
    with ``path`` unchanged and no temporary file left.
    """
    final = Path(path)
    _guard.check_target(final, "output", named=None)
    try:
        old = os.lstat(final)
        mode = stat.S_IMODE(old.st_mode) if stat.S_ISREG(old.st_mode) else None
    except OSError:
        mode = None
    _guard.record(final)
    tmp = temporary_name(final)
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL
    flags |= getattr(os, "O_BINARY", 0) | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    with deferred():  # a signal now would only throw away bytes already computed
        try:
            fd = (opener or os.open)(tmp, flags, 0o666)
            try:
                if mode is not None:  # the replaced file's permissions, not the umask's
                    os.fchmod(fd, mode)
                _write_all(fd, data)
                os.fsync(fd)
                written = os.fstat(fd)
            finally:
                os.close(fd)
            now = os.lstat(tmp)
            if (now.st_dev, now.st_ino) != (written.st_dev, written.st_ino):
                raise OSError(f"{tmp} is no longer the temporary file written; not used")
            os.replace(tmp, final)
        except OSError as err:
            _remove(tmp)
            if (converted := as_write_error(err, final)) is not err:
                raise converted from err
            raise
        except BaseException:
            _remove(tmp)
            raise
    _fsync_dir(final.parent)
    return final


def _remove(path: Path) -> None:
    try:
        path.unlink(missing_ok=True)
    except OSError:  # pragma: no cover - nothing more can be done about it
        pass


def netcdf_bytes(ds, *, encoding=None, attrs=None):
    """``ds`` as NetCDF-4 bytes (h5netcdf engine), built in memory; ``attrs`` are added to
    a shallow copy's global attributes (``ds`` itself is not changed)."""
    if attrs:
        ds = ds.copy(deep=False)
        ds.attrs.update(attrs)
    with _local_scheduler():
        try:
            return ds.to_netcdf(engine="h5netcdf", encoding=encoding)
        except ValueError as err:  # xarray < 2025: in-memory bytes only through scipy
            if "engine" not in str(err):
                raise
        return _h5netcdf_in_memory(ds, encoding)


def _local_scheduler():
    """Dask's synchronous scheduler for the write. With a ``distributed.Client`` as the
    default (a study's driver), xarray would take a cluster-wide lock named after the
    target, which for an in-memory target fails ("Semaphore or Lock ... not known")."""
    try:
        import dask
    except ImportError:  # pragma: no cover - dask is a dependency
        return contextlib.nullcontext()
    return dask.config.set(scheduler="synchronous")


def _h5netcdf_in_memory(ds, encoding):
    """The same bytes through h5netcdf on a BytesIO (what newer xarray does itself)."""
    import io

    import h5netcdf
    from xarray.backends import H5NetCDFStore

    buffer = io.BytesIO()
    store = H5NetCDFStore(h5netcdf.File(buffer, "w"), mode="w")
    try:
        ds.dump_to_store(store, encoding=encoding)
    finally:
        store.close()
    return buffer.getbuffer()


def write_netcdf_atomic(ds, path, *, encoding=None, attrs=None, opener=None) -> Path:
    """Write ``ds`` to ``path`` as NetCDF-4 (h5netcdf), atomically; see the module docstring.

    ``encoding`` as for ``Dataset.to_netcdf``; ``attrs`` are added to the file's global
    attributes (not to ``ds``); ``opener`` as for :func:`write_bytes_atomic`. Raises
    :class:`WriteError` on a full disk, quota or I/O error, with ``path`` unchanged and
    no temporary file left.
    """
    with deferred():  # serialising too: a finished result is not thrown away half-saved
        data = netcdf_bytes(ds, encoding=encoding, attrs=attrs)
        return write_bytes_atomic(path, data, opener=opener)


def read_netcdf(path, *, refusal: str):
    """Load a NetCDF file (h5netcdf) into memory; ``ParameterError(f"{refusal}: {err}")``
    (one line) when it cannot be read. ``refusal`` says what the file was expected to be."""
    import xarray as xr

    from ._files import regular_input

    try:  # a FIFO or device is refused before it is opened (it could block forever)
        return xr.load_dataset(regular_input(path, "file"), engine="h5netcdf")
    except ParameterError as err:
        raise ParameterError(f"{refusal}: {err}") from None
    except Exception as err:  # noqa: BLE001 - h5py's checksum RuntimeError, KeyError, ...
        why = " ".join(f"{type(err).__name__}: {err}".split())[:300]
        raise ParameterError(f"{refusal} ({why})") from None


def _probe(probe: Path, what: str, named: Path) -> None:
    """Create the new file ``probe`` (``O_EXCL``, never through a link) and remove it at
    once: a one-line ParameterError naming ``what`` and ``named`` if its directory does
    not take it (permissions, a read-only mount, a full disk)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
    try:
        os.close(os.open(probe, flags, 0o600))
    except OSError as err:
        raise ParameterError(
            f"{what} {str(named)!r} cannot be written: {err.strerror or err} "
            f"in {str(probe.parent)!r}"
        ) from None
    _remove(probe)


def check_writable(path, what: str = "output", *, inputs=(), protected=()) -> Path:
    """Refuse, before any work, an output file that could not be written at the end.

    ``path``'s directory must exist and take a new file there: a temporary file is
    created (``O_EXCL``, never through a link) and removed at once, which also catches a
    read-only mount that permission bits alone would not show. ``path`` itself must not
    be a directory, and an existing ``path`` must be a file the writer replaces (see
    :mod:`roughcontact._guard`): a regular file, not a link, device or FIFO, not
    write-protected and none of ``inputs`` (the command's input files, compared by
    ``st_dev``/``st_ino``, so another path or a hard link to one is refused too) or
    ``protected`` (files the command must not touch), nor a file of a study (its task
    files, ``study.json``, ``study.toml``, lock) when ``path``'s directory holds one. ``path`` is
    registered as a name the user gave and ``inputs`` as inputs: the writer refuses
    them again when it writes. Returns ``path`` as a :class:`~pathlib.Path`.

    Raises
    ------
    ParameterError
        One line naming ``what`` and ``path``: missing or read-only directory, ...
    """
    final = Path(os.fspath(path))
    if "\0" in str(final):
        raise ParameterError(f"{what}: a file name cannot hold a NUL character")
    parent = final.parent
    if not parent.is_dir():
        why = "does not exist" if not parent.exists() else "is not a directory"
        raise ParameterError(f"{what} {str(final)!r}: its directory {str(parent)!r} {why}")
    if final.is_dir() and not final.is_symlink():
        raise ParameterError(f"{what} {str(final)!r} is a directory; expected a file name")
    _guard.protect(*inputs, *protected)
    _guard.name_output(final)
    _guard.check_target(final, what)
    if (parent / _guard.STUDY_FILES[0]).is_file():  # a study directory: its task files, ...
        _guard.check_not_study_file(parent, final, what)
    _probe(final.with_name(f".{final.name}.{uuid.uuid4().hex[:12]}.probe"), what, final)
    return final


def check_directory_writable(path, what: str = "output directory") -> Path:
    """Refuse, before any work, an output directory that could not be made or written.

    ``path`` must be a directory or not exist yet; the nearest existing one of it and
    its parents must take a new file (a probe file is created there and removed at once,
    which also catches a read-only mount). Nothing else is created.

    Raises
    ------
    ParameterError
        One line naming ``what`` and ``path``.
    """
    directory = Path(os.fspath(path))
    if "\0" in str(directory):
        raise ParameterError(f"{what}: a directory name cannot hold a NUL character")
    if directory.exists() and not directory.is_dir():
        raise ParameterError(f"{what} {str(directory)!r} exists and is not a directory")
    base = directory
    while not base.exists() and not base.is_symlink() and base != base.parent:
        base = base.parent
    if not base.is_dir():
        raise ParameterError(
            f"{what} {str(directory)!r} cannot be created: {str(base)!r} is not a directory"
        )
    _probe(base / f".roughcontact-probe-{uuid.uuid4().hex[:12]}", what, directory)
    return directory


def claim_directory(path, what: str = "-o/--output", *, force: bool = False) -> Path:
    """Claim a report directory before any work (:func:`roughcontact._guard.claim_directory`):
    refused if it holds files roughcontact did not write there, unless ``force``."""
    directory = check_directory_writable(path, what)
    return _guard.claim_directory(directory, what, force=force, write=write_bytes_atomic)


def output_directory(path, what: str = "output directory") -> Path:
    """Make the directory ``path`` (and its parents) for outputs; never write through a link.

    A symbolic link planted at ``path`` is replaced by a fresh directory (the link
    itself is removed, never what it points to): files written there then stay inside
    the named output instead of landing wherever the link points. An existing real
    directory is kept; any other file there is refused (ParameterError), not removed.
    """
    directory = Path(os.fspath(path))
    try:
        if directory.is_symlink():
            directory.unlink()
        elif directory.exists() and not directory.is_dir():
            raise ParameterError(f"{what} {str(directory)!r} exists and is not a directory")
        directory.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise ParameterError(
            f"{what} {str(directory)!r} cannot be created: {err.strerror or err}"
        ) from None
    return directory
