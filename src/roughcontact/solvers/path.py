"""Quasi-static approach/retraction paths, each state warm-started from the last."""

from __future__ import annotations

import contextlib
import functools
import math
import time

import numpy as np
from array_api_compat import is_jax_array  # (looks at sys.modules: imports no jax)

from .._accelerator import routed, to_device
from .._backend import (
    array_device,
    array_namespace,
    dtype_name,
    to_numpy,
)
from .._validate import ParameterError, step_indices, step_list
from ..analysis.contact_geometry import patch_count
from ..pathdata import load_libraries, path_dataset
from .inputs import check_problem, checked_heights, height_statistics
from .reductions import fetch
from .result import STATE_SCALARS, SolveStatus
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


@routed
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
    until_area=None,
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
        After the approach, go back through the same values in reverse (with
        ``until_area``: through the values the approach visited).
    fields_at : sequence of int
        Steps whose pressure, gap and deflection fields are kept (``field_step`` dim).
        Negative steps count from the end of the path followed. Without ``until_area``
        a step outside ``[-n, n)`` (n: the steps of the whole path, retraction
        included) is a ParameterError, raised before any solve. With ``until_area``,
        whose length is known only when the approach stops, steps past the end of the
        path followed are ignored (no error: the length depends on the solves).
    jump_factor : float
        A step is flagged as an instability (jump into or out of contact) when the
        largest change of the deflection exceeds ``jump_factor`` times the change of
        the offset plus half the interaction's range (Δr, ρ, δ; a0 for the untruncated
        LJ wall); the non-adhesive hard wall has no instabilities. Sites at the edge of
        a growing contact move by more than ``|Δd|`` on a stable branch too, but not by a
        sizeable fraction of the range unless the state jumps: on a stable branch the
        contact sites follow the rigid surface (``|Δw| ≈ |Δd|``) while a jump moves parts of
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
    until_area : float, optional
        Aim the approach at a repulsive area: A_rep/A0 in (0, 1]. The approach stops
        after the first step whose ``repulsive_area >= until_area`` (then retracts
        through the values visited, in reverse, if ``retract``); ``offsets``/``loads`` are
        then the farthest extent tried. Recorded in the attrs ``until_area`` (NaN when not
        given) and ``until_area_reached`` (1/0).

    Returns
    -------
    xarray.Dataset
        Indexed by ``step``: offset, load, repulsive/attractive load and area, mean gap,
        perimeter, corrected_repulsive_area (Yastrebov et al. 2017), iterations,
        residual, converged, status (the :class:`SolveStatus` value), solve_seconds,
        repulsive_patches (number of connected repulsive patches, periodic unless the
        substrate has a free boundary), branch
        ("approach"/"retract"),
        jump; ``heights`` (dims ``x``, ``y``: the rigid surface's heights h, length,
        float64 on the host). Attrs: the provenance of :func:`provenance` (surface
        statistics, the substrate's ``to_attrs()`` - for a ``Substrate`` its
        contact_modulus, pixel_size, grid, thickness (inf: half-space), poisson, base (""
        for a half-space), periodic: enough to rebuild it; interaction parameters),
        ``pull_off`` (per A0, >= 0: the magnitude of the most
        negative load on retraction, or 0 if none is negative; NaN - ``null`` in JSON -
        when it was not measured: no retraction, or a retraction whose last step still has
        repulsive contact, e.g. a path starting inside contact), ``separated`` (1 if the
        retraction's last step has ``repulsive_area == 0``, else 0), ``until_area``,
        ``until_area_reached``, ``all_converged``. Loads and areas per A0.

    Raises
    ------
    PathError
        When a step ends in a non-finite state; its ``partial`` has every step before.
    PathInterrupted
        On Ctrl-C (KeyboardInterrupt) anywhere in the path (in a step, between two, or
        while the finished steps are gathered); its ``partial`` has every finished step.
    """
    if (offsets is None) == (loads is None):
        raise ParameterError("give exactly one of offsets or loads")
    control = "offset" if offsets is not None else "load"
    try:
        values = np.atleast_1d(np.asarray(offsets if offsets is not None else loads, dtype=float))
    except (TypeError, ValueError):
        raise ParameterError(f"{control}s must be a sequence of numbers") from None
    if values.ndim != 1:
        raise ParameterError(
            f"{control}s must be a 1-D sequence of values (one per step), got an array of "
            f"shape {values.shape}"
        )
    if values.size == 0:
        raise ParameterError(f"{control}s must contain at least one value (the path is empty)")
    if not np.all(np.isfinite(values)):
        raise ParameterError(f"{control}s must be finite")
    if until_area is not None:
        until_area = _area_target(until_area)
    plan = _Plan(values, retract, fields_at, until_area is None)

    jump_length = _jump_length(interaction)
    attrs = provenance(heights, substrate, interaction)
    attrs["until_area"] = math.nan if until_area is None else until_area
    host_heights = np.array(to_numpy(heights), dtype=np.float64)
    heights = to_device(heights, device, dtype or "float64")
    dtype = dtype_name(heights)
    checked = contextlib.nullcontext
    if is_jax_array(heights):  # checked once: the states' solves then read nothing for it
        heights, _ = check_problem(heights, substrate, tol, None, None, dtype)
        checked = functools.partial(checked_heights, heights, height_statistics(heights))
    attrs |= {"dtype": dtype, "device": str(array_device(heights))}
    rows, previous, t0 = [], None, time.perf_counter()
    saved = t0
    # (row, its patch count and largest change of the deflection, the jump threshold):
    # device scalars off NumPy, read for every state since the last in one transfer when a
    # dataset is made, so a state's solve is its only read of the device
    pending = []

    def settle():
        if not pending:
            return
        xp = array_namespace(previous.deflection)
        values = fetch(xp, [v for _, patches, dw, _ in pending for v in (patches, dw)])
        for (row, _, _, threshold), patches, dw in zip(
            pending, values[::2], values[1::2], strict=True
        ):
            row["repulsive_patches"] = int(patches)
            row["jump"] = threshold is not None and bool(dw > threshold)
        pending.clear()

    def dataset():
        settle()
        reached = until_area is not None and any(
            r["repulsive_area"] >= until_area for r in rows[: plan.approach_steps or None]
        )
        extra = {"until_area_reached": int(reached)}
        return path_dataset(
            rows, plan.branch, plan.fields, control, attrs | extra, host_heights,
            total_seconds=time.perf_counter() - t0,
        )  # fmt: skip

    # the dataset's libraries now, before any step: a signal during an import leaves the
    # module half-made, and the handler below makes the dataset (the path lost otherwise)
    load_libraries()

    step = 0
    try:
        while step < plan.size:
            value = plan.values[step]
            kwargs = {control: float(value)}
            with checked():
                res = solve(
                    heights, substrate, interaction, initial=previous, tol=tol,
                    max_iter=max_iter, dtype=dtype, **kwargs,
                )  # fmt: skip
            if res.status is SolveStatus.NON_FINITE or not math.isfinite(res.load):
                why = f"step {step} ({control} = {value:g}): {res.message}"
                raise PathError(why, dataset())
            row = {k: getattr(res, k) for k in STATE_SCALARS}
            row["status"] = res.status.value
            # counted on the device: a step copies no field to the host (only fields_at);
            # on a free boundary patches do not wrap. The count and the largest change of
            # the deflection are read later (settle; on JAX both device scalars)
            xp = array_namespace(res.deflection)
            patches = patch_count(res.pressure > 0, periodic=substrate.periodic)
            dw, threshold = 0.0, None
            if previous is not None:
                dw = xp.max(xp.abs(res.deflection - previous.deflection))
                threshold = jump_factor * abs(res.offset - previous.offset) + jump_length
            row["repulsive_patches"], row["jump"] = 0, False  # (until settled)
            pending.append((row, patches, dw, threshold))
            rows.append(row)
            plan.keep(step, (res.pressure, res.gap, res.deflection))
            if until_area is not None and plan.approach_steps is None:
                if res.repulsive_area >= until_area or step == values.size - 1:
                    plan.stop_approach(step)
            previous = res
            if progress is not None:
                progress(step + 1, plan.size, res)
            if checkpoint is not None and time.perf_counter() - saved >= checkpoint_seconds:
                checkpoint(dataset())
                saved = time.perf_counter()
            step += 1
        return dataset()
    except KeyboardInterrupt as interrupt:
        # anywhere in a step (the solve, its bookkeeping, progress, a checkpoint) or
        # between two, or while the last rows are settled: the partial path holds every
        # step whose row is in
        done = len(rows)
        i, where = (step, "in") if done == step and step < plan.size else (done - 1, "after")
        try:
            partial = dataset()
        except Exception:  # (the signal broke what makes it): the plain interruption
            raise interrupt from None
        raise PathInterrupted(
            f"interrupted {where} step {i} ({control} = {plan.values[i]:g})", partial
        ) from None


def _area_target(until_area) -> float:
    try:
        a = float(until_area)
    except (TypeError, ValueError):
        raise ParameterError(f"until_area must be a number in (0, 1], got {until_area!r}") from None
    if not (0 < a <= 1):
        raise ParameterError(f"until_area must be in (0, 1] (A_rep/A0), got {until_area!r}")
    return a


class _Plan:
    """The values of a path, its branches and which steps keep their fields.

    Without an area target the whole path is known in advance. With one, the approach
    may stop early (:meth:`stop_approach`); the retraction then mirrors the values
    visited. Negative ``fields_at`` steps are resolved once the length is known: the
    approach steps they can name are among the last ``max |step|`` ones, held meanwhile.
    """

    def __init__(self, approach, retract, fields_at, known):
        self.approach = approach
        self.retract = bool(retract)
        self.requested = step_list("fields_at", fields_at)
        self.fields = {}
        self._held = {}
        self._depth = max([-i for i in self.requested if i < 0], default=0)
        self.approach_steps = None
        self._set_values(approach)
        if known:
            self.stop_approach(approach.size - 1)
            # the length is known: a step outside [-size, size) is an error, before any work
            self._wanted = set(step_indices("fields_at", self.requested, self.size))
        else:
            self._wanted = {i for i in self.requested if i >= 0}

    def _set_values(self, approach):
        n = approach.size
        self.values = approach
        self.branch = ["approach"] * n
        if self.retract and n > 1:
            self.values = np.concatenate((approach, approach[-2::-1]))
            self.branch += ["retract"] * (n - 1)

    @property
    def size(self) -> int:
        return self.values.size

    def stop_approach(self, step):
        """The approach ends after ``step``: fix the retraction and the field steps."""
        self.approach_steps = step + 1
        self._set_values(self.approach[: step + 1])
        self._wanted = {i for i in self.requested if 0 <= i < self.size}
        self._wanted |= {self.size + i for i in self.requested if -self.size <= i < 0}
        for s, arrays in self._held.items():
            if s in self._wanted:
                self.fields[s] = _on_host(arrays)
        self._held = {}

    def keep(self, step, arrays):
        """Keep the fields of ``step`` if asked for: on the host; held ones where they are."""
        if step in self._wanted:
            self.fields[step] = _on_host(arrays)
        elif self.approach_steps is None and self._depth:
            self._held[step] = arrays
            self._held.pop(step - self._depth, None)


def _on_host(arrays):
    """NumPy copies of a step's fields, for the dataset (the only fields that leave the device)."""
    return tuple(to_numpy(a) for a in arrays)


def _jump_length(interaction) -> float:
    """Half the distance over which the law attracts: the scale of a snap (length)."""
    if interaction is None or not interaction.adhesive:
        return math.inf  # the hard wall: every non-adhesive path is stable
    scale = interaction.range or interaction.equilibrium_distance
    return 0.5 * float(scale)


def provenance(heights, substrate, interaction) -> dict:
    """Everything needed to analyse a path without its inputs: NetCDF-ready attributes.

    Surface statistics (h_rms, h'rms, h''rms, d_rep = 4h'rms/h''rms: spectral on a
    periodic substrate, finite differences inside the window on a free one; the shortest
    wavelength present), the substrate's own description (its ``to_attrs()``: for a
    :class:`~roughcontact.Substrate` E*, a0, grid, nominal area, thickness (inf for a
    half-space), ν, base ("" for a half-space), periodic (0 for a free boundary) and the
    kind tag ``substrate``; :func:`roughcontact.elastic.substrate_from_attrs` rebuilds it)
    and the interaction's parameters, each under its own key (units as in the rest of the
    API): those of the interaction registry's one list,
    :data:`~roughcontact.interactions.registry.LAW_ATTRIBUTES`.
    """
    from .. import __version__
    from ..interactions.registry import law_parameters
    from ..surfaces.statistics import short_cutoff_estimate, statistics

    a0 = substrate.pixel_size
    stats = statistics(heights, pixel_size=a0, periodic=substrate.periodic)
    describe = getattr(substrate, "to_attrs", None)  # operators written before to_attrs
    described = dict(describe()) if describe is not None else {
        "contact_modulus": substrate.contact_modulus, "pixel_size": a0,
        "grid": list(substrate.shape), "periodic": int(bool(substrate.periodic)),
        "substrate": repr(substrate),
    }  # fmt: skip
    kind_tag = described.pop("substrate")  # written after the interaction, as it always was
    attrs = {
        "rms_height": stats.rms_height,
        "rms_slope": stats.rms_slope,
        "rms_curvature": stats.rms_curvature,
        "predicted_d_rep": stats.predicted_d_rep,
        "short_cutoff_estimate": short_cutoff_estimate(heights, pixel_size=a0),
        **described,
        "interaction_name": "hardwall" if interaction is None else interaction.name,
        "interaction": repr(interaction),
        "substrate": kind_tag,
        "roughcontact_version": __version__,
    }
    attrs.update(law_parameters(interaction))  # the registry's recorded parameters
    return attrs
