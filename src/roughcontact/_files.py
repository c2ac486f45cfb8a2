"""The reading edge: every input file is checked to be a regular file before it is opened.

A FIFO (named pipe), a character or block device, a socket or a directory given where a
file is expected would make a reader block forever (a FIFO with no writer) or read
without end (``/dev/zero``). :func:`regular_input` looks at the file's kind with
``stat`` (which never blocks) and refuses anything but a regular file in one line;
:func:`open_input` opens with ``O_NONBLOCK`` and checks the opened descriptor again, so
a file swapped for a FIFO between the two cannot block either. Symbolic links are
followed for reading (a link to a measurement is ordinary); writes never follow one
(:mod:`roughcontact._io`).

:func:`npy_header` reads the header of a ``.npy`` file and compares the size it claims
(shape x item size) with the bytes the file holds, before numpy allocates anything: a
200-byte file claiming a 10^5 x 10^5 array is refused as corrupt instead of asking for
80 GB. A file without the ``.npy`` magic bytes (an instrument file renamed ``.npy``) is
named as such.
"""

from __future__ import annotations

import errno
import os
import stat
from pathlib import Path

from .errors import ParameterError

__all__ = ["npy_header", "open_input", "read_array", "regular_input"]

_KINDS = (
    (stat.S_ISDIR, "a directory"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)
_CLOEXEC = getattr(os, "O_CLOEXEC", 0)
NPY_MAGIC = b"\x93NUMPY"


def _kind(mode: int) -> str:
    for test, words in _KINDS:
        if test(mode):
            return words
    return "not a regular file"


def _refuse(path, what: str, why: str) -> ParameterError:
    return ParameterError(f"{what} {str(path)!r}: {why}")


def regular_input(path, what: str = "file", expected: str = "") -> Path:
    """``path`` as a :class:`~pathlib.Path` if it names a regular file (links followed).

    Parameters
    ----------
    path : str or os.PathLike
        The input file.
    what : str
        What the file is, for the message (``"surface"``, ``"study file"``, ...).
    expected : str
        What was expected, appended to the message (``"; expected ..."``).

    Raises
    ------
    ParameterError
        One line: the file is missing, unreadable, or a directory, FIFO, device or
        socket (read, those could block forever or never end).
    """
    p = Path(os.fspath(path))
    tail = f"; expected {expected}" if expected else ""
    if "\0" in str(p):
        raise _refuse(repr(str(p))[1:-1], what, f"a file name cannot hold a NUL character{tail}")
    try:
        st = os.stat(p)
    except FileNotFoundError:
        raise _refuse(p, what, f"no such file{tail}") from None
    except OSError as err:
        raise _refuse(p, what, f"cannot be read ({err.strerror or err}){tail}") from None
    if not stat.S_ISREG(st.st_mode):
        raise _refuse(p, what, f"is {_kind(st.st_mode)}, not a regular file; refused{tail}")
    return p


def open_input(path, what: str = "file", expected: str = ""):
    """A binary file object reading the regular file ``path`` (see :func:`regular_input`).

    Opened without blocking and checked on the descriptor: a FIFO put in the file's
    place after the check is refused too.
    """
    p = regular_input(path, what, expected)
    tail = f"; expected {expected}" if expected else ""
    try:
        fd = os.open(p, os.O_RDONLY | _NONBLOCK | _CLOEXEC | getattr(os, "O_BINARY", 0))
    except OSError as err:
        raise _refuse(p, what, f"cannot be read ({err.strerror or err}){tail}") from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise _refuse(p, what, f"is {_kind(st.st_mode)}, not a regular file; refused{tail}")
        if _NONBLOCK:
            os.set_blocking(fd, True)
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def read_input_bytes(path, what: str = "file", expected: str = "", limit: int | None = None):
    """The bytes of the regular file ``path`` (at most ``limit`` of them)."""
    with open_input(path, what, expected) as f:
        try:
            return f.read() if limit is None else f.read(limit)
        except OSError as err:
            if err.errno == errno.EISDIR:  # pragma: no cover - refused above
                raise _refuse(path, what, "is a directory") from None
            raise _refuse(path, what, f"cannot be read ({err.strerror or err})") from None


def npy_header(path, expected: str = "") -> tuple:
    """``(shape, dtype)`` of a ``.npy`` file, checked against the file's size.

    Raises
    ------
    ParameterError
        One line: not a ``.npy`` file (no magic bytes: e.g. an instrument file renamed
        ``.npy``), an unreadable header, an object (pickle) dtype, or a header whose
        shape x item size exceeds the bytes in the file (truncated or corrupt).
    """
    import numpy as np

    tail = f"; expected {expected}" if expected else ""
    with open_input(path, "path", expected) as f:
        if f.read(len(NPY_MAGIC)) != NPY_MAGIC:
            raise _refuse(
                path,
                "path",
                "is not a NumPy .npy file (it does not start with the .npy magic bytes); an "
                "instrument file must keep its own extension (.spm, .datx, .plu, ...), text "
                f"a .txt/.csv one{tail}",
            )
        f.seek(0)
        try:
            version = np.lib.format.read_magic(f)
            reader = {
                (1, 0): np.lib.format.read_array_header_1_0,
                (2, 0): np.lib.format.read_array_header_2_0,
            }.get(version)
            if reader is None:
                raise ValueError(f"unsupported .npy format version {version}")
            shape, fortran, dtype = reader(f)
        except Exception as err:  # noqa: BLE001 - numpy's parser: ValueError, TokenError, ...
            why = " ".join(str(err).split())[:200]
            raise _refuse(path, "path", f"corrupt .npy header ({why}){tail}") from None
        offset = f.tell()
        size = os.fstat(f.fileno()).st_size
    if dtype.hasobject:
        raise _refuse(
            path, "path", f"holds Python objects (dtype {dtype}), which are not read{tail}"
        )
    count = 1
    for n in shape:
        count *= int(n)
    claimed = count * dtype.itemsize
    if claimed > size - offset:
        raise _refuse(
            path,
            "path",
            f"corrupt or truncated .npy file: its header claims shape {tuple(shape)} of "
            f"{dtype} ({claimed} bytes) but the file holds {max(size - offset, 0)} bytes of "
            f"data{tail}",
        )
    return tuple(shape), dtype


def read_array(p: Path, expected: str):
    """The array of a ``.npy`` or plain text file ``p``, as float64 (any number of
    dimensions): the one reader of plain height files (``load_heights``, ``load_topography``).

    Text files hold one grid row per line, values separated by whitespace or commas,
    ``#`` comments. Boolean, complex, object and text arrays are rejected, never
    converted; every failure is one :class:`ParameterError` naming the file and
    ``expected``.
    """
    import io as _io
    import warnings

    import numpy as np

    from ._validate import real_array

    if p.suffix.lower() == ".npy":  # the claimed size against the file's, before numpy
        npy_header(p, expected)
    try:
        if p.suffix.lower() == ".npy":
            with open_input(p, "path", expected) as f:
                data = np.load(f, allow_pickle=False)
        else:
            with open_input(p, "path", expected) as f:
                text = f.read().decode("utf-8").replace(",", " ")
            with warnings.catch_warnings():  # an empty file: the shape check says it in one line
                warnings.simplefilter("ignore", UserWarning)
                data = np.loadtxt(_io.StringIO(text), dtype=float)
    except ParameterError:
        raise
    except (OSError, ValueError, UnicodeDecodeError, EOFError) as exc:
        raise ParameterError(
            f"path {str(p)!r}: could not read heights ({exc}); expected {expected}"
        ) from None
    try:
        # the dtype first: bool, complex (imaginary part), object and text never convert
        return np.asarray(real_array("heights", data), dtype=np.float64)
    except ParameterError as exc:
        raise ParameterError(f"path {str(p)!r}: expected {expected} ({exc})") from None
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(
            f"path {str(p)!r}: data of dtype {data.dtype} is not numeric; expected {expected}"
        ) from None
