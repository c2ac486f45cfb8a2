r"""The paper's simulation for a measured surface: is it sticky, measured on the lattice?

:func:`roughcontact.stick` answers with Eq. 10 of Pastewka & Robbins (2014) from a scan's
statistics. With ``simulate=True`` it also runs the paper's simulation on synthetic
surfaces that continue the measured spectrum down to the interaction scale
(:func:`simulate_stickiness`):

* **Surface** (lattice units, a0 = ``atomic_spacing``): ``size`` x ``size`` sites, a
  self-affine spectrum (:func:`roughcontact.self_affine`) with the scan's fitted Hurst
  exponent H (clipped into [:data:`HURST_MIN`, 1] when the fit is outside, said in the
  notes), the short cutoff lambda_s = :data:`SHORT_CUTOFF` a0 (the paper's smallest),
  the long cutoff lambda_L = ``size`` a0/2 (the paper's L = 2 lambda_L) and the rms slope
  h'_rms of the scan extrapolated down to lambda_s
  (:meth:`ScaleStatistics.extrapolated_at`, the same numbers as the Eq. 10 verdict). The
  synthetic surface is a window of ``size`` a0 onto the smallest scales: Eqs. 6-10 depend
  on h'_rms, H and lambda_s, not on the long scales it leaves out.
* **Interaction**: with ``interaction_range`` (what :func:`roughcontact.stick` passes:
  the range Delta_r the user asked for) a Maugis-Dugdale zone on a hard wall
  (:class:`roughcontact.MaugisDugdale`: the stress w/Delta_r up to the gap Delta_r), so
  that w and Delta_r are both the user's. The paper's smoothed 9-3 wall cannot do this:
  continuity ties ``w = k Delta_r^2/12``, so with its stiffness k = E*/(2 a0) the range
  is ``sqrt(24 a0 l_a)`` (silicon: 0.065 nm, not 0.5 nm), and with the range forced the
  stiffness drops to ``12 w/Delta_r^2`` (silicon: E*/(59 a0)), a soft core that spread
  the repulsion and measured kappa_rep = 40 on a surface where the hard wall gives 3.2
  (64^2 sites, h'_rms = 0.3, l_a/a0 = 5e-4: sticky there, not sticky on the hard wall,
  as Eq. 10 predicts). Without ``interaction_range`` the paper's wall
  (:meth:`roughcontact.SmoothLJ93.from_adhesion_length`), for which ``l_a/a0`` must lie
  in :data:`ADHESION_RANGE`: at ``l_a/a0 = 0.1`` its range grows to ``sqrt(24 a0 l_a)``
  and the approach is pulled into an adhered state whose repulsive area never reaches
  1 %; the paper's largest is 0.05. With the range given, :data:`ADHESION_RANGE_GIVEN`
  reaches soft materials (PDMS: E 2 MPa, nu 0.5, w 0.05 J/m^2, l_a/a0 = 62.5): there no
  seed reaches 1 % repulsive area on approach: at the first offset within reach of the
  attraction the attractive area jumps to 77 % of A0 (``di-1.di``, 64^2 sites; 85-96 %
  further in) under a tensile load of -1.7 E* A0, and separating takes a finite pull-off
  force -- the surfaces jump into contact, the model's own limit for soft solids,
  reported as "sticky" when every seed does so (:data:`JUMP_AREA`). No coarse-graining
  is assumed: the lattice stays a0.
* **Path**: an elastic substrate of thickness ``size`` a0 on a rigid base (nu = 1/2,
  as the study of :mod:`roughcontact.studies` runs the paper), approached at offsets in
  bearing-area units (:func:`roughcontact.solvers.offsets.relative_offsets`: the
  fraction of A0 the undeformed surfaces would overlap) after three lead-in offsets
  beyond the reach of the attraction, until A_rep reaches :data:`UNTIL_AREA`, then
  retracted through the same offsets (pull-off force).
* **Analysis**: :func:`roughcontact.analysis.path_analysis.analyze_path` at
  A_rep = 1 % of A0 with the hard-wall reference: kappa, kappa_rep, kappa_att, the
  measured verdict (sticky iff 1/kappa < 0) and Eq. 10's prediction on the same surface
  (``predicted_verdict``). A seed whose steps around 1 % did not converge, or whose path
  never reaches 1 %, is recorded with its error and left out of the combination.
* **Over seeds**: :func:`roughcontact.analysis.stickiness.inverse_mean` of 1/kappa (and of
  the predicted 1/kappa): sticky iff its confidence interval lies below 0, not sticky
  above, else undecided.

Lengths of the results are in SI (m) unless named ``*_over_a0``; loads per A0 in units
of E* (``pull_off``) and in Pa (``pull_off_pressure = pull_off E*``). The simulation
takes seconds (64^2) to minutes (256^2, the default, a few seeds) on a CPU.

Reference: L. Pastewka and M. O. Robbins, PNAS 111, 3298 (2014), Methods, Eqs. 2-10.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np

from .._validate import ParameterError, Range, json_safe
from .simulate_units import SIMULATION_UNITS
from .synthetic import HURST_MIN, SHORT_CUTOFF, SIZE, synthetic_surface

__all__ = [
    "ADHESION_RANGE",
    "ADHESION_RANGE_GIVEN",
    "SEEDS",
    "SIMULATION_UNITS",
    "SIZE",
    "SeedRun",
    "Simulation",
    "check_options",
    "simulate_stickiness",
    "synthetic_surface",
]

#: Number of surface realisations (seeds 1, 2, ...).
SEEDS = Range(1, 32, integer=True)
#: l_a/a0 = w/(E* a0) the simulation handles with the paper's parametrisation (module
#: docstring: measured limit).
ADHESION_RANGE = Range(1e-5, 0.05)
#: l_a/a0 handled with the range given (the wall's stiffness 12 w/range^2): soft materials
#: such as PDMS (l_a/a0 ~ 60) included (module docstring).
ADHESION_RANGE_GIVEN = Range(1e-5, 100.0)
#: A_rep/A0 of the analysis (the paper's 1 %).
TARGET_AREA = 0.01
#: The approach stops at the first step with A_rep/A0 at least this (1 % is bracketed).
UNTIL_AREA = 0.015
#: Offsets as bearing-area fractions of A0 (A_rep/A0 from ~1e-4 to a few %, continued to 0.2
#: for strongly adhesive surfaces whose repulsive area grows slowly).
BEARING_AREA = (0.0, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 6e-3, 7e-3, 8.5e-3,
                0.01, 0.012, 0.015, 0.02, 0.025, 0.03, 0.04, 0.05, 0.06, 0.08, 0.1, 0.12,
                0.15, 0.2)  # fmt: skip
#: Solver tolerance (largest force imbalance per site / E*) and iteration cap.
TOL, MAX_ITER = 1e-7, 20000


def _lead_in(range_over_a0: float) -> tuple:
    """Lead-in offsets [a0 above the first contact]: the approach starts beyond the
    attraction's reach (so jumps into contact are followed) and the retraction returns
    there (so the surfaces separate and the pull-off force is measured)."""
    return (2.0 + 2.0 * range_over_a0, 1.0 + range_over_a0, 0.5)


def check_options(size, seeds) -> tuple[int, int]:
    """``(size, seeds)`` checked against :data:`SIZE` and :data:`SEEDS`."""
    return SIZE.check("simulate_size", size), SEEDS.check("simulate_seeds", seeds)


def _adhesion_over_a0(work_of_adhesion, contact_modulus, atomic_spacing, given=False) -> float:
    la = work_of_adhesion / contact_modulus / atomic_spacing
    accepted = ADHESION_RANGE_GIVEN if given else ADHESION_RANGE
    if not accepted.contains(la):
        raise ParameterError(
            f"simulate: the adhesion length l_a/a0 = work_of_adhesion/(E* atomic_spacing) = "
            f"{la:.3g} must be {ADHESION_RANGE.accepted} for the simulation (the paper's "
            f"smoothed 9-3 wall; l_a/a0 << 1 for real solids): use Eq. 10 alone, or check "
            f"work_of_adhesion, modulus and atomic_spacing"
        )
    return la


@dataclass(frozen=True)
class SeedRun:
    """One realisation: its path analysed at A_rep = 1 % (dimensionless unless stated).

    ``kappa``, ``kappa_rep``, ``kappa_att``, ``inverse_kappa`` and ``verdict`` are the
    measured ones (:class:`~roughcontact.analysis.path_analysis.PathAnalysis`),
    ``predicted_kappa``/``predicted_verdict`` Eq. 10's on the same surface (with the
    measured kappa_rep and d_rep); ``attractive_area`` per A0; ``pull_off`` per A0 in
    units of E*, ``pull_off_pressure`` in Pa (NaN: the retraction did not separate the
    surfaces). ``error`` is empty, or why the seed has no analysis (steps around 1 % not
    converged, 1 % not reached, a failed step). ``path`` (the xarray path), ``heights``
    (a0), ``analysis`` and ``pressure_map`` (the approach state nearest 1 %, units of E*;
    None except for the first seed) are kept for inspection, not serialised.
    """

    seed: int
    kappa: float
    kappa_rep: float
    kappa_att: float
    inverse_kappa: float
    verdict: str
    predicted_kappa: float
    predicted_verdict: str
    attractive_area: float
    pull_off: float
    pull_off_pressure: float
    steps: int
    steps_not_converged: int
    seconds: float
    error: str = ""
    warnings: tuple = ()
    path: object = field(default=None, repr=False, compare=False)
    heights: object = field(default=None, repr=False, compare=False)
    analysis: object = field(default=None, repr=False, compare=False)
    pressure_map: object = field(default=None, repr=False, compare=False)

    def to_dict(self) -> dict:
        d = {f.name: getattr(self, f.name) for f in dataclasses.fields(self) if f.repr}
        d["warnings"] = list(self.warnings)
        return json_safe(d)


@dataclass(frozen=True)
class Simulation:
    """The simulation of :func:`simulate_stickiness` (SI lengths; see the module docstring).

    ``verdict`` ("sticky", "not sticky", "undecided") is the measured one over the seeds,
    from ``inverse_kappa`` (:class:`~roughcontact.analysis.stickiness.InverseMean` of the
    per-seed kappa); ``predicted_verdict`` Eq. 10's from ``predicted_inverse_kappa``.
    ``surface`` and ``interaction`` describe the synthetic system; ``runs`` the seeds.
    """

    surface: dict
    interaction: dict
    path: dict
    runs: tuple
    inverse_kappa: object
    predicted_inverse_kappa: object
    verdict: str
    predicted_verdict: str
    notes: tuple
    seconds: float

    @property
    def sticky(self) -> bool | None:
        """True (sticky), False (not sticky) or None (undecided)."""
        return {"sticky": True, "not sticky": False}.get(self.verdict)

    @property
    def pull_off_pressure(self) -> float:
        """Mean pull-off pressure over the seeds that measured one [Pa] (NaN: none)."""
        values = [r.pull_off_pressure for r in self.runs if math.isfinite(r.pull_off_pressure)]
        return float(np.mean(values)) if values else math.nan

    @property
    def contact_map(self):
        """``(seed, pressure)`` of the first seed's approach state nearest 1 %, or None."""
        for r in self.runs:
            if r.pressure_map is not None:
                return r.seed, r.pressure_map
        return None

    def to_dict(self) -> dict:
        inv, pred = self.inverse_kappa, self.predicted_inverse_kappa
        d = {
            "verdict": self.verdict,
            "sticky": self.sticky,
            "predicted_verdict": self.predicted_verdict,
            "kappa": inv.value,
            "inverse_kappa": inv.mean,
            "inverse_kappa_interval": [inv.low, inv.high],
            "predicted_kappa": pred.value,
            "predicted_inverse_kappa": pred.mean,
            "predicted_inverse_kappa_interval": [pred.low, pred.high],
            "confidence": inv.confidence,
            "seeds_analysed": inv.n,
            "pull_off_pressure": self.pull_off_pressure,
            "target_area": TARGET_AREA,
            "surface": dict(self.surface),
            "interaction": dict(self.interaction),
            "path": dict(self.path),
            "seeds": [r.to_dict() for r in self.runs],
            "seconds": self.seconds,
            "notes": list(self.notes),
        }
        return json_safe(d)


def _run_seed(seed, heights, law, modulus, keep_map) -> SeedRun:
    from ..elastic import Substrate
    from ..workflows.pipeline import run_path

    t0 = time.perf_counter()
    n = heights.shape[0]
    substrate = Substrate((n, n), contact_modulus=1.0, thickness=float(n), poisson=0.5,
                          base="bonded")  # fmt: skip
    run = run_path(
        heights,
        substrate,
        law,
        offsets=BEARING_AREA,
        offset_unit="bearing_area",
        lead_in=_lead_in(law.range),
        retract=True,
        tol=TOL,
        max_iter=MAX_ITER,
        until_area=UNTIL_AREA,
        # the pressure of the approach state nearest 1 % (Fig. 1's choice)
        fields_at_area=[TARGET_AREA] if keep_map else (),
        analysis={"target_area": TARGET_AREA, "hard_wall_reference": True},
        keep_partial=True,  # a non-finite state: the steps before it are kept
    )
    error = _seed_error(run)
    a = run.analysis
    nan = math.nan
    return SeedRun(
        seed=int(seed),
        kappa=a.kappa if a else nan,
        kappa_rep=a.kappa_rep if a else nan,
        kappa_att=a.kappa_att if a else nan,
        inverse_kappa=a.inverse_kappa if a else nan,
        verdict=a.verdict if a else "",
        predicted_kappa=a.predicted_kappa if a else nan,
        predicted_verdict=a.predicted_verdict if a else "",
        attractive_area=a.attractive_area if a else nan,
        pull_off=run.pull_off,
        pull_off_pressure=run.pull_off * modulus,
        steps=run.steps,
        steps_not_converged=run.steps_not_converged,
        seconds=time.perf_counter() - t0,
        error=error.splitlines()[0] if error else "",
        warnings=tuple(a.warnings) if a else (),
        path=run.path,
        heights=heights,
        analysis=a,
        pressure_map=next(iter(run.area_fields.values()))[0] if run.area_fields else None,
    )


def _seed_error(run) -> str:
    """Why a seed has no analysis: a failed step, unconverged steps around 1 %, 1 % not
    reached; empty when it has one."""
    from ..analysis.path_analysis import UnconvergedPathError

    if run.path_error:
        return f"path stopped: {run.path_error}"
    if isinstance(run.analysis_failure, UnconvergedPathError):
        return f"not converged: {run.analysis_failure}"
    return run.analysis_error


def simulate_stickiness(
    stats,
    *,
    contact_modulus: float,
    work_of_adhesion: float,
    atomic_spacing: float,
    size: int = 256,
    seeds: int = 3,
    progress=None,
    interaction_range: float | None = None,
) -> Simulation:
    """Run the paper's simulation on synthetic surfaces continuing the scan's spectrum.

    Parameters
    ----------
    stats : ScaleStatistics
        The scan's statistics (SI; :func:`~roughcontact.topography.scale_statistics`).
    contact_modulus : float
        E* [Pa].
    work_of_adhesion : float
        w [J/m^2].
    atomic_spacing : float
        a0 [m]: the lattice spacing and the wall's equilibrium distance.
    size : int
        n, sites per axis, in :data:`SIZE`.
    seeds : int
        Realisations (seeds 1 ... ``seeds``), in :data:`SEEDS`.
    progress : callable, optional
        ``progress(k, seeds)`` before realisation k (1-based).
    interaction_range : float, optional
        Delta_r [m] of the wall: the range the user asked for, with the stiffness
        ``k = 12 w/Delta_r^2`` that continuity of the smoothed wall requires. None: the
        paper's parametrisation (k = E*/(2 a0), range ``sqrt(24 a0 l_a)``).

    Returns
    -------
    Simulation

    Raises
    ------
    ParameterError
        For ``size``/``seeds`` outside their ranges, or l_a/a0 outside
        :data:`ADHESION_RANGE`.
    """
    from ..analysis.stickiness import inverse_mean
    from ..interactions import MaugisDugdale, SmoothLJ93
    from .notes import simulation_notes

    n, count = check_options(size, seeds)
    E, w, a0 = float(contact_modulus), float(work_of_adhesion), float(atomic_spacing)
    la = _adhesion_over_a0(w, E, a0, given=interaction_range is not None)
    t0 = time.perf_counter()
    if interaction_range is None:
        law = SmoothLJ93.from_adhesion_length(la)
    else:
        law = MaugisDugdale(work_of_adhesion=la, range=float(interaction_range) / a0)
    runs, surface = [], None
    for k in range(1, count + 1):
        if progress is not None:
            progress(k, count)
        heights, surface = synthetic_surface(stats, atomic_spacing=a0, size=n, seed=k)
        runs.append(_run_seed(k, heights, law, E, keep_map=k == 1))
    inv = inverse_mean([r.kappa for r in runs])
    pred = inverse_mean([r.predicted_kappa for r in runs])
    surface_d = {
        "size": n,
        "atomic_spacing": a0,
        "physical_size": n * a0,
        "short_cutoff": SHORT_CUTOFF * a0,
        "long_cutoff": surface["long_cutoff"] * a0,
        "short_cutoff_over_a0": SHORT_CUTOFF,
        "long_cutoff_over_a0": surface["long_cutoff"],
        "hurst": surface["hurst"],
        "hurst_fitted": surface["hurst_fitted"],
        "rms_slope": surface["rms_slope"],
    }
    interaction = {
        "law": law.name,
        "adhesion_length": la * a0,
        "adhesion_length_over_a0": la,
        "range": law.range * a0,
        "range_over_a0": law.range,
        "stiffness": (getattr(law, "stiffness", None) or math.inf) * E / a0,
        "parametrisation": "paper's 9-3 wall: k = E*/(2 a0)"
        if interaction_range is None
        else "Maugis-Dugdale zone of the range given on a hard wall",
        "work_of_adhesion": w,
        "contact_modulus": E,
    }
    path = {
        "control": "offset",
        "bearing_area": list(BEARING_AREA),
        "lead_in": list(_lead_in(law.range)),
        "until_area": UNTIL_AREA,
        "tol": TOL,
        "max_iter": MAX_ITER,
        "thickness": n * a0,
        "poisson": 0.5,
    }
    verdict, extra = _verdict(inv, runs, law, la, surface["rms_slope"])
    return Simulation(
        surface=surface_d,
        interaction=interaction,
        path=path,
        runs=tuple(runs),
        inverse_kappa=inv,
        predicted_inverse_kappa=pred,
        verdict=verdict,
        predicted_verdict=pred.verdict,
        notes=tuple(simulation_notes(surface, runs, law, a0, HURST_MIN, SHORT_CUTOFF) + extra),
        seconds=time.perf_counter() - t0,
    )


#: Attractive area (fraction of A0) that marks a jump into contact (module docstring).
JUMP_AREA = 0.5


def _jump_into_contact(run):
    """``(attractive area, load)`` where a seed that never reached 1 % repulsive area
    jumped into contact (attractive area >= JUMP_AREA of A0 under a tensile load, every
    step converged, a finite pull-off force); None otherwise."""
    ds = run.path
    if ds is None or not run.error.startswith("target area") or run.steps_not_converged:
        return None
    if not (math.isfinite(run.pull_off) and run.pull_off > 0):
        return None
    att = np.asarray(ds["attractive_area"].values, dtype=float)
    load = np.asarray(ds["load"].values, dtype=float)
    i = int(np.argmax(att))
    return (float(att[i]), float(load[i])) if att[i] >= JUMP_AREA and load[i] < 0 else None


def _verdict(inv, runs, law, la, slope):
    """The simulated verdict and its notes: the seeds' kappa, the soft-solid limit (every
    seed jumped into contact) and the finite-size guard (module docstring)."""
    from ..theory.pastewka_robbins import necessary_condition

    verdict, extra = inv.verdict, []
    jumps = [_jump_into_contact(r) for r in runs]
    rough = min(float(np.std(r.heights)) for r in runs)  # a0
    if inv.n == 0 and runs and all(j is not None for j in jumps):
        area = min(j[0] for j in jumps)
        extra.append(
            f"simulation: on approach every seed jumped into contact (attractive area >= "
            f"{area:.0%} of A0 under a tensile load) before A_rep reached 1 %, and needed a "
            "finite pull-off force to separate"
        )
        if la > rough:  # w/E* beyond the window's roughness: flattening it costs less
            verdict = "sticky"
            extra[-1] += ": the model's limit for soft solids, sticky"
            return verdict, extra
    shallow = rough < MIN_ROUGHNESS_OVER_RANGE * law.range
    if verdict == "sticky" and shallow and not necessary_condition(la, slope):
        verdict = "undecided"
        extra.append(
            f"simulation: undecided: its seeds stuck although l_a/a0 = {la:.3g} fails the "
            f"necessary condition l_a/a0 > 0.49 h'rms = {0.49 * slope:.3g}, and the synthetic "
            f"surfaces (rms height {rough:.3g} a0) lie within reach of the attraction (range "
            f"{law.range:.3g} a0): a finite-size effect; use a larger --simulate-size"
        )
    return verdict, extra


#: Smallest rms height of the synthetic window, in interaction ranges, below which a
#: simulated "sticky" that contradicts the necessary condition is a finite-size effect
#: (silicon, h'rms 0.2, Delta_r = 1.67 a0: sticky at 64^2 sites, rms height 0.54 a0, not
#: sticky at 128^2, 0.85 a0).
MIN_ROUGHNESS_OVER_RANGE = 0.5
