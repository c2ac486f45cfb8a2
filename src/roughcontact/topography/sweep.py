r"""The verdict of Eq. 10 (Pastewka & Robbins 2014) against the smallest roughness scale (SI).

The criterion (:func:`roughcontact.criterion.stickiness_criterion`) needs the rms slope
``h'_rms`` and curvature ``h''_rms`` (through ``d_rep = 4 h'_rms/h''_rms``, Eq. 9), and
both are set by the smallest scales of the roughness, often below what an instrument
resolves (the paper's Discussion). So the verdict is evaluated as a function of the
smallest roughness scale ``lambda_s``, from the smallest measured scale ``lambda_c``
(the reliability cutoff) down to the atomic spacing ``a0``:

* at ``lambda_s = lambda_c`` with the measured statistics (no assumption);
* below it with the measured self-affine spectrum continued to ``lambda_s``
  (:meth:`ScaleStatistics.extrapolated_at`, Hurst exponent H fitted to the PSD).

The verdict is **sticky** if the margin ``kappa_rep/kappa_att`` exceeds 1 for every
``lambda_s`` in ``[a0, lambda_c]``, **not sticky** if it stays below 1 for every one,
and otherwise **depends on roughness below X** (``sticky = None``), X the largest
``lambda_s`` at which the verdict flips. The uncertainty of H is propagated: the sweep
is repeated for H across ``H +- 2 sigma`` (about 95 %), and a verdict that flips for
any of them is undecided too (X is then the largest flip scale among them). The margin is
reported at the measured scale (``margin``) and at the atomic scale (``margin_atomic``,
extrapolated).

``kappa_rep = 2`` is the paper's choice (Fig. 4, "the shaded region shows the
prediction for adhesion using the value kappa_rep = 2"); give ``kappa_rep=`` to use a
measured one.

Reference: L. Pastewka and M. O. Robbins, PNAS 111, 3298 (2014), Eqs. 9, 10 and the
Discussion.

**When the extrapolation is not supported** (the spectrum between the instrument's
limits is not self-affine, :mod:`roughcontact.topography.fitrange`), ``no_extrapolation``
names why, and the only answer is the one at the measured scale (``scope``
``"measured scale"``, ``sticky_measured_scale``; ``sticky`` is None: finer roughness can
still flip it), unless the necessary condition ``l_a/a0 > 0.49 h'_rms`` already
fails there: roughness below the measured scale can only raise ``h'_rms``, so the
surface is then not sticky at every smaller scale too (``scope`` ``"all scales
(necessary condition)"``).

**Validity of the continuum criterion.** Eq. 10 treats contacts as continuum patches;
where the extrapolation reaches ``d_rep <=`` :data:`CONTINUUM_MIN_D_REP` ``a0`` or
``h'_rms >= 1`` it is outside its validity (``continuum_limit``, the largest such
``lambda_s``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import ParameterError
from ..criterion import stickiness_criterion
from ..theory.pastewka_robbins import KAPPA_REP
from ._text import length_text, range_text
from .statistics import ScaleStatistics

__all__ = ["CONTINUUM_MIN_D_REP", "HURST_SIGMAS", "Verdict", "stickiness_verdict"]

#: d_rep (in a0) below which the continuum Eq. 10 is outside its validity ("a few a0").
CONTINUUM_MIN_D_REP = 3.0

#: How many standard errors of H the verdict's band spans (2: about 95 %).
HURST_SIGMAS = 2.0
#: the widest Hurst band in standard errors (beyond, the band is all of (0, 1] and more)
MAX_HURST_SIGMAS = 10.0
#: Hurst exponents sampled across the band (odd: the fitted one is the middle one).
HURST_SAMPLES = 9
#: Smallest scales per decade of the sweep from lambda_c to a0.
SWEEP_PER_DECADE = 24


_length_text = length_text


@dataclass(frozen=True)
class Verdict:
    """Eq. 10 against the smallest roughness scale (see the module docstring).

    Attributes
    ----------
    sticky : bool or None
        The whole surface's answer: True (sticky for every lambda_s in [a0, lambda_c]
        and every H of the band), False (never sticky there, or the necessary condition
        fails with the measured roughness already), None (depends on roughness below
        ``depends_below``, or nothing could be extrapolated: ``scope`` ``"measured
        scale"``, see ``sticky_measured_scale``).
    text : str
        ``"sticky"``, ``"not sticky"`` or ``"depends on roughness below X nm (...)"``.
    margin : float
        ``kappa_rep/kappa_att`` with the measured statistics (lambda_s = lambda_c).
    margin_atomic : float
        The same extrapolated to lambda_s = a0 with the fitted H.
    margin_atomic_range : (float, float)
        Its smallest and largest value over the H band.
    flip_scale : float or None
        Largest lambda_s [m] at which the verdict flips, with the fitted H.
    flip_scales : tuple of float
        Every lambda_s [m] in the range at which it flips (fitted H), largest first.
    flip_scale_range : (float, float) or None
        Smallest and largest first flip scale over the H band [m] (None: no H flips).
    depends_below : float or None
        The largest flip scale over the H band [m]: the verdict is open for roughness
        below it (None when the verdict is decided).
    hurst : tuple of float
        The Hurst exponents of the band (the middle one the fitted H).
    scales : ndarray
        The lambda_s of the sweep [m], from lambda_c down to a0.
    margins : ndarray, shape (len(hurst), len(scales))
        The margin at every lambda_s for every H.
    slopes, curvatures : ndarray, shape (len(hurst), len(scales))
        ``h'_rms`` [1] and ``h''_rms`` [1/m] used (measured at lambda_c, extrapolated
        below).
    measured, atomic : StickinessCriterion
        The full criterion at lambda_c (measured) and at a0 (fitted H, extrapolated;
        None without an extrapolation).
    scope : str
        ``"all scales"`` (lambda_s from lambda_c to a0), ``"measured scale"`` (no
        extrapolation: ``no_extrapolation`` says why) or ``"all scales (necessary
        condition)"`` (not sticky: the necessary condition fails with the measured
        roughness already).
    no_extrapolation : str
        Why the spectrum supports no extrapolation, or ``""``.
    continuum_limit : float or None
        Largest lambda_s [m] where the extrapolation reaches d_rep <=
        :data:`CONTINUUM_MIN_D_REP` a0 or h'_rms >= 1 (None: nowhere).
    continuum_reason : str
        What is reached there, or ``""``.
    sticky_measured_scale : bool or None
        Eq. 10 with the measured roughness alone (lambda_s = lambda_c): True or False;
        a scoped answer, not the surface's (``sticky`` is that). None only for records
        built without it.
    """

    sticky: bool | None
    text: str
    margin: float
    margin_atomic: float
    margin_atomic_range: tuple
    flip_scale: float | None
    flip_scales: tuple
    flip_scale_range: tuple | None
    depends_below: float | None
    hurst: tuple
    scales: np.ndarray = field(repr=False)
    margins: np.ndarray = field(repr=False)
    slopes: np.ndarray = field(repr=False)
    curvatures: np.ndarray = field(repr=False)
    measured: object = field(repr=False)
    atomic: object = field(repr=False)
    scope: str = "all scales"
    no_extrapolation: str = ""
    continuum_limit: float | None = None
    continuum_reason: str = ""
    sticky_measured_scale: bool | None = None

    @property
    def extrapolated(self) -> bool:
        """Whether the verdict rests on the self-affine extrapolation below lambda_c."""
        return not self.no_extrapolation

    @property
    def centre(self) -> int:
        """Row of the fitted H in ``margins``, ``slopes``, ``curvatures``."""
        return len(self.hurst) // 2


def stickiness_verdict(
    stats: ScaleStatistics,
    *,
    work_of_adhesion,
    contact_modulus=None,
    youngs_modulus=None,
    poisson=None,
    interaction_range="0.5 nm",
    kappa_rep=KAPPA_REP,
    atomic_spacing="0.3 nm",
    hurst_sigmas: float = HURST_SIGMAS,
    no_extrapolation: str = "",
) -> Verdict:
    """Eq. 10 for every smallest roughness scale from the measured one down to a0.

    Parameters
    ----------
    stats : ScaleStatistics
        From :func:`roughcontact.topography.statistics.scale_statistics` (SI units).
    work_of_adhesion, contact_modulus, youngs_modulus, poisson : float or str
        As for :func:`roughcontact.criterion.stickiness_criterion`, as are
    interaction_range, kappa_rep, atomic_spacing : float or str
        As for :func:`roughcontact.criterion.stickiness_criterion` (numbers in SI or
        strings with units; give ``contact_modulus`` E* or ``youngs_modulus`` with
        ``poisson``).
    hurst_sigmas : float
        Half-width of the H band in standard errors (in [0, 10]; 0: the fitted H only).
    no_extrapolation : str
        Why the spectrum supports no extrapolation below the measured scale (e.g.
        :func:`~roughcontact.topography.fitrange.self_affine_problem`); ``""`` (default)
        extrapolates.

    Returns
    -------
    Verdict
    """
    material = {
        "work_of_adhesion": work_of_adhesion,
        "contact_modulus": contact_modulus,
        "youngs_modulus": youngs_modulus,
        "poisson": poisson,
        "interaction_range": interaction_range,
        "kappa_rep": kappa_rep,
        "atomic_spacing": atomic_spacing,
    }

    def criterion(slope, curvature):
        return stickiness_criterion(rms_slope=slope, rms_curvature=curvature, **material)

    measured = criterion(stats.rms_slope, stats.rms_curvature)  # validates the inputs
    try:
        k = math.nan if isinstance(hurst_sigmas, bool) else float(hurst_sigmas)
    except (TypeError, ValueError):
        k = math.nan
    if not (math.isfinite(k) and 0 <= k <= MAX_HURST_SIGMAS):
        raise ParameterError(
            f"hurst_sigmas must be a number in [0, {MAX_HURST_SIGMAS:g}] (standard errors of "
            f"H; a wider band spans every H), got {hurst_sigmas!r}"
        )
    a0, lam_c = measured.atomic_spacing, stats.measured_scale
    if no_extrapolation:
        return _measured_only(stats, measured, a0, str(no_extrapolation))
    if a0 < lam_c:
        n = max(2, math.ceil(SWEEP_PER_DECADE * math.log10(lam_c / a0)) + 1)
        scales = np.geomspace(lam_c, a0, n)
    else:  # nothing unresolved above the atomic scale
        scales = np.array([lam_c])
    fit = stats.fit
    if k > 0 and fit.hurst_stderr > 0:
        hursts = np.linspace(*fit.interval(k), HURST_SAMPLES)
    else:
        hursts = np.array([fit.hurst])

    def margin_at(lam, H):
        s, c = stats.extrapolated_at(lam, hurst=H)
        return criterion(s, c).margin

    margins = np.empty((hursts.size, scales.size))
    slopes, curvatures = np.empty_like(margins), np.empty_like(margins)
    firsts, flips_centre = [], ()
    for i, H in enumerate(hursts):
        s, c = stats.extrapolated_at(scales, hurst=H)
        slopes[i], curvatures[i] = s, c
        margins[i] = [criterion(si, ci).margin for si, ci in zip(s, c, strict=True)]
        flips = _crossings(scales, margins[i], lambda lam, H=H: margin_at(lam, H) - 1.0)
        if flips:
            firsts.append(flips[0])
        if i == hursts.size // 2:
            flips_centre = flips
    centre = hursts.size // 2
    atomic_s, atomic_c = slopes[centre, -1], curvatures[centre, -1]
    atomic = criterion(atomic_s, atomic_c)
    sticky_all = bool(np.all(margins > 1.0))
    not_sticky_all = bool(np.all(margins <= 1.0))
    sticky = True if sticky_all else False if not_sticky_all else None
    depends_below = max(firsts) if sticky is None and firsts else None
    flip_range = (min(firsts), max(firsts)) if firsts else None
    text = _text(sticky, depends_below, flips_centre, flip_range, hursts, measured, a0)
    limit, why = _continuum_limit(scales, slopes[centre], curvatures[centre], a0)
    return Verdict(
        sticky=sticky,
        text=text,
        margin=measured.margin,
        margin_atomic=atomic.margin,
        margin_atomic_range=(float(margins[:, -1].min()), float(margins[:, -1].max())),
        flip_scale=flips_centre[0] if flips_centre else None,
        flip_scales=tuple(flips_centre),
        flip_scale_range=flip_range,
        depends_below=depends_below,
        hurst=tuple(float(h) for h in hursts),
        scales=scales,
        margins=margins,
        slopes=slopes,
        curvatures=curvatures,
        measured=measured,
        atomic=atomic,
        continuum_limit=limit,
        continuum_reason=why,
        sticky_measured_scale=bool(measured.sticky),
    )


def _measured_only(stats, measured, a0, reason) -> Verdict:
    """The verdict at the measured scale alone (module docstring)."""
    lam_c = stats.measured_scale
    where = f"roughness down to {length_text(lam_c)}"
    if not measured.necessary_condition_met:
        sticky, scope = False, "all scales (necessary condition)"
        text = (
            f"not sticky: the necessary condition l_a/a0 > 0.49 h'rms fails with the "
            f"measured h'rms = {measured.rms_slope:.3g} ({where}), and finer roughness only "
            "raises h'rms"
        )
    else:
        # a scoped answer: roughness below the measured scale can still flip it, so the
        # surface's answer is open (sticky None); the measured one is kept beside it
        sticky, scope = None, "measured scale"
        now = "sticky" if measured.sticky else "not sticky"
        text = (
            f"no verdict for the whole surface: {now} at the measured scale ({where}) only; "
            "no extrapolated verdict"
        )
    one = np.array([[measured.margin]])
    limit, why = _continuum_limit(
        np.array([lam_c]), np.array([measured.rms_slope]), np.array([measured.rms_curvature]), a0
    )
    return Verdict(
        sticky=sticky,
        text=text,
        margin=measured.margin,
        margin_atomic=math.nan,
        margin_atomic_range=(math.nan, math.nan),
        flip_scale=None,
        flip_scales=(),
        flip_scale_range=None,
        depends_below=None,
        hurst=(float(stats.fit.hurst),),
        scales=np.array([lam_c]),
        margins=one,
        slopes=np.array([[measured.rms_slope]]),
        curvatures=np.array([[measured.rms_curvature]]),
        measured=measured,
        atomic=None,
        scope=scope,
        no_extrapolation=reason,
        continuum_limit=limit,
        continuum_reason=why,
        sticky_measured_scale=bool(measured.sticky),
    )


def _continuum_limit(scales, slopes, curvatures, a0):
    """Largest lambda_s where d_rep <= CONTINUUM_MIN_D_REP a0 or h'rms >= 1, and what."""
    d_rep = 4 * slopes / curvatures
    for lam, d, s in zip(scales, d_rep, slopes, strict=True):
        out = []
        if d <= CONTINUUM_MIN_D_REP * a0:
            out.append(f"d_rep = {length_text(d)} <= {CONTINUUM_MIN_D_REP:g} a0")
        if s >= 1:
            out.append(f"h'rms = {s:.3g} >= 1")
        if out:
            return float(lam), " and ".join(out)
    return None, ""


def _crossings(scales, margins, f) -> tuple:
    """Every lambda where ``margin - 1`` changes sign between sweep points, refined by
    Brent's method in log(lambda); largest first."""
    from scipy.optimize import brentq

    above = margins > 1.0
    out = []
    for j in np.flatnonzero(above[:-1] != above[1:]):
        lo, hi = math.log(scales[j + 1]), math.log(scales[j])

        def g(t):
            return f(math.exp(t))

        g_lo, g_hi = g(lo), g(hi)
        if g_lo * g_hi > 0:  # a flip on a sweep point, its sign lost to round-off
            out.append(math.exp(lo if abs(g_lo) < abs(g_hi) else hi))
            continue
        out.append(math.exp(brentq(g, lo, hi, xtol=1e-12, rtol=1e-12)))
    return tuple(out)


def _text(sticky, depends_below, flips_centre, flip_range, hursts, measured, a0) -> str:
    if sticky is True:
        return "sticky"
    if sticky is False:
        return "not sticky"
    H = hursts[hursts.size // 2]
    band = f"H = {range_text(hursts[0], hursts[-1], '.2f')}"
    now = "sticky" if measured.sticky else "not sticky"
    if flips_centre:
        lo, hi = flip_range
        detail = f"{now} at the measured scale, flips at {_length_text(flips_centre[0])} "
        detail += f"with H = {H:.2f}"
        if hursts.size > 1:
            detail += f", at {_length_text(lo)} to {_length_text(hi)} within {band}"
    else:
        detail = f"{now} down to {_length_text(a0)} with H = {H:.2f}, flips within {band}"
    return f"depends on roughness below {_length_text(depends_below)} ({detail})"
