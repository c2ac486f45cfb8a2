r"""Fourier modes, windows, binned power spectra, scale-dependent rms slope and curvature.

Everything here works on measured height data in SI units (heights and pixel sizes in m):
a 2D map ``heights[i, j]`` at ``x = i dx, y = j dy`` or a 1D profile ``heights[i]``.
The modes, their normalisation, the windows and the bins are those of
:mod:`roughcontact.spectra`, the package's one definition of the spectrum; this module
adds the measured-data front end (checks, per-axis pixel sizes, log bins, cumulative
moments by scale).
:mod:`roughcontact.topography.statistics` builds on these (with the Hurst fit of
:mod:`roughcontact.topography.hurst`) and re-exports every public name.

**Window.** Measured scans are not periodic: their FFT sees a jump between opposite
edges, whose leakage (a spectrum falling only as ``q^-2``) swamps the small-scale part of
the spectrum that slopes and curvatures come from. Non-periodic data (the default) are
therefore multiplied by a Hann window before the FFT, normalised so that the mean of its
square is 1 (the mean-square height of stationary data is kept): the 1D ``hann`` window
along x for profiles (SciPy's periodic Hann), the rotationally symmetric one
``w(r) = [1 + cos(pi r/r_max)]/2`` (``r_max = min(Lx, Ly)/2``, 0 beyond) for maps,
as in SurfaceTopography (Jacobs, Junge & Pastewka 2017). Periodic data are not windowed.
The mean is subtracted first (detrending is the caller's choice, e.g. ``detrend``). The
window's own gradient adds ``h grad w`` to the slopes: on surfaces whose height comes from
the longest wavelengths (H near 1) h'_rms comes out a few per cent high, and a windowed
scan holds fewer independent modes (``PowerSpectrum.efficiency``), which the Hurst fit's
error accounts for.

**PSD convention** (Persson et al. 2005, as :func:`roughcontact.surfaces.power_spectrum`)::

    C(q)   = (2 pi)^-2 \int d^2x <h(x) h(0)> exp(-i q.x),  h_rms^2 = \int d^2q C(q)
    C1D(q) = (2 pi)^-1 \int dx   <h(x) h(0)> exp(-i q x),  h_rms^2 = \int_-inf^inf dq C1D

C in m^4, C1D in m^3. SurfaceTopography (and contact.engineering) use
``C_ST = (2 pi)^2 C`` and ``C1D_ST = 2 pi C1D``. C1D of a map is the average over its
profiles along x (the first axis).

**Scale-dependent rms slope and curvature (the definition used throughout).** The rms
slope and curvature of the surface low-pass filtered at the wavelength lambda, i.e. with
roughness only down to a smallest scale ``lambda_s = lambda`` (Pastewka & Robbins 2014;
the moments of the PSD, Persson et al. 2005, Jacobs et al. 2017)::

    h'_rms(lambda)^2  = \int_{|q| <= 2 pi/lambda} d^2q q^2 C(q)   = <|grad h|^2>
    h''_rms(lambda)^2 = \int_{|q| <= 2 pi/lambda} d^2q q^4 C(q)   = <(lap h)^2>

evaluated as exact sums over the FFT modes (no binning). This is the quantity of Eqs. 1,
8 and 9 of Pastewka & Robbins for a surface whose short cutoff is lambda. (It is not the
finite-difference "scale-dependent slope" of Sanner et al., Appl. Surf. Sci. Adv. 7,
100190 (2022), which SurfaceTopography's ``scale_dependent_slope_*`` compute; the two
differ by factors of order 1 at a given lambda.)

References
----------
B. N. J. Persson et al., J. Phys.: Condens. Matter 17, R1 (2005).
T. D. B. Jacobs, T. Junge and L. Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._validate import ParameterError, positive, real_array
from ..spectra import (
    bin_modes,
    hann_1d,
    log_edges,
    mode_cell,
    mode_power,
    radial_hann,
    window_efficiency,
)

__all__ = [
    "PowerSpectrum",
    "power_spectrum_1d",
    "power_spectrum_2d",
    "scale_dependent_rms",
]

#: Fewest points along an axis (a Hann window over fewer says nothing about slopes).
MIN_POINTS = 8


# --------------------------------------------------------------------------- inputs


def _grid(heights, pixel_size):
    """``heights`` as a finite float array (1D or 2D) and the pixel size per axis (m)."""
    h = real_array("heights", heights)
    h = np.asarray(h, dtype=float)
    if h.ndim not in (1, 2):
        raise ParameterError(f"heights must be a 1D profile or a 2D map, got {h.ndim} dimension(s)")
    if min(h.shape) < MIN_POINTS:
        raise ParameterError(
            f"heights must have at least {MIN_POINTS} points along every axis, got shape {h.shape}"
        )
    if not np.all(np.isfinite(h)):
        raise ParameterError("heights must be finite everywhere (found NaN or inf)")
    if isinstance(pixel_size, (tuple, list, np.ndarray)):
        sizes = tuple(pixel_size)
        if len(sizes) != h.ndim:
            raise ParameterError(
                f"pixel_size must give one size per axis ({h.ndim}), got {pixel_size!r}"
            )
    else:
        sizes = (pixel_size,) * h.ndim
    sizes = tuple(positive("pixel_size", s) for s in sizes)
    return h, sizes


def _windowed(h, sizes, periodic, *, profiles=False):
    """Mean-free heights times the window; the window's name and efficiency.

    ``profiles``: every profile along x of a map gets its own mean removed and the 1D
    window (for C1D); otherwise maps get the radial window.
    """
    if profiles and h.ndim == 2:
        h = h - h.mean(axis=0, keepdims=True)
    else:
        h = h - h.mean()
    if periodic:
        return h, "none (periodic)", 1.0
    if h.ndim == 1 or profiles:
        w, name = hann_1d(h.shape[0]), "hann"
        hw = h * (w if h.ndim == 1 else w[:, None])
    else:
        w, name = radial_hann(h.shape, sizes), "hann (radial)"
        hw = h * w
    return hw, name, window_efficiency(w)


@dataclass(frozen=True)
class _Modes:
    """Fourier modes of the windowed data: ``|q|`` (1/m) and ``p``, each mode's share of
    ``<h^2>`` (m^2; Parseval: ``sum(p) = <h_w^2>``), sorted by ``|q|``, ``q = 0`` dropped;
    ``cell`` is dq (1D) or dqx dqy (2D), so that ``C = p/cell``."""

    q: np.ndarray
    p: np.ndarray
    cell: float
    dim: int
    window: str
    efficiency: float
    cum2: np.ndarray = field(init=False, repr=False)
    cum4: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        # the moments up to each mode: sum_{q' <= q_i} q'^k p (k = 2, 4), 0 before the first
        for k in (2, 4):
            cum = np.concatenate([[0.0], np.cumsum(self.q**k * self.p)])
            object.__setattr__(self, f"cum{k}", cum)


def _modes(h, sizes, periodic, *, profiles=False):
    """The :class:`_Modes` of a map (2D FFT) or of profiles along x (1D FFT, averaged
    over a map's lines when ``profiles``), and the windowed heights."""
    hw, window, eff = _windowed(h, sizes, periodic, profiles=profiles)
    q, p = mode_power(hw, sizes, profiles=profiles)
    q, p = q.ravel(), p.ravel()
    dim = 2 if h.ndim == 2 and not profiles else 1
    cell = mode_cell(h.shape[:dim], sizes)
    order = np.argsort(q, kind="stable")
    q, p = q[order], p[order]
    keep = q > 0
    modes = _Modes(q=q[keep], p=p[keep], cell=cell, dim=dim, window=window, efficiency=eff)
    return modes, hw


# --------------------------------------------------------------------------- PSD


@dataclass(frozen=True)
class PowerSpectrum:
    """A binned power spectral density (see the module docstring for the convention).

    Attributes
    ----------
    q : ndarray
        Mean ``|q|`` of the modes in each non-empty bin [1/m].
    psd : ndarray
        Mean PSD of those modes: C(q) [m^4] (``dim = 2``, radially averaged) or C1D(q)
        [m^3] (``dim = 1``, profiles along x, averaged over lines).
    counts : ndarray of int
        Modes per bin (1D: both signs of q).
    dim : int
        2 for C(q), 1 for C1D(q).
    cell : float
        Area (2D, [1/m^2]) or length (1D, [1/m]) of one mode in q-space; Parseval:
        ``sum(psd * counts * cell) = <h^2>`` of the (windowed) data.
    window : str
        ``"hann"``, ``"hann (radial)"`` or ``"none (periodic)"``.
    efficiency : float
        Independent modes per mode, ``<w^2>^2/<w^4>`` of the window w (1 without one;
        0.51 for the 1D Hann, 0.25 for the radial one): a window averages neighbouring
        modes, so a bin of n modes holds about ``n * efficiency`` independent ones.
    """

    q: np.ndarray
    psd: np.ndarray
    counts: np.ndarray
    dim: int
    cell: float
    window: str
    efficiency: float = 1.0

    def to_dict(self) -> dict:
        return {
            "q": self.q.tolist(),
            "psd": self.psd.tolist(),
            "counts": self.counts.tolist(),
            "dim": self.dim,
            "window": self.window,
            "efficiency": self.efficiency,
        }


def _binned(modes: _Modes, points_per_decade: int) -> PowerSpectrum:
    ppd = _points_per_decade(points_per_decade)
    q, c = modes.q, modes.p / modes.cell
    qb, cb, counts = bin_modes(q, c, log_edges(float(q[0]), float(q[-1]), ppd))
    return PowerSpectrum(q=qb, psd=cb, counts=counts, dim=modes.dim, cell=modes.cell,
                         window=modes.window, efficiency=modes.efficiency)  # fmt: skip


def _points_per_decade(value) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        raise ParameterError(f"points_per_decade must be an integer >= 1, got {value!r}")
    return int(value)


def power_spectrum_2d(heights, pixel_size, *, periodic=False, points_per_decade=10):
    """Radially averaged 2D PSD C(q) of a height map, in log-spaced bins.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights [m] (any length unit gives C in that unit^4).
    pixel_size : float or (float, float)
        Grid spacing per axis [m].
    periodic : bool
        True: no window. False (default): the radial Hann window (module docstring).
    points_per_decade : int
        Bins per decade of q (log-spaced from the smallest to the largest ``|q|``).

    Returns
    -------
    PowerSpectrum
        ``dim = 2``, C in m^4 (Persson's convention; ``(2 pi)^2 C`` is
        SurfaceTopography's).
    """
    h, sizes = _grid(heights, pixel_size)
    if h.ndim != 2:
        raise ParameterError("power_spectrum_2d needs a 2D map; use power_spectrum_1d")
    return _binned(_modes(h, sizes, periodic)[0], points_per_decade)


def power_spectrum_1d(heights, pixel_size, *, periodic=False, points_per_decade=10):
    """1D PSD C1D(q) of a profile, or of the profiles along x of a map averaged over lines.

    Parameters as for :func:`power_spectrum_2d` (``heights`` may be 1D; for maps only the
    x pixel size matters; non-periodic profiles get the 1D Hann window along x).

    Returns
    -------
    PowerSpectrum
        ``dim = 1``, C1D in m^3, ``h_rms^2 = int_-inf^inf C1D dq`` (``2 pi C1D`` is
        SurfaceTopography's).
    """
    h, sizes = _grid(heights, pixel_size)
    return _binned(_modes(h, sizes, periodic, profiles=True)[0], points_per_decade)


# --------------------------------------------------------------------------- slopes


def scale_dependent_rms(heights, pixel_size, scales, *, periodic=False):
    """rms slope and curvature of the data low-pass filtered at each wavelength in ``scales``.

    ``h'_rms(lambda)^2 = sum_{0 < |q| <= 2 pi/lambda} q^2 p_q`` and ``h''_rms(lambda)^2 =
    sum q^4 p_q`` over the FFT modes of the (windowed) data, ``p_q`` a mode's share of
    ``<h^2>`` (module docstring). Maps: ``|q|`` of the 2D modes (gradient and Laplacian);
    profiles: ``|q_x|`` (``dh/dx`` and ``d^2h/dx^2``, no isotropy factor).

    Parameters
    ----------
    heights : 1D or 2D array
        Heights [m].
    pixel_size : float or tuple
        Grid spacing per axis [m].
    scales : array_like
        Smallest wavelengths lambda > 0 [m].
    periodic : bool
        True: no window.

    Returns
    -------
    rms_slope : ndarray
        [dimensionless]
    rms_curvature : ndarray
        [1/m]
    """
    h, sizes = _grid(heights, pixel_size)
    modes = _modes(h, sizes, periodic)[0]
    lam = np.asarray(scales, dtype=float)
    if lam.size == 0 or not np.all(np.isfinite(lam)) or np.any(lam <= 0):
        raise ParameterError(f"scales must be wavelengths > 0 (m), got {scales!r}")
    return _moments_at(modes, lam)


def _moments_at(modes: _Modes, lam):
    """(rms slope, rms curvature) of the modes with ``|q| <= 2 pi/lam`` (own dimension)."""
    lam = np.asarray(lam, dtype=float)
    n = np.searchsorted(modes.q, 2 * np.pi / lam * (1 + 1e-12), side="right")
    return np.sqrt(modes.cum2[n]), np.sqrt(modes.cum4[n])
