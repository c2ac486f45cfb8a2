r"""The self-affine (Hurst) fit of a power spectrum and its extrapolation to smaller scales.

The spectra come from :mod:`roughcontact.topography.spectrum` (C(q) of a map in m^4,
C1D(q) of a profile in m^3, Persson's convention); all lengths in m.

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
Those of :mod:`roughcontact.spectra`: the PSD convention (Persson et al. 2005), the
self-affine fit and its reliable range (Jacobs, Junge & Pastewka 2017), the slope and
curvature at the short cutoff (Pastewka & Robbins 2014, Eqs. 1, 8, 9).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, json_ready, positive
from .spectrum import PowerSpectrum

__all__ = [
    "HurstFit",
    "fit_hurst",
]

#: Fewest PSD bins a Hurst fit accepts.
MIN_FIT_BINS = 3
#: Default fit range: from ``FIT_SHORT_PIXELS`` pixels (the last octave below it is
#: distorted by the grid) up to ``1/FIT_LONG_FRACTION`` of the scan size (longer
#: wavelengths hold few modes, are shaped by detrending and the window, and usually lie
#: beyond the self-affine range).
FIT_SHORT_PIXELS = 4.0
FIT_LONG_FRACTION = 4.0


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
