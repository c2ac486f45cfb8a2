"""Reading and writing height maps (``.npy``, plain text, or instrument files).

Text files hold one grid row (fixed ``i``, i.e. fixed ``x``) per line, values separated
by whitespace or commas; lines starting with ``#`` are comments. Heights are in the
same length unit as the pixel size the caller uses. Any other file (AFM, interferometer,
stylus profilometer formats) is read through SurfaceTopography by
:func:`roughcontact.topography.load_topography`, in metres.
"""

from __future__ import annotations

import io as _io
import os
from pathlib import Path

import numpy as np

from .._backend import to_numpy
from .._files import read_array, regular_input
from .._validate import ParameterError, heights2d

__all__ = ["load_heights", "save_heights"]

_EXPECTED = "a 2D array (at least 2x2) of finite real heights with a finite rms"


def _existing_file(path) -> Path:
    """``path`` if it is a regular file: a FIFO or device is refused before it is opened
    (reading it could block forever), a missing file in one line."""
    return regular_input(path, "path", f"a .npy, text or instrument file holding {_EXPECTED}")


def _read_array(p: Path, expected: str = _EXPECTED) -> np.ndarray:
    """:func:`roughcontact._files.read_array` with this module's expectation."""
    return read_array(p, expected)


def load_heights(path, channel=None) -> np.ndarray:
    """Load a height map from a ``.npy`` file, a text file or an instrument file.

    Parameters
    ----------
    path : str or os.PathLike
        File to read. ``.npy`` is read with :func:`numpy.load` (no pickles); a plain
        text file (numbers separated by whitespace or commas, ``#`` starts a comment)
        with :func:`numpy.loadtxt`, heights as stored (the caller's length unit). Any
        other file is an instrument file (AFM, interferometer, ...) read by
        :func:`roughcontact.topography.load_topography` (needs SurfaceTopography):
        its heights are returned **in metres**, whatever unit the file stores, and its
        pixel size (also in metres) is in ``load_topography(path).pixel_size``.
    channel : str or int, optional
        Channel of an instrument file, by name or index (default: the file's default
        channel). ``.npy`` and text files have one channel (None, 0 or ``"heights"``).

    Returns
    -------
    ndarray of float64, shape (nx, ny)

    Raises
    ------
    ParameterError
        If the file is missing or unreadable, or does not hold a 2D array of finite
        real numbers (boolean, complex, object and text arrays are rejected, never
        converted; heights whose rms overflows too; an instrument line scan is 1D); the
        message names the path and what was expected.
    """
    from ..topography.read import file_kind, load_topography

    p = _existing_file(path)
    if file_kind(p) == "instrument":
        topo = load_topography(p, channel=channel)
        if topo.dim != 2:
            raise ParameterError(
                f"path {str(p)!r}: holds a {topo.dim}D line scan of {topo.shape[0]} points; "
                f"expected {_EXPECTED} (read line scans with roughcontact.load_topography)"
            )
        return np.array(topo.heights, dtype=np.float64)
    if channel not in (None, 0, "0", "heights"):
        raise ParameterError(
            f"channel must be None, 0 or 'heights' for {str(p)!r} (a .npy or text file has "
            f"one channel), got {channel!r}"
        )
    data = _read_array(p)
    try:
        return np.array(heights2d("heights", data), dtype=np.float64)
    except ParameterError as exc:
        raise ParameterError(f"path {str(p)!r}: expected {_EXPECTED} ({exc})") from None


def save_heights(path, heights) -> Path:
    """Save a height map as ``.npy`` (binary) or as text (any other suffix).

    Text is written with full double precision (``%.17g``), one grid row per line,
    comma separated if the suffix is ``.csv`` and space separated otherwise, so
    :func:`load_heights` reads back the identical array.

    Parameters
    ----------
    path : str or os.PathLike
        Destination. The suffix selects the format.
    heights : (nx, ny) array
        Finite heights (NumPy or any array-API array; copied to host memory).

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    roughcontact._io.WriteError
        The disk is full (quota, I/O error): an existing file at ``path`` is unchanged.
    ParameterError
        Any other failure to write (missing or read-only directory, ...), in one line.

    Notes
    -----
    The file is written atomically (a temporary file in the same directory, fsync'ed and
    renamed over ``path``); a symbolic link at ``path`` is replaced, never followed.
    """
    from .._io import WriteError, write_bytes_atomic

    p = Path(os.fspath(path))
    h = np.asarray(to_numpy(heights2d("heights", heights)), dtype=np.float64)
    buffer = _io.BytesIO()  # built in memory: the file on disk is the old one or the new
    if p.suffix.lower() == ".npy":
        np.save(buffer, h, allow_pickle=False)
    else:
        delim = "," if p.suffix.lower() == ".csv" else " "
        np.savetxt(buffer, h, fmt="%.17g", delimiter=delim)
    try:
        # atomic (temporary file, fsync, rename): a full disk leaves an existing file as
        # it was; a symbolic link at ``path`` is replaced, never written through
        write_bytes_atomic(p, buffer.getbuffer())
    except WriteError:
        raise
    except OSError as exc:
        raise ParameterError(f"path {str(p)!r}: could not write ({exc})") from None
    return p
