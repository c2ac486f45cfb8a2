"""Reading and writing height maps (``.npy`` or plain text).

Text files hold one grid row (fixed ``i``, i.e. fixed ``x``) per line, values separated
by whitespace or commas; lines starting with ``#`` are comments. Heights are in the
same length unit as the pixel size the caller uses.
"""

from __future__ import annotations

import io as _io
import os
from pathlib import Path

import numpy as np

from .._backend import to_numpy
from .._validate import ParameterError, heights2d, real_array

__all__ = ["load_heights", "save_heights"]

_EXPECTED = "a 2D array (at least 2x2) of finite real heights with a finite rms"


def load_heights(path) -> np.ndarray:
    """Load a height map from a ``.npy`` file or a whitespace/comma separated text file.

    Parameters
    ----------
    path : str or os.PathLike
        File to read. ``.npy`` is read with :func:`numpy.load` (no pickles); any other
        suffix is read as text with :func:`numpy.loadtxt` (commas are treated as
        separators, ``#`` starts a comment).

    Returns
    -------
    ndarray of float64, shape (nx, ny)

    Raises
    ------
    ParameterError
        If the file is missing or unreadable, or does not hold a 2D array of finite
        real numbers (boolean, complex, object and text arrays are rejected, never
        converted; heights whose rms overflows too); the message names the path and
        what was expected.
    """
    p = Path(os.fspath(path))
    if not p.is_file():
        raise ParameterError(
            f"path {str(p)!r}: no such file; expected a .npy or text file holding {_EXPECTED}"
        )
    try:
        if p.suffix.lower() == ".npy":
            data = np.load(p, allow_pickle=False)
        else:
            text = p.read_text().replace(",", " ")
            data = np.loadtxt(_io.StringIO(text), dtype=float)
    except (OSError, ValueError, UnicodeDecodeError) as exc:
        raise ParameterError(
            f"path {str(p)!r}: could not read heights ({exc}); expected {_EXPECTED}"
        ) from None
    try:
        # the dtype first: bool, complex (imaginary part), object and text never convert
        data = np.asarray(real_array("heights", data), dtype=np.float64)
        return np.array(heights2d("heights", data), dtype=np.float64)
    except ParameterError as exc:
        raise ParameterError(f"path {str(p)!r}: expected {_EXPECTED} ({exc})") from None
    except (TypeError, ValueError, OverflowError):
        raise ParameterError(
            f"path {str(p)!r}: data of dtype {data.dtype} is not numeric; expected {_EXPECTED}"
        ) from None


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
    """
    p = Path(os.fspath(path))
    h = np.asarray(to_numpy(heights2d("heights", heights)), dtype=np.float64)
    try:
        if p.suffix.lower() == ".npy":
            with open(p, "wb") as f:
                np.save(f, h, allow_pickle=False)
        else:
            delim = "," if p.suffix.lower() == ".csv" else " "
            np.savetxt(p, h, fmt="%.17g", delimiter=delim)
    except OSError as exc:
        raise ParameterError(f"path {str(p)!r}: could not write ({exc})") from None
    return p
