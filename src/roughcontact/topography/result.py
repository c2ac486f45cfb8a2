"""What :func:`roughcontact.stick` returns: :class:`StickResult` and the units of its JSON.

:data:`UNITS` names the unit of every number in :meth:`StickResult.to_dict` (SI).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._validate import json_safe
from .simulate import SIMULATION_UNITS
from .statistics import ScaleStatistics
from .sweep import Verdict

__all__ = ["UNITS", "StickResult"]


#: The unit of every number in :meth:`StickResult.to_dict` (dotted paths for nested keys;
#: list entries take the unit of their list).
UNITS = {
    "sticky": "bool or null (the whole surface's answer; null: undecided)",
    "sticky_measured_scale": "bool or null (Eq. 10 with the roughness down to measured_scale)",
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
    "inputs.counter_modulus": "Pa (the counter-surface's; None: rigid)",
    "inputs.counter_poisson": "1",
    "continuum_limit": "m (largest lambda_s where Eq. 10 leaves its validity)",
    "good_range.short": "m",
    "good_range.long": "m",
    "good_range.resolution": "m",
    "good_range.noise_floor": "m",
    "good_range.noise_level": "m^4 (2D C(q)) or m^3 (1D C1D(q))",
    "kappa_rep_comparison.*": "1 (kappa_rep; margin at the measured scale)",
    "missing_data.points": "grid points",
    "missing_data.fraction": "1",
    "missing_data.outliers": "grid points (outliers removed among the missing points)",
    "missing_data.slope_change": "1 (rms slope of the filled scan / of the measured pixels - 1)",
    "outliers.points": "grid points",
    "outliers.fraction": "1",
    "outliers.spikes": "grid points",
    "outliers.sentinel_value": "outliers.unit (the file's height unit)",
    "outliers.sentinel_points": "grid points",
    "outliers.isolated": "grid points",
    "outliers.threshold": "1 (robust standard deviations)",
    "outliers.scale": "outliers.unit (per direction)",
    "criterion_measured.*": "SI: Pa, J/m^2, m, 1/m; see roughcontact criterion --json",
    "criterion_atomic.*": "SI: Pa, J/m^2, m, 1/m; see roughcontact criterion --json",
    "criteria.*": "SI: Pa, J/m^2, m, 1/m (inputs); each criterion's parameter is dimensionless;"
    " scale in m",
    "model_checks.monti_sanner_pastewka.threshold": "1",
    "model_checks.monti_sanner_pastewka.measured.scale": "m",
    "model_checks.monti_sanner_pastewka.measured.g0": "m (16/3 h'rms^2/h''rms)",
    "model_checks.monti_sanner_pastewka.measured.rho_over_g0": "1",
    "model_checks.monti_sanner_pastewka.extrapolated.scale": "m",
    "model_checks.monti_sanner_pastewka.extrapolated.g0": "m",
    "model_checks.monti_sanner_pastewka.extrapolated.rho_over_g0": "1",
    "hysteresis.dissipated_energy_si": "J/m^2 (mean over seeds; _std: sample sd)",
    "hysteresis.dissipated_energy_scan": "J (over scan_area, extrapolated)",
    "hysteresis.scan_area": "m^2",
    "hysteresis.jumps_mean": "jumps per cycle",
    "hysteresis.seeds.dissipated_energy": "E* a0 per A0 (the simulation's lattice units)",
    "hysteresis.seeds.dissipated_energy_si": "J/m^2",
    "hysteresis.seeds.energy_uncertainty_si": "J/m^2",
    "hysteresis.seeds.raw_dissipated_energy_si": "J/m^2 (the trapezoid's, before the zero rule)",
    "hysteresis.seeds.tolerance_si": "J/m^2 (the solver's tolerance x the path's length)",
    "hysteresis.seeds.energy_per_jump_joules": "J (over patch_area)",
    "hysteresis.seeds.patch_area": "m^2 (the simulated patch, size^2 a0^2)",
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
    good_range : GoodRange or None
        The wavelengths between the instrument's limits
        (:func:`~roughcontact.topography.fitrange.good_range`; None when the user set
        both the fit range and the reliability cutoff).
    kappa_rep_check : dict or None
        The verdict under the other kappa_rep (``"kappa_rep"``, ``"source"``,
        ``"verdict"``: a :class:`Verdict`), whether the two agree and which one stands
        and why (``"agree"``, ``"stand_behind"``, ``"why"``).
    criteria : dict or None
        The field's stickiness criteria side by side at the measured scale
        (:func:`roughcontact.stickiness.criteria_table`, with ``"scale"`` [m]).
    hysteresis : dict or None
        The simulation's approach–retraction cycles in SI (J/m², J over the scan):
        :func:`roughcontact.topography.hysteresis.simulation_hysteresis`; None without
        a simulation.
    model_checks : dict or None
        Checks of the model's assumptions the field uses
        (:func:`roughcontact.topography.modelchecks.model_checks`: Monti, Sanner &
        Pastewka's rho/g0 < 0.1 at the measured scale and extrapolated).
    """

    topography: object = field(repr=False)
    statistics: ScaleStatistics = field(repr=False)
    verdict: Verdict
    inputs: dict
    notes: tuple
    simulation: object = None
    good_range: object = None
    kappa_rep_check: dict | None = None
    criteria: dict | None = None
    hysteresis: dict | None = None
    model_checks: dict | None = None

    @property
    def sticky(self) -> bool | None:
        """The whole surface's answer: True or False only where it holds for every
        smallest roughness scale down to a0 (or the necessary condition fails with the
        measured roughness), else None (it depends on roughness below the resolved
        scale, or nothing could be extrapolated)."""
        return self.verdict.sticky

    @property
    def sticky_measured_scale(self) -> bool | None:
        """Eq. 10 with the measured roughness alone (at ``measured_scale``): True or
        False, a scoped answer (roughness below that scale can flip it)."""
        return self.verdict.sticky_measured_scale

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
            "sticky_measured_scale": v.sticky_measured_scale,
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
            "scope": v.scope,
            "no_extrapolation": v.no_extrapolation or None,
            "continuum_limit": v.continuum_limit,
            "continuum_reason": v.continuum_reason or None,
            "good_range": None if self.good_range is None else self.good_range.to_dict(),
            "kappa_rep_comparison": self._kappa_rep_dict(),
            "missing_data": dict(getattr(topo, "info", {}).get("missing_data") or {}) or None,
            "outliers": dict(getattr(topo, "info", {}).get("outliers") or {}) or None,
            "extrapolated": None
            if crit_a is None
            else {
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
                "channel_index": (getattr(topo, "info", {}) or {}).get("channel_index"),
                "channels": list((getattr(topo, "info", {}) or {}).get("channels") or []),
                "tip_radius_stated": (getattr(topo, "info", {}) or {}).get("tip_radius_stated"),
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
            "criterion_atomic": None if crit_a is None else crit_a.to_dict(),
            "notes": list(self.notes),
            "simulation": None if self.simulation is None else self.simulation.to_dict(),
            "criteria": self.criteria,
            "hysteresis": self.hysteresis,
            "model_checks": self.model_checks,
            "units": dict(UNITS),
        }
        return json_safe(d)

    def _kappa_rep_dict(self):
        k = self.kappa_rep_check
        if k is None:
            return None
        v, other = self.verdict, k["verdict"]
        return {
            "given": {"kappa_rep": v.measured.kappa_rep, "sticky": v.sticky, "verdict": v.text,
                      "margin": v.margin},
            "other": {"kappa_rep": other.measured.kappa_rep, "source": k["source"],
                      "sticky": other.sticky, "verdict": other.text, "margin": other.margin},
            "agree": k["agree"],
            "stand_behind": k["stand_behind"],
            "why": k["why"],
        }  # fmt: skip
