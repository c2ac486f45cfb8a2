"""Deterministic reference geometries on a periodic grid.

Convention (the README's 'The model'): the rigid surface sits at ``z = d - h``, so larger ``h`` is
closer to the substrate and summits are maxima of ``h``. Grid index ``i`` along axis 0
is ``x = i * pixel_size``; ``j`` along axis 1 is ``y = j * pixel_size``.
"""

from __future__ import annotations

import math

import numpy as np

from .._validate import PIXEL_SIZE, ParameterError, positive, shape2d
from .._validate import finite as _finite

__all__ = ["egg_box", "flat", "sinusoid", "sphere"]


def _coordinates(nx: int, ny: int, a: float):
    x = np.arange(nx, dtype=float)[:, None] * a
    y = np.arange(ny, dtype=float)[None, :] * a
    return x, y


def _check_divides(name: str, wavelength: float, period: float, axis: int) -> None:
    m = period / wavelength
    k = round(m)
    if k < 1 or abs(m - k) > 1e-9 * max(1.0, m):
        raise ParameterError(
            f"{name} must divide the period along axis {axis} (L = {period}) an integer "
            f"number of times (L/{name} in {{1, 2, 3, ...}}), got {name} = {wavelength} "
            f"(L/{name} = {m:.6g})"
        )


def flat(shape) -> np.ndarray:
    """A flat surface, ``h = 0`` everywhere.

    Parameters
    ----------
    shape : int or (int, int)
        Grid size.

    Returns
    -------
    ndarray of float64
    """
    nx, ny = shape2d("shape", shape)
    return np.zeros((nx, ny))


def sphere(
    shape,
    radius: float,
    *,
    pixel_size: float = 1.0,
    center=None,
    exact: bool = False,
) -> np.ndarray:
    r"""A single spherical summit (Hertz indenter) of radius ``R``.

    By default the paraboloid ``h = -r^2 / (2R)`` (K. L. Johnson, Contact Mechanics, 1985,
    section 4.1: the small-slope approximation used by Hertz theory); with ``exact=True``
    the true cap ``h = sqrt(R^2 - r^2) - R`` for ``r <= R`` and ``h = -R`` (its value at
    the rim ``r = R``) for ``r > R``. The summit ``h = 0`` is at ``r = 0``.
    ``r`` is the plain Euclidean distance from ``center``, *not* the periodic
    minimum-image distance: the surface has a kink at the cell boundary, which is
    harmless when the cell is large compared with the contact radius.

    Parameters
    ----------
    shape : int or (int, int)
        Grid size ``(nx, ny)``.
    radius : float
        Radius of curvature R [length], > 0.
    pixel_size : float, optional
        Grid spacing a0 [length], > 0.
    center : (float, float), optional
        Summit position ``(x, y)`` [length]. Default: the grid point nearest the cell
        centre, ``(nx // 2, ny // 2) * pixel_size``.
    exact : bool, optional
        Use the spherical cap instead of the paraboloid.

    Returns
    -------
    ndarray of float64, shape (nx, ny)
        Heights [length], maximal (zero) at the summit.
    """
    nx, ny = shape2d("shape", shape)
    R = positive("radius", radius)
    a = PIXEL_SIZE.check("pixel_size", pixel_size)
    if center is None:
        cx, cy = (nx // 2) * a, (ny // 2) * a
    else:
        try:
            cx, cy = (float(c) for c in center)
        except (TypeError, ValueError):
            raise ParameterError(
                f"center must be a pair of finite numbers (x, y), got {center!r}"
            ) from None
        if not (math.isfinite(cx) and math.isfinite(cy)):
            raise ParameterError(f"center must be a pair of finite numbers (x, y), got {center!r}")
    x, y = _coordinates(nx, ny, a)
    r2 = (x - cx) ** 2 + (y - cy) ** 2
    if not exact:
        return -r2 / (2 * R)
    return np.sqrt(np.clip(R**2 - r2, 0.0, None)) - R


def _wave(shape, wavelength, amplitude, pixel_size):
    """The checked ``(nx, ny, wavelength, amplitude, pixel_size)`` of a periodic wave."""
    nx, ny = shape2d("shape", shape)
    lam = positive("wavelength", wavelength)
    return nx, ny, lam, _finite("amplitude", amplitude), PIXEL_SIZE.check("pixel_size", pixel_size)


def sinusoid(
    shape,
    wavelength: float,
    amplitude: float,
    *,
    axis: int = 0,
    pixel_size: float = 1.0,
) -> np.ndarray:
    r"""A one-dimensional wavy surface ``h = amplitude * cos(2 pi s / wavelength)``.

    ``s`` is the coordinate along ``axis`` (``x`` for 0, ``y`` for 1); ``h`` is constant
    along the other axis. Crests (summits) are at ``s = 0, wavelength, ...``. This is
    the geometry of Westergaard's problem (Johnson 1985, section 13.2), see
    :mod:`roughcontact.theory.westergaard`.

    Parameters
    ----------
    shape : int or (int, int)
        Grid size ``(nx, ny)``.
    wavelength : float
        Wavelength lambda [length], > 0; the period ``L = n * pixel_size`` along
        ``axis`` must be an integer multiple of it.
    amplitude : float
        Amplitude Delta [length] (finite).
    axis : {0, 1}
        Direction of the corrugation.
    pixel_size : float, optional
        Grid spacing a0 [length], > 0.

    Returns
    -------
    ndarray of float64, shape (nx, ny)
        Heights h [length], constant along the axis other than ``axis``.
    """
    nx, ny, lam, A, a = _wave(shape, wavelength, amplitude, pixel_size)
    if axis not in (0, 1) or isinstance(axis, bool):
        raise ParameterError(f"axis must be 0 or 1, got {axis!r}")
    n = (nx, ny)[axis]
    _check_divides("wavelength", lam, n * a, axis)
    s = np.arange(n, dtype=float) * a
    prof = A * np.cos(2 * np.pi * s / lam)
    return np.broadcast_to(prof[:, None] if axis == 0 else prof[None, :], (nx, ny)).copy()


def egg_box(shape, wavelength: float, amplitude: float, *, pixel_size: float = 1.0) -> np.ndarray:
    r"""An egg-box surface ``h = amplitude * cos(2 pi x / lambda) * cos(2 pi y / lambda)``.

    Parameters
    ----------
    shape : int or (int, int)
        Grid size ``(nx, ny)``.
    wavelength : float
        Wavelength lambda [length], > 0; both periods ``nx*pixel_size`` and
        ``ny*pixel_size`` must be integer multiples of it.
    amplitude : float
        Amplitude [length] (finite).
    pixel_size : float, optional
        Grid spacing a0 [length], > 0.

    Returns
    -------
    ndarray of float64, shape (nx, ny)
        Heights h [length], summits at the grid origin and its periodic images.
    """
    nx, ny, lam, A, a = _wave(shape, wavelength, amplitude, pixel_size)
    _check_divides("wavelength", lam, nx * a, 0)
    _check_divides("wavelength", lam, ny * a, 1)
    x, y = _coordinates(nx, ny, a)
    return A * np.cos(2 * np.pi * x / lam) * np.cos(2 * np.pi * y / lam)
