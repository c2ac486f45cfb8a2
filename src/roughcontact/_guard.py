"""What the one writer may replace, and the record of the output directories it fills.

:func:`roughcontact._io.write_bytes_atomic` renames a new file over its target. A rename
replaces whatever directory entry is there, so the writer first asks :func:`refusal`:

- only a regular file is replaced: a device (``/dev/null``, ``/dev/full``), a FIFO, a
  socket or a directory at the name is refused;
- a symbolic link at a name the user gave (registered by
  :func:`roughcontact._io.check_writable`: ``-o /dev/stdout``) is refused; inside the
  directories the program fills (a study, a report), a link planted under one of its own
  names is replaced, never followed;
- a write-protected file (no write permission bit, or not writable by this user) is
  refused: its mode would silently become the default one;
- an input of the command (:func:`protect`: the same ``st_dev``/``st_ino``, whatever
  path or hard link names it) is refused.

The command line checks its outputs with the same rules before any work
(:func:`roughcontact._io.check_writable`), so a refusal costs nothing computed.

A report directory (``stick -o``, ``figures -o``, ``study report -o``, ``demo -o``) is
claimed with :func:`claim_directory` before the work: a directory holding files the
program did not write there is refused (one line) unless ``force``. Every file the writer
then puts below a claimed directory is recorded in its manifest, :data:`MANIFEST_NAME`
(before the file is written: a kill leaves no file of ours unrecorded), so a rerun into
the same directory finds only its own files and goes ahead.

The state lives for one command (:func:`command_scope`, around every command line
command); outside one, nothing is protected or claimed and the writer's rules on the
target's kind and permissions still apply.
"""

from __future__ import annotations

import contextlib
import json
import os
import re
import stat
from pathlib import Path

from .errors import ParameterError

__all__ = [
    "MANIFEST_NAME",
    "claim_directory",
    "command_scope",
    "name_output",
    "protect",
    "record",
    "refusal",
]

#: The record of the files roughcontact wrote into an output directory (JSON).
MANIFEST_NAME = ".roughcontact-manifest.json"
_MANIFEST_FORMAT = "roughcontact-output-manifest"
_MANIFEST_LIMIT = 16 << 20  # bytes read of a manifest at most
#: names below a claimed directory that are ours without a record: the manifest, a
#: directory lock (:mod:`roughcontact.studies.lock`), the writer's temporaries and probes
_OURS = re.compile(
    r"^(\.roughcontact\.lock|\.roughcontact-probe-[0-9a-f]{12}|\..+\.[0-9a-f]{12}\.(tmp|probe))$"
)
_KINDS = (
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISSOCK, "a socket"),
    (stat.S_ISDIR, "a directory"),
)


class _State:
    def __init__(self):
        self.inputs: dict[tuple[int, int], str] = {}  # (st_dev, st_ino) -> name given
        self.named: set[str] = set()  # absolute paths of outputs the user named
        self.claimed: dict[str, list[str]] = {}  # absolute directory -> recorded names
        self.accepted: dict[str, list[str]] = {}  # ... -> foreign files a --force run kept
        self.write = None  # the writer of the manifests (roughcontact._io.write_bytes_atomic)


_state = _State()


@contextlib.contextmanager
def command_scope():
    """A fresh state (no inputs, outputs or directories) for one command, reset after."""
    global _state
    previous, _state = _state, _State()
    try:
        yield
    finally:
        _state = previous


def _abs(path) -> str:
    return os.path.abspath(os.fspath(path))


def protect(*paths) -> None:
    """Register the existing ``paths`` (links followed) as inputs: never replaced."""
    for p in paths:
        if p is None:
            continue
        try:
            st = os.stat(p)
        except (OSError, ValueError):
            continue  # missing: the reader says so
        _state.inputs[(st.st_dev, st.st_ino)] = str(p)


def name_output(path) -> None:
    """Register ``path`` as an output the user named: a link there is refused, not replaced."""
    _state.named.add(_abs(path))


def _kind(mode: int) -> str:
    for test, words in _KINDS:
        if test(mode):
            return words
    return "not a regular file"


def _write_protected(path, st) -> bool:
    if not st.st_mode & 0o222:
        return True  # mode 444: protected even from root, who may write anything
    try:
        return not os.access(path, os.W_OK, follow_symlinks=False)
    except (NotImplementedError, TypeError):  # pragma: no cover - no follow_symlinks here
        return not os.access(path, os.W_OK)


def refusal(path, *, named: bool | None = None) -> str | None:
    """Why the writer must not replace ``path`` (words after its name), or None.

    ``named``: a name the user gave (a link is refused); default: registered by
    :func:`name_output`.
    """
    try:
        st = os.lstat(path)
    except FileNotFoundError:
        return None
    except OSError as err:
        return f"cannot be checked ({err.strerror or err})"
    if named is None:
        named = _abs(path) in _state.named
    if stat.S_ISLNK(st.st_mode):
        if not named:
            return None  # a planted link under the program's own name: replaced
        try:
            target = os.readlink(path)
        except OSError:
            target = "?"
        return (
            f"is a symbolic link (to {target!r}); only a regular file is replaced: name "
            "the file itself"
        )
    if not stat.S_ISREG(st.st_mode):
        return f"is {_kind(st.st_mode)}; only a regular file is replaced"
    if (st.st_dev, st.st_ino) in _state.inputs:
        given = _state.inputs[(st.st_dev, st.st_ino)]
        same = "" if _abs(given) == _abs(path) else f", the file {given!r}"
        return f"is an input of this command{same}; it is never overwritten"
    if _write_protected(path, st):
        return f"is write-protected (mode {stat.S_IMODE(st.st_mode):04o}); it is not replaced"
    return None


def check_target(path, what: str, *, named: bool | None = True) -> None:
    """Raise a one-line ParameterError if the writer would refuse ``path``."""
    if (why := refusal(path, named=named)) is not None:
        raise ParameterError(f"{what} {str(path)!r} {why}; refused")


# --- the manifest of an output directory ----------------------------------------------


def _read_manifest(directory: Path) -> tuple[list[str], list[str]]:
    """The names recorded in ``directory``'s manifest, and the foreign files a ``--force``
    run accepted there (``([], [])`` if none or unreadable)."""
    path = directory / MANIFEST_NAME
    try:
        if not stat.S_ISREG(os.lstat(path).st_mode):
            return [], []
        with open(path, "rb") as f:
            data = json.loads(f.read(_MANIFEST_LIMIT).decode("utf-8"))
    except (OSError, ValueError):
        return [], []
    if not isinstance(data, dict) or data.get("format") != _MANIFEST_FORMAT:
        return [], []
    files, accepted = data.get("files"), data.get("accepted", [])
    if not isinstance(files, list) or not isinstance(accepted, list):
        return [], []
    return [f for f in files if isinstance(f, str)], [f for f in accepted if isinstance(f, str)]


def _foreign(directory: Path, recorded: set[str], most: int | None = 3) -> list[str]:
    """Up to ``most`` (None: all) entries below ``directory`` that roughcontact did not
    write there: any file not recorded (nor a lock or temporary of ours), any link, FIFO
    or device."""
    found = []
    for root, dirs, files in os.walk(directory, followlinks=False):
        dirs.sort()
        for name in sorted(files) + [d for d in dirs if os.path.islink(os.path.join(root, d))]:
            full = os.path.join(root, name)
            rel = os.path.relpath(full, directory)
            if rel == MANIFEST_NAME:
                continue
            try:
                regular = stat.S_ISREG(os.lstat(full).st_mode)
            except OSError:
                continue  # gone meanwhile
            if regular and (rel in recorded or _OURS.match(name)):
                continue
            found.append(rel)
            if most is not None and len(found) >= most:
                return found
    return found


def claim_directory(directory: Path, what: str, *, force: bool, write) -> Path:
    """Claim the output ``directory`` (checked writable by the caller,
    :func:`roughcontact._io.claim_directory`) for this command, before any work; ``write``
    writes its manifest (``write(path, bytes)``, the writer). If it exists, every file
    below it must be one that roughcontact wrote there (its manifest)
    unless ``force``. Files the writer then puts below ``directory`` are recorded; so are the
    regular files that a ``force`` run found there (the user accepted them: a study's own
    inputs beside its report, say), so that a rerun into the directory needs no ``force``.
    A file that appears later is foreign again.

    Raises
    ------
    ParameterError
        One line naming ``what``, ``path`` and up to three files it holds.
    """
    _state.write = write
    recorded, accepted = _read_manifest(directory) if directory.is_dir() else ([], [])
    if directory.is_dir():
        known = set(recorded) | set(accepted)
        if force:
            accepted = sorted(  # every foreign regular file there now
                f for f in _foreign(directory, set(recorded), most=None)
                if stat.S_ISREG(os.lstat(directory / f).st_mode)
            )  # fmt: skip
        elif foreign := _foreign(directory, known):
            names = ", ".join(repr(f) for f in foreign) + (", ..." if len(foreign) >= 3 else "")
            raise ParameterError(
                f"{what} {str(directory)!r} holds files roughcontact did not write there "
                f"({names}); name a new or empty directory, or add --force to write into it "
                "anyway (files of the names written are then replaced)"
            )
        if force and accepted != _read_manifest(directory)[1]:
            _write_manifest(directory, recorded, accepted)  # the user's word, kept now
    _state.claimed[_abs(directory)] = list(recorded)
    _state.accepted[_abs(directory)] = list(accepted)
    return directory


def record(final) -> None:
    """Record ``final`` in the manifest of each claimed directory holding it (before the
    writer writes it)."""
    if not _state.claimed:
        return
    target = _abs(final)
    for directory, names in _state.claimed.items():
        rel = os.path.relpath(target, directory)
        if rel.startswith(os.pardir) or rel in names or os.path.basename(rel) == MANIFEST_NAME:
            continue
        names.append(rel)
        _write_manifest(Path(directory), names, _state.accepted.get(directory, []))


def _write_manifest(directory: Path, names: list[str], accepted: list[str]) -> None:
    accepted = sorted(set(accepted).difference(names))  # a file written is ours now
    data = {"format": _MANIFEST_FORMAT, "files": sorted(names), "accepted": accepted}
    text = json.dumps(data, indent=1)
    directory.mkdir(parents=True, exist_ok=True)
    _state.write(directory / MANIFEST_NAME, (text + "\n").encode("utf-8"))


# --- a study directory's own files ----------------------------------------------------

#: The files of a study directory (``roughcontact.studies.store``: its manifest
#: ``study.json``, the study file's copy, task files, failure records, the lock and the
#: writer's temporaries), never replaced by another command's output.
STUDY_FILES = ("study.json", "study.toml", "task-*.nc", "task-*.json", ".roughcontact.lock",
               ".*.tmp")  # fmt: skip


def _study_source(directory: Path):
    """The study file a study directory was run from (its manifest's ``source``), or None."""
    try:
        fd = os.open(directory / STUDY_FILES[0], os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0))
        with os.fdopen(fd, "rb") as f:
            if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
                return None
            source = json.loads(f.read(_MANIFEST_LIMIT).decode("utf-8")).get("source")
    except (OSError, ValueError, AttributeError):
        return None
    return source if isinstance(source, str) and not source.startswith("<") else None


def check_not_study_file(out_dir, path, what: str = "output") -> None:
    """Refuse ``path`` as an output if it is a study file of ``out_dir`` (one line).

    A study's own files (:data:`STUDY_FILES`, and the study file it was run from) are
    never replaced by another command's output: by name in the study directory, and by
    ``st_dev``/``st_ino`` wherever another path or a hard link names one (registered as
    inputs for the writer).
    """
    import fnmatch

    out = Path(out_dir)
    if not out.is_dir():
        return
    own = [p for p in out.iterdir() if any(fnmatch.fnmatch(p.name, n) for n in STUDY_FILES)]
    protect(*(p for p in own if stat.S_ISREG(os.lstat(p).st_mode)))
    if (source := _study_source(out)) is not None:
        protect(source)
    target = Path(path)
    try:
        inside = target.parent.resolve() == out.resolve()
    except OSError:
        inside = False
    if inside and any(fnmatch.fnmatch(target.name, n) for n in STUDY_FILES):
        raise ParameterError(
            f"{what} {str(path)!r} is a file of the study in {str(out_dir)!r} (its task files, "
            f"{STUDY_FILES[0]}, study.toml and lock are never replaced); name another file"
        )
    check_target(target, what)
