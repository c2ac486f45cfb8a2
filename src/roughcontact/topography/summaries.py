"""The answer of :func:`roughcontact.stick` in lines of text.

* :func:`summary` -- a few lines: the verdict, the margin measured and extrapolated, what
  is measured and what extrapolated, and the scale the verdict depends on;
* :func:`simulation_summary`, :func:`hysteresis_summary` -- the simulation's lines
  (``stick(..., simulate=True)``) and its approach-retraction cycles.

Values in SI units with readable prefixes.
"""

from __future__ import annotations

import numpy as np

from ._text import length_text as _length_text
from ._text import range_text
from .result import StickResult

__all__ = ["hysteresis_summary", "simulation_summary", "summary"]


def summary(result: StickResult) -> list[str]:
    """The verdict and every note, in lines of text (SI values with readable prefixes)."""
    s, v, fit = result.statistics, result.verdict, result.statistics.fit
    c = v.centre
    lam_c, a0 = s.measured_scale, float(result.inputs["atomic_spacing"])
    lines = [f"verdict: {v.text}"]
    first = [
        n
        for n in result.notes
        if n.startswith("no extrapolated verdict") or n.startswith("pixel_size '")
    ]
    lines += first
    lines.append(_answers(v, lam_c))
    lines.append(
        f"measured down to {_length_text(lam_c)}: h'rms = {s.rms_slope:.3g}, "
        f"h''rms = {s.rms_curvature:.3g} 1/m, d_rep = {_length_text(s.d_rep)}, margin "
        f"kappa_rep/kappa_att = {v.margin:.3g} (> 1 sticks)"
    )
    if v.extrapolated and v.scales.size > 1:
        lo, hi = v.margin_atomic_range
        band = range_text(v.hurst[0], v.hurst[-1], ".2f")
        lines.append(
            f"extrapolated down to {_length_text(a0)} with H = {fit.hurst:.2f} +- "
            f"{fit.hurst_stderr:.2f}: h'rms = {v.slopes[c, -1]:.3g}, "
            f"h''rms = {v.curvatures[c, -1]:.3g} 1/m, "
            f"d_rep = {_length_text(4 * v.slopes[c, -1] / v.curvatures[c, -1])}, margin "
            f"{v.margin_atomic:.3g} ({range_text(lo, hi)} within H = {band})"
        )
    good = result.good_range
    lines.append(
        f"fit range: {_length_text(fit.scale_range[0])} to {_length_text(fit.scale_range[1])}"
        + (
            ""
            if good is None
            else f" (the instrument's limits: good data from {_length_text(good.short)})"
            if good.reasons
            else " (no resolution limit or noise floor found in the PSD)"
        )
    )
    if v.sticky is None and v.depends_below is not None:
        lines.append(
            f"the verdict depends on roughness below {_length_text(v.depends_below)}, "
            f"below the measured {_length_text(lam_c)}: measure finer or with a sharper tip"
        )
    lines += [f"note: {n}" for n in result.notes if n not in first]
    if result.simulation is not None:
        lines += simulation_summary(result.simulation)
    if result.hysteresis is not None:
        lines += hysteresis_summary(result.hysteresis)
    if result.criteria is not None:
        from ..stickiness import format_table

        lines.append(
            f"the field's criteria side by side, with the roughness down to the measured "
            f"{_length_text(result.criteria['scale'])} (no extrapolation):"
        )
        lines += format_table(result.criteria).splitlines()
    return lines


def _answers(v, lam_c) -> str:
    """The whole surface's answer (``sticky``) beside the measured scale's
    (``sticky_measured_scale``), as the JSON keys hold them."""
    words = {True: "sticky", False: "not sticky", None: "undecided"}
    whole = words[v.sticky]
    if v.sticky is None and v.scope == "measured scale":
        whole += " (nothing extrapolated below the measured scale)"
    elif v.sticky is None:
        whole += " (depends on unmeasured roughness)"
    return (
        f"answer for the whole surface (sticky): {whole}; with the roughness down to the "
        f"measured {_length_text(lam_c)} only (sticky_measured_scale): "
        f"{words[v.sticky_measured_scale]}"
    )


def simulation_summary(sim) -> list[str]:
    """Three lines on the simulation of :mod:`roughcontact.topography.simulate`."""
    s, i, inv = sim.surface, sim.interaction, sim.inverse_kappa
    interval = "" if inv.n < 2 else f", 1/kappa in [{inv.low:.3g}, {inv.high:.3g}]"
    from .notes import predicted_reason, seed_status

    seeds = "; ".join(seed_status(r) for r in sim.runs)
    why = predicted_reason(sim)
    pull = sim.pull_off_pressure
    how = (
        f"over {inv.n} of {len(sim.runs)} seeds{interval}"
        if inv.n
        else f"({len(sim.runs)} seeds, none analysed at 1 %: see the notes)"
    )
    return [
        f"simulated: {sim.verdict} {how}; Eq. 10 on the same surfaces: {sim.predicted_verdict}"
        + (f" ({why})" if why else ""),
        f"simulation: {s['size']}^2 sites of a0 = {_length_text(s['atomic_spacing'])}, "
        f"lambda_s = {s['short_cutoff_over_a0']:g} a0, H = {s['hurst']:.2f}, "
        f"h'rms = {s['rms_slope']:.3g}; wall l_a/a0 = {i['adhesion_length_over_a0']:.3g}, "
        f"range {_length_text(i['range'])} ({i.get('parametrisation', '')})",
        f"per seed kappa (kappa_rep, kappa_att) at A_rep = 1 %: {seeds}; pull-off pressure "
        + (f"{pull:.3g} Pa" if np.isfinite(pull) else "not measured"),
    ] + [f"note: {n}" for n in sim.notes]


def hysteresis_summary(hy) -> list[str]:
    """The simulation's approach–retraction cycles in SI
    (:func:`roughcontact.topography.hysteresis.simulation_hysteresis`)."""
    w, sd = hy["dissipated_energy_si"], hy["dissipated_energy_si_std"]
    if not np.isfinite(w):
        return ["hysteresis: not measured (no seed's cycle has a retraction)"]
    seeds = hy["seeds"]
    if seeds and all(s.get("zero_within_tolerance") for s in seeds):
        bound = max(float(s["energy_uncertainty_si"]) for s in seeds)
        return [
            f"hysteresis: none: no seed's cycle has a jump, so the energy dissipated per "
            f"approach–retraction cycle is 0 within ± {bound:.2g} J/m^2 (the solver's "
            "tolerance)",
            f"hysteresis per seed: {'; '.join(_seed_energy(s) for s in seeds)}",
        ] + [f"note: {n}" for n in hy["notes"]]
    spread = f" ± {sd:.3g}" if np.isfinite(sd) else " (1 seed: no spread)"
    scan = hy["dissipated_energy_scan"]
    per_seed = "; ".join(_seed_energy(s) for s in hy["seeds"])
    return [
        f"hysteresis: energy dissipated per approach–retraction cycle {w:.3g}{spread} J/m^2 "
        f"(mean ± sd over seeds), {hy['jumps_mean']:.3g} jumps per cycle"
        + (f"; over the scanned area {scan:.3g} J" if np.isfinite(scan) else ""),
        f"hysteresis per seed: {per_seed}",
    ] + [f"note: {n}" for n in hy["notes"]]


def _seed_energy(s) -> str:
    """One seed's dissipated energy: a jump-free cycle as 0 within its bound."""
    if s.get("zero_within_tolerance"):
        return (
            f"seed {s['seed']}: 0 (within ± {s['energy_uncertainty_si']:.2g}) J/m^2, "
            f"{s['jumps']} jumps"
        )
    return f"seed {s['seed']}: {s['dissipated_energy_si']:.3g} J/m^2, {s['jumps']} jumps"
