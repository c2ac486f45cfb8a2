r"""The paper's analysis of a load path: κ, κ_rep, κ_att and the contact geometry at 1 %.

Pastewka & Robbins, PNAS 111, 3298 (2014). Along the approach branch of a path (an
``xarray.Dataset`` from :func:`roughcontact.approach_retract`, or its NetCDF file) every
observable is interpolated linearly in :math:`A_{rep}` to the state where the repulsive
area is ``target_area`` of :math:`A_0` (1 % in the paper), and

.. math::
    \kappa = \frac{h'_{rms} E^* A_{rep}}{N},\quad
    \kappa_{rep} = \frac{h'_{rms} E^* A_{rep}}{N_{rep}},\quad
    \kappa_{att} = \frac{h'_{rms} E^* A_{rep}}{N_{att}},\qquad
    \frac1\kappa = \frac1{\kappa_{rep}} - \frac1{\kappa_{att}}

(Eqs. 2-3, 7), :math:`d_{rep} = \pi A_{rep}/P` (Eq. 5), :math:`d_{att} = A_{att}/P`, the
mean repulsive and attractive pressures and Eq. 4's ratio
:math:`(N_{att}/A_{att})/(w/\Delta r)`. κ is also fitted as the slope of
:math:`A_{rep}` against N over the small-area part of the branch (the lines of Fig. 2),
with its standard error (``kappa_fit``: a different quantity from ``kappa``, the ratio at
the target area, and labelled differently everywhere). All areas and loads per
:math:`A_0`; lengths in the path's units.

**Verdict.** One rule (:mod:`roughcontact.analysis.stickiness`): measured sticky ⇔
κ < 0 at the target area,
i.e. :math:`1/\kappa < 0`; predicted: the same rule on Eq. 7's
:math:`1/\kappa = 1/\kappa_{rep} - 1/\kappa_{att}` (Eq. 10), with the measured κ_rep
(``predicted_*``) and, for reference, the continuum hard-wall κ_rep = 2
(``predicted_*_continuum``). The pull-off force is reported beside the verdict.

**Two κ_rep.** ``kappa_rep`` is the paper's definition on the paper's wall; the
hard-wall reference (:mod:`.hard_wall_reference`) solves the non-adhesive hard wall on
the same surface: ``kappa_rep_hard_wall`` at the same repulsive area,
``kappa_rep_hard_wall_corrected`` with the perimeter-corrected area, and ``band_width``
:math:`\delta = (A_{rep} - A_{rep}^{hw})/P` at the same repulsive load, the band of
weakly repulsive sites a soft wall adds around every contact.

**Convergence.** The analysis never interpolates across a step that did not converge:
it raises :class:`UnconvergedPathError` naming the steps and residuals, unless
``allow_unconverged=True``, which marks the result ``reliable = False``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import FIT_MAX_AREA, TARGET_AREA, ParameterError, json_ready
from ..pathdata import REQUIRED, check_path, read_path
from .hard_wall_reference import BAND_WARNING as BAND_WARNING  # public, kept here too
from .hard_wall_reference import reference_fields
from .hysteresis import hysteresis
from .path import interpolate_at_area
from .stickiness import NOT_STICKY, STICKY, is_sticky

__all__ = ["PathAnalysis", "UnconvergedPathError", "analyze_path", "load_path"]

#: The variables the analysis reads (the path layout's required ones).
_REQUIRED = REQUIRED


class UnconvergedPathError(ParameterError):
    """The steps the analysis would interpolate between did not converge."""


@dataclass(frozen=True)
class PathAnalysis:
    """Measured quantities of one path at ``target_area`` (see the module docstring).

    ``kappa`` is the ratio :math:`h'_{rms}E^*A_{rep}/N` at the target area and
    ``inverse_kappa`` its inverse (the additive quantity over seeds); ``kappa_fit`` the
    slope of :math:`A_{rep}(N)` (a different quantity). ``sticky`` (measured) is
    :func:`roughcontact.analysis.stickiness.is_sticky` of κ, ``verdict`` its words; the
    pull-off force
    (``pull_off``, per A0; NaN when the retraction never separated the surfaces) is not
    part of the verdict. ``predicted_*``: the Pastewka–Robbins theory (Eqs. 6, 7, 10,
    with the measured κ_rep and the measured d_rep; ``*_from_curvature`` with d_rep =
    4h'rms/h''rms; ``*_continuum`` with the continuum hard-wall κ_rep = 2) for laws with
    a range Δr and a work of adhesion (None/NaN otherwise), see
    :func:`roughcontact.theory.pastewka_robbins.predict`. ``kappa_rep_hard_wall``,
    ``kappa_rep_hard_wall_corrected``, ``hard_wall_repulsive_area`` (the hard wall's
    A_rep/A0 at this path's N_rep), ``band_width`` δ (length) and ``band_fraction``
    (πδ/d_rep): the hard-wall reference (NaN when the surface is not available).
    ``necessary_condition_met`` is None and ``necessary_condition`` says "not
    applicable: <reason>" when its assumptions (δh ≥ a0, Δr ≈ a0) do not hold.
    ``kappa_att`` and ``area_ratio`` are ``inf`` without attraction; ``kappa_fit_error``
    is the standard error of the fitted slope. ``reliable`` is False only when
    ``allow_unconverged`` let unconverged steps into the result; ``unconverged_steps``
    counts them on the analysed branch. ``warnings`` lists conditions under which the
    paper's analysis is not meaningful (too few asperities in contact, a jump inside the
    interpolation bracket, a wide repulsive band, ...). ``dissipated_energy`` (per A0,
    pressure × length; NaN without a retraction), ``dissipated_energy_bound``, ``jumps`` and
    ``energy_per_jump``: the whole cycle's hysteresis, :func:`.hysteresis.hysteresis`;
    ``cycle_closed`` whether the path is a closed cycle (False: a warning says why and
    ``dissipated_energy`` is not a cycle's dissipation; None without a retraction).
    """

    target_area: float
    offset: float
    load: float
    repulsive_load: float
    attractive_load: float
    attractive_area: float
    perimeter: float
    kappa: float
    kappa_rep: float
    kappa_att: float
    area_ratio: float
    repulsive_pressure: float
    attractive_pressure: float
    attractive_pressure_over_w_per_dr: float
    d_rep: float
    d_att: float
    d_rep_predicted: float
    kappa_fit: float
    kappa_fit_error: float
    fit_points: int
    contact_stiffness: float
    pull_off: float
    sticky: bool
    rms_slope: float
    contact_modulus: float
    predicted_area_ratio: float = math.nan
    predicted_kappa_att: float = math.nan
    predicted_kappa: float = math.nan
    predicted_margin: float = math.nan
    predicted_sticky: bool | None = None
    predicted_area_ratio_from_curvature: float = math.nan
    predicted_kappa_att_from_curvature: float = math.nan
    predicted_sticky_from_curvature: bool | None = None
    necessary_condition_met: bool | None = None
    warnings: list[str] = field(default_factory=list)
    inverse_kappa: float = math.nan
    verdict: str = ""
    predicted_verdict: str = ""
    predicted_kappa_continuum: float = math.nan
    predicted_sticky_continuum: bool | None = None
    kappa_rep_hard_wall: float = math.nan
    kappa_rep_hard_wall_corrected: float = math.nan
    hard_wall_repulsive_area: float = math.nan
    band_width: float = math.nan
    band_fraction: float = math.nan
    necessary_condition: str = ""
    reliable: bool = True
    unconverged_steps: int = 0
    # the whole cycle's hysteresis (:mod:`.hysteresis`): -∮N dd per A0, its jump bound, jumps
    dissipated_energy: float = math.nan
    dissipated_energy_bound: float = math.nan
    jumps: int = 0
    energy_per_jump: float = math.nan
    #: whether the path is a closed cycle (the retraction returns to the first offset with
    #: no load); None without a retraction. False: dissipated_energy is no cycle's.
    cycle_closed: bool | None = None

    def to_dict(self) -> dict:
        """JSON-ready: non-finite numbers become None."""
        return json_ready(self)


def load_path(path):
    """Open a path NetCDF file written by roughcontact; a clear error if it is not one.

    :func:`roughcontact.pathdata.read_path`: a one-line ParameterError when the file is not
    NetCDF or not a path the analysis can read (:func:`_check`).
    """
    return read_path(path)


def _check(ds):
    """A one-line ParameterError unless ``ds`` is a path the analysis can read.

    :func:`roughcontact.pathdata.check_path`, the one check of the path layout.
    """
    check_path(ds)


def _fit_kappa(load, area, max_area, rms_slope, modulus):
    """Slope of A_rep against N over 0 < A_rep <= max_area: κ and its standard error."""
    use = (area > 0) & (area <= max_area)
    x, y = load[use], area[use]
    if x.size < 3 or np.ptp(x) == 0:
        return math.nan, math.nan, int(x.size)
    slope, intercept = np.polyfit(x, y, 1)
    resid = y - (slope * x + intercept)
    se = math.sqrt(float(resid @ resid) / (x.size - 2) / float(((x - x.mean()) ** 2).sum()))
    scale = rms_slope * modulus
    return float(slope * scale), float(se * scale), int(x.size)


def _ratio(a, b):
    return a / b if b != 0 else (math.inf if a > 0 else math.nan)


def _bracket(area, target) -> list[int]:
    """Indices of the (one or two) states ``interpolate_at_area`` interpolates between."""
    order = np.argsort(area, kind="stable")
    k = int(np.searchsorted(area[order], target))
    if k < area.size and area[order][k] == target:
        return [int(order[k])]
    return [int(i) for i in order[max(k - 1, 0) : k + 1]]


def _not_reached(col, target, branch, control, steps) -> str:
    """How far the branch got and which offset (or load) would reach ``target``."""
    area, x = col["repulsive_area"], col[control]
    i = int(np.argmax(area))
    text = f"target area {target} is not reached: " + (
        f"the {branch} branch reaches A_rep/A0 = {area[i]:.4g} at most (step {steps[i]}, "
        f"{control} {x[i]:.6g}), short of the target {target:g}"
        if area[i] < target
        else f"the {branch} branch starts above the target {target:g} "
        f"(A_rep/A0 = {area.min():.4g} at its first step)"
    )
    if area[i] < target and area.size >= 2 and i > 0:
        slope = (area[i] - area[i - 1]) / (x[i] - x[i - 1]) if x[i] != x[i - 1] else 0.0
        if slope != 0 and math.isfinite(slope):
            needed = x[i] + (target - area[i]) / slope
            article = "a" if control == "load" else "an"
            text += (
                f"; extrapolating its last two steps, A_rep/A0 = {target:g} needs {article} "
                f"{control} of about {needed:.6g}: extend the path (e.g. 'roughcontact path ... "
                f"--until-area {target:g}')"
            )
    return text


def _convergence(ds, on, bracket, steps, allow):
    """(unconverged step indices on the branch, warnings); raises on an unconverged bracket."""
    if "converged" not in ds.variables:
        return [], []
    ok = np.asarray(ds["converged"].values, dtype=bool)[on]
    residual = (
        np.asarray(ds["residual"].values, dtype=float)[on]
        if "residual" in ds.variables
        else np.full(ok.size, math.nan)
    )
    bad = [i for i in range(ok.size) if not ok[i]]
    inside = [i for i in bracket if not ok[i]]
    named = ", ".join(f"{steps[i]} (residual {residual[i]:.3g})" for i in inside)
    if inside and not allow:
        raise UnconvergedPathError(
            f"the steps around the target area did not converge: step {named}; the analysis "
            "does not interpolate across them. Rerun the path with a larger max_iter (or a "
            "smaller step), or pass allow_unconverged=True (--allow-unconverged) to get a "
            "result marked unreliable"
        )
    warnings = []
    if inside:
        warnings.append(f"UNRELIABLE: interpolated across unconverged step {named}")
    if len(bad) > len(inside):
        warnings.append(
            f"{len(bad) - len(inside)} other unconverged steps on the branch were left out "
            "of the fit of kappa_fit"
        )
    return bad, warnings


def analyze_path(
    ds,
    *,
    target_area: float = 0.01,
    branch: str = "approach",
    fit_max_area: float = 0.05,
    allow_unconverged: bool = False,
    hard_wall_reference: bool = True,
    heights=None,
    substrate=None,
    device: str | None = None,
) -> PathAnalysis:
    """Analyse a load path at ``target_area`` (the paper's 1 % of A0).

    Parameters
    ----------
    ds : xarray.Dataset or path-like
        A path from :func:`roughcontact.approach_retract` (or its NetCDF file).
    target_area : float
        :math:`A_{rep}/A_0` to interpolate to, in (0, 1).
    branch : {"approach", "retract"}
        Which branch of the path to analyse (the paper loads: approach).
    fit_max_area : float
        Largest :math:`A_{rep}/A_0` used by the linear fit of :math:`A_{rep}(N)`, in (0, 1].
    allow_unconverged : bool
        Interpolate across unconverged steps anyway; the result says ``reliable=False``.
    hard_wall_reference : bool
        Solve the hard wall on the same surface for ``kappa_rep_hard_wall``,
        ``kappa_rep_hard_wall_corrected`` and ``band_width`` (a few solves; needs the
        heights: from ``heights`` or the path's ``heights`` variable).
    heights : (nx, ny) array, optional
        The path's surface (length), if the dataset does not hold it.
    substrate : Substrate, optional
        The path's substrate; default: rebuilt from the dataset's attributes.
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where the hard-wall reference's solves compute (default: where ``heights``
        live); a study task passes its own device.

    Raises
    ------
    UnconvergedPathError
        If a step the interpolation needs did not converge (unless ``allow_unconverged``).
    ParameterError
        If ``ds`` is not a roughcontact path, or the branch never reaches ``target_area``
        (the message says how far it got and which offset would reach it).
    """
    if not hasattr(ds, "variables"):
        if not isinstance(ds, (str, bytes)) and not hasattr(ds, "__fspath__"):
            raise ParameterError(
                "ds must be a path dataset (xarray.Dataset from approach_retract or "
                f"read_path) or the name of its NetCDF file, got {type(ds).__name__}"
            )
        ds = load_path(ds)
    _check(ds)
    target = TARGET_AREA.check("target_area", target_area)
    fit_max_area = FIT_MAX_AREA.check("fit_max_area", fit_max_area)
    if branch not in ("approach", "retract"):
        raise ParameterError(f"branch must be 'approach' or 'retract', got {branch!r}")
    on = np.asarray(ds["branch"].values == branch)
    if on.sum() < 2:
        raise ParameterError(f"the path has fewer than 2 steps on its {branch} branch")
    steps = np.asarray(ds["step"].values if "step" in ds.coords else np.arange(on.size))[on]
    col = {k: np.asarray(ds[k].values, dtype=float)[on] for k in _REQUIRED if k != "branch"}
    area = col["repulsive_area"]
    if not area.min() <= target <= area.max():
        control = "load" if ds.attrs.get("control") == "load" else "offset"
        message = _not_reached(col, target, branch, control, steps)
        if "converged" in ds.variables:
            bad = int((~np.asarray(ds["converged"].values, dtype=bool)[on]).sum())
            message += f" ({bad} steps of the branch did not converge)" if bad else ""
        raise ParameterError(message)
    bracket = _bracket(area, target)
    bad, warnings = _convergence(ds, on, bracket, steps, allow_unconverged)
    at = {k: interpolate_at_area(area, v, target) for k, v in col.items()}
    a = ds.attrs
    slope, modulus = float(a["rms_slope"]), float(a["contact_modulus"])
    scale = slope * modulus * target
    w, dr = float(a.get("work_of_adhesion", math.nan)), float(a.get("range", math.nan))
    lam_s = float(a.get("short_cutoff_estimate", math.nan))
    if math.isfinite(lam_s) and target * float(a["nominal_area"]) / lam_s**2 < 10:
        warnings.append(
            f"A_rep/lambda_s^2 = {target * float(a['nominal_area']) / lam_s**2:.3g} < 10: too "
            "few asperities in contact for the paper's statistical analysis"
        )
    if "jump" in ds.variables and len(bracket) == 2:
        if np.asarray(ds["jump"].values, dtype=bool)[on][bracket].any():
            warnings.append("a jump (instability) lies inside the interpolation bracket")
    d = col["offset"]
    grad = np.gradient(col["load"], d) if np.all(np.diff(d) != 0) else np.full(d.size, np.nan)
    stiffness = -interpolate_at_area(area, grad, target)
    fit = np.ones(area.size, dtype=bool)
    fit[bad] = False
    kappa_fit, kappa_err, n_fit = _fit_kappa(
        col["load"][fit], area[fit], fit_max_area, slope, modulus
    )
    pull_off = float(a.get("pull_off", math.nan))
    warnings += _pull_off_warnings(ds, a)
    kappa = _ratio(scale, at["load"]) if at["load"] != 0 else math.inf
    kappa_rep = _ratio(scale, at["repulsive_load"])
    d_rep = _ratio(math.pi * target, at["perimeter"])
    theory = _theory(a, kappa_rep, d_rep, w / modulus, dr)
    reference = (
        reference_fields(ds, heights, substrate, target, at, kappa_rep, d_rep, device)
        if hard_wall_reference
        else {"warnings": []}
    )
    warnings += reference.pop("warnings")
    sticky = bool(is_sticky(kappa))
    hy = hysteresis(ds)
    closed = None if not math.isfinite(hy.dissipated_energy) else bool(hy.closed)
    if closed is False:
        warnings.append(_open_cycle_warning(ds))
    return PathAnalysis(
        target_area=target,
        offset=at["offset"],
        load=at["load"],
        repulsive_load=at["repulsive_load"],
        attractive_load=at["attractive_load"],
        attractive_area=at["attractive_area"],
        perimeter=at["perimeter"],
        kappa=kappa,
        kappa_rep=kappa_rep,
        kappa_att=_ratio(scale, at["attractive_load"]),
        area_ratio=_ratio(target, at["attractive_area"]),
        repulsive_pressure=at["repulsive_load"] / target,
        attractive_pressure=_ratio(at["attractive_load"], at["attractive_area"]),
        attractive_pressure_over_w_per_dr=_ratio(
            _ratio(at["attractive_load"], at["attractive_area"]), w / dr
        ),
        d_rep=d_rep,
        d_att=_ratio(at["attractive_area"], at["perimeter"]),
        d_rep_predicted=float(a.get("predicted_d_rep", math.nan)),
        kappa_fit=kappa_fit,
        kappa_fit_error=kappa_err,
        fit_points=n_fit,
        contact_stiffness=stiffness,
        pull_off=pull_off,
        sticky=sticky,
        rms_slope=slope,
        contact_modulus=modulus,
        **theory,
        **reference,
        warnings=warnings,
        inverse_kappa=at["load"] / scale,
        verdict=STICKY if sticky else NOT_STICKY,
        reliable=not any(i in bad for i in bracket),
        unconverged_steps=len(bad),
        dissipated_energy=hy.dissipated_energy,
        dissipated_energy_bound=hy.energy_uncertainty,
        jumps=hy.jumps,
        energy_per_jump=hy.energy_per_jump,
        cycle_closed=closed,
    )


def _open_cycle_warning(ds) -> str:
    """Why the path is no closed cycle, and what its dissipated_energy then is."""
    why = []
    if math.isfinite(float(ds.attrs.get("until_area", math.nan))):
        until = float(ds.attrs["until_area"])
        why.append(f"the approach stopped at A_rep/A0 = {until:g} (until_area)")
    if not math.isfinite(float(ds.attrs.get("pull_off", math.nan))):
        why.append("the retraction never separated the surfaces")
    reason = "; ".join(why) or "the retraction does not end where the approach began, unloaded"
    return (
        f"the cycle is not closed ({reason}): dissipated_energy is -∮N dd over the path, "
        "not a closed cycle's dissipation; it includes elastic energy still stored "
        "(cycle_closed: false)"
    )


def _pull_off_warnings(ds, attrs) -> list[str]:
    """Why the pull-off force may be missing or rest on unconverged steps."""
    if "retract" not in set(np.asarray(ds["branch"].values).tolist()):
        return []
    out = []
    if not math.isfinite(float(attrs.get("pull_off", math.nan))):
        out.append("pull-off not measured: the retraction never separated the surfaces")
    if "converged" in ds.variables:
        back = np.asarray(ds["branch"].values) == "retract"
        n = int((~np.asarray(ds["converged"].values, dtype=bool)[back]).sum())
        if n:
            out.append(f"the pull-off force rests on a retraction with {n} unconverged steps")
    return out


def _theory(attrs, kappa_rep, d_rep, adhesion_length, interaction_range) -> dict:
    """Pastewka–Robbins predictions for the path's parameters, or {} if they do not apply."""
    from ..theory.pastewka_robbins import (
        KAPPA_REP,
        height_change,
        necessary_condition_applicability,
        necessary_condition_verdict,
        predict,
    )

    usable = [adhesion_length, interaction_range, kappa_rep, d_rep]
    if not all(math.isfinite(v) and v > 0 for v in usable):
        return {}
    a0 = float(attrs.get("equilibrium_distance", attrs["pixel_size"]))
    common = {
        "rms_slope": float(attrs["rms_slope"]),
        "interaction_range": interaction_range,
        "adhesion_length": adhesion_length,
        "atomic_spacing": a0,
    }
    measured = predict(d_rep=d_rep, kappa_rep=kappa_rep, **common)
    continuum = predict(d_rep=d_rep, kappa_rep=KAPPA_REP, **common)
    curvature = predict(rms_curvature=float(attrs["rms_curvature"]), kappa_rep=kappa_rep, **common)
    met = bool(measured.necessary_condition_met)
    reason = necessary_condition_applicability(
        height_change(common["rms_slope"], d_rep), interaction_range, a0
    )
    sticky = is_sticky(measured.kappa)
    return {
        "predicted_area_ratio": measured.area_ratio,
        "predicted_kappa_att": measured.kappa_att,
        "predicted_kappa": measured.kappa,
        "predicted_margin": measured.margin,
        "predicted_sticky": sticky,
        "predicted_verdict": STICKY if sticky else NOT_STICKY,
        "predicted_kappa_continuum": continuum.kappa,
        "predicted_sticky_continuum": is_sticky(continuum.kappa),
        "predicted_area_ratio_from_curvature": curvature.area_ratio,
        "predicted_kappa_att_from_curvature": curvature.kappa_att,
        "predicted_sticky_from_curvature": is_sticky(curvature.kappa),
        "necessary_condition_met": None if reason else met,
        "necessary_condition": necessary_condition_verdict(met, reason),
    }
