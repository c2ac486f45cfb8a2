r"""Where a measured spectrum is good: the instrument's limits and the self-affine test.

A measured PSD is the surface's only between two limits the instrument sets:

* at short wavelengths the **resolution**: an anti-aliasing filter, the optics' transfer
  function or a blunt tip make the spectrum fall *faster* than any self-affine one
  (local Hurst exponent above 1), and
* an **instrument noise floor**: white measurement noise adds a constant to C(q), so
  the spectrum *flattens* (local exponent towards ``-d/2``, H = -1 for a map) where
  the surface's own spectrum falls below the noise.

Fitting H across either limit gives a fit that follows the instrument instead of the
surface (an H above 1 or below 0, or one that is merely wrong). :func:`good_range`
finds both limits from the binned PSD:

1. **resolution**: two or more bins at the short-wavelength end over which the PSD
   falls with a Hurst exponent above :data:`H_STEEP` (bin to bin) are cut, as long as
   that leaves at least half the decades (a spectrum that is steep
   throughout is the surface's, and the self-affine test below judges it);
2. **noise floor**: ``C(q) = A (q/q_p)^-(d+2H) + N`` is fitted to the remaining bins
   (least squares of log C) and compared with the pure power law; a floor is detected
   when it lowers the residual sum of squares by at least :data:`NOISE_GAIN` and the
   noise is at least half the PSD at the shortest wavelength. The good data then end
   where the surface's power law is :data:`SIGNAL_TO_NOISE` times the floor (the noise
   is then below 20 % of the PSD and adds less than that to slope and curvature there).

:func:`self_affine_problem` then judges the fit between these limits: a Hurst exponent
outside (0, 1) is not self-affine (H <= 0: the rms slope grows without bound however
little roughness is added, H >= 1: not a fractal power law, often a resolution limit);
a two-sigma band that reaches H <= 0 cannot be told from a flat spectrum (an H of 0.04
continued over three decades gives h'_rms of order 5: the issue's .plu and .nid cases);
a standard error above :data:`MAX_HURST_STDERR` (a two-sigma band wider than 0.6, most
of the physical range) whose band leaves (0, 1) is too poor to continue over decades (a
wide band inside (0, 1) is propagated: the verdict then depends on it).

Lengths in m, wavevectors in 1/m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "GoodRange",
    "H_STEEP",
    "MAX_HURST_STDERR",
    "NOISE_GAIN",
    "SIGNAL_TO_NOISE",
    "clamp_fit_range",
    "good_range",
    "self_affine_problem",
]

#: Local Hurst exponent above which the short-wavelength end is a resolution limit.
H_STEEP = 1.25
#: The noise model must divide the residual sum of squares by at least this.
NOISE_GAIN = 2.0
#: The good range ends where the surface's PSD is this many times the noise floor.
SIGNAL_TO_NOISE = 4.0
#: Largest standard error of H that still supports an extrapolation.
MAX_HURST_STDERR = 0.15
#: Fewest bins between the limits (as ``hurst.MIN_FIT_BINS``, plus margin).
MIN_BINS = 4


@dataclass(frozen=True)
class GoodRange:
    """The wavelengths between the instrument's limits (see the module docstring).

    Attributes
    ----------
    short : float
        Shortest good wavelength [m] (>= the ``short`` given to :func:`good_range`).
    long : float
        Longest wavelength of the range examined [m].
    resolution : float or None
        Wavelength [m] below which the spectrum is steeper than self-affine
        (local H > :data:`H_STEEP`); None: no such limit found.
    noise_floor : float or None
        Wavelength [m] where the surface's fitted spectrum meets the white-noise floor
        (signal = noise); None: no floor detected.
    noise_level : float or None
        The floor N [m^4 (2D) or m^3 (1D)].
    usable : bool
        Whether at least an octave and :data:`MIN_BINS` bins remain between ``short``
        and ``long``.
    reasons : tuple of str
        What was cut and why, in words.
    """

    short: float
    long: float
    resolution: float | None
    noise_floor: float | None
    noise_level: float | None
    usable: bool
    reasons: tuple

    def to_dict(self) -> dict:
        return {
            "short": self.short,
            "long": self.long,
            "resolution": self.resolution,
            "noise_floor": self.noise_floor,
            "noise_level": self.noise_level,
            "usable": self.usable,
            "reasons": list(self.reasons),
        }


def _noise_fit(x, y, d):
    """(RSS of the power law, RSS with a floor, (log A, H, log N) at the pivot) in logs."""
    from scipy.optimize import least_squares

    xm = x.mean()
    slope, icpt = np.polyfit(x - xm, y, 1)
    rss_pure = float(np.sum((y - (icpt + slope * (x - xm))) ** 2))

    def resid(p):
        la, H, ln = p
        return np.logaddexp(la - (d + 2 * H) * (x - xm), ln) - y

    best = None
    for start in (y.min() - 1.0, y.min() + 0.5, y.min() - 4.0):
        p0 = (icpt, (-slope - d) / 2 + 0.3, start)
        try:
            r = least_squares(resid, p0, method="trf", max_nfev=2000)
        except (ValueError, FloatingPointError):  # pragma: no cover - degenerate input
            continue
        if best is None or r.cost < best.cost:
            best = r
    if best is None:  # pragma: no cover
        return rss_pure, rss_pure, None
    return rss_pure, float(2 * best.cost), (best.x, xm)


def good_range(spectrum, short: float, long: float) -> GoodRange:
    """The wavelengths of ``spectrum`` between its resolution limit and noise floor.

    Parameters
    ----------
    spectrum : PowerSpectrum
        The binned PSD (C(q) of a map, C1D(q) of a profile).
    short, long : float
        The range examined [m]: from the smallest reliable wavelength (Nyquist or tip
        cutoff) to the longest wavelength of the fit.

    Returns
    -------
    GoodRange
    """
    d = spectrum.dim
    q_lo, q_hi = 2 * np.pi / long, 2 * np.pi / short
    sel = (spectrum.q >= q_lo * (1 - 1e-12)) & (spectrum.q <= q_hi * (1 + 1e-12))
    sel &= spectrum.psd > 0
    q, c = spectrum.q[sel], spectrum.psd[sel]
    reasons = []
    if q.size < MIN_BINS:
        return GoodRange(short, long, None, None, None, False, ())
    x, y = np.log(q), np.log(c)
    # 1. the resolution limit: a steep tail at the short end
    n = x.size
    while n >= 2 and (-(y[n - 1] - y[n - 2]) / (x[n - 1] - x[n - 2]) - d) / 2 > H_STEEP:
        n -= 1  # the pairwise exponent of the last two bins
    resolution = None
    if n <= x.size - 2 and (x[n - 1] - x[0]) >= 0.5 * (x[-1] - x[0]) and n >= MIN_BINS:
        resolution = float(2 * np.pi / math.sqrt(q[n - 1] * q[n]))
        reasons.append(
            f"the spectrum falls faster than self-affine (local H > {H_STEEP:g}) below "
            f"{_length(resolution)}: the instrument's resolution"
        )
    else:
        n = x.size
    x, y, q = x[:n], y[:n], q[:n]
    cut = short if resolution is None else resolution
    # 2. the noise floor
    noise_floor = noise_level = None
    if x.size >= MIN_BINS + 1:
        rss_pure, rss_noise, fitted = _noise_fit(x, y, d)
        if fitted is not None:
            (la, H, ln), xm = fitted
            noise_share = 1.0 / (1.0 + math.exp(la - (d + 2 * H) * (x[-1] - xm) - ln))
            if rss_noise * NOISE_GAIN <= rss_pure and noise_share >= 0.5 and H > -0.5:
                # signal = k N at log q = xm + (la - ln - log k)/(d + 2H)
                def q_at(k):
                    return math.exp(xm + (la - ln - math.log(k)) / (d + 2 * H))

                noise_floor = float(2 * np.pi / q_at(1.0))
                noise_level = float(math.exp(ln))
                good = float(2 * np.pi / q_at(SIGNAL_TO_NOISE))
                cut = max(cut, good)
                reasons.append(
                    f"instrument noise floor: the spectrum flattens onto white noise "
                    f"below {_length(noise_floor)} (the surface's power is "
                    f"{SIGNAL_TO_NOISE:g}x the noise at {_length(good)})"
                )
    kept = (2 * np.pi / spectrum.q >= cut * (1 - 1e-9)) & sel
    kept &= 2 * np.pi / spectrum.q <= long * (1 + 1e-9)
    usable = bool(cut * 2 <= long * (1 + 1e-9) and kept.sum() >= MIN_BINS)
    return GoodRange(float(cut), float(long), resolution, noise_floor, noise_level, usable,
                     tuple(reasons))  # fmt: skip


def clamp_fit_range(fit_range, pixel_size, shape):
    """A user's Hurst-fit range clamped to the wavelengths the scan holds.

    The scan's PSD holds wavelengths from the Nyquist wavelength (2 pixels) to the scan
    size; a range reaching beyond is cut to them (a fit cannot use what is not there,
    and the range it reports must be the one it used).

    Parameters
    ----------
    fit_range : (float, float) or None
        (shortest, longest) wavelength [m].
    pixel_size : tuple of float
        Grid spacing per axis [m].
    shape : tuple of int
        Grid points per axis.

    Returns
    -------
    (tuple or None, str)
        The range to fit and a note (``""`` when nothing was cut).

    Raises
    ------
    ParameterError
        When less than an octave of the range lies within the data (one line naming
        ``fit_range`` and the scan's range).
    """
    from ..errors import ParameterError

    if fit_range is None:
        return None, ""
    lo, hi = (float(x) for x in fit_range)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
        raise ParameterError(
            f"fit_range must be (shortest, longest) wavelength with 0 < shortest < longest, "
            f"got {fit_range!r}"
        )
    shortest = 2 * max(pixel_size)
    longest = min(n * a for n, a in zip(shape, pixel_size, strict=True))
    new_lo, new_hi = max(lo, shortest), min(hi, longest)
    span = f"{_length(shortest)} (Nyquist, 2 pixels) to {_length(longest)} (the scan size)"
    if not 2 * new_lo <= new_hi * (1 + 1e-9):
        raise ParameterError(
            f"fit_range (--fit-range) {_length(lo)} to {_length(hi)} leaves less than an "
            f"octave within the scan's wavelengths, {span}; accepted: a range within them"
        )
    if (new_lo, new_hi) == (lo, hi):
        return (lo, hi), ""
    cut = []
    if new_lo > lo:
        cut.append(f"{_length(lo)} raised to {_length(new_lo)} (Nyquist, 2 pixels)")
    if new_hi < hi:
        cut.append(f"{_length(hi)} lowered to {_length(new_hi)} (the scan size)")
    note = (
        f"--fit-range (fit_range) {_length(lo)} to {_length(hi)} reaches beyond the data and "
        f"was clamped to it: {'; '.join(cut)}; the scan holds wavelengths {span} only"
    )
    return (new_lo, new_hi), note


def self_affine_problem(fit) -> str:
    """Why ``fit`` (a :class:`~.statistics.HurstFit`) supports no extrapolation, or ``""``."""
    span = f"from {_length(fit.scale_range[0])} to {_length(fit.scale_range[1])}"
    if not 0 < fit.hurst < 1:
        return (
            f"the spectrum {span} is not self-affine (H = {fit.hurst:.2f} +- "
            f"{fit.hurst_stderr:.2f}, outside (0, 1))"
        )
    lo, hi = fit.interval(2.0)
    if lo <= 0:
        return (
            f"the spectrum {span} is not self-affine within its uncertainty (H = "
            f"{fit.hurst:.2f} +- {fit.hurst_stderr:.2f}: the two-sigma band reaches H <= 0, "
            "where the rms slope grows without bound as finer roughness is added)"
        )
    if fit.hurst_stderr > MAX_HURST_STDERR and not 0 < lo < hi < 1:
        return (
            f"the spectrum {span} fits a power law poorly (H = {fit.hurst:.2f} +- "
            f"{fit.hurst_stderr:.2f}: a standard error above {MAX_HURST_STDERR:g} and a "
            f"two-sigma band {lo:.2f} to {hi:.2f} that leaves (0, 1))"
        )
    return ""


def _length(metres):
    from ._text import length_text

    return length_text(metres)
