r"""The adhesion hysteresis of ``stick --simulate``'s cycles, in SI.

The simulation of :mod:`roughcontact.topography.simulate` approaches each synthetic
surface until the repulsive area reaches its target and retracts it through the same
offsets; every seed's path is one approach–retraction cycle in lattice units (lengths
in a0, pressures in E*, loads per A0). :func:`simulation_hysteresis` measures each
cycle's dissipated energy ``W = -∮ N dd`` per A0
(:func:`roughcontact.analysis.hysteresis.hysteresis`) and converts it with the
simulation's own scales, ``a0`` [m] and ``E*`` [Pa]:

.. math::
    W_{SI} = W\, E^* a_0 \;[\mathrm{J/m^2}], \qquad
    W_{scan} = W_{SI}\, A_{scan} \;[\mathrm{J}],

where ``A_scan`` is the scanned area (a 2D scan's physical size; none for a line scan).
``W_scan`` assumes the dissipation per area of the simulated patch holds over the whole
scan: an extrapolation, said so in the notes. The hysteresis is the elastic one this
model predicts (jumps between stable branches), not viscoelastic losses, and it depends
on how far the approach went (the path's target area).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["simulation_hysteresis"]


def _seed(run, a0, modulus) -> dict | None:
    from ..analysis.hysteresis import hysteresis, hysteresis_in_si

    ds = run.path
    if ds is None or "branch" not in ds.variables:
        return None
    from .simulate import TOL

    hy = hysteresis(ds, solver_tolerance=TOL)  # loads per A0 in E*: the solver's tolerance
    si = hysteresis_in_si(hy, length_scale=a0, pressure_scale=modulus,
                          nominal_area=float(ds.attrs["nominal_area"]))  # fmt: skip
    scale = a0 * modulus  # E* a0 per A0 -> J/m^2
    return {
        "seed": run.seed,
        "dissipated_energy": hy.dissipated_energy,
        "dissipated_energy_si": si["dissipated_energy_per_area"],
        "energy_uncertainty_si": si["energy_uncertainty_per_area"],
        "jumps": hy.jumps,
        "jumps_in": hy.jumps_in,
        "jumps_out": hy.jumps_out,
        "energy_per_jump_joules": si["energy_per_jump"],
        "patch_area": si["nominal_area"],
        "closed": hy.closed,
        "warnings": list(hy.warnings),
        "zero_within_tolerance": hy.zero_within_tolerance,
        "raw_dissipated_energy_si": hy.raw_dissipated_energy * scale,
        "tolerance_si": hy.tolerance * scale,
    }


def simulation_hysteresis(simulation, *, atomic_spacing, contact_modulus, scan_area=None):
    """Every seed's cycle of ``simulation`` in SI, their mean and spread.

    Parameters
    ----------
    simulation : roughcontact.topography.simulate.Simulation
        Its ``runs`` keep their lattice-unit paths (a0, E*).
    atomic_spacing : float
        a0 [m], the simulation's length unit.
    contact_modulus : float
        E* [Pa], the simulation's pressure unit.
    scan_area : float, optional
        The scanned area [m²] (None: a line scan, no energy over the scan).

    Returns
    -------
    dict
        ``seeds`` (per seed: ``dissipated_energy`` [E* a0 per A0],
        ``dissipated_energy_si`` and ``energy_uncertainty_si`` [J/m²], ``jumps``,
        ``jumps_in``, ``jumps_out``, ``energy_per_jump_joules`` [J over the simulated
        patch ``patch_area`` m²], ``closed``, ``warnings``, ``zero_within_tolerance``
        (a jump-free cycle: W = 0 within ``energy_uncertainty_si``),
        ``raw_dissipated_energy_si`` and ``tolerance_si`` [J/m²]); over the seeds with a
        retraction ``dissipated_energy_si`` (mean) and ``dissipated_energy_si_std``
        [J/m²] (sample standard deviation, NaN with one seed), ``jumps_mean``;
        ``scan_area`` [m²] and ``dissipated_energy_scan`` [J] (mean × scan area, NaN
        without an area); ``notes`` (what the numbers rest on). None when no seed has a
        path.
    """
    from .simulate import TOL

    a0, E = float(atomic_spacing), float(contact_modulus)
    seeds = [s for s in (_seed(r, a0, E) for r in simulation.runs) if s is not None]
    if not seeds:
        return None
    w = np.array([s["dissipated_energy_si"] for s in seeds], dtype=float)
    w = w[np.isfinite(w)]
    jumps = [s["jumps"] for s in seeds if math.isfinite(s["dissipated_energy_si"])]
    mean = float(np.mean(w)) if w.size else math.nan
    area = math.nan if scan_area is None else float(scan_area)
    until = simulation.path.get("until_area") if isinstance(simulation.path, dict) else None
    notes = [
        "the synthetic surfaces' cycles (approach until A_rep = "
        + (f"{100 * until:g} %" if isinstance(until, (int, float)) else "its target")
        + " of A0, then retraction through the same offsets); the dissipation grows with "
        "how far the approach goes",
        "elastic hysteresis only (jumps between stable branches); viscoelastic losses of "
        "real adhesives are not in this model",
        f"W in SI = W × E* a0 with E* = {E:.4g} Pa and a0 = {a0:.4g} m",
    ]
    if math.isfinite(area):
        notes.append(
            "energy over the scanned area = mean W per area × the scan's area: assumes the "
            "simulated patch's dissipation per area holds over the whole scan (extrapolated)"
        )
    else:
        notes.append("no scanned area (a line scan): no energy over the scan")
    if not w.size:
        notes.append("no seed's path has a retraction: no dissipated energy")
    zeros = [s for s in seeds if s["zero_within_tolerance"]]
    if zeros:
        notes.append(
            f"{len(zeros)} of {len(seeds)} cycles have no jumps (or a W below zero within its "
            "bound): a cycle on one stable branch dissipates nothing, so W is reported as 0 "
            "within its bound (energy_uncertainty_si: the solver's tolerance on the load, "
            f"{TOL:g} E* per site, times the path's length in offset, or the trapezoid's "
            "residual if larger); never negative"
        )
    for s in seeds:  # what the rule could not settle, per seed
        for w in s["warnings"]:
            if "without flagged jumps" in w or "negative beyond" in w:
                notes.append(f"seed {s['seed']}: {w}")
    open_cycles = sum(not s["closed"] for s in seeds)
    if open_cycles:
        notes.append(
            f"{open_cycles} of {len(seeds)} cycles are not closed (the retraction ended in "
            "contact or under load): their W includes energy still stored"
        )
    return {
        "seeds": seeds,
        "dissipated_energy_si": mean,
        "dissipated_energy_si_std": float(np.std(w, ddof=1)) if w.size > 1 else math.nan,
        "jumps_mean": float(np.mean(jumps)) if jumps else math.nan,
        "scan_area": area,
        "dissipated_energy_scan": mean * area,
        "notes": notes,
    }
