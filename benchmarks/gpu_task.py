"""One task of a study, timed: its path and its analysis (issue 34's paper-scale check).

Picks the task of ``--study`` (default ``studies/paper.toml``) with the given parameters
(default: the paper's reference set H = 0.5, h'rms = 0.1, lambda_s = 4, l_a = 0.005) and
runs it in this process with :func:`roughcontact.studies.task.compute_task` on
``--device``, as a study's worker does; prints the setup, path and analysis times (the
dataset's own ``*_seconds`` attributes), the solver iterations and the analysis.

``--size N`` runs the same task on an N x N grid (lambda_L = N/2 and thickness N, as the
paper's L = 2 lambda_L = thickness), e.g. 512 for a task small enough to compare the GPU
with one CPU core (``--device cpu --threads 1``: one FFT thread, one BLAS thread).
``--write-study OUT.toml`` writes instead a study file holding just that task (for
``roughcontact study run OUT.toml --device cuda``, the real Dask path).

    python benchmarks/gpu_task.py --device cuda                  # 4096², H100: ~?? s
    python benchmarks/gpu_task.py --device cpu --size 128        # a dry run
"""

from __future__ import annotations

import sys

if __name__ == "__main__":  # before NumPy loads its BLAS: see _threads.py
    import _threads

    _threads.preset_from_argv(sys.argv[1:], "--threads", default=None)

import argparse
import dataclasses
import json
import os
import re
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
PARAMS = {"hurst": 0.5, "rms_slope": 0.1, "short_cutoff": 4.0, "adhesion_length": 0.005}


def pick(study, params: dict):
    for task in study.tasks:
        if all(task.params[k] == v for k, v in params.items()):
            return task
    raise SystemExit(f"no task with {params} in {study.source}")


def resized(task, n: int):
    p = dict(task.params, size=n, long_cutoff=n / 2, thickness=float(n))
    return dataclasses.replace(task, params=p)


def write_study(path: Path, source: Path, params: dict, size: int | None) -> None:
    """The study file with one value per swept key (and ``size``), so it holds one task."""
    text = source.read_text()
    for key, value in params.items():
        text = re.sub(rf"(?m)^{key}\s*=\s*\[[^\]]*\]", f"{key} = {value!r}", text)
    if size:
        for key, value in (("size", size), ("long_cutoff", size / 2), ("thickness", size)):
            text = re.sub(rf"(?m)^{key}\s*=\s*[^#\n]*", f"{key} = {float(value)!r} ", text)
        text = re.sub(r"(?m)^size = ([0-9]+)\.0", r"size = \1", text)
    text = re.sub(r'(?m)^name\s*=\s*"[^"]*"', 'name = "one-task"', text, count=1)
    path.write_text(text)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--study", type=Path, default=ROOT / "studies" / "paper.toml")
    ap.add_argument("--device", default="cuda")
    ap.add_argument("--size", type=int, default=None, help="grid side (default: the study's)")
    ap.add_argument("--threads", type=int, default=None, help="FFT and BLAS threads")
    ap.add_argument("--dtype", choices=["float64", "float32"], default=None)
    ap.add_argument("--write-study", type=Path, metavar="OUT.toml")
    ap.add_argument(
        "--runs",
        type=int,
        default=1,
        help="run the task this many times in this process and report each: on an "
        "accelerator the first compiles every grid's loops (a study's worker does that once "
        "per grid), the later ones are what each further task of a study costs",
    )
    ap.add_argument("--json", metavar="OUT")
    args = ap.parse_args(argv)
    if args.threads:
        os.environ["ROUGHCONTACT_FFT_WORKERS"] = str(args.threads)
    if args.write_study:
        write_study(args.write_study, args.study, PARAMS, args.size)
        return 0
    from roughcontact.studies import load_study
    from roughcontact.studies.task import compute_task

    task = pick(load_study(args.study), PARAMS)
    if args.size:
        task = resized(task, args.size)
    if args.dtype:
        solver = dict(task.settings["solver"], dtype=args.dtype)
        task = dataclasses.replace(task, settings=dict(task.settings, solver=solver))
    task = dataclasses.replace(task, device=None if args.device == "cpu" else args.device)
    rows = []
    for run in range(max(args.runs, 1)):
        t0 = time.perf_counter()
        ds = compute_task(task)
        rows.append(report(task, ds, time.perf_counter() - t0, args, run))
    if args.json:
        Path(args.json).write_text(json.dumps(rows[0] if len(rows) == 1 else rows, indent=1))
    return 0


def report(task, ds, wall: float, args, run: int) -> dict:
    """The task's times and answers (the dataset's own ``*_seconds``), printed in a line."""
    a = ds.attrs
    analysis = json.loads(a["analysis"]) if a["analysis"] else {}
    row = {
        "size": task.params["size"],
        "device": args.device,
        "threads": args.threads,
        "run": run,
        "wall_seconds": wall,
        **{k: float(a[k]) for k in ("setup_seconds", "path_seconds", "analysis_seconds")},
        "steps": int(ds.sizes["step"]),
        "iterations": int(np.asarray(ds["iterations"].values).sum()),
        "steps_not_converged": int(a["steps_not_converged"]),
        "analysis_error": a["analysis_error"],
        "kappa": analysis.get("kappa"),
        "kappa_rep": analysis.get("kappa_rep"),
        "kappa_rep_hard_wall": analysis.get("kappa_rep_hard_wall"),
    }
    print(
        f"task {task.params['size']}² on {args.device} (threads {args.threads}, run {run + 1}"
        f"{', compiles' if run == 0 and args.device != 'cpu' else ''}): "
        f"{wall:.1f} s = setup {row['setup_seconds']:.1f} + path {row['path_seconds']:.1f} "
        f"({row['steps']} steps, {row['iterations']} iterations, "
        f"{row['steps_not_converged']} not converged) + analysis {row['analysis_seconds']:.1f}; "
        f"kappa {row['kappa']}, kappa_rep {row['kappa_rep']}, hard wall "
        f"{row['kappa_rep_hard_wall']} {row['analysis_error']}",
        flush=True,
    )
    return row


if __name__ == "__main__":
    sys.exit(main())
