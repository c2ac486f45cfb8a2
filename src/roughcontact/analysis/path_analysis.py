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
with its standard error. All areas and loads per :math:`A_0`; lengths in the path's units.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import ParameterError, in_range, json_ready
from .path import interpolate_at_area

__all__ = ["PathAnalysis", "analyze_path", "load_path"]

_REQUIRED = ("offset", "load", "repulsive_load", "attractive_load", "repulsive_area",
             "attractive_area", "perimeter", "branch")  # fmt: skip
_REQUIRED_ATTRS = ("rms_slope", "contact_modulus", "pixel_size", "nominal_area")
# a pull-off below this fraction of the repulsive load at the target area is what a few
# isolated asperities give on any adhesive surface (it does not grow with the contact),
# not macroscopic stickiness; κ < 0 is the paper's criterion proper
STICKY_PULL_OFF = 0.1


@dataclass(frozen=True)
class PathAnalysis:
    """Measured quantities of one path at ``target_area`` (see the module docstring).

    ``sticky`` (measured) is True when κ < 0 (the surfaces hold together under tension
    at the target area) or when the pull-off force exceeds ``STICKY_PULL_OFF`` (10 %) of
    the repulsive load at the target area.
    ``predicted_*``: the Pastewka–Robbins theory (Eqs. 6, 7, 10, with the measured
    κ_rep and the measured d_rep; ``*_from_curvature`` with d_rep = 4h'rms/h''rms) for
    laws with a range Δr and a work of adhesion (None/NaN otherwise), see
    :func:`roughcontact.theory.pastewka_robbins.predict`.
    ``kappa_att`` and ``area_ratio`` are ``inf`` without attraction; ``kappa_fit_error``
    is the standard error of the fitted slope; ``warnings`` lists conditions under which
    the paper's analysis is not meaningful (too few asperities in contact, a jump
    inside the interpolation bracket, ...).
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

    def to_dict(self) -> dict:
        """JSON-ready: non-finite numbers become None."""
        return json_ready(self)


def load_path(path):
    """Open a path NetCDF file written by roughcontact; a clear error if it is not one."""
    import xarray as xr

    try:
        ds = xr.load_dataset(path, engine="h5netcdf")
    except (OSError, ValueError) as err:
        raise ParameterError(
            f"path file {str(path)!r} is not a readable NetCDF file: {err}"
        ) from None
    return ds


def _check(ds):
    missing = [k for k in _REQUIRED if k not in ds.variables]
    missing += [f"attribute {k}" for k in _REQUIRED_ATTRS if k not in ds.attrs]
    if missing:
        raise ParameterError(
            "path dataset lacks " + ", ".join(missing) + " (not written by roughcontact "
            "approach_retract / 'roughcontact path', or by an older version)"
        )


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


def analyze_path(
    ds, *, target_area: float = 0.01, branch: str = "approach", fit_max_area: float = 0.05
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
        Largest :math:`A_{rep}/A_0` used by the linear fit of :math:`A_{rep}(N)`.

    Raises
    ------
    ParameterError
        If ``ds`` is not a roughcontact path, or the branch never reaches ``target_area``.
    """
    if not hasattr(ds, "variables"):
        ds = load_path(ds)
    _check(ds)
    target = in_range("target_area", target_area, 1e-12, 1.0)
    if branch not in ("approach", "retract"):
        raise ParameterError(f"branch must be 'approach' or 'retract', got {branch!r}")
    on = np.asarray(ds["branch"].values == branch)
    if on.sum() < 2:
        raise ParameterError(f"the path has fewer than 2 steps on its {branch} branch")
    col = {k: np.asarray(ds[k].values, dtype=float)[on] for k in _REQUIRED if k != "branch"}
    area = col["repulsive_area"]
    try:
        at = {k: interpolate_at_area(area, v, target) for k, v in col.items()}
    except ParameterError as err:
        raise ParameterError(f"{err}; extend the path to reach A_rep/A0 = {target}") from None
    a = ds.attrs
    slope, modulus = float(a["rms_slope"]), float(a["contact_modulus"])
    scale = slope * modulus * target
    w, dr = float(a.get("work_of_adhesion", math.nan)), float(a.get("range", math.nan))
    warnings = []
    lam_s = float(a.get("short_cutoff_estimate", math.nan))
    if math.isfinite(lam_s) and target * float(a["nominal_area"]) / lam_s**2 < 10:
        warnings.append(
            f"A_rep/lambda_s^2 = {target * float(a['nominal_area']) / lam_s**2:.3g} < 10: too "
            "few asperities in contact for the paper's statistical analysis"
        )
    if "jump" in ds.variables:
        jump = np.asarray(ds["jump"].values, dtype=bool)[on]
        order = np.argsort(area, kind="stable")
        k = int(np.searchsorted(area[order], target))
        if 0 < k < area.size and jump[order][max(k - 1, 0) : k + 1].any():
            warnings.append("a jump (instability) lies inside the interpolation bracket")
    d = col["offset"]
    grad = np.gradient(col["load"], d) if np.all(np.diff(d) != 0) else np.full(d.size, np.nan)
    stiffness = -interpolate_at_area(area, grad, target)
    kappa_fit, kappa_err, n_fit = _fit_kappa(col["load"], area, fit_max_area, slope, modulus)
    pull_off = float(a.get("pull_off", math.nan))
    kappa = _ratio(scale, at["load"]) if at["load"] != 0 else math.inf
    kappa_rep = _ratio(scale, at["repulsive_load"])
    d_rep = _ratio(math.pi * target, at["perimeter"])
    theory = _theory(a, kappa_rep, d_rep, w / modulus, dr)
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
        sticky=bool(kappa < 0 or (pull_off > STICKY_PULL_OFF * at["repulsive_load"])),
        rms_slope=slope,
        contact_modulus=modulus,
        **theory,
        warnings=warnings,
    )


def _theory(attrs, kappa_rep, d_rep, adhesion_length, interaction_range) -> dict:
    """Pastewka–Robbins predictions for the path's parameters, or {} if they do not apply."""
    from ..theory.pastewka_robbins import predict

    usable = [adhesion_length, interaction_range, kappa_rep, d_rep]
    if not all(math.isfinite(v) and v > 0 for v in usable):
        return {}
    common = {
        "rms_slope": float(attrs["rms_slope"]),
        "interaction_range": interaction_range,
        "adhesion_length": adhesion_length,
        "kappa_rep": kappa_rep,
        "atomic_spacing": float(attrs.get("equilibrium_distance", attrs["pixel_size"])),
    }
    measured = predict(d_rep=d_rep, **common)
    curvature = predict(rms_curvature=float(attrs["rms_curvature"]), **common)
    return {
        "predicted_area_ratio": measured.area_ratio,
        "predicted_kappa_att": measured.kappa_att,
        "predicted_kappa": measured.kappa,
        "predicted_margin": measured.margin,
        "predicted_sticky": bool(measured.sticky),
        "predicted_area_ratio_from_curvature": curvature.area_ratio,
        "predicted_kappa_att_from_curvature": curvature.kappa_att,
        "predicted_sticky_from_curvature": bool(curvature.sticky),
        "necessary_condition_met": bool(measured.necessary_condition_met),
    }
