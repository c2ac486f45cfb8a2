r"""Power spectra, scale-dependent rms slope and curvature, and the self-affine fit (SI).

Everything here works on measured height data in SI units (heights and pixel sizes in m):
a 2D map ``heights[i, j]`` at ``x = i dx, y = j dy`` or a 1D profile ``heights[i]``.
:func:`scale_statistics` gathers, for one scan, the binned PSD, the measured
scale-dependent rms slope and curvature and the Hurst fit with its extrapolation. The
parts live in two modules, whose public names are re-exported here:

* :mod:`roughcontact.topography.spectrum`: the window, the PSD convention and the
  definition of the scale-dependent rms slope and curvature (:class:`PowerSpectrum`,
  :func:`power_spectrum_1d`, :func:`power_spectrum_2d`, :func:`scale_dependent_rms`);
* :mod:`roughcontact.topography.hurst`: the self-affine fit and its extrapolation below
  the smallest measured scale (:class:`HurstFit`, :func:`fit_hurst`).

**Profiles (1D).** A profile only gives ``<(dh/dx)^2>`` and ``<(d^2h/dx^2)^2>``. For an
isotropic surface ``<|grad h|^2> = 2 <(dh/dx)^2>`` and ``<(lap h)^2> = (8/3)
<(d^2h/dx^2)^2>`` (the angular averages of ``cos^2`` and ``cos^4``; Nayak, J. Lubr.
Technol. 93, 398 (1971)); :class:`ScaleStatistics` reports these 2D-equivalent values
for profiles and says so (``isotropy_assumed``).

References
----------
Those of :mod:`roughcontact.spectra` (Persson et al. 2005; Jacobs, Junge & Pastewka
2017; Pastewka & Robbins 2014); for profiles P. R. Nayak, J. Lubr. Technol. 93, 398 (1971).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import ParameterError, positive
from .hurst import FIT_LONG_FRACTION as FIT_LONG_FRACTION
from .hurst import FIT_SHORT_PIXELS as FIT_SHORT_PIXELS
from .hurst import MIN_FIT_BINS as MIN_FIT_BINS
from .hurst import HurstFit as HurstFit
from .hurst import fit_hurst as fit_hurst
from .spectrum import MIN_POINTS as MIN_POINTS
from .spectrum import PowerSpectrum as PowerSpectrum
from .spectrum import _binned, _grid, _Modes, _modes, _moments_at
from .spectrum import power_spectrum_1d as power_spectrum_1d
from .spectrum import power_spectrum_2d as power_spectrum_2d
from .spectrum import scale_dependent_rms as scale_dependent_rms

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

#: ``<|grad h|^2>/<(dh/dx)^2>`` and ``<(lap h)^2>/<(d2h/dx2)^2>`` of an isotropic surface.
ISOTROPIC_SLOPE_FACTOR = 2.0
ISOTROPIC_CURVATURE_FACTOR = 8.0 / 3.0


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
