"""``roughcontact demo``: a non-adhesive load path, then a built-in adhesive study.

**The load path** (:func:`demo_path`): the benchmarks' default surface (H = 0.8,
h'rms = 0.1, λs = 8 a0, λL = L/2) pushed onto an elastic half-space (E* = 1) at
increasing loads under load control, each state warm-started from the last
(:func:`roughcontact.run_path`), with A_rep/A0 against N/A0 and κ_rep at 1 %
repulsive area, from the site count and from the perimeter-corrected area (Pastewka &
Robbins, PNAS 111, 3298 (2014), Eq. 2; the paper reports κ_rep ≈ 2 for its own soft wall,
which the study below does not reproduce: see its report).

**The adhesive study** (:func:`run_demo_study`): one surface family (H = 0.8,
h'rms = 0.1, λs = 4 a0, λL = L/2: at 256², A_rep/λs² ≈ 41 at 1 % contact, enough
contacts for the paper's statistics) on a half-space, the paper's smoothed 9-3 LJ wall at
adhesion lengths from clearly non-sticky to clearly sticky, five seeds; each task an
approach/retraction path analysed at A_rep = 1 % of A0, keeping the pressure map of its
approach state nearest A_rep = 2 % of A0; Fig. 1 follows seed 1's approaches again with
finer steps there, so that its panels (and a hard wall's, the paper's Fig. 1B) show the
same A_rep (:mod:`roughcontact.workflows.figure1`). The seeds are
combined by :func:`roughcontact.studies.aggregate.aggregate_seeds` (through 1/κ), the
verdicts by the one rule of :mod:`roughcontact.analysis.stickiness`. Results, figures and
a Markdown report (:mod:`roughcontact.workflows.report`) go to one directory; a rerun
resumes what is there.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..errors import ParameterError

__all__ = [
    "ADHESION_LENGTHS",
    "MAP_AREA",
    "SHORT_CUTOFF",
    "check_demo_study",
    "demo_path",
    "demo_study",
    "run_demo_study",
]

#: From clearly not sticky to clearly sticky for this surface family: the measured onset
#: (κ changing sign) lies between 0.001 and 0.005 at 256², so both sides are tested.
ADHESION_LENGTHS = (0.0005, 0.001, 0.002, 0.005, 0.02)
#: What the hard wall's κ_rep is compared with, said beside it (text and JSON).
KAPPA_REP_NOTE = (
    "hard wall; the paper reports kappa_rep ~ 2 for its own, soft wall (not reproduced "
    "with that wall: see the study's report); comparing it with a hard wall is our reading"
)
#: A_rep/A0 of the contact maps of Fig. 1 (about the paper's; the figures' default).
MAP_AREA = 0.02
#: λs of the study's surfaces (a0).
SHORT_CUTOFF = 4.0
#: The path's rows: the per-step variables reported, and their Python types.
_ROW = {
    "load": float,
    "repulsive_area": float,
    "corrected_repulsive_area": float,
    "offset": float,
    "perimeter": float,
    "mean_gap": float,
    "iterations": int,
    "converged": bool,
    "solve_seconds": float,
}


def demo_path(*, size: int = 512, seed: int = 2014, loads=None, tol: float = 1e-8, progress=None):
    """Run the demo's load path; return a JSON-ready dict.

    Parameters
    ----------
    size : int
        Grid size n (n × n sites, lattice units).
    seed : int
        Seed of the surface.
    loads : sequence of float, optional
        Mean pressures N/A0 in units of E* (default: 8 loads from 1.5e-4 to 3e-3).
    tol : float
        Solver tolerance, in (0, 1).
    progress : callable, optional
        ``progress(step, n_steps, result)`` after each state.

    Returns
    -------
    dict
        ``surface`` (parameters and statistics), ``path`` (one row per load: load,
        repulsive_area, corrected_repulsive_area, offset, perimeter, mean_gap, iterations,
        converged, solve_seconds), ``all_converged``, ``total_seconds``, ``kappa_rep``,
        ``kappa_rep_corrected``, ``kappa_rep_note`` (what it is compared with) and
        ``load_at_1_percent`` (``kappa_rep`` None and
        ``kappa_rep_error`` when 1 % is not bracketed), ``path_error`` if a step failed
        (the steps before it are kept).
    """
    from ..analysis.path import interpolate_at_area, kappa
    from ..elastic import Substrate
    from ..solvers import PathInterrupted
    from ..surfaces import self_affine, statistics
    from .pipeline import run_path

    hurst, rms_slope, short_cutoff = 0.8, 0.1, 8.0
    heights = self_affine(
        (size, size),
        hurst=hurst,
        rms_slope=rms_slope,
        short_cutoff=short_cutoff,
        long_cutoff=size / 2,
        seed=seed,
    )
    stats = statistics(heights)
    substrate = Substrate((size, size), contact_modulus=1.0)
    loads = np.geomspace(1.5e-4, 3e-3, 8) if loads is None else np.asarray(loads, dtype=float)
    t0 = time.perf_counter()
    try:  # a failed step keeps the steps before it (path_error)
        run = run_path(heights, substrate, loads=loads, retract=False, tol=tol,
                       progress=progress, keep_partial=True)  # fmt: skip
    except PathInterrupted as err:
        # nothing of a stopped demo is kept: stop as the signal itself does (its exit
        # code and message), not with the path's partial result
        raise err.__context__ or KeyboardInterrupt() from None
    ds, error = run.path, run.path_error or None
    rows = [{k: kind(ds[k].values[i]) for k, kind in _ROW.items()} for i in range(ds.sizes["step"])]
    out = {
        "surface": {
            "size": size,
            "hurst": hurst,
            "short_cutoff": short_cutoff,
            "long_cutoff": size / 2,
            "seed": seed,
            **stats.to_dict(),
        },
        "path": rows,
        "all_converged": all(r["converged"] for r in rows) and error is None,
        "total_seconds": time.perf_counter() - t0,
    }
    if error is not None:
        out["path_error"] = error
    areas, path_loads = [r["repulsive_area"] for r in rows], [r["load"] for r in rows]
    try:
        load_1 = interpolate_at_area(areas, path_loads, 0.01)
        out["kappa_rep"] = kappa(0.01, load_1, stats.rms_slope)
        out["load_at_1_percent"] = load_1
        # the same with the perimeter-corrected area (Yastrebov et al. 2017): the
        # estimate of the continuum area, free of the lattice's bias
        corrected = [r["corrected_repulsive_area"] for r in rows]
        out["kappa_rep_corrected"] = kappa(
            0.01, interpolate_at_area(corrected, path_loads, 0.01), stats.rms_slope
        )
        out["kappa_rep_note"] = KAPPA_REP_NOTE
    except ValueError as err:
        out["kappa_rep"], out["kappa_rep_error"] = None, str(err)
    return out


def demo_study(size: int, seeds) -> dict:
    """The built-in study as the dict a TOML study file would give."""
    return {
        "study": {"name": "demo", "description": "roughcontact demo: Figs. 1-4"},
        "surface": {
            "size": int(size),
            "hurst": 0.8,
            "rms_slope": 0.1,
            "short_cutoff": SHORT_CUTOFF,
            "seeds": [int(s) for s in seeds],
        },
        "substrate": {"contact_modulus": 1.0},
        "interaction": {"law": "lj93smooth", "adhesion_length": list(ADHESION_LENGTHS)},
        "path": {
            "unit": "rms_height",
            "start": 0.5,
            "stop": -2.0,
            "step": 0.125,
            "retract": True,
            # the retraction returns to 3 a0 above the first contact, beyond the reach
            # of the strongest attraction, so that the pull-off is measured
            "lead_in": [3.0, 1.5],
        },
        "solver": {"tol": 1e-6},
        "analysis": {"target_area": 0.01},
        # Fig. 1 needs one pressure map per task, at the approach state nearest MAP_AREA
        # (the state figure1 shows); a few 100 kB in all instead of 0.5 MB per step
        "output": {"fields_at_area": [MAP_AREA], "fields": ["pressure"]},
    }


def check_demo_study(size: int, seeds: int) -> None:
    """Refuse (ParameterError, one line), before any work, a demo study of ``seeds``
    realisations on grids of ``size`` x ``size`` points that the study's checks would
    refuse."""
    from ..studies import study_from_dict
    from ..studies.spec import MAX_TASKS

    most = MAX_TASKS // len(ADHESION_LENGTHS)
    if seeds > most:
        raise ParameterError(
            f"--seeds must be <= {most} (a study of at most {MAX_TASKS} tasks), got {seeds}"
        )
    study_from_dict(demo_study(size, [1]))


def run_demo_study(
    out_dir,
    *,
    size: int = 256,
    seeds=(1, 2, 3, 4, 5),
    workers=None,
    progress=True,
    hard_wall=None,
):
    """Run (or resume) the built-in study, collect it, draw Figs. 1-4, write ``report.md``.

    ``hard_wall``: the result of :func:`demo_path` (the demo's hard-wall load path), put
    into ``report.md`` as the demo prints it.

    The directory is locked for the whole run (:mod:`roughcontact.studies.lock`): a second
    demo writing into it fails at once instead of mixing its files with this one's.

    Returns a JSON-ready dict: the per-ℓa table, the paths of the outputs, the run summary,
    the areas of Fig. 1's maps.
    """
    from ..studies import run_study, study_from_dict
    from ..studies.lock import directory_lock

    out = Path(out_dir)
    spec = study_from_dict(demo_study(size, seeds), source="<roughcontact demo>")
    with directory_lock(out, hint="run 'roughcontact demo' again (it resumes)"):
        summary = run_study(spec, out / "tasks", resume=True, workers=workers, progress=progress)
        return _outputs(out, size, seeds, summary, hard_wall)


def _map_rows(maps, pressures, labels) -> list[dict]:
    """ℓa (None: the hard wall), seed and the A_rep/A0, A_att/A0 of each map of Fig. 1."""
    from ..studies.store import task_parameters

    seed = task_parameters(maps[0].attrs).get("seed") if maps else None
    las = [task_parameters(ds.attrs).get("adhesion_length") for ds in maps]
    if len(pressures) == len(maps) + 1:
        las.insert(0, None)  # the hard wall's panel comes first
    return [
        {
            "adhesion_length": la,
            "label": label,
            "seed": seed,
            "repulsive_area": float((p > 0).mean()),
            "attractive_area": float((p < 0).mean()),
        }
        for la, p, label in zip(las, pressures, labels, strict=True)
    ]


def _figures(out: Path, ds):
    """Draw Figs. 1-4 (PNG and PDF) from the collected study and its task files."""
    from .._io import output_directory
    from ..plot import save_figures, study_maps
    from ..plot._data import STATISTICAL_CONTACTS
    from .figure1 import same_area_maps

    maps = study_maps(out / "tasks")
    pressures, labels = same_area_maps(maps, MAP_AREA) if maps else ([], [])
    figures = save_figures(
        ds,
        output_directory(out / "figures"),  # a link planted there is replaced
        formats=("png", "pdf"),
        maps=pressures or None,
        labels=labels or None,
        target_area=MAP_AREA,
        min_area_per_cutoff=STATISTICAL_CONTACTS,
    )
    return figures, _map_rows(maps, pressures, labels)


def _outputs(out: Path, size, seeds, summary, hard_wall=None) -> dict:
    """Collect the finished study, draw the figures, write ``report.md`` and the study's
    report (``study-report/``, with ``report.html``); the JSON dict."""
    from .._io import write_bytes_atomic, write_netcdf_atomic
    from ..plot._data import STATISTICAL_CONTACTS, eq4_outliers
    from ..studies import collect_study
    from ..studies.aggregate import aggregate_seeds
    from .report import report_lines, summary_lines, table_lines

    ds = collect_study(out / "tasks")
    write_netcdf_atomic(ds, out / "demo.nc")  # atomic; a full disk is one clear error
    figures, map_rows = _figures(out, ds)
    rows = aggregate_seeds(ds)
    summary_text = summary_lines(rows, eq4=eq4_outliers(ds, STATISTICAL_CONTACTS))
    report = report_lines(
        hard_wall=hard_wall,
        size=size,
        seeds=seeds,
        short_cutoff=SHORT_CUTOFF,
        rows=rows,
        summary=summary_text,
        map_rows=map_rows,
        map_area=MAP_AREA,
        run=summary,
        figures=figures,
    )
    # atomic, and a link planted at report.md is replaced rather than written through
    write_bytes_atomic(out / "report.md", ("\n".join(report) + "\n").encode("utf-8"))
    # the study's own report (`roughcontact study report demo.nc -o study-report`): the
    # paper's claims one by one, README.md and one self-contained report.html
    from ..htmlreport import command_line
    from ..studies.report import write_report as study_report

    study_report(out / "demo.nc", out / "study-report", command=command_line())
    return {
        "table": rows,
        "summary": summary_text,
        "report": str(out / "report.md"),
        "report_html": str(out / "study-report" / "report.html"),
        "dataset": str(out / "demo.nc"),
        "figures": {k: [str(x) for x in v] for k, v in figures.items()},
        "tasks": summary.tasks,
        "failed": summary.failed,
        "analysis_errors": summary.analysis_errors,
        "contact_maps": map_rows,
        "table_markdown": table_lines(rows),
    }
