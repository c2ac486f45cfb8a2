"""Quasi-static approach/retraction paths, each state warm-started from the last."""

from __future__ import annotations

import math
import time

import numpy as np

from .._backend import array_device, computes_on_heights_device, dtype_name, to_device
from .._validate import ParameterError
from ..analysis.contact_geometry import contact_patches
from .result import STATE_SCALARS
from .solve import solve

__all__ = ["PathError", "PathInterrupted", "approach_retract"]


class PathError(RuntimeError):
    """A step failed irrecoverably; ``partial`` holds the dataset of the steps before it."""

    def __init__(self, message, partial):
        super().__init__(message)
        self.partial = partial


class PathInterrupted(KeyboardInterrupt):
    """Ctrl-C during a path; ``partial`` holds the dataset of the steps finished before it.

    A :class:`KeyboardInterrupt`, so code that does not look for it still stops as usual.
    """

    def __init__(self, message, partial):
        super().__init__(message)
        self.partial = partial


@computes_on_heights_device
def approach_retract(
    heights,
    substrate,
    interaction=None,
    *,
    offsets=None,
    loads=None,
    retract=True,
    tol=None,
    max_iter=5000,
    fields_at=(),
    jump_factor=2.0,
    progress=None,
    device=None,
    dtype=None,
    checkpoint=None,
    checkpoint_seconds=60.0,
):
    """Follow a quasi-static path and return it as an ``xarray.Dataset``.

    Parameters
    ----------
    heights, substrate, interaction
        As for :func:`roughcontact.solve`.
    offsets : sequence of float
        Offsets ``d`` (length) of the approach, in order (decreasing ``d`` approaches).
    loads : sequence of float
        Load control instead: mean pressures N/A0 (pressure units), in order.
    retract : bool
        After the approach, go back through the same values in reverse.
    fields_at : sequence of int
        Steps whose pressure, gap and deflection fields are kept (``field_step`` dim).
    jump_factor : float
        A step is flagged as an instability (jump into or out of contact) when the
        largest change of the deflection exceeds ``jump_factor`` times the change of
        the offset plus half the interaction's range (Δr, ρ, δ; a0 for the untruncated
        LJ wall); the non-adhesive hard wall has no instabilities. Sites at the edge of
        a growing contact move by more than |Δd| on a stable branch too, but not by a
        sizeable fraction of the range unless the state jumps: on a stable branch the
        contact sites follow the rigid surface (|Δw| ≈ |Δd|) while a jump moves parts of
        the substrate by the interaction range or more.
    progress : callable, optional
        ``progress(step, n_steps, result)`` after every step (e.g. a progress bar).
    device, dtype
        Where and in which precision to compute, as for :func:`roughcontact.solve`; the
        heights are moved once, before the first step. Recorded in the attrs.
    checkpoint : callable, optional
        ``checkpoint(dataset)`` with the steps done so far, after a step when at least
        ``checkpoint_seconds`` (s) have passed since the last call (0: after every step):
        for writing partial results that survive a crash or a kill.

    Returns
    -------
    xarray.Dataset
        Indexed by ``step``: offset, load, repulsive/attractive load and area, mean gap,
        perimeter, corrected_repulsive_area (Yastrebov et al. 2017), iterations,
        residual, converged, solve_seconds, repulsive_patches (number of connected
        repulsive patches, periodic), branch ("approach"/"retract"),
        jump; attrs: the provenance of :func:`provenance` (surface statistics,
        substrate, interaction parameters) and ``pull_off`` (per A0, >= 0: magnitude of the
        most negative load on retraction), ``all_converged``. Loads and areas per A0.

    Raises
    ------
    PathError
        When a step ends in a non-finite state; its ``partial`` has every step before.
    PathInterrupted
        On Ctrl-C (KeyboardInterrupt) during a step; its ``partial`` has every step before.
    """
    if (offsets is None) == (loads is None):
        raise ParameterError("give exactly one of offsets or loads")
    control = "offset" if offsets is not None else "load"
    values = np.atleast_1d(np.asarray(offsets if offsets is not None else loads, dtype=float))
    if values.size == 0:
        raise ParameterError(f"{control}s must contain at least one value (the path is empty)")
    if not np.all(np.isfinite(values)):
        raise ParameterError(f"{control}s must be finite")
    branch = ["approach"] * values.size
    if retract and values.size > 1:
        values = np.concatenate((values, values[-2::-1]))
        branch += ["retract"] * (values.size - len(branch))
    fields_at = {int(i) % values.size for i in fields_at}

    jump_length = _jump_length(interaction)
    attrs = provenance(heights, substrate, interaction)
    heights = to_device(heights, device, dtype or "float64")
    dtype = dtype_name(heights)
    attrs |= {"dtype": dtype, "device": str(array_device(heights))}
    rows, fields, previous, t0 = [], {}, None, time.perf_counter()
    saved = t0
    for step, value in enumerate(values):
        kwargs = {control: float(value)}
        try:
            res = solve(
                heights, substrate, interaction, initial=previous, tol=tol,
                max_iter=max_iter, dtype=dtype, **kwargs,
            )  # fmt: skip
        except KeyboardInterrupt:
            raise PathInterrupted(
                f"interrupted in step {step} ({control} = {value:g})",
                _dataset(rows, branch, fields, control, t0, attrs),
            ) from None
        if "non-finite" in res.message or not math.isfinite(res.load):
            raise PathError(
                f"step {step} ({control} = {value:g}): {res.message}",
                _dataset(rows, branch, fields, control, t0, attrs),
            )
        row = {k: getattr(res, k) for k in STATE_SCALARS}
        row["repulsive_patches"] = int(contact_patches(res.pressure > 0)[1].size)
        if previous is None:
            row["jump"] = False
        else:
            dw = float(np.abs(res.deflection - previous.deflection).max())
            dd = abs(res.offset - previous.offset)
            row["jump"] = bool(dw > jump_factor * dd + jump_length)
        rows.append(row)
        if step in fields_at:
            fields[step] = (res.pressure, res.gap, res.deflection)
        previous = res
        if progress is not None:
            progress(step + 1, values.size, res)
        if checkpoint is not None and time.perf_counter() - saved >= checkpoint_seconds:
            checkpoint(_dataset(rows, branch, fields, control, t0, attrs))
            saved = time.perf_counter()
    return _dataset(rows, branch, fields, control, t0, attrs)


def _jump_length(interaction) -> float:
    """Half the distance over which the law attracts: the scale of a snap (length)."""
    if interaction is None or not getattr(interaction, "adhesive", True):
        return math.inf  # the hard wall: every non-adhesive path is stable
    scale = getattr(interaction, "range", None) or interaction.equilibrium_distance
    return 0.5 * float(scale)


def provenance(heights, substrate, interaction) -> dict:
    """Everything needed to analyse a path without its inputs: NetCDF-ready attributes.

    Surface statistics (spectral h_rms, h'rms, h''rms, d_rep = 4h'rms/h''rms, the
    shortest wavelength present), the substrate (E*, a0, grid, thickness, ν) and the
    interaction's parameters, each under its own key (units as in the rest of the API).
    """
    from .. import __version__
    from ..surfaces.statistics import short_cutoff_estimate, statistics

    a0 = substrate.pixel_size
    stats = statistics(heights, pixel_size=a0)
    attrs = {
        "rms_height": stats.rms_height,
        "rms_slope": stats.rms_slope,
        "rms_curvature": stats.rms_curvature,
        "predicted_d_rep": stats.predicted_d_rep,
        "short_cutoff_estimate": short_cutoff_estimate(heights, pixel_size=a0),
        "contact_modulus": substrate.contact_modulus,
        "pixel_size": a0,
        "grid": list(substrate.shape),
        "nominal_area": substrate.nominal_area,
        "thickness": math.inf if substrate.thickness is None else substrate.thickness,
        "poisson": substrate.poisson,
        "interaction_name": getattr(interaction, "name", "hardwall"),
        "interaction": repr(interaction),
        "substrate": repr(substrate),
        "roughcontact_version": __version__,
    }
    for key in _LAW_PARAMETERS:
        value = getattr(interaction, key, None)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            attrs[key] = float(value)
    return attrs


_LAW_PARAMETERS = (
    "work_of_adhesion",
    "range",
    "stiffness",
    "equilibrium_distance",
    "core_stiffness",
)


def _dataset(rows, branch, fields, control, t0, attrs):
    import xarray as xr

    n = len(rows)
    columns = (*STATE_SCALARS, "repulsive_patches", "jump")
    data = {k: ("step", np.array([r[k] for r in rows]) if n else np.zeros(0)) for k in columns}
    data["branch"] = ("step", np.array(branch[:n], dtype=str))
    ds = xr.Dataset(data, coords={"step": np.arange(n)})
    if fields:
        steps = sorted(fields)
        ds = ds.assign_coords(field_step=steps)
        for i, name in enumerate(("pressure", "gap", "deflection")):
            ds[name] = (("field_step", "x", "y"), np.stack([fields[s][i] for s in steps]))
    retract_loads = [r["load"] for r, b in zip(rows, branch, strict=False) if b == "retract"]
    pull_off = max(0.0, -min(retract_loads)) if retract_loads else math.nan
    ds.attrs.update(
        {
            "control": control,
            "pull_off": pull_off,
            "all_converged": int(all(r["converged"] for r in rows)),
            "total_seconds": time.perf_counter() - t0,
            **attrs,
            "units": "lattice units unless given: loads and areas per nominal area A0",
        }
    )
    return ds
