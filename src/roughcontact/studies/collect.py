"""Gather a study directory into one labelled dataset (``task`` × ``step``).

Parameters become coordinates on ``task``, the per-path analysis
(:class:`~roughcontact.analysis.path_analysis.PathAnalysis`) data variables on ``task``
(NaN where a quantity does not exist or the task did not finish), and the per-step curves
are padded with NaN (False, "" for flags and labels) along ``step``. Tasks are in the
order of their ids, so two collects of the same study directory are identical.
"""

from __future__ import annotations

import dataclasses
import json
import math
import warnings
from pathlib import Path

import numpy as np

from .._validate import ParameterError
from ..pathdata import PER_STEP, VARIABLES
from . import store
from .schema import SWEEP_KEYS

__all__ = ["STEP_VARIABLES", "collect_study", "read_collected"]

#: The per-step variables of the task files collected along ``step``: every one of the path
#: layout's but ``status`` (in a collected study, ``status`` is the task's).
STEP_VARIABLES = tuple(name for name in PER_STEP if name != "status")
_KIND = {v.name: v.kind for v in VARIABLES}
# path-level attributes of a task file -> variable names in the collected dataset
_PATH_ATTRS = {
    "pull_off": "pull_off",
    "rms_height": "measured_rms_height",
    "rms_slope": "measured_rms_slope",
    "rms_curvature": "rms_curvature",
    "predicted_d_rep": "predicted_d_rep",
    "short_cutoff_estimate": "short_cutoff_estimate",
    "steps_not_converged": "steps_not_converged",
    "task_seconds": "task_seconds",
    "path_seconds": "path_seconds",
}
TIMINGS = ("task_seconds", "path_seconds", "solve_seconds")


def _analysis_keys():
    """Names of the path analysis' scalars, and which of them are text."""
    from ..analysis.path_analysis import PathAnalysis

    fields = [f for f in dataclasses.fields(PathAnalysis) if f.name != "warnings"]
    return [f.name for f in fields], {f.name for f in fields if f.type in (str, "str")}


def _fill_hysteresis(data, records) -> None:
    """Hysteresis of tasks analysed before the analysis had it: from their collected steps."""
    from ..analysis.hysteresis import hysteresis_from_steps

    names = ("dissipated_energy", "dissipated_energy_bound", "jumps", "energy_per_jump")
    for i, (status, _, _, steps) in enumerate(records):
        if status != "done" or "dissipated_energy" not in data:
            continue
        if not math.isnan(data["dissipated_energy"][1][i]) or "offset" not in steps:
            continue
        hy = hysteresis_from_steps(
            steps["offset"], steps["load"], steps["branch"], steps.get("jump"),
            steps.get("converged"),
        )  # fmt: skip
        values = (hy.dissipated_energy, hy.energy_uncertainty, hy.jumps, hy.energy_per_jump)
        for name, v in zip(names, values, strict=True):
            data[name][1][i] = v


def _number(value) -> float:
    if value is None:
        return math.nan
    return float(value)


#: the reason of a task whose file belongs to another study or other parameters
FOREIGN = (
    "its task file was written for another study or other parameters (its task_key is "
    "not the manifest's): ignored; run the study again with --resume to compute it"
)


DAMAGED = (
    "its task file is not a readable NetCDF file (damaged): ignored; run the study again "
    "with --resume to compute it"
)


def _read(out, task):
    """(status, reason, attrs, step arrays) of one task (a manifest entry)."""
    import xarray as xr

    path = store.task_path(out, task["id"])
    failure = store.failure_path(out, task["id"])
    key = task.get("key")
    try:
        if store.is_regular(path):
            with xr.open_dataset(path, engine="h5netcdf") as ds:
                if store.MARKER in ds.attrs:
                    if key is not None and ds.attrs.get("task_key") != key:
                        return "missing", FOREIGN, {}, {}
                    steps = {k: ds[k].values for k in STEP_VARIABLES if k in ds.variables}
                    return "done", "", dict(ds.attrs), steps
    except (OSError, ValueError, KeyError):
        pass
    except Exception:  # noqa: BLE001 - damaged bytes: h5py's checksum RuntimeError, ...
        return "missing", DAMAGED, {}, {}
    if failure.exists() or failure.is_symlink():
        try:
            if not store.is_regular(failure):
                raise OSError("not a regular file")
            record = json.loads(failure.read_text())
            if key is not None and record.get("task_key", key) != key:
                return "missing", FOREIGN, {}, {}
            reason = record.get("reason", "failed")
        except (OSError, ValueError, AttributeError):
            reason = "failed (unreadable failure record)"
        return "failed", reason, {}, {}
    return "missing", "not run or not finished (run the study again with --resume)", {}, {}


#: The keys of a manifest (``study.json``) that collecting reads, and their types.
_MANIFEST_KEYS = {"name": str, "sha256": str, "settings": dict, "tasks": list}


def _check_manifest(manifest, out: Path) -> dict:
    """The manifest if it has what collecting reads; else one ParameterError line."""
    where = f"{str(out / store.MANIFEST)!r}"
    hint = "(edited or damaged: not as 'roughcontact study run' writes it)"
    if not isinstance(manifest, dict):
        raise ParameterError(
            f"{where} is not a study manifest: expected a JSON object, got "
            f"{type(manifest).__name__} {hint}"
        )
    for key, kind in _MANIFEST_KEYS.items():
        if key not in manifest:
            raise ParameterError(f"{where} lacks the key {key!r} {hint}")
        if not isinstance(manifest[key], kind):
            raise ParameterError(
                f"{where}: {key} = {_short(manifest[key])} has the wrong type: expected "
                f"{kind.__name__} {hint}"
            )
    for i, task in enumerate(manifest["tasks"]):
        ok = (
            isinstance(task, dict)
            and isinstance(task.get("id"), str)
            and isinstance(task.get("params"), dict)
        )
        if not ok:
            raise ParameterError(
                f"{where}: tasks[{i}] = {_short(task)} is not a task: expected an object "
                f"with a string 'id' and an object 'params' {hint}"
            )
    for key in (*SWEEP_KEYS, "seed"):  # the coordinates on 'task'
        values = [t["params"].get(key) for t in manifest["tasks"]]
        ints = key in ("size", "seed")
        scalar = (int,) if ints else (str, bool, int, float, type(None))
        text = [isinstance(v, str) for v in values]
        bad = [v for v in values if not isinstance(v, scalar) or (ints and isinstance(v, bool))]
        if bad or (any(text) and not all(text)):
            value = bad[0] if bad else values
            expected = "integers" if ints else "numbers, or strings in every task"
            raise ParameterError(
                f"{where}: the tasks' {key} = {_short(value)} has the wrong type: expected "
                f"{expected} {hint}"
            )
    if "description" in manifest and not isinstance(manifest["description"], str):
        manifest["description"] = str(manifest["description"])
    return manifest


def _short(value, width: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= width else text[: width - 3] + "..."


def collect_study(out_dir, *, include_timings: bool = True):
    """One ``xarray.Dataset`` of a whole study directory.

    Parameters
    ----------
    out_dir : path-like
        A directory written by :func:`roughcontact.studies.run_study`.
    include_timings : bool
        Keep the wall-clock variables (``task_seconds``, ``path_seconds``,
        ``solve_seconds``), which differ between two runs of the same study.

    Returns
    -------
    xarray.Dataset
        Dimensions ``task`` (sorted task ids) and ``step``. Coordinates on ``task``: the
        parameters (hurst, rms_slope, short_cutoff, long_cutoff, size, pixel_size,
        contact_modulus, thickness (inf: half-space), law, adhesion_length = w/E*, range,
        work_of_adhesion, stiffness, ..., seed). Variables on ``task``: every scalar of
        the path analysis (kappa, inverse_kappa, kappa_rep, kappa_rep_hard_wall,
        kappa_rep_hard_wall_corrected, band_width, kappa_att, area_ratio, d_rep, pull_off,
        sticky (1/0), reliable (1/0), predicted_*, ...; the text ones, verdict,
        predicted_verdict and necessary_condition, as strings), analysis_warnings,
        analysis_error, measured surface statistics, steps_not_converged, n_steps,
        status ("done", "failed", "missing"; a task file whose task_key is not the
        manifest's, e.g. copied from another study, is ignored with a RuntimeWarning and
        the task counted as missing: attribute tasks_foreign), failed (True unless done),
        failure_reason,
        task_file. On ``task`` × ``step``: the per-step variables of the path layout
        (:data:`STEP_VARIABLES`: offset, load, repulsive/attractive load and area,
        perimeter, perimeter_edges, corrected_repulsive_area, mean_gap, iterations,
        converged, residual, solve_seconds, repulsive_patches, jump, branch). Areas and loads
        per A0 (loads in units of E*), lengths in units of a0.
    """
    import xarray as xr

    from .. import __version__

    out = Path(out_dir)
    manifest = _check_manifest(store.read_manifest(out), out)
    tasks = sorted(manifest["tasks"], key=lambda t: t["id"])
    if not tasks:
        raise ParameterError(f"study directory {str(out)!r} lists no tasks")
    records = [_read(out, t) for t in tasks]
    foreign = sum(r[1] == FOREIGN for r in records)
    if foreign:
        warnings.warn(
            f"{foreign} task file(s) in {str(out)!r} belong to another study or other "
            "parameters (task_key differs from the manifest's): ignored, counted as missing",
            RuntimeWarning,
            stacklevel=2,
        )
    n_steps = [len(r[3].get("offset", ())) for r in records]
    width = max(n_steps)
    coords = {"task": [t["id"] for t in tasks], "step": np.arange(width)}
    for key in (*SWEEP_KEYS, "seed"):
        values = [t["params"].get(key) for t in tasks]
        if key == "thickness":
            values = [math.inf if v is None else v for v in values]
        if all(isinstance(v, str) for v in values) or all(isinstance(v, bool) for v in values):
            coords[key] = ("task", np.array(values))
        elif key in ("size", "seed"):
            coords[key] = ("task", np.array(values, dtype=np.int64))
        else:
            coords[key] = ("task", np.array([_number(v) for v in values]))
    data = {}
    analyses = [json.loads(r[2].get("analysis", "{}") or "{}") for r in records]
    keys, text = _analysis_keys()
    for key in keys:
        if key in coords:  # rms_slope, contact_modulus: the parameters are coordinates
            continue
        if key in text:  # verdicts and notes ("" where the task has no analysis)
            data[key] = ("task", np.array([str(a.get(key) or "") for a in analyses]))
        else:
            data[key] = ("task", np.array([_number(a.get(key)) for a in analyses]))
    _fill_hysteresis(data, records)
    data["analysis_warnings"] = (
        "task",
        np.array(["; ".join(a.get("warnings", [])) for a in analyses]),
    )
    data["analysis_error"] = ("task", np.array([r[2].get("analysis_error", "") for r in records]))
    for attr, name in _PATH_ATTRS.items():
        if name in data:  # an analysis variable of the same name (pull_off) wins
            continue
        data[name] = ("task", np.array([_number(r[2].get(attr)) for r in records]))
    data["all_converged"] = (
        "task",
        np.array([bool(r[2].get("all_converged", 0)) for r in records]),
    )
    data["n_steps"] = ("task", np.array(n_steps, dtype=np.int64))
    data["status"] = ("task", np.array([r[0] for r in records]))
    data["failed"] = ("task", np.array([r[0] != "done" for r in records]))
    data["failure_reason"] = ("task", np.array([r[1] for r in records]))
    data["task_file"] = (
        "task",
        np.array(
            [
                store.task_path(".", t["id"]).name if r[0] == "done" else ""
                for t, r in zip(tasks, records, strict=True)
            ]
        ),
    )
    for name in STEP_VARIABLES:
        flag, label = _KIND[name] == "b", _KIND[name] == "U"
        fill = False if flag else ("" if label else math.nan)
        dtype = bool if flag else (object if label else float)
        block = np.full((len(tasks), width), fill, dtype=dtype)
        for i, r in enumerate(records):
            if name in r[3]:
                block[i, : n_steps[i]] = r[3][name]
        data[name] = (("task", "step"), block.astype(str) if label else block)
    ds = xr.Dataset(data, coords=coords)
    if not include_timings:
        ds = ds.drop_vars([k for k in TIMINGS if k in ds.variables])
    ds.attrs.update(
        {
            "study_name": manifest["name"],
            "study_description": manifest.get("description", ""),
            "study_sha256": manifest["sha256"],
            "study_settings": json.dumps(manifest["settings"], sort_keys=True),
            "tasks_done": int(sum(r[0] == "done" for r in records)),
            "tasks_failed": int(sum(r[0] == "failed" for r in records)),
            "tasks_missing": int(sum(r[0] == "missing" for r in records)),
            "tasks_foreign": int(foreign),
            "roughcontact_version": __version__,
            "units": "lattice units unless given: loads and areas per nominal area A0, "
            "lengths in units of the pixel size, pressures in units of E*",
        }
    )
    return ds


def read_collected(source, *, include_timings: bool = True):
    """The collected dataset of a study directory (collected now) or of a collected ``.nc``.

    Parameters
    ----------
    source : path-like
        A study directory or a file written by ``roughcontact study collect``.
    include_timings : bool
        Keep the wall-clock variables (see :func:`collect_study`).

    Raises
    ------
    ParameterError
        One line when ``source`` is neither, or the file holds no ``task`` dimension.
    """
    from .._io import read_netcdf

    src = Path(source)
    if src.is_dir():
        return collect_study(src, include_timings=include_timings)
    refusal = f"{str(src)!r} is neither a study directory nor a readable NetCDF file"
    ds = read_netcdf(src, refusal=refusal)
    if "task" not in ds.dims:
        raise ParameterError(
            f"{str(src)!r} is not a collected study (no 'task' dimension); make one with "
            "'roughcontact study collect DIR -o OUT.nc'"
        )
    if not include_timings:
        ds = ds.drop_vars([k for k in TIMINGS if k in ds.variables])
    return ds
