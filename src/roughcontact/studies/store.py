"""The result store of a study: one NetCDF file per task, written atomically.

Layout of a study directory::

    study.json                  the manifest: the study's tasks, settings and file hash
    study.toml                  a copy of the study file as run
    task-00000.nc               one finished task (path + provenance + analysis)
    task-00001.failed.json      one failed task (reason and traceback)
    .task-00002.nc.<id>.tmp     a write in progress (removed when a run starts)
    .roughcontact.lock          the lock of the run writing here (:mod:`.lock`)

A task file is built in memory with the completion marker attribute :data:`MARKER`,
written to a temporary name in the same directory, fsync'ed and then renamed over its
final name (``os.replace``, atomic on POSIX and Windows), and the directory is fsync'ed
(:func:`roughcontact._io.write_netcdf_atomic`; a full disk is one clear error).
A file is taken as finished only if it opens, carries the marker and the task's
parameter hash (``task_key``); anything else is removed and recomputed.

Nothing is written through a symbolic link planted in the directory (it may come from
somebody else): temporary files are created with ``O_EXCL | O_NOFOLLOW`` and renamed
over the final name (which replaces a link there instead of following it), the manifest
is read only from a regular file, and the lock file is refused if it is a link.
"""

from __future__ import annotations

import json
import os
import stat
import time
from pathlib import Path

from .._guard import STUDY_FILES
from .._guard import check_not_study_file as check_not_study_file  # its public name
from .._validate import ParameterError
from ..pathdata import FIELDS
from .lock import UnsafePath, open_regular

__all__ = [
    "MANIFEST",
    "MARKER",
    "PARAMETERS_ATTR",
    "check_task",
    "failure_path",
    "read_manifest",
    "task_files",
    "task_keys",
    "task_parameters",
    "task_path",
    "write_failure",
    "write_manifest",
    "write_task",
]

MARKER = "roughcontact_task_complete"
#: The attribute of a task file holding the task's parameters (JSON).
PARAMETERS_ATTR = "task_parameters"
MANIFEST = "study.json"
_TMP = ".tmp"
_TASK_FILES = "task-*.nc"  # the names of task_path
_COMPRESSION = {"zlib": True, "complevel": 4}


def task_path(out_dir, task_id: str) -> Path:
    """Final location of a finished task's NetCDF file."""
    return Path(out_dir) / f"task-{task_id}.nc"


def task_files(out_dir) -> list[Path]:
    """The task files (:func:`task_path`) in a study directory, sorted by task id.

    Only regular files: a symbolic link, FIFO or device planted under a task file's name
    is left out (never followed; opening a FIFO would block).
    """
    return sorted(p for p in Path(out_dir).glob(_TASK_FILES) if is_regular(p))


def task_keys(out_dir) -> dict | None:
    """``{task file name: task key}`` of the manifest, or None without a readable one.

    A task file is the study's own only if its ``task_key`` attribute is the key here:
    a file copied in from another study (or run with other parameters) is not.
    """
    try:
        manifest = read_manifest(out_dir)
        return {task_path(".", t["id"]).name: t.get("key") for t in manifest["tasks"]}
    except (ParameterError, KeyError, TypeError):
        return None


def is_regular(path) -> bool:
    """Is ``path`` itself a regular file (not a link to one, not a FIFO or device)?"""
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False


def task_parameters(attrs) -> dict:
    """The parameters of a task (``{}`` if not given) from a task file's attributes."""
    return json.loads(attrs.get(PARAMETERS_ATTR, "{}") or "{}")


def failure_path(out_dir, task_id: str) -> Path:
    """Location of a failed task's JSON record."""
    return Path(out_dir) / f"task-{task_id}.failed.json"


def _write_bytes(final: Path, data: bytes) -> Path:
    """Write ``data`` to ``final`` atomically (the one writer of :mod:`roughcontact._io`,
    temporaries opened by :func:`.lock.open_regular`); a full disk is a ``WriteError``."""
    from .._io import write_bytes_atomic

    return write_bytes_atomic(final, data, opener=open_regular)


def _write_json(final: Path, obj) -> Path:
    text = json.dumps(obj, indent=1, sort_keys=True, allow_nan=True) + "\n"
    return _write_bytes(final, text.encode("utf-8"))


def _field_encoding(ds) -> dict:
    """Lossless compression of the contact maps, most of whose sites are exactly zero.

    A 256² pressure map at 2 % contact shrinks from 530 kB to about 60 kB; the per-step
    curves are left as they are (small, and read by every resume check).
    """
    return {name: dict(_COMPRESSION) for name in FIELDS if name in ds.variables}


def write_task(out_dir, task, ds) -> Path:
    """Write a finished task atomically (:func:`roughcontact.pathdata.write_path`).

    The file is built in memory with the completion marker :data:`MARKER` and appears
    under its name only complete (renamed over it once written and fsync'ed). A full
    disk (or quota, I/O error) raises :class:`roughcontact._io.WriteError`, one line,
    with every finished task file intact and no temporary file left.
    """
    from ..pathdata import write_path

    marker = {MARKER: time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    path = write_path(
        ds,
        task_path(out_dir, task.id),
        encoding=_field_encoding(ds),
        attrs=marker,
        opener=open_regular,
    )
    failure_path(out_dir, task.id).unlink(missing_ok=True)
    return path


def write_failure(out_dir, task, reason: str, traceback: str = "", **extra) -> Path:
    """Record a failed task (JSON: id, parameters, reason, traceback)."""
    record = {
        "task_id": task.id,
        "task_key": task.key,
        "parameters": task.params,
        "reason": reason,
        "traceback": traceback,
        "time": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        **extra,
    }
    task_path(out_dir, task.id).unlink(missing_ok=True)
    final = failure_path(out_dir, task.id)
    try:
        return _write_json(final, record)
    except OSError as err:  # a full disk: the one-line WriteError of the task files
        from .._io import as_write_error

        if (converted := as_write_error(err, final)) is not err:
            raise converted from err
        raise


def check_task(out_dir, task):
    """Is the task finished? Returns ``(True, attrs)`` or ``(False, why)``.

    Finished: the file exists, opens as NetCDF, carries :data:`MARKER` and the task's
    parameter hash, and its per-step variables can be read.
    """
    import xarray as xr

    path = task_path(out_dir, task.id)
    if not path.exists() and not path.is_symlink():
        return False, "missing"
    if not is_regular(path):
        return False, "not a regular file (a link, FIFO or device): recomputed"
    try:
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            attrs = dict(ds.attrs)
            if MARKER not in attrs:
                return False, "no completion marker (incomplete write)"
            if attrs.get("task_key") != task.key:
                return False, "written for other parameters"
            ds[["offset", "load", "repulsive_area", "converged"]].load()
    except Exception as err:  # noqa: BLE001 - any unreadable file is simply not finished
        return False, f"unreadable ({type(err).__name__}: {err})"
    return True, attrs


def clean_temporary(out_dir) -> int:
    """Remove the temporary files that a killed run left behind; return how many."""
    n = 0
    for tmp in Path(out_dir).glob(f".task-*{_TMP}"):
        tmp.unlink(missing_ok=True)
        n += 1
    return n


def existing_results(out_dir) -> bool:
    """Does ``out_dir`` already hold a study (a manifest or task files)?"""
    out = Path(out_dir)
    return out.is_dir() and (
        (out / MANIFEST).exists() or any(out.glob(_TASK_FILES)) or any(out.glob("task-*.json"))
    )


def write_manifest(out_dir, spec) -> Path:
    """The study's tasks, settings and provenance (``study.json``) and its file's copy."""
    out = Path(out_dir)
    manifest = {
        "name": spec.name,
        "description": spec.description,
        "source": spec.source,
        "sha256": spec.sha256,
        "settings": spec.settings,
        "axes": spec.axes,
        "tasks": [{"id": t.id, "key": t.key, "params": t.params} for t in spec.tasks],
    }
    # both through new temporary files: a link planted at either name is replaced
    _write_bytes(out / "study.toml", spec.text.encode("utf-8"))
    return _write_json(out / MANIFEST, manifest)


def read_manifest(out_dir) -> dict:
    """The manifest of a study directory; a clear error if there is none.

    A symbolic link (or anything but a regular file) named ``study.json`` is refused
    (:class:`~.lock.UnsafePath`), not followed.
    """
    path = Path(out_dir) / MANIFEST
    try:
        fd = open_regular(path, os.O_RDONLY)
        with os.fdopen(fd, "rb") as f:
            manifest = json.loads(f.read().decode("utf-8"))
    except UnsafePath:
        raise
    except FileNotFoundError:
        raise ParameterError(
            f"{str(out_dir)!r} is not a study directory (no {MANIFEST}; run "
            "'roughcontact study run STUDY.toml -o DIR' first)"
        ) from None
    except (OSError, ValueError) as err:
        raise ParameterError(f"cannot read {path}: {err}") from None
    if not isinstance(manifest, dict):
        raise ParameterError(f"cannot read {path}: not a study manifest (a JSON object)")
    return manifest


#: names of a study directory's own files (fnmatch patterns)
#: a study's own files (the writer's rule, :func:`roughcontact._guard.check_not_study_file`)
assert MANIFEST == STUDY_FILES[0] and _TASK_FILES in STUDY_FILES
