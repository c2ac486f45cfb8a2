"""The demo's Fig. 1: contact maps of one surface at the same repulsive area.

The study keeps, per task, the pressure map of the approach step nearest A_rep = MAP_AREA;
with steps of 1/8 rms height those differ by up to ±15 % in A_rep between the adhesion
lengths. For the figure the approach of each task of the shown seed is followed again —
the same steps from the same start, so the same history — up to the step before
MAP_AREA, and then in ``substeps`` finer steps up to the study's next step (once more,
finer, where that stays 3 % off); the state nearest MAP_AREA is drawn. A jump into
contact can skip MAP_AREA: the panels print their A_rep. The non-adhesive panel (the
paper's Fig. 1B) is a hard wall on the same surface under load control, the load
corrected until A_rep is as near.
Lengths in a0, areas per A0, loads in units of E*.
"""

from __future__ import annotations

import json

import numpy as np

__all__ = ["same_area_maps"]


def _inputs(ds):
    """Heights, substrate, law and approach values of a study's task file ``ds``."""
    from ..studies.store import task_parameters
    from ..studies.task import task_inputs

    settings = json.loads(ds.attrs["task_settings"])
    return (*task_inputs(task_parameters(ds.attrs), settings["path"]), settings)


def _refined(ds, target, substeps):
    """The pressure map nearest A_rep/A0 = ``target`` on the task's approach, refined."""
    from .pipeline import run_path

    heights, substrate, law, values, settings = _inputs(ds)
    area = ds["repulsive_area"].values[ds["branch"].values == "approach"]
    reached = np.flatnonzero(area >= target)
    if settings["path"]["control"] != "offset" or reached.size == 0 or reached[0] == 0:
        return None  # nothing to refine: the stored map stays
    k = int(reached[0])
    offsets = values[:k]
    lo, hi = values[k - 1], values[k]
    for _ in range(2):  # a second, finer pass where the first stays 3 % off
        offsets = np.concatenate([offsets, np.linspace(lo, hi, substeps + 1)[1:]])
        first = offsets.size - substeps - 1
        path = run_path(
            heights,
            substrate,
            law,
            offsets=offsets,
            retract=False,
            until_area=target,
            tol=settings["solver"]["tol"],
            max_iter=settings["solver"]["max_iter"],
            fields_at=list(range(first, offsets.size)),
        ).path
        rep = np.asarray(path["pressure"].values > 0).mean(axis=(1, 2))
        j = int(np.argmin(np.abs(rep - target)))
        if abs(rep[j] / target - 1.0) <= 0.03 or rep.size < 2 or rep[-1] < target:
            break
        # the last field step is the first at or past the target: refine before it
        offsets = offsets[: first + rep.size - 1]
        lo, hi = offsets[-1], path["offset"].values[-1]
    return np.asarray(path["pressure"].values[j]), heights, substrate


def _hard_wall(heights, substrate, target, slope):
    """The hard wall's pressure at A_rep/A0 ≈ ``target`` (load corrected: A_rep ∝ N)."""
    from ..solvers import solve

    load, state = slope * target / 2.0, None  # Eq. 2 with κ_rep = 2 as the first guess
    for _ in range(6):
        state = solve(heights, substrate, load=load, initial=state, tol=1e-8)
        if abs(state.repulsive_area / target - 1.0) < 2e-3 or state.repulsive_area == 0:
            break
        load *= target / state.repulsive_area
    return np.asarray(state.pressure)


def same_area_maps(maps, target, *, substeps=8):
    """Pressure maps and panel labels of Fig. 1 at A_rep/A0 ≈ ``target`` on one surface.

    Parameters
    ----------
    maps : sequence of xarray.Dataset
        The task files of one seed (:func:`roughcontact.plot.study_maps`), one per ℓa.
    target : float
        A_rep/A0 of the panels (dimensionless).
    substeps : int
        Finer steps between the study's two steps around ``target``.

    Returns
    -------
    (list of 2D arrays, list of str)
        The pressures (repulsive p > 0, attractive p < 0; units of E*) and the panel
        labels (mathtext): first the non-adhesive hard wall on the same surface, then one
        per task in the order given. A task that cannot be refined keeps its stored map.
    """
    from ..plot._data import la_label
    from ..studies.store import task_parameters
    from ..surfaces import statistics

    pressures, labels, surface = [], [], None
    for ds in maps:
        got = _refined(ds, target, substeps)
        p = task_parameters(ds.attrs)
        if got is None:
            pressures.append(np.asarray(ds["pressure"].values[0]))
        else:
            pressures.append(got[0])
            surface = surface or got[1:]
        la = p.get("adhesion_length")
        labels.append(la_label(float(la) / p["pixel_size"]) if la else "non-adhesive")
    if surface is not None:
        heights, substrate = surface
        slope = statistics(heights, pixel_size=substrate.pixel_size).rms_slope
        pressures.insert(
            0, _hard_wall(heights, substrate, target, slope * substrate.contact_modulus)
        )
        labels.insert(0, "non-adhesive (hard wall)")
    return pressures, labels
