r"""Is my surface sticky? Eq. 10 of Pastewka & Robbins (2014) for a measured scan (SI).

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
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import ParameterError, json_safe, positive
from ..criterion import parse_quantity, stickiness_criterion
from ..theory.pastewka_robbins import KAPPA_REP
from .simulate import SIMULATION_UNITS
from .statistics import ScaleStatistics, scale_statistics

__all__ = ["UNITS", "StickResult", "Verdict", "stick", "stickiness_verdict"]

#: How many standard errors of H the verdict's band spans (2: about 95 %).
HURST_SIGMAS = 2.0
#: the widest Hurst band in standard errors (beyond, the band is all of (0, 1] and more)
MAX_HURST_SIGMAS = 10.0
#: Hurst exponents sampled across the band (odd: the fitted one is the middle one).
HURST_SAMPLES = 9
#: Smallest scales per decade of the sweep from lambda_c to a0.
SWEEP_PER_DECADE = 24


def _length_text(metres: float) -> str:
    """``12.3 nm``, ``4.56 um``, ``0.3 nm``: a length with a readable prefix."""
    if metres is None or not math.isfinite(metres):
        return "n/a"
    for factor, unit in ((1e-3, "mm"), (1e-6, "um"), (1e-9, "nm")):
        if metres >= factor:
            return f"{metres / factor:.3g} {unit}"
    return f"{metres / 1e-9:.3g} nm"


@dataclass(frozen=True)
class Verdict:
    """Eq. 10 against the smallest roughness scale (see the module docstring).

    Attributes
    ----------
    sticky : bool or None
        True (sticky for every lambda_s in [a0, lambda_c] and every H of the band),
        False (never sticky there), None (depends on roughness below ``depends_below``).
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
        The full criterion at lambda_c (measured) and at a0 (fitted H, extrapolated).
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
    )


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
    band = f"H = {hursts[0]:.2f}-{hursts[-1]:.2f}"
    now = "sticky" if measured.sticky else "not sticky"
    if flips_centre:
        lo, hi = flip_range
        detail = f"{now} at the measured scale, flips at {_length_text(flips_centre[0])} "
        detail += f"with H = {H:.2f}"
        if hursts.size > 1:
            detail += f", at {_length_text(lo)}-{_length_text(hi)} within {band}"
    else:
        detail = f"{now} down to {_length_text(a0)} with H = {H:.2f}, flips within {band}"
    return f"depends on roughness below {_length_text(depends_below)} ({detail})"


# --------------------------------------------------------------------------- one call


#: The unit of every number in :meth:`StickResult.to_dict` (dotted paths for nested keys;
#: list entries take the unit of their list).
UNITS = {
    "margin": "1 (kappa_rep/kappa_att at the measured scale; > 1 sticky)",
    "margin_atomic": "1 (kappa_rep/kappa_att at lambda_s = a0, extrapolated)",
    "margin_atomic_range": "1",
    "rms_slope": "1 (measured, down to measured_scale)",
    "rms_curvature": "1/m (measured, down to measured_scale)",
    "d_rep": "m (4 rms_slope/rms_curvature, measured)",
    "rms_height": "m (after detrending)",
    "measured_scale": "m",
    "reliability_cutoff": "m",
    "flip_scale": "m",
    "flip_scales": "m",
    "flip_scale_range": "m",
    "depends_below": "m",
    "hurst": "1",
    "hurst_stderr": "1",
    "hurst_interval": "1",
    "hurst_fit_range": "m",
    "psd_prefactor": "m^4 (2D C(q)) or m^3 (1D C1D(q)), Persson's convention",
    "psd_pivot_wavevector": "1/m",
    "psd_dim": "1 (2: C(q) of a map, 1: C1D(q) of a profile)",
    "measured.scale": "m",
    "measured.rms_slope": "1",
    "measured.rms_curvature": "1/m",
    "measured.d_rep": "m",
    "measured.margin": "1",
    "extrapolated.scale": "m",
    "extrapolated.hurst": "1",
    "extrapolated.rms_slope": "1",
    "extrapolated.rms_curvature": "1/m",
    "extrapolated.d_rep": "m",
    "extrapolated.margin": "1",
    "extrapolated.margin_range": "1",
    "extrapolated.rms_slope_range": "1",
    "extrapolated.rms_curvature_range": "1/m",
    "curve.scale": "m",
    "curve.rms_slope": "1",
    "curve.rms_curvature": "1/m",
    "curve.margin": "1",
    "curve.margin_low": "1",
    "curve.margin_high": "1",
    "scan.dim": "1 (number of axes)",
    "scan.shape": "grid points",
    "scan.pixel_size": "m",
    "scan.physical_size": "m",
    "scan.window_efficiency": "1",
    "inputs.contact_modulus": "Pa",
    "inputs.youngs_modulus": "Pa",
    "inputs.poisson": "1",
    "inputs.work_of_adhesion": "J/m^2",
    "inputs.interaction_range": "m",
    "inputs.kappa_rep": "1",
    "inputs.atomic_spacing": "m",
    "inputs.tip_radius": "m",
    "inputs.hurst_sigmas": "standard errors",
    "inputs.adhesion_length": "m (w/E*)",
    "criterion_measured.*": "SI: Pa, J/m^2, m, 1/m; see roughcontact criterion --json",
    "criterion_atomic.*": "SI: Pa, J/m^2, m, 1/m; see roughcontact criterion --json",
    **SIMULATION_UNITS,
}


@dataclass(frozen=True)
class StickResult:
    """What :func:`stick` found (SI units; ``to_dict()`` for JSON, with ``units``).

    Attributes
    ----------
    topography : Topography
        The scan as analysed (after detrending).
    statistics : ScaleStatistics
        PSD, measured scale-dependent slope and curvature, Hurst fit.
    verdict : Verdict
        Eq. 10 against the smallest roughness scale.
    inputs : dict
        The material and analysis parameters in SI units.
    notes : tuple of str
        What the user should know about how the numbers were obtained.
    simulation : Simulation or None
        The paper's simulation on synthetic surfaces continuing the scan's spectrum
        (:mod:`roughcontact.topography.simulate`; None unless ``simulate=True``).
    """

    topography: object = field(repr=False)
    statistics: ScaleStatistics = field(repr=False)
    verdict: Verdict
    inputs: dict
    notes: tuple
    simulation: object = None

    @property
    def sticky(self) -> bool | None:
        """True, False, or None (depends on roughness below the resolved scale)."""
        return self.verdict.sticky

    @property
    def margin(self) -> float:
        """``kappa_rep/kappa_att`` with the measured statistics (> 1 sticky)."""
        return self.verdict.margin

    def to_dict(self, *, curve_points: int = 49) -> dict:
        """JSON-ready dict: the verdict, measured and extrapolated values, ``units``.

        ``curve_points`` sweep points (from lambda_c to a0) go into ``curve``.
        """
        s, v, fit = self.statistics, self.verdict, self.statistics.fit
        c = v.centre
        keep = np.unique(np.linspace(0, v.scales.size - 1, curve_points).round().astype(int))
        topo = self.topography
        crit_m, crit_a = v.measured, v.atomic
        d = {
            "sticky": v.sticky,
            "verdict": v.text,
            "margin": v.margin,
            "margin_atomic": v.margin_atomic,
            "margin_atomic_range": list(v.margin_atomic_range),
            "rms_slope": s.rms_slope,
            "rms_curvature": s.rms_curvature,
            "d_rep": s.d_rep,
            "rms_height": s.rms_height,
            "measured_scale": s.measured_scale,
            "reliability_cutoff": s.reliability_cutoff,
            "flip_scale": v.flip_scale,
            "flip_scales": list(v.flip_scales),
            "flip_scale_range": None if v.flip_scale_range is None else list(v.flip_scale_range),
            "depends_below": v.depends_below,
            "hurst": fit.hurst,
            "hurst_stderr": fit.hurst_stderr,
            "hurst_interval": [v.hurst[0], v.hurst[-1]],
            "hurst_fit_range": list(fit.scale_range),
            "psd_prefactor": fit.psd_pivot,
            "psd_pivot_wavevector": fit.q_pivot,
            "psd_dim": fit.dim,
            "measured": {
                "scale": s.measured_scale,
                "rms_slope": s.rms_slope,
                "rms_curvature": s.rms_curvature,
                "d_rep": s.d_rep,
                "margin": v.margin,
                "sticky": crit_m.sticky,
            },
            "extrapolated": {
                "scale": float(v.scales[-1]),
                "hurst": fit.hurst,
                "rms_slope": float(v.slopes[c, -1]),
                "rms_curvature": float(v.curvatures[c, -1]),
                "d_rep": float(4 * v.slopes[c, -1] / v.curvatures[c, -1]),
                "margin": v.margin_atomic,
                "sticky": crit_a.sticky,
                "margin_range": list(v.margin_atomic_range),
                "rms_slope_range": [float(v.slopes[:, -1].min()), float(v.slopes[:, -1].max())],
                "rms_curvature_range": [
                    float(v.curvatures[:, -1].min()),
                    float(v.curvatures[:, -1].max()),
                ],
            },
            "provenance": {
                "measured": [
                    "rms_slope",
                    "rms_curvature",
                    "d_rep",
                    "rms_height",
                    "margin",
                    "measured.*",
                    "hurst",
                    "hurst_stderr",
                    "psd_prefactor",
                ],
                "extrapolated": [
                    "margin_atomic",
                    "margin_atomic_range",
                    "extrapolated.*",
                    "flip_scale",
                    "flip_scales",
                    "flip_scale_range",
                    "depends_below",
                    "curve.* below measured_scale",
                ],
            },  # fmt: skip
            "curve": {
                "scale": v.scales[keep].tolist(),
                "rms_slope": v.slopes[c, keep].tolist(),
                "rms_curvature": v.curvatures[c, keep].tolist(),
                "margin": v.margins[c, keep].tolist(),
                "margin_low": v.margins[:, keep].min(axis=0).tolist(),
                "margin_high": v.margins[:, keep].max(axis=0).tolist(),
            },
            "scan": {
                "source": getattr(topo, "source", ""),
                "channel": getattr(topo, "channel", ""),
                "dim": s.dim,
                "shape": list(s.shape),
                "pixel_size": list(s.pixel_size),
                "physical_size": [n * a for n, a in zip(s.shape, s.pixel_size, strict=True)],
                "periodic": s.periodic,
                "detrend": self.inputs.get("detrend"),
                "window": s.window,
                "window_efficiency": s.psd.efficiency,
                "isotropy_assumed": s.isotropy_assumed,
            },
            "inputs": dict(self.inputs),
            "criterion_measured": crit_m.to_dict(),
            "criterion_atomic": crit_a.to_dict(),
            "notes": list(self.notes),
            "simulation": None if self.simulation is None else self.simulation.to_dict(),
            "units": dict(UNITS),
        }
        return json_safe(d)


def _length(name, value):
    if value is None:
        return None
    return positive(name, parse_quantity(value, "length", name))


def stick(
    scan,
    *,
    modulus,
    work_of_adhesion,
    interaction_range="0.5 nm",
    poisson=None,
    tip_radius=None,
    channel=None,
    detrend="plane",
    kappa_rep=KAPPA_REP,
    atomic_spacing="0.3 nm",
    pixel_size=None,
    height_unit=None,
    periodic=False,
    reliability_cutoff=None,
    fit_range=None,
    hurst_sigmas: float = HURST_SIGMAS,
    simulate: bool = False,
    simulate_size: int = 256,
    simulate_seeds: int = 3,
    simulate_progress=None,
) -> StickResult:
    """Is this measured surface sticky? Pastewka & Robbins (2014), Eq. 10, for a scan.

    Reads the scan, detrends it, computes its PSD and scale-dependent slope and
    curvature (:mod:`roughcontact.topography.statistics`), fits the Hurst exponent
    between a quarter of the scan size and the reliability cutoff, and evaluates Eq. 10
    for every smallest roughness scale from the reliability cutoff down to the atomic
    spacing (:func:`stickiness_verdict`).

    Parameters
    ----------
    scan : path-like or Topography
        An instrument, ``.npy`` or text file (read by ``load_topography``) or a
        ``Topography`` in metres.
    modulus : float or str
        Contact modulus E* (without ``poisson``) or Young's modulus E (with it) [Pa],
        e.g. ``"10 MPa"``; ``E* = E/(1 - poisson^2)`` against a rigid counter-surface.
    work_of_adhesion : float or str
        w [J/m^2], e.g. ``"50 mJ/m^2"``.
    interaction_range : float or str
        Delta_r [m], default ``"0.5 nm"``.
    poisson : float, optional
        Poisson ratio in (-1, 0.5]: ``modulus`` is then Young's modulus.
    tip_radius : float or str, optional
        Radius of the scanning probe [m]: sets the reliability cutoff (below which the
        tip cannot follow the surface) through ``reliability_cutoff(topo, tip_radius)``
        (Sanner et al. 2022); without it, the radius stored in the file if any. The
        cutoff length is taken as the shortest reliable wavelength, as SurfaceTopography
        does (its PSD keeps ``q < 2 pi/cutoff``).
    channel : str, optional
        The data channel of a multi-channel file.
    detrend : str
        How to detrend before the analysis (``detrend(topo, mode=...)``), default
        ``"plane"``.
    kappa_rep : float
        The non-adhesive prefactor, default 2 (the paper's choice).
    atomic_spacing : float or str
        a0 [m], the smallest roughness scale considered, default ``"0.3 nm"``.
    pixel_size, height_unit : optional
        For files without units (``.npy``, text): grid spacing [m] and the heights' unit.
    periodic : bool
        Whether a file's scan is one period of a periodic surface (no window).
    reliability_cutoff : float or str, optional
        The shortest reliable wavelength [m], instead of ``tip_radius``.
    fit_range : (float, float), optional
        Wavelengths [m] of the Hurst fit (default: see ``scale_statistics``).
    hurst_sigmas : float
        Half-width of the H band in standard errors, default 2 (about 95 %), at most 10.
    simulate : bool
        Also run the paper's simulation on synthetic surfaces continuing the scan's
        spectrum down to ``atomic_spacing`` (:func:`~.simulate.simulate_stickiness`;
        seconds to minutes; needs ``l_a/a0 = w/(E* a0)`` in
        :data:`~.simulate.ADHESION_RANGE`).
    simulate_size, simulate_seeds : int
        Sites per axis of the synthetic surfaces (default 256, in [64, 1024]) and their
        number (default 3, in [1, 32]).
    simulate_progress : callable, optional
        ``simulate_progress(k, seeds)`` before realisation k.

    Returns
    -------
    StickResult
        ``.sticky`` (True, False or None), ``.margin``, ``.verdict``, ``.to_dict()``.
    """
    from .topography import Topography

    E = positive("modulus", parse_quantity(modulus, "pressure", "modulus"))
    if simulate:
        from .simulate import check_options

        check_options(simulate_size, simulate_seeds)  # before any work
    tip = _length("tip_radius", tip_radius)
    given_cutoff = _length("reliability_cutoff", reliability_cutoff)
    if tip is not None and given_cutoff is not None:
        raise ParameterError("give tip_radius or reliability_cutoff, not both")
    topo = _read(scan, channel, pixel_size, height_unit, periodic, Topography)
    from .._plausibility import check_heights

    check_heights(topo.heights, "scan")  # |h| past 1e150 is out of range, not "flat"
    raw = float(np.std(topo.heights))
    topo = _detrend(topo, detrend)
    if not float(np.std(topo.heights)) > 1e-12 * raw:  # what is left is round-off
        raise ParameterError(f"scan is flat after detrend={detrend!r}: no roughness to analyse")
    notes = []
    cutoff, tip_source, cutoff_source = given_cutoff, "not used", "reliability_cutoff"
    if cutoff is None:
        from .prepare import reliability_cutoff as tip_cutoff

        reliability = tip_cutoff(topo, tip)
        if reliability.all_scales:
            raise ParameterError(f"scan: {reliability.message}")
        cutoff, tip, tip_source = (
            reliability.cutoff,
            reliability.tip_radius,
            reliability.tip_radius_source,
        )
        cutoff_source = "tip radius" if cutoff is not None else "none (Nyquist wavelength)"
        if tip is not None:
            notes.append(f"reliability: {reliability.message}")
    stats = scale_statistics(
        topo.heights,
        topo.pixel_size,
        periodic=topo.periodic,
        reliability_cutoff=cutoff,
        fit_range=fit_range,
    )
    material = {"contact_modulus": E} if poisson is None else {"youngs_modulus": E}
    v = stickiness_verdict(
        stats,
        work_of_adhesion=work_of_adhesion,
        poisson=poisson,
        interaction_range=interaction_range,
        kappa_rep=kappa_rep,
        atomic_spacing=atomic_spacing,
        hurst_sigmas=hurst_sigmas,
        **material,
    )
    m = v.measured
    inputs = {
        "contact_modulus": m.contact_modulus,
        "youngs_modulus": m.youngs_modulus,
        "poisson": m.poisson,
        "work_of_adhesion": m.work_of_adhesion,
        "interaction_range": m.interaction_range,
        "kappa_rep": m.kappa_rep,
        "kappa_rep_note": "the paper's choice kappa_rep = 2 (PNAS 2014, Fig. 4)"
        if m.kappa_rep == KAPPA_REP
        else "given",
        "atomic_spacing": m.atomic_spacing,
        "adhesion_length": m.adhesion_length,
        "tip_radius": tip,
        "tip_radius_source": tip_source,
        "reliability_cutoff_source": cutoff_source,
        "detrend": detrend,
        "hurst_sigmas": float(hurst_sigmas),
    }
    simulation = None
    if simulate:
        from .simulate import simulate_stickiness

        simulation = simulate_stickiness(
            stats,
            contact_modulus=m.contact_modulus,
            work_of_adhesion=m.work_of_adhesion,
            atomic_spacing=m.atomic_spacing,
            size=simulate_size,
            seeds=simulate_seeds,
            progress=simulate_progress,
        )
    return StickResult(
        topography=topo,
        statistics=stats,
        verdict=v,
        inputs=inputs,
        notes=tuple(notes + _notes(stats, v, m)),
        simulation=simulation,
    )


def _read(scan, channel, pixel_size, height_unit, periodic, Topography):
    """The scan as a Topography in metres (a file read by ``load_topography``)."""
    if isinstance(scan, Topography):
        if channel is not None or pixel_size is not None or height_unit is not None:
            raise ParameterError(
                "channel, pixel_size and height_unit apply to a file, not to a Topography"
            )
        topo = scan
    else:
        from .read import load_topography

        px = pixel_size
        if px is not None and not isinstance(px, (tuple, list)):
            px = _length("pixel_size", px)
        elif px is not None:
            px = tuple(_length("pixel_size", p) for p in px)
        topo = load_topography(
            scan, channel=channel, periodic=bool(periodic), pixel_size=px,
            height_unit=height_unit,
        )  # fmt: skip
    if topo.length_unit != "m":
        raise ParameterError(
            "scan has no length unit (lattice units): give pixel_size (m) and height_unit "
            "for a file without units, e.g. pixel_size='10 nm', height_unit='nm'"
        )
    return topo


def _detrend(topo, mode):
    from .prepare import detrend

    return detrend(topo, mode=mode)


def _notes(stats: ScaleStatistics, v: Verdict, m) -> list:
    lam_c = stats.measured_scale
    fit = stats.fit
    notes = []
    if stats.reliability_cutoff is None:
        notes.append(
            f"no reliability cutoff known (give tip_radius): the data are taken as "
            f"measured down to the Nyquist wavelength {_length_text(lam_c)}"
        )
    notes.append(
        f"measured: rms slope, curvature, d_rep and margin with roughness down to "
        f"{_length_text(lam_c)}; extrapolated below it with the self-affine fit "
        f"H = {fit.hurst:.3f} +- {fit.hurst_stderr:.3f} "
        f"(fitted from {_length_text(fit.scale_range[0])} to {_length_text(fit.scale_range[1])})"
    )
    if not 0 < fit.hurst < 1:
        notes.append(
            f"the fitted H = {fit.hurst:.3f} is outside (0, 1): the spectrum is not "
            "self-affine in the fit range, treat the extrapolation with care"
        )
    if stats.isotropy_assumed:
        notes.append(
            "a line scan: 2D rms slope and curvature from the profile assuming an isotropic "
            "surface (<|grad h|^2> = 2 <h_x^2>, <(lap h)^2> = 8/3 <h_xx^2>)"
        )
    if not stats.periodic:
        notes.append(f"PSD of non-periodic data with a {stats.window} window")
    top = float(v.slopes[v.centre, -1])
    if top > 1:
        notes.append(
            f"the extrapolated rms slope reaches {top:.3g} > 1 at {_length_text(m.atomic_spacing)}:"
            " a power law continued that far is doubtful; the measured margin and the flip "
            "scale are the robust results"
        )
    if m.atomic_spacing >= lam_c:
        notes.append("the atomic spacing is not below the measured scale: nothing extrapolated")
    if not m.necessary_condition_met:
        notes.append("the necessary condition l_a/a0 > 0.49 h'rms is not met at the measured scale")
    if m.kappa_rep == KAPPA_REP:
        notes.append(
            "kappa_rep = 2, the paper's choice (PNAS 2014, Fig. 4); set kappa_rep to change"
        )
    return notes
