r"""Power spectra, scale-dependent rms slope and curvature, and the self-affine fit (SI).

Everything here works on measured height data in SI units (heights and pixel sizes in m):
a 2D map ``heights[i, j]`` at ``x = i dx, y = j dy`` or a 1D profile ``heights[i]``.

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

**Profiles (1D).** A profile only gives ``<(dh/dx)^2>`` and ``<(d^2h/dx^2)^2>``. For an
isotropic surface ``<|grad h|^2> = 2 <(dh/dx)^2>`` and ``<(lap h)^2> = (8/3)
<(d^2h/dx^2)^2>`` (the angular averages of ``cos^2`` and ``cos^4``; Nayak, J. Lubr.
Technol. 93, 398 (1971)); :class:`ScaleStatistics` reports these 2D-equivalent values
for profiles and says so (``isotropy_assumed``).

**Self-affine fit and extrapolation.** Between a long scale and the reliability cutoff
the binned PSD is fitted by ``C = C_p (q/q_p)^-(d + 2H)`` (d = 2 for C, 1 for C1D;
ordinary least squares of log C on log q; ``q_p`` the geometric centre of the fitted
bins, where the errors of ``C_p`` and H are uncorrelated). Continuing that power law
from ``q_c = 2 pi/lambda_c`` (the smallest measured scale) to ``q_s = 2 pi/lambda_s``
adds to the measured moments::

    m_k(lambda_s) = m_k(lambda_c) + g C_p q_p^(d+2H) \int_{q_c}^{q_s} q^(k-1-2H) dq,

``g = 2 pi`` (2D) or 2 (1D, both signs of q), ``k = 2`` for ``h'_rms^2`` and 4 for
``h''_rms^2``. For ``0 < H < 1`` and ``q_s >> q_c``: ``h'_rms ~ lambda_s^(H-1)``,
``h''_rms ~ lambda_s^(H-2)`` and ``d_rep = 4 h'_rms/h''_rms ~ lambda_s``.

References
----------
B. N. J. Persson et al., J. Phys.: Condens. Matter 17, R1 (2005).
T. D. B. Jacobs, T. Junge and L. Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001 (2017).
L. Pastewka and M. O. Robbins, PNAS 111, 3298 (2014), Eqs. 1, 8, 9.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import ParameterError, json_ready, positive, real_array

__all__ = [
    "HurstFit",
    "PowerSpectrum",
    "ScaleStatistics",
    "fit_hurst",
    "power_spectrum_1d",
    "power_spectrum_2d",
    "scale_dependent_rms",
    "scale_statistics",
]

#: Fewest points along an axis (a Hann window over fewer says nothing about slopes).
MIN_POINTS = 8
#: Fewest PSD bins a Hurst fit accepts.
MIN_FIT_BINS = 3
#: Default fit range: from ``FIT_SHORT_PIXELS`` pixels (the last octave below it is
#: distorted by the grid) up to ``1/FIT_LONG_FRACTION`` of the scan size (longer
#: wavelengths hold few modes, are shaped by detrending and the window, and usually lie
#: beyond the self-affine range).
FIT_SHORT_PIXELS = 4.0
FIT_LONG_FRACTION = 4.0
#: ``<|grad h|^2>/<(dh/dx)^2>`` and ``<(lap h)^2>/<(d2h/dx2)^2>`` of an isotropic surface.
ISOTROPIC_SLOPE_FACTOR = 2.0
ISOTROPIC_CURVATURE_FACTOR = 8.0 / 3.0


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


def _hann_1d(n: int) -> np.ndarray:
    """SciPy's periodic Hann window of n points, scaled to a mean square of 1."""
    from scipy.signal import get_window

    w = get_window("hann", n)
    return w * math.sqrt(n / float(np.sum(w * w)))


def _radial_hann(shape, sizes) -> np.ndarray:
    """The rotationally symmetric Hann window of a map, scaled to a mean square of 1."""
    nx, ny = shape
    x = sizes[0] * (np.arange(nx) - nx // 2)
    y = sizes[1] * (np.arange(ny) - ny // 2)
    r = np.hypot(x[:, None], y[None, :])
    r_max = min(nx * sizes[0], ny * sizes[1]) / 2
    w = np.where(r <= r_max, 0.5 + 0.5 * np.cos(np.pi * r / r_max), 0.0)
    return w * math.sqrt(w.size / float(np.sum(w * w)))


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
        w, name = _hann_1d(h.shape[0]), "hann"
        hw = h * (w if h.ndim == 1 else w[:, None])
    else:
        w, name = _radial_hann(h.shape, sizes), "hann (radial)"
        hw = h * w
    return hw, name, 1.0 / float(np.mean(w**4))


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
    nx = h.shape[0]
    if h.ndim == 2 and not profiles:
        ny = h.shape[1]
        p = (np.abs(np.fft.fft2(hw)) ** 2).ravel() / float(nx * ny) ** 2
        qx = 2 * np.pi * np.fft.fftfreq(nx, d=sizes[0])
        qy = 2 * np.pi * np.fft.fftfreq(ny, d=sizes[1])
        q = np.hypot(qx[:, None], qy[None, :]).ravel()
        cell, dim = (2 * np.pi / (nx * sizes[0])) * (2 * np.pi / (ny * sizes[1])), 2
    else:
        p = np.abs(np.fft.fft(hw, axis=0)) ** 2 / float(nx) ** 2
        if p.ndim == 2:
            p = p.mean(axis=1)
        q = np.abs(2 * np.pi * np.fft.fftfreq(nx, d=sizes[0]))
        cell, dim = 2 * np.pi / (nx * sizes[0]), 1
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
    lo, hi = float(q[0]), float(q[-1])
    nb = max(1, math.ceil(math.log10(hi / lo) * ppd)) if hi > lo else 1
    edges = np.geomspace(lo, hi, nb + 1)
    idx = np.clip(np.searchsorted(edges, q, side="right") - 1, 0, nb - 1)
    counts = np.bincount(idx, minlength=nb)
    keep = counts > 0
    qb = np.bincount(idx, weights=q, minlength=nb)[keep] / counts[keep]
    cb = np.bincount(idx, weights=c, minlength=nb)[keep] / counts[keep]
    return PowerSpectrum(q=qb, psd=cb, counts=counts[keep], dim=modes.dim, cell=modes.cell,
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


# --------------------------------------------------------------------------- fit


@dataclass(frozen=True)
class HurstFit:
    r"""Power law ``C = psd_pivot (q/q_pivot)^-(dim + 2 hurst)`` fitted to a PSD.

    Attributes
    ----------
    hurst : float
        Hurst exponent H [dimensionless].
    hurst_stderr : float
        Its standard error: the larger of the least-squares error from the scatter of
        the bins about the line and the statistical error of bins averaging ``n`` modes
        (relative error ``1/sqrt(n)`` of each bin's mean for a Gaussian random surface).
    dim : int
        2 (C(q), exponent ``-2-2H``) or 1 (C1D(q), exponent ``-1-2H``).
    q_pivot : float
        Geometric centre of the fitted bins [1/m].
    psd_pivot : float
        Fitted PSD at ``q_pivot`` [m^4 (2D), m^3 (1D)].
    scale_range : (float, float)
        Shortest and longest wavelength of the fit, ``2 pi/q`` [m].
    bins : int
        Number of PSD bins fitted.
    """

    hurst: float
    hurst_stderr: float
    dim: int
    q_pivot: float
    psd_pivot: float
    scale_range: tuple
    bins: int

    def interval(self, k: float = 2.0) -> tuple[float, float]:
        """``(H - k sigma, H + k sigma)``; k = 2 is about 95 %."""
        return self.hurst - k * self.hurst_stderr, self.hurst + k * self.hurst_stderr

    def psd(self, q, hurst: float | None = None):
        """The fitted power law at ``q`` [1/m], optionally with another H (same pivot)."""
        H = self.hurst if hurst is None else hurst
        return self.psd_pivot * (np.asarray(q, dtype=float) / self.q_pivot) ** (-self.dim - 2 * H)

    def tail(self, k: int, q_from: float, q_to, hurst: float | None = None):
        """``g int_{q_from}^{q_to} q^k C(q) dq`` of the power law: the k-th moment that
        roughness between the two wavevectors adds (module docstring; k = 2 gives the
        slope's, k = 4 the curvature's share, in the data's own dimension)."""
        H = self.hurst if hurst is None else hurst
        g = 2 * np.pi if self.dim == 2 else 2.0
        amp = g * self.psd_pivot * self.q_pivot ** (self.dim + 2 * H)
        return amp * _power_integral(k - 1 - 2 * H, q_from, q_to)

    def to_dict(self) -> dict:
        d = json_ready(self)
        d["scale_range"] = list(self.scale_range)
        return d


def _power_integral(p: float, a, b):
    """``int_a^b q^p dq`` (the logarithm at ``p = -1``); ``b`` may be an array."""
    b = np.asarray(b, dtype=float)
    if abs(p + 1) < 1e-9:
        return np.log(b / a)
    return (b ** (p + 1) - a ** (p + 1)) / (p + 1)


def fit_hurst(spectrum: PowerSpectrum, scale_range) -> HurstFit:
    """Fit ``C ~ q^-(d+2H)`` to the bins of ``spectrum`` with ``2 pi/q`` in ``scale_range``.

    Parameters
    ----------
    spectrum : PowerSpectrum
        From :func:`power_spectrum_2d` (d = 2) or :func:`power_spectrum_1d` (d = 1).
    scale_range : (float, float)
        Shortest and longest wavelength of the self-affine range [m].

    Returns
    -------
    HurstFit

    Raises
    ------
    ParameterError
        Fewer than :data:`MIN_FIT_BINS` bins in the range.
    """
    lo, hi = (positive("fit scale", s) for s in scale_range)
    if not lo < hi:
        raise ParameterError(
            f"fit_range must be (shortest, longest) wavelength with shortest < longest, "
            f"got {scale_range!r}"
        )
    q_lo, q_hi = 2 * np.pi / hi, 2 * np.pi / lo
    sel = (spectrum.q >= q_lo * (1 - 1e-12)) & (spectrum.q <= q_hi * (1 + 1e-12))
    sel &= spectrum.psd > 0
    if sel.sum() < MIN_FIT_BINS:
        raise ParameterError(
            f"the fit range {lo:.3g} m to {hi:.3g} m holds {int(sel.sum())} PSD bins, at "
            f"least {MIN_FIT_BINS} are needed; widen fit_range or give a larger scan"
        )
    x, y, n = np.log(spectrum.q[sel]), np.log(spectrum.psd[sel]), spectrum.counts[sel]
    xm = x.mean()
    sxx = float(np.sum((x - xm) ** 2))
    slope = float(np.sum((x - xm) * (y - y.mean())) / sxx)
    intercept = float(y.mean())  # at x = xm: uncorrelated with the slope
    resid = y - (intercept + slope * (x - xm))
    dof = max(1, x.size - 2)
    err_scatter = math.sqrt(float(np.sum(resid**2)) / dof / sxx)
    # A bin's mean of n independent, exponentially distributed |H_q|^2 has a relative
    # error 1/sqrt(n); q and -q are one mode (real data) and a window correlates neighbours.
    n = np.maximum(n * spectrum.efficiency / 2, 1.0)
    err_counting = math.sqrt(float(np.sum((x - xm) ** 2 / n)) / sxx**2)
    d = spectrum.dim
    return HurstFit(
        hurst=(-slope - d) / 2,
        hurst_stderr=max(err_scatter, err_counting) / 2,
        dim=d,
        q_pivot=float(math.exp(xm)),
        psd_pivot=float(math.exp(intercept)),
        scale_range=(lo, hi),
        bins=int(sel.sum()),
    )


# --------------------------------------------------------------------------- summary


@dataclass(frozen=True)
class ScaleStatistics:
    """Statistics of one scan at the scale that matters (see :func:`scale_statistics`).

    Slopes and curvatures are 2D-equivalent (``<|grad h|^2>^(1/2)``, ``<(lap h)^2>^(1/2)``,
    PNAS 2014 Eqs. 1 and 8); for profiles through the isotropy factors of the module
    docstring (``isotropy_assumed``). Lengths in m, curvatures in 1/m.

    Attributes
    ----------
    dim : int
        1 (profile) or 2 (map).
    shape, pixel_size : tuple
        Grid points and spacing per axis [m].
    periodic : bool
        Whether the data were taken as periodic (no window).
    window : str
        Window of the FFT.
    psd : PowerSpectrum
        The spectrum that is fitted: C(q) of a map, C1D(q) of a profile.
    profile_psd : PowerSpectrum
        C1D(q) of the profiles along x (the same as ``psd`` for a profile).
    rms_height : float
        ``<(h - <h>)^2>^(1/2)`` of the data as given (no window) [m].
    reliability_cutoff : float or None
        The instrument's reliability cutoff as given [m] (None: not known).
    measured_scale : float
        lambda_c, the smallest scale taken as measured: the reliability cutoff, or the
        Nyquist wavelength ``2 max(pixel_size)`` when none is known or it is finer [m].
    rms_slope, rms_curvature, d_rep : float
        ``h'_rms``, ``h''_rms`` [1/m] and ``d_rep = 4 h'_rms/h''_rms`` [m] (Eq. 9) with
        the roughness down to ``measured_scale`` (measured values).
    scales, slopes, curvatures : ndarray
        The measured scale-dependent ``h'_rms(lambda)``, ``h''_rms(lambda)`` for lambda
        from the scan size down to ``measured_scale``.
    fit : HurstFit
        The self-affine fit used for the extrapolation below ``measured_scale``.
    isotropy_assumed : bool
        True for profiles.
    """

    dim: int
    shape: tuple
    pixel_size: tuple
    periodic: bool
    window: str
    psd: PowerSpectrum
    profile_psd: PowerSpectrum
    rms_height: float
    reliability_cutoff: float | None
    measured_scale: float
    rms_slope: float
    rms_curvature: float
    d_rep: float
    scales: np.ndarray
    slopes: np.ndarray
    curvatures: np.ndarray
    fit: HurstFit
    isotropy_assumed: bool
    modes: _Modes = field(repr=False, compare=False)

    @property
    def factors(self) -> tuple[float, float]:
        """Factors from the data's own moments to 2D-equivalent ``h'^2``, ``h''^2``."""
        if self.isotropy_assumed:
            return ISOTROPIC_SLOPE_FACTOR, ISOTROPIC_CURVATURE_FACTOR
        return 1.0, 1.0

    def measured_at(self, scale):
        """Measured (h'_rms, h''_rms) with roughness down to ``scale >= measured_scale`` [m]."""
        lam = np.asarray(scale, dtype=float)
        if np.any(lam < self.measured_scale * (1 - 1e-9)):
            raise ParameterError(
                f"scale must be >= the measured scale {self.measured_scale:.4g} m; "
                "use extrapolated_at below it"
            )
        s, c = _moments_at(self.modes, lam)
        f1, f2 = self.factors
        return s * math.sqrt(f1), c * math.sqrt(f2)

    def extrapolated_at(self, scale, hurst: float | None = None):
        """(h'_rms, h''_rms) with roughness down to ``scale`` [m]: measured to
        ``measured_scale``, the fitted power law (with ``hurst`` if given) below it."""
        lam = np.atleast_1d(np.asarray(scale, dtype=float))
        if lam.size == 0 or not np.all(np.isfinite(lam)) or np.any(lam <= 0):
            raise ParameterError(f"scale must be wavelengths > 0 (m), got {scale!r}")
        lam_c = self.measured_scale
        q_c = 2 * np.pi / lam_c
        s, c = _moments_at(self.modes, np.maximum(lam, lam_c))
        s2, c2 = s**2, c**2
        below = lam < lam_c
        q_s = 2 * np.pi / lam[below]
        s2[below] += self.fit.tail(2, q_c, q_s, hurst)
        c2[below] += self.fit.tail(4, q_c, q_s, hurst)
        f1, f2 = self.factors
        out = np.sqrt(f1 * s2), np.sqrt(f2 * c2)
        if np.ndim(scale) == 0:
            return float(out[0][0]), float(out[1][0])
        return out


def scale_statistics(
    heights,
    pixel_size,
    *,
    periodic: bool = False,
    reliability_cutoff: float | None = None,
    fit_range=None,
    points_per_decade: int = 10,
) -> ScaleStatistics:
    """PSD, measured scale-dependent slope and curvature, and the self-affine fit.

    Parameters
    ----------
    heights : 1D or 2D array
        Heights [m] of a profile or a map (detrended as wanted; the mean is removed).
    pixel_size : float or tuple
        Grid spacing per axis [m].
    periodic : bool
        True: the data are one period of a periodic surface (no window).
    reliability_cutoff : float, optional
        The instrument's shortest reliable wavelength [m] (e.g. from the tip radius).
        None: the data are trusted down to the Nyquist wavelength ``2 max(pixel_size)``.
    fit_range : (float, float), optional
        Shortest and longest wavelength [m] of the Hurst fit. Default: from
        ``max(measured scale, 4 pixels)`` to a quarter of the scan size.
    points_per_decade : int
        PSD bins per decade.

    Returns
    -------
    ScaleStatistics
    """
    h, sizes = _grid(heights, pixel_size)
    if not np.ptp(h) > 0:
        raise ParameterError("heights are flat (all equal): there is no roughness to analyse")
    modes = _modes(h, sizes, bool(periodic))[0]
    psd = profile_psd = _binned(modes, points_per_decade)
    if h.ndim == 2:
        profile_psd = _binned(_modes(h, sizes, bool(periodic), profiles=True)[0], points_per_decade)
    nyquist = 2 * max(sizes)
    size = min(n * a for n, a in zip(h.shape, sizes, strict=True))
    if reliability_cutoff is not None:
        rc = positive("reliability_cutoff", reliability_cutoff)
        if rc >= size / 2:
            raise ParameterError(
                f"reliability_cutoff must be below half the scan size ({size / 2:.3g} m), "
                f"got {rc:.3g} m: nothing of the scan is reliable"
            )
    else:
        rc = None
    lam_c = max(rc or 0.0, nyquist)
    if fit_range is None:
        fit_range = (max(lam_c, FIT_SHORT_PIXELS * max(sizes)), size / FIT_LONG_FRACTION)
        if not 2 * fit_range[0] <= fit_range[1]:
            raise ParameterError(
                f"the scan is too small for the default Hurst fit (from {fit_range[0]:.3g} m, "
                f"4 pixels or the reliability cutoff, to a quarter of the scan, "
                f"{fit_range[1]:.3g} m, at least an octave); give fit_range or a larger scan"
            )
    else:
        fit_range = tuple(fit_range)
        if len(fit_range) != 2:
            raise ParameterError(f"fit_range must be (shortest, longest) in m, got {fit_range!r}")
    fit = fit_hurst(psd, fit_range)
    scales = np.geomspace(size, lam_c, max(2, math.ceil(10 * math.log10(size / lam_c)) + 1))
    s, c = _moments_at(modes, scales)
    iso = h.ndim == 1
    f1, f2 = (ISOTROPIC_SLOPE_FACTOR, ISOTROPIC_CURVATURE_FACTOR) if iso else (1.0, 1.0)
    s, c = s * math.sqrt(f1), c * math.sqrt(f2)
    sl, cu = float(s[-1]), float(c[-1])
    return ScaleStatistics(
        dim=h.ndim,
        shape=tuple(h.shape),
        pixel_size=sizes,
        periodic=bool(periodic),
        window=modes.window,
        psd=psd,
        profile_psd=profile_psd,
        rms_height=float(np.std(h)),
        reliability_cutoff=rc,
        measured_scale=lam_c,
        rms_slope=sl,
        rms_curvature=cu,
        d_rep=4 * sl / cu if cu > 0 else math.nan,
        scales=scales,
        slopes=s,
        curvatures=c,
        fit=fit,
        isotropy_assumed=iso,
        modes=modes,
    )
