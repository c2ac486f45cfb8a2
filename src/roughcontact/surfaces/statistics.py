"""Statistical descriptors of a height map h(x, y): one period, or a window.

All averages ``<.>`` are means over the grid points of one period (area A0 = Lx*Ly).
Lengths are in units of the pixel size a0 unless ``pixel_size`` is given. A map that is
a window of a larger surface (a measured scan, a free-boundary solve: ``periodic=False``)
has no derivative across its edges: there the finite differences below are taken only
where both neighbours lie inside the window.

Two ways of taking derivatives are offered:

``method="spectral"`` (default)
    Derivatives of the trigonometric interpolant of the samples, evaluated on the grid:
    the periodic case of the package's one spectrum definition,
    :func:`roughcontact.spectra.periodic_moments`.
    With the unnormalised DFT ``H(q) = sum_x h(x) exp(-i q.x)`` and ``N = nx*ny``
    (Parseval)::

        h_rms^2   = (1/N^2) sum_{q != 0} |H(q)|^2
        h'_rms^2  = (1/N^2) sum_q (qx'^2 + qy'^2) |H(q)|^2
        h''_rms^2 = (1/N^2) sum_q (qx^2 + qy^2)^2 |H(q)|^2

    **Nyquist convention.** For an even number of points along an axis the Nyquist
    mode ``cos(pi x / a0)`` has a first derivative ``-(pi/a0) sin(pi x / a0)`` that
    vanishes on every grid point, so its *first* derivative is taken as zero:
    ``qx' = 0`` on the Nyquist row (and ``qy' = 0`` on the Nyquist column), while the
    second derivative (Laplacian) uses the full ``q^2 = qx^2 + qy^2``. The spectral
    values therefore equal the grid means of the spectrally differentiated fields
    ``grad h`` and ``lap h``. :func:`roughcontact.surfaces.self_affine` normalises
    with exactly this function, and never populates Nyquist modes, so a requested
    ``rms_slope`` or ``rms_height`` is reproduced to round-off.

``method="finite-difference"``
    Central differences ``(h[i+1] - h[i-1]) / (2 a0)`` for the gradient and the
    5-point Laplacian ``(h[i+1,j] + h[i-1,j] + h[i,j+1] + h[i,j-1] - 4 h[i,j]) / a0^2``.
    For ``h = A cos(q x)`` these give ``h'_rms = A sin(q a0) / (sqrt(2) a0)`` and
    ``h''_rms = 4 A sin^2(q a0 / 2) / (sqrt(2) a0^2)``, i.e. the spectral values to
    ``O((q a0)^2)``. Periodic maps wrap around; on a window the gradient along an axis is
    averaged over the points with both neighbours along it, the Laplacian over the
    interior points (so a plane's slope and a paraboloid's curvature are exact). The
    spectral method assumes periodicity (the wrap-around jump of a window would enter
    as a spurious slope) and is refused for a window.

The power spectrum follows Persson's convention (B. N. J. Persson et al.,
J. Phys.: Condens. Matter 17, R1 (2005)), see :func:`power_spectrum`: the periodic,
unwindowed, linearly binned case of :mod:`roughcontact.spectra`.

References
----------
L. Pastewka and M. O. Robbins, "Contact between rough surfaces and a criterion for
macroscopic adhesion", PNAS 111, 3298 (2014), Eqs. 1, 8, 9.
T. D. B. Jacobs, T. Junge and L. Pastewka, "Quantitative characterization of surface
topography using spectral analysis", Surf. Topogr.: Metrol. Prop. 5, 013001 (2017).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from .._backend import array_namespace, to_numpy
from .._validate import PIXEL_SIZE, ParameterError, heights2d
from ..spectra import (
    bin_modes,
    linear_edges,
    mode_cell,
    mode_power,
    periodic_moments,
    wavevectors,
)

__all__ = [
    "SurfaceStatistics",
    "power_spectrum",
    "rms_curvature",
    "rms_height",
    "rms_slope",
    "short_cutoff_estimate",
    "statistics",
]

_METHODS = ("spectral", "finite-difference")


@dataclass(frozen=True)
class SurfaceStatistics:
    """Summary statistics of a height map (see :func:`statistics`).

    Attributes
    ----------
    rms_height : float
        ``h_rms = <(h - <h>)^2>^(1/2)`` [length].
    rms_slope : float
        ``h'_rms = <|grad h|^2>^(1/2)`` (PNAS 2014, Eq. 1) [dimensionless].
    rms_curvature : float
        ``h''_rms = <(lap h)^2>^(1/2)`` (PNAS 2014, Eq. 8; ``1/R = h''_rms / 2``)
        [1/length].
    predicted_d_rep : float
        ``d_rep = 4 h'_rms / h''_rms`` (PNAS 2014, Eq. 9) [length]; NaN if
        ``h''_rms = 0``.
    predicted_delta_h : float
        ``delta_h = h'_rms^2 / h''_rms`` (PNAS 2014, Eq. 9) [length]; NaN if
        ``h''_rms = 0``.
    method : str
        ``"spectral"`` or ``"finite-difference"``: how the derivatives were taken.
    periodic : bool
        Whether the map was taken as one period (True) or as a window (False).
    """

    rms_height: float
    rms_slope: float
    rms_curvature: float
    predicted_d_rep: float
    predicted_delta_h: float
    method: str
    periodic: bool = True

    def to_dict(self) -> dict:
        """Return the fields as a plain ``dict`` (floats, the method string, ``periodic``)."""
        d = asdict(self)
        return {k: (v if isinstance(v, str | bool) else float(v)) for k, v in d.items()}


def _check_method(method: str | None, periodic: bool) -> str:
    """The method to use: the default (None) is spectral on a period, else differences."""
    if method is None:
        return "spectral" if periodic else "finite-difference"
    if method not in _METHODS:
        raise ParameterError(f"method must be one of {_METHODS}, got {method!r}")
    if method == "spectral" and not periodic:
        raise ParameterError(
            "method='spectral' needs a periodic map; with periodic=False use "
            "method='finite-difference' (the default)"
        )
    return method


def _fd_moments(h, pixel_size: float, periodic: bool) -> tuple[float, float, float]:
    """Same as :func:`roughcontact.spectra.periodic_moments` with central / 5-point
    differences: wrapping around a period, or on a window only where the stencil fits
    inside the map."""
    xp = array_namespace(h)
    a = pixel_size
    hm = h - xp.mean(h)
    if periodic:
        up, down = xp.roll(h, -1, axis=0), xp.roll(h, 1, axis=0)
        right, left = xp.roll(h, -1, axis=1), xp.roll(h, 1, axis=1)
        gx, gy = (up - down) / (2 * a), (right - left) / (2 * a)
        lap = (up + down + right + left - 4 * h) / a**2
    else:
        if min(h.shape) < 3:
            raise ParameterError(
                f"heights must be at least 3 x 3 points for periodic=False, got {h.shape}"
            )
        gx = (h[2:, :] - h[:-2, :]) / (2 * a)
        gy = (h[:, 2:] - h[:, :-2]) / (2 * a)
        c = h[1:-1, 1:-1]
        lap = (h[2:, 1:-1] + h[:-2, 1:-1] + h[1:-1, 2:] + h[1:-1, :-2] - 4 * c) / a**2
    # gx and gy may cover different points (a window): average each over its own
    return (
        float(xp.mean(hm * hm)),
        float(xp.mean(gx * gx)) + float(xp.mean(gy * gy)),
        float(xp.mean(lap * lap)),
    )


def _moments(heights, pixel_size, method, periodic=True):
    h = heights2d("heights", heights)
    a = PIXEL_SIZE.check("pixel_size", pixel_size)
    method = _check_method(method, periodic)
    # slopes and curvatures of representable heights may still overflow (tiny pixels):
    # they come out inf, without warnings, and print as null in JSON
    with np.errstate(over="ignore", invalid="ignore"):
        if method == "spectral":
            return periodic_moments(h, a)
        return _fd_moments(h, a, periodic)


def statistics(
    heights,
    *,
    pixel_size: float = 1.0,
    method: str | None = None,
    periodic: bool = True,
) -> SurfaceStatistics:
    r"""Root-mean-square height, slope and curvature of a height map.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights h [length] on a grid, ``x = i*pixel_size``, ``y = j*pixel_size``.
        NumPy or any array-API array (e.g. CuPy).
    pixel_size : float, optional
        Grid spacing a0 [length], in [1e-25, 1e25]. Default 1.
    method : {"spectral", "finite-difference"}, optional
        How derivatives are taken (see the module docstring, including the Nyquist
        convention of the spectral method). Default: spectral on a periodic map,
        finite differences on a window (spectral derivatives need periodicity).
    periodic : bool, optional
        Whether ``heights`` is one period of a periodic surface (default) or a window of
        a larger one (a measured scan, a free-boundary substrate: at least 3 x 3
        points), whose edges carry no derivative.

    Returns
    -------
    SurfaceStatistics
        ``h_rms = <(h-<h>)^2>^(1/2)``, ``h'_rms = <|grad h|^2>^(1/2)`` (Eq. 1),
        ``h''_rms = <(lap h)^2>^(1/2)`` (Eq. 8), ``d_rep = 4 h'_rms/h''_rms`` and
        ``delta_h = h'_rms^2/h''_rms`` (Eq. 9).

    References
    ----------
    Pastewka & Robbins, PNAS 111, 3298 (2014), Eqs. 1, 8, 9.
    """
    method = _check_method(method, periodic)
    m0, m2, m4 = _moments(heights, pixel_size, method, periodic)
    hrms, sl, cu = math.sqrt(m0), math.sqrt(m2), math.sqrt(m4)
    if cu > 0:
        d_rep, dh = 4 * sl / cu, sl**2 / cu
    else:
        d_rep = dh = math.nan
    return SurfaceStatistics(
        rms_height=hrms,
        rms_slope=sl,
        rms_curvature=cu,
        predicted_d_rep=d_rep,
        predicted_delta_h=dh,
        method=method,
        periodic=bool(periodic),
    )


def rms_height(heights, *, pixel_size: float = 1.0) -> float:
    """``h_rms = <(h - <h>)^2>^(1/2)`` [length] (grid mean; independent of the method)."""
    return math.sqrt(_moments(heights, pixel_size, "spectral")[0])


def rms_slope(
    heights, *, pixel_size: float = 1.0, method: str | None = None, periodic: bool = True
) -> float:
    """``h'_rms = <|grad h|^2>^(1/2)`` (PNAS 2014, Eq. 1); see :func:`statistics`."""
    return math.sqrt(_moments(heights, pixel_size, method, periodic)[1])


def rms_curvature(
    heights, *, pixel_size: float = 1.0, method: str | None = None, periodic: bool = True
) -> float:
    """``h''_rms = <(lap h)^2>^(1/2)`` [1/length] (PNAS 2014, Eq. 8); see :func:`statistics`."""
    return math.sqrt(_moments(heights, pixel_size, method, periodic)[2])


def power_spectrum(
    heights,
    *,
    pixel_size: float = 1.0,
    nbins: int | None = None,
    return_counts: bool = False,
):
    r"""Radially averaged (isotropic) power spectral density C(q).

    Convention (Persson et al., J. Phys.: Condens. Matter 17, R1 (2005)):
    ``C(q) = (2 pi)^-2 \int d^2x <h(x) h(0)> exp(-i q.x)``, so that
    ``h_rms^2 = \int d^2q C(q)``. On the periodic grid the integral is a sum over the
    discrete wavevectors with cell ``dqx*dqy = (2 pi/Lx)(2 pi/Ly)``, and per mode::

        C(q) = a0^4 |H(q)|^2 / ((2 pi)^2 A0),   H(q) = sum_x h(x) exp(-i q.x),

    with ``A0 = Lx*Ly``. The ``q = 0`` mode is excluded. Modes are grouped into
    ``nbins`` equal-width annuli of ``|q|`` from 0 to the largest ``|q|`` on the grid
    (corners included), and C is averaged within each non-empty annulus. Parseval holds
    exactly::

        h_rms^2 = sum_bins C_bin * count_bin * (2 pi/Lx) * (2 pi/Ly).

    Parameters
    ----------
    heights : (nx, ny) array
        Heights [length] on a periodic grid.
    pixel_size : float, optional
        Grid spacing a0 [length], > 0.
    nbins : int, optional
        Number of annuli (>= 1). Default ``min(nx, ny) // 2``.
    return_counts : bool, optional
        Also return the number of modes in each bin.

    Returns
    -------
    q : ndarray
        Mean ``|q|`` of the modes in each non-empty bin [1/length].
    C : ndarray
        Averaged PSD [length^4].
    counts : ndarray of int, only if ``return_counts``
        Modes per bin.
    """
    h = heights2d("heights", heights)
    a = PIXEL_SIZE.check("pixel_size", pixel_size)
    h = np.asarray(to_numpy(h), dtype=float)
    nx, ny = h.shape
    if nbins is None:
        nbins = max(1, min(nx, ny) // 2)
    if isinstance(nbins, bool) or not isinstance(nbins, (int, np.integer)) or nbins < 1:
        raise ParameterError(f"nbins must be an integer >= 1, got {nbins!r}")
    q, p = mode_power(h, (a, a))
    C = p / mode_cell(h.shape, (a, a))
    q, C = q.ravel()[1:], C.ravel()[1:]  # drop q = 0 (index 0 in fft layout)
    qb, Cb, counts = bin_modes(q, C, linear_edges(q.max(), nbins))
    if return_counts:
        return qb, Cb, counts
    return qb, Cb


def short_cutoff_estimate(heights, *, pixel_size: float = 1.0, rtol: float = 1e-12) -> float:
    r"""Shortest wavelength present in the surface, :math:`2\pi / q_{max}` (length).

    :math:`q_{max}` is the largest :math:`|q|` whose Fourier power exceeds ``rtol`` times
    the largest power. For a Fourier-filtered surface (:func:`self_affine`) this recovers
    its short cutoff λs exactly (up to the grid's discrete wavevectors); a measured
    surface gives the Nyquist wavelength ~2 a0. Used for the Pastewka–Robbins
    condition that the repulsive area spans many :math:`\lambda_s^2` (PNAS 2014).
    """
    h = to_numpy(heights2d("heights", heights))
    a0 = PIXEL_SIZE.check("pixel_size", pixel_size)
    nx, ny = h.shape
    power = np.abs(np.fft.rfft2(h - h.mean())) ** 2
    q = np.hypot(wavevectors(nx, a0)[:, None], wavevectors(ny, a0, real=True)[None])
    present = power > rtol * power.max() if power.max() > 0 else np.zeros_like(power, bool)
    return float(2 * np.pi / q[present].max()) if present.any() else math.inf
