"""One task of a study, run on a worker: surface → substrate → law → path → analysis.

One task = one surface realisation × one parameter set × its whole path: generate the
surface, build the substrate and the interaction (:func:`task_inputs`), then follow the
approach (and retraction) and analyse it with :func:`roughcontact.run_path`. The result is
the path dataset with the task's provenance in its attributes; it is written by the
driver (:mod:`.store`).
"""

from __future__ import annotations

import json
import os
import platform
import socket
import time
import traceback

import numpy as np

from ..pathdata import FIELDS, add_fields
from ..workflows.pipeline import AreaFields, approach_offsets
from .schema import make_interaction
from .spec import Task
from .store import PARAMETERS_ATTR

__all__ = ["AreaFields", "compute_task", "path_values", "run_task", "with_fields"]
# AreaFields lives in roughcontact.workflows.pipeline (run_path keeps the fields); the name
# stays importable from here


def path_values(path: dict, heights, law, params: dict) -> np.ndarray:
    """The offsets (length) or loads (mean pressure) of a task's approach.

    Offsets (:func:`roughcontact.solvers.offsets.relative_offsets`, shared with
    ``roughcontact path --offset-unit``) are relative to the first contact of the summit,
    ``max(h) + d0`` (``d0`` the law's equilibrium distance: a0 for the Lennard-Jones
    walls, 0 for the hard-core laws), in units of length or of the surface's rms height;
    or (``unit = "bearing_area"``) fractions v in [0, 1]: ``d = d0 + quantile(h, 1 - v)``, where the
    undeformed rigid surface would overlap a fraction v of the substrate (the repulsive
    area grows roughly in proportion, whatever the height distribution's tail).
    ``lead_in`` offsets (length above the first contact) come before them. Loads are
    in units of E* or of ``h'rms E*`` (``unit = "rms_slope_modulus"``, Fig. 2's abscissa).
    """
    from ..surfaces.statistics import statistics

    if path["values"] is not None:
        values = np.asarray(path["values"], dtype=float)
    elif path["num"] is not None:
        space = np.geomspace if path["spacing"] == "geometric" else np.linspace
        values = space(path["start"], path["stop"], path["num"])
    else:  # start, stop, step as 'roughcontact path --offsets' steps them
        from ..solvers.offsets import stepped_values

        values = stepped_values(path["start"], path["stop"], path["step"], name="[path]")
    if path["control"] == "offset":
        a0 = params["pixel_size"]
        return approach_offsets(heights, values, path["unit"], law, a0, path["lead_in"])
    a0, periodic = params["pixel_size"], params.get("periodic", True)
    stats = statistics(heights, pixel_size=a0, periodic=periodic)
    scale = stats.rms_slope if path["unit"] == "rms_slope_modulus" else 1.0
    return values * scale * params["contact_modulus"]


def with_fields(ds, extra: dict):
    """``ds`` with the fields ``{step: (pressure, gap, deflection)}`` added on ``field_step``.

    Steps already stored (``fields_at``) are kept; the result has the layout of
    :func:`roughcontact.approach_retract`'s fields, sorted by step
    (:func:`roughcontact.pathdata.add_fields`).
    """
    return add_fields(ds, extra)


#: The task parameters of its surface (:func:`roughcontact.self_affine`) and substrate
#: (:class:`roughcontact.Substrate`).
_SURFACE = ("hurst", "rms_slope", "rms_height", "short_cutoff", "long_cutoff", "rolloff",
            "pixel_size", "seed")  # fmt: skip
_SUBSTRATE = ("contact_modulus", "pixel_size", "thickness", "poisson", "base")


def task_inputs(params: dict, path_settings: dict):
    """The surface, substrate, law and path values of a task's parameters.

    ``params``: a task's parameters (:attr:`Task.params`, or read back from its file with
    :func:`~roughcontact.studies.store.task_parameters`); ``path_settings``: its
    ``[path]`` settings. Returns ``(heights, substrate, law, values)`` in the study's
    units; the one place a task's inputs are built, so a figure that re-follows a task
    solves exactly the task's problem.
    """
    from ..elastic import Substrate
    from ..surfaces import self_affine

    p, n = params, params["size"]
    # the parameters carry the names of the keywords they are passed as
    heights = self_affine((n, n), **{k: p[k] for k in _SURFACE})
    substrate = Substrate((n, n), **{k: p[k] for k in _SUBSTRATE}, periodic=p.get("periodic", True))
    law = make_interaction(p)
    return heights, substrate, law, path_values(path_settings, heights, law, p)


def compute_task(task: Task):
    """Run one task in this process and return its dataset (path, provenance, analysis)."""
    from ..workflows.pipeline import run_path

    p, s = task.params, task.settings
    t0, started = time.perf_counter(), time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
    heights, substrate, law, values = task_inputs(p, s["path"])
    t1 = time.perf_counter()
    run = run_path(
        heights,
        substrate,
        law,
        retract=s["path"]["retract"],
        tol=s["solver"]["tol"],
        max_iter=s["solver"]["max_iter"],
        fields_at=s["output"]["fields_at"],
        fields_at_area=s["output"].get("fields_at_area", ()),
        device=task.device,  # the hard-wall reference's solves too
        dtype=s["solver"].get("dtype", "float64"),
        analysis=s["analysis"],
        **{f"{s['path']['control']}s": values},
    )
    ds = run.path
    ds = ds.drop_vars([f for f in FIELDS if f in ds.variables and f not in s["output"]["fields"]])
    analysis = run.analysis.to_dict() if run.analysis is not None else {}
    error = run.analysis_error
    # the surface is regenerated from the task's parameters and seed; not stored
    ds = ds.drop_vars("heights", errors="ignore")
    t3 = time.perf_counter()
    ds.attrs.update(
        {
            "task_id": task.id,
            "task_key": task.key,
            PARAMETERS_ATTR: json.dumps(p, sort_keys=True),
            "task_settings": json.dumps(s, sort_keys=True),
            "seed": int(p["seed"]),
            "solver_tol": float(s["solver"]["tol"]),
            "solver_max_iter": int(s["solver"]["max_iter"]),
            "solver_dtype": s["solver"].get("dtype", "float64"),
            "steps_not_converged": run.steps_not_converged,
            "analysis": json.dumps(analysis, sort_keys=True),
            "analysis_error": error,
            "setup_seconds": t1 - t0,
            "path_seconds": run.path_seconds,
            "analysis_seconds": run.analysis_seconds,
            "task_seconds": t3 - t0,
            "started_utc": started,
            "hostname": socket.gethostname(),
            "python_version": platform.python_version(),
            "numpy_version": np.__version__,
        }
    )
    return ds


def run_task(task: Task) -> dict:
    """Worker entry point: ``{"status": "done", "dataset": ds}`` or a failure record.

    Every exception is caught and returned with its traceback, so one failing task
    never stops the study. Inside a Dask worker the FFTs use one thread each unless
    ``ROUGHCONTACT_FFT_WORKERS`` is set (the worker's task threads already fill the cores).
    """
    try:
        from distributed import get_worker

        get_worker()
        os.environ.setdefault("ROUGHCONTACT_FFT_WORKERS", "1")
    except (ImportError, ValueError):
        pass  # not on a Dask worker: leave the FFT threads as they are
    try:
        return {"status": "done", "dataset": compute_task(task)}
    except Exception as err:  # noqa: BLE001 - recorded, the study goes on
        return {
            "status": "failed",
            "reason": f"{type(err).__name__}: {err}",
            "traceback": traceback.format_exc(),
            "hostname": socket.gethostname(),
        }
