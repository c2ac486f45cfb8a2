"""Grid repairs done while reading: filling missing points, resampling a line scan.

Both are recorded by the caller in ``Topography.info``; neither is ever done silently.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError

__all__ = ["harmonic_fill", "uniform_positions"]


def harmonic_fill(heights: np.ndarray, missing: np.ndarray, periodic: bool = False) -> np.ndarray:
    """Fill the ``missing`` points by harmonic interpolation (a discrete Laplace equation).

    Every missing point takes the mean of its nearest neighbours (2 per axis, fewer at a
    non-periodic edge), the known points are fixed: the 5-point (2D) or 3-point (1D)
    Laplacian of the result vanishes on the missing points. A plane (a line in 1D) is
    therefore reproduced exactly inside the scan; at a non-periodic edge the missing
    neighbour is left out, i.e. a zero-slope (Neumann) condition there.

    Parameters
    ----------
    heights : ndarray, shape (nx,) or (nx, ny)
        Heights (any length unit); values at missing points are ignored.
    missing : ndarray of bool, same shape
        The points to fill; at least one point must be known.
    periodic : bool
        Whether neighbours wrap around the edges.

    Returns
    -------
    ndarray of float64
        A copy of ``heights`` with the missing points filled.

    References
    ----------
    The "harmonic" filling of undefined data of SurfaceTopography
    (ContactEngineering, ``interpolate_undefined_data(method="harmonic")``).
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.linalg import spsolve

    h = np.array(heights, dtype=np.float64)
    missing = np.asarray(missing, dtype=bool)
    idx = np.flatnonzero(missing)
    n = idx.size
    if n == 0:
        return h
    if n == h.size:
        raise ParameterError("heights: every point is missing; nothing to interpolate from")
    flat_h, flat_missing = h.ravel(), missing.ravel()
    number = np.full(h.size, -1)
    number[idx] = np.arange(n)
    coords = np.unravel_index(idx, h.shape)
    diag = np.zeros(n)
    rhs = np.zeros(n)
    rows, cols = [], []
    for axis in range(h.ndim):
        for step in (-1, 1):
            c = list(coords)
            c[axis] = c[axis] + step
            if periodic:
                c[axis] = c[axis] % h.shape[axis]
                valid = np.ones(n, dtype=bool)
            else:
                valid = (c[axis] >= 0) & (c[axis] < h.shape[axis])
            me = np.flatnonzero(valid)
            nb = np.ravel_multi_index(tuple(ci[valid] for ci in c), h.shape)
            diag[me] += 1
            unknown = flat_missing[nb]
            rows.append(me[unknown])
            cols.append(number[nb[unknown]])
            np.add.at(rhs, me[~unknown], flat_h[nb[~unknown]])
    rows = np.concatenate([np.arange(n), *rows])
    cols = np.concatenate([np.arange(n), *cols])
    vals = np.concatenate([diag, -np.ones(rows.size - n)])
    matrix = coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsc()
    flat_h = flat_h.copy()
    flat_h[idx] = spsolve(matrix, rhs)
    return flat_h.reshape(h.shape)


def uniform_positions(x: np.ndarray) -> tuple[float, float, float]:
    """The uniform grid closest to positions ``x`` (least squares), and how far off.

    Returns ``(start, step, deviation)``: the grid ``start + i * step`` fitted to
    ``x[i]`` by least squares, and the largest ``|x[i] - start - i step|`` in units of
    ``step``. Positions rounded to a fixed number of digits (as profilometers write
    them) deviate by at most half their last digit. Positions must increase strictly.
    """
    x = np.asarray(x, dtype=np.float64)
    if x.size < 2 or not np.all(np.diff(x) > 0):
        raise ParameterError("positions of a line scan must increase strictly (at least 2)")
    i = np.arange(x.size, dtype=np.float64)
    step, start = np.polyfit(i, x, 1)
    return float(start), float(step), float(np.max(np.abs(x - start - step * i)) / step)
