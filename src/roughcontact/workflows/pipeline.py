"""One path, end to end: surface → substrate → law → values → path → analysis.

:func:`run_path` is the one place the library follows a quasi-static path: the study's
task (:func:`roughcontact.studies.task.compute_task`), the ``stick`` simulation
(:func:`roughcontact.topography.simulate.simulate_stickiness`), the ``roughcontact path``
command, the demo's load path and Fig. 1's refined approach all call it. It turns the
approach values into offsets (relative to the first contact, after an optional lead-in),
follows them with :func:`roughcontact.approach_retract`, keeps the fields of the approach
states nearest given repulsive areas (:class:`AreaFields`) and, when asked, analyses the
path with :func:`roughcontact.analysis.path_analysis.analyze_path`. What it did comes back
in one frozen record, :class:`PathRun`.

Units are those of the inputs (lattice units a0 = 1, E* = 1 unless given): lengths as the
heights, loads per A0 in pressure units, areas per A0.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from .._backend import to_numpy
from ..errors import ParameterError

__all__ = ["AreaFields", "PathRun", "approach_offsets", "run_path"]

#: Units of ``offset_unit``: "absolute" offsets d (length) as given, or values relative
#: to the first contact (:func:`roughcontact.relative_offsets`).
OFFSET_UNITS = ("absolute", "length", "rms_height", "bearing_area")


class AreaFields:
    """Progress callback that keeps the fields of the approach states nearest given areas.

    For each target A_rep/A0 the approach step whose repulsive area is closest (the first
    on a tie) keeps its pressure, gap and deflection, as :func:`~roughcontact.plot.figure1`
    would pick it among stored steps. Only the best state so far is held per target, so
    the memory does not grow with the path (the paper's grids hold 4096² sites).

    Parameters
    ----------
    targets : sequence of float
        Repulsive areas per A0 (``[output] fields_at_area``).
    approach_steps : int
        Number of approach steps (lead-in included); retraction steps are not considered.
    until_area : float, optional
        The approach's ``until_area`` (A_rep/A0): it ends at the first state whose
        repulsive area reaches it, so no later state (the retraction) is considered.
    """

    def __init__(self, targets, approach_steps: int, until_area: float | None = None):
        self.targets = [float(t) for t in targets]
        self.approach_steps = int(approach_steps)
        self.until_area = until_area
        self._best = {}  # target -> (distance, step, (pressure, gap, deflection))
        self._done = False

    def __call__(self, step, n_steps, result):
        """``approach_retract``'s ``progress(step, n_steps, result)``; ``step`` counts from 1."""
        from ..analysis.contact_geometry import area_fraction

        if self._done:
            return
        index = step - 1
        if self.targets and index < self.approach_steps:
            # the sites Fig. 1 paints orange (p > 0), so that its choice is this one
            area = area_fraction(result.pressure > 0)  # counted on the device
            for target in self.targets:
                distance = abs(area - target)
                if target not in self._best or distance < self._best[target][0]:
                    self._best[target] = (
                        distance,
                        index,
                        (result.pressure, result.gap, result.deflection),
                    )
        if self.until_area is not None:  # the approach stops here: the retraction follows
            self._done = result.repulsive_area >= self.until_area

    def fields(self) -> dict:
        """``{step: (pressure, gap, deflection)}`` of the chosen states, NumPy (the edge)."""
        return {step: tuple(to_numpy(a) for a in arrays) for _, step, arrays in self._best.values()}


def approach_offsets(heights, values, unit="absolute", interaction=None, pixel_size=1.0,
                     lead_in=None) -> np.ndarray:  # fmt: skip
    """The offsets d (length) of an approach given in ``unit``, after an optional lead-in.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights h of the rigid surface (length).
    values : sequence of float
        The approach in ``unit``: offsets d (length) for ``"absolute"``; otherwise relative
        to the first contact (:func:`roughcontact.relative_offsets`: ``"length"``,
        ``"rms_height"`` or bearing-area fractions in [0, 1], ``"bearing_area"``).
    unit : {"absolute", "length", "rms_height", "bearing_area"}
        The unit of ``values``.
    interaction : interaction law, optional
        Gives the equilibrium distance d0 of the first contact ``max(h) + d0``.
    pixel_size : float
        a0 (length).
    lead_in : sequence of float, optional
        Offsets (length above the first contact) followed before ``values``.

    Returns
    -------
    numpy.ndarray
        float64 offsets d (length), the lead-in first.
    """
    from ..solvers.offsets import relative_offsets

    if unit not in OFFSET_UNITS:
        raise ParameterError(
            f"offset_unit must be one of {', '.join(map(repr, OFFSET_UNITS))}, got {unit!r}"
        )
    if unit == "absolute":
        offsets = np.asarray(values, dtype=float)
    else:
        offsets = relative_offsets(heights, values, unit, interaction, pixel_size)
    if lead_in is None:
        return offsets
    lead = relative_offsets(heights, lead_in, "length", interaction, pixel_size)
    return np.concatenate((lead, offsets))


@dataclass(frozen=True)
class PathRun:
    """What :func:`run_path` did: the path, its inputs and its analysis.

    Attributes
    ----------
    path : xarray.Dataset
        The path of :func:`roughcontact.approach_retract` (the steps before a failed one,
        with ``path_error``), with the fields of the area-picked states added on
        ``field_step`` (:func:`roughcontact.pathdata.add_fields`).
    heights, substrate, interaction
        The surface (length), the substrate and the law the path was followed on.
    control : {"offset", "load"}
        What the path controlled.
    values : numpy.ndarray
        The offsets d (length, lead-in included) or loads (mean pressure) it was given.
    area_fields : dict
        ``{step: (pressure, gap, deflection)}`` (NumPy) of the approach states nearest
        the ``fields_at_area`` targets; empty without targets.
    analysis : PathAnalysis or None
        :func:`~roughcontact.analysis.path_analysis.analyze_path` of the path; None when not
        asked for, when the path failed, or when the analysis failed (``analysis_failure``).
    analysis_failure : ParameterError or None
        Why the analysis failed (the target area not reached, unconverged steps there).
    path_error : str
        Empty, or the message of the step that failed (``keep_partial=True``).
    path_seconds, analysis_seconds : float
        Wall-clock seconds of the path (fields added) and of its analysis.
    """

    path: object = field(repr=False)
    heights: object = field(repr=False)
    substrate: object = field(repr=False)
    interaction: object
    control: str
    values: np.ndarray = field(repr=False)
    area_fields: dict = field(default_factory=dict, repr=False)
    analysis: object = None
    analysis_failure: ParameterError | None = None
    path_error: str = ""
    path_seconds: float = 0.0
    analysis_seconds: float = 0.0

    @property
    def analysis_error(self) -> str:
        """Why the analysis failed, one message; empty when it did not fail."""
        return "" if self.analysis_failure is None else str(self.analysis_failure)

    @property
    def steps(self) -> int:
        """Number of steps followed (approach and retraction)."""
        return int(self.path.sizes["step"])

    @property
    def steps_not_converged(self) -> int:
        """Number of steps whose state did not converge."""
        return int((~np.asarray(self.path["converged"].values, dtype=bool)).sum())

    @property
    def pull_off(self) -> float:
        """Pull-off force per A0 (pressure units, >= 0); NaN when not measured."""
        return float(self.path.attrs.get("pull_off", math.nan))

    def summary(self) -> dict:
        """JSON-ready: ``pull_off`` (None when not measured), ``steps``, ``all_converged``,
        ``solve_seconds`` (s, summed over the steps) and ``jumps`` (step indices)."""
        pull_off = self.pull_off
        return {
            "pull_off": pull_off if math.isfinite(pull_off) else None,
            "steps": self.steps,
            "all_converged": bool(self.path.attrs["all_converged"]),
            "solve_seconds": float(self.path["solve_seconds"].sum()),
            "jumps": [int(i) for i in np.flatnonzero(self.path["jump"].values)],
        }


def run_path(
    heights,
    substrate,
    interaction=None,
    *,
    offsets=None,
    loads=None,
    offset_unit: str = "absolute",
    lead_in=None,
    fields_at_area=(),
    until_area=None,
    progress=None,
    device=None,
    analysis=None,
    keep_partial: bool = False,
    **options,
) -> PathRun:
    """Follow a quasi-static path on a surface and (optionally) analyse it.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights h of the rigid surface (length).
    substrate : ElasticOperator
        The elastic substrate (e.g. :class:`roughcontact.Substrate`).
    interaction : interaction law, optional
        The surface interaction (default: the non-adhesive hard wall).
    offsets : sequence of float
        The approach as offsets in ``offset_unit`` (decreasing d approaches).
    loads : sequence of float
        Load control instead: mean pressures N/A0 (pressure units).
    offset_unit : {"absolute", "length", "rms_height", "bearing_area"}
        The unit of ``offsets`` (:func:`approach_offsets`): offsets d (length) as given,
        or relative to the first contact ``max(h) + d0``.
    lead_in : sequence of float, optional
        Offsets (length above the first contact) followed before ``offsets``.
    fields_at_area : sequence of float
        Repulsive areas A_rep/A0: the fields of the approach state nearest each are kept
        (:class:`AreaFields`) and added to the path.
    until_area : float, optional
        End the approach at the first state with A_rep/A0 >= ``until_area``, in (0, 1]
        (:func:`roughcontact.approach_retract`).
    progress : callable, optional
        ``progress(step, n_steps, result)`` after every step.
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where the path, and the analysis's hard-wall reference, compute.
    **options
        The other options of :func:`roughcontact.approach_retract`, with its defaults:
        ``retract``, ``tol`` (largest force imbalance per site, units of E*), ``max_iter``,
        ``fields_at``, ``jump_factor``, ``dtype``, ``checkpoint``, ``checkpoint_seconds`` (s).
    analysis : mapping, optional
        Analyse the path with :func:`~roughcontact.analysis.path_analysis.analyze_path`
        and these options (``{}``: its defaults), on the path's heights, substrate and
        device. None: no analysis.
    keep_partial : bool
        On a failed step (:class:`roughcontact.PathError`) return the steps before it,
        with ``path_error``, instead of raising.

    Returns
    -------
    PathRun

    Raises
    ------
    ParameterError
        For bad inputs, before any solve.
    PathError
        When a step fails and not ``keep_partial``; its ``partial`` has every step before.
    PathInterrupted
        On Ctrl-C during a step; its ``partial`` has every step before.
    """
    from ..pathdata import add_fields
    from ..solvers import PathError, approach_retract

    if offsets is not None:
        offsets = approach_offsets(heights, offsets, offset_unit, interaction,
                                   getattr(substrate, "pixel_size", 1.0), lead_in)  # fmt: skip
    elif offset_unit != "absolute" or lead_in is not None:
        raise ParameterError("offset_unit and lead_in apply to offsets only")
    control = "offset" if offsets is not None else "load"
    values = offsets if offsets is not None else loads
    targets, nearest = tuple(fields_at_area), None
    if targets:
        nearest = AreaFields(targets, np.size(values), until_area)
        progress = _both(nearest, progress)
    t0, error = time.perf_counter(), ""
    try:
        ds = approach_retract(heights, substrate, interaction, offsets=offsets, loads=loads,
                              until_area=until_area, progress=progress, device=device,
                              **options)  # fmt: skip
    except PathError as err:
        if not keep_partial:
            raise
        ds, error = err.partial, str(err)
    area_fields = nearest.fields() if nearest is not None else {}
    ds = add_fields(ds, area_fields)
    t1 = time.perf_counter()
    result, failure = None, None
    if analysis is not None and not error:
        from ..analysis.path_analysis import analyze_path

        try:
            result = analyze_path(ds, heights=heights, substrate=substrate, device=device,
                                  **analysis)  # fmt: skip
        except ParameterError as err:  # the target area not reached, unconverged steps
            failure = err
    return PathRun(
        path=ds,
        heights=heights,
        substrate=substrate,
        interaction=interaction,
        control=control,
        values=np.asarray(values, dtype=float),
        area_fields=area_fields,
        analysis=result,
        analysis_failure=failure,
        path_error=error,
        path_seconds=t1 - t0,
        analysis_seconds=time.perf_counter() - t1,
    )


def _both(first, second):
    """One progress callback calling ``first``, then ``second`` (if any)."""
    if second is None:
        return first

    def progress(step, n_steps, result):
        first(step, n_steps, result)
        second(step, n_steps, result)

    return progress
