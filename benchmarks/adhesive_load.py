"""Load-controlled adhesive solves and paths beside offset-controlled ones (README.md here).

Two parts, both on the issue's surface ``self_affine((n, n), hurst=0.8, rms_slope=0.1,
short_cutoff=4, seed=7)`` (E* = 1, a0 = 1) with ``SmoothLJ93.from_adhesion_length(la)``:

* **cold cases**: ``rc.solve(h, sub, law, load=N)`` from the undeformed substrate (from 128²
  on it starts from the same load solved on the 2x2-coarsened grid: those iterations are
  printed beside the fine grid's, and the time ratio includes them; ``--no-coarse-start``
  turns that start off for the A/B), then the
  offset-controlled cold solve at the offset it found (the same state: the largest gap
  difference is printed), and with ``--nested`` the root search over nested
  offset-controlled solves that load control used before (forced by passing a minimiser that
  is not ``minimize_energy`` itself): iterations, inner solves, seconds, status, state.
* **paths**: ``approach_retract(loads=...)`` over ``--path-loads`` (warm-started steps), and
  ``approach_retract(offsets=...)`` over the offsets that path found (the same states):
  iterations per step, median of the warm steps (the first step is cold in both) and the
  ratio load / offset.

Counts are the figures to compare (the machine is shared); seconds are printed beside
them. Run alone or from ``adhesive.py --load-control`` (the same rows beside the peers).

    python benchmarks/adhesive_load.py --sizes 128 256 --adhesion-lengths 0.005 0.05 --nested
    python benchmarks/adhesive_load.py --law exponential --sizes 128 --nested  # a hard core
    python benchmarks/adhesive_load.py --law dugdale --surface rough --sizes 128 \
        --adhesion-lengths 0.01 --loads 0 1e-3   # the cold hard core that crawled into contact

``--surface rough`` takes ``self_affine((n, n), hurst=0.5, rms_slope=0.2, short_cutoff=4,
seed=5)`` instead, where a cold Maugis-Dugdale solve at load 0 once crawled through the jump
into contact (1210 iterations at 128², against 25 offset-controlled) and now restarts from
a hard-wall state (its message says so).
"""

from __future__ import annotations

import argparse
import functools
import sys
import time

import numpy as np


def issue_surface(n: int, name: str = "issue") -> np.ndarray:
    """The issue's surface, or ``rough`` (H 0.5, h'rms 0.2, seed 5: see the docstring)."""
    import roughcontact as rc

    if name == "rough":
        return rc.self_affine((n, n), hurst=0.5, rms_slope=0.2, short_cutoff=4, seed=5)
    return rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=7)


def make_law(name: str, la: float):
    """``lj93smooth``: the paper's wall at adhesion length ``la``; ``exponential``: the
    hard-core Exponential law with work of adhesion ``la`` E* a0 and range a0;
    ``dugdale``: Maugis-Dugdale with work of adhesion ``la`` E* a0 and range a0/2."""
    import roughcontact as rc

    if name == "dugdale":
        return rc.MaugisDugdale(work_of_adhesion=la, range=0.5)
    if name == "exponential":
        return rc.Exponential(work_of_adhesion=la, range=1.0)
    return rc.SmoothLJ93.from_adhesion_length(la)


def _nested(h, sub, law, load, tol, max_iter):
    """Load control by the root search over nested offset solves (the method before)."""
    import importlib

    module = "bounded" if law.hard_core else "smooth"
    solver = importlib.import_module(f"roughcontact.solvers.{module}")
    one = solver.minimize_energy_bounded if law.hard_core else solver.minimize_energy
    load_control = importlib.import_module("roughcontact.solvers.load_control")
    inner = {"solves": 0}

    def minimize(*args, **kwargs):
        inner["solves"] += 1
        return one(*args, **kwargs)

    res = load_control.solve_at_load(
        functools.partial(minimize), h, sub, law, load=load, initial=None, tol=tol,
        max_iter=max_iter, callback=None,
    )  # fmt: skip
    return res, inner["solves"]


class _CoarseCount:
    """Counts the iterations of the nested iteration's coarse solves (load_control's
    ``_coarse_start``: ``result.iterations`` counts the fine grid's, as the hard wall's
    nested iteration does); ``enabled=False`` turns the nested start off (the A/B)."""

    def __init__(self, enabled=True):
        import importlib

        self.lc = importlib.import_module("roughcontact.solvers.load_control")
        self.enabled, self.iterations = enabled, 0

    def __enter__(self):
        self.original = self.lc._coarse_start

        def counting(*args, **kwargs):
            out = self.original(*args, **kwargs) if self.enabled else None
            self.iterations += 0 if out is None else out[2]
            return out

        self.lc._coarse_start = counting
        return self

    def __exit__(self, *exc):
        self.lc._coarse_start = self.original


def _row(kind, res, seconds, extra=""):
    p = float(np.abs(res.pressure).max())
    return (
        f"{kind:<22} {res.iterations:>6} {seconds:>8.2f} {res.status.value:<15} "
        f"{res.load:>+11.4e} {100 * res.repulsive_area:>7.2f} {p:>9.3g} {res.offset:>10.6f} {extra}"
    )


COLD_HEADER = (
    f"{'n la load | solve':<22} {'its':>6} {'s':>8} {'status':<15} {'load':>11} {'A_rep%':>7} "
    f"{'max|p|':>9} {'offset':>10}"
)


def cold_cases(sizes, adhesion_lengths, loads, tol, max_iter, nested, log=print,
               law_name="lj93smooth", coarse_start=True, surface="issue"):
    """The issue's cold cases: one dict per (n, la, load)."""
    import roughcontact as rc

    out = []
    log(COLD_HEADER)
    for n in sizes:
        h = issue_surface(n, surface)
        sub = rc.Substrate((n, n))
        for la in adhesion_lengths:
            law = make_law(law_name, la)
            for load in loads:
                log(f"# n={n} {law_name} la={la:g} load={load:g}")
                with _CoarseCount(coarse_start) as coarse:
                    t0 = time.perf_counter()
                    res = rc.solve(h, sub, law, load=load, tol=tol, max_iter=max_iter)
                    t_load = time.perf_counter() - t0
                restarted = "; restarted from a hard wall" if "hard-wall" in res.message else ""
                log(_row("  load control", res, t_load,
                         (f"+ {coarse.iterations} its on the coarse grid" if coarse.iterations
                          else "") + restarted))  # fmt: skip
                t0 = time.perf_counter()
                same = rc.solve(h, sub, law, offset=res.offset, tol=tol, max_iter=max_iter)
                t_off = time.perf_counter() - t0
                gap = float(np.abs(same.gap - res.gap).max())
                log(_row("  offset (same d)", same, t_off, f"max|dgap| {gap:.1e}"))
                row = dict(
                    n=n, law=law_name, adhesion_length=la, load=load,
                    load_iterations=res.iterations,
                    load_seconds=t_load, load_status=res.status.value, load_reached=res.load,
                    repulsive_area=res.repulsive_area, offset=res.offset,
                    max_pressure=float(np.abs(res.pressure).max()),
                    offset_iterations=same.iterations, offset_seconds=t_off,
                    same_state_max_gap_difference=gap,
                    ratio=res.iterations / max(same.iterations, 1),
                    coarse_iterations=coarse.iterations, time_ratio=t_load / t_off,
                    surface=surface, restarted_from_hard_wall=bool(restarted),
                )  # fmt: skip
                if nested:
                    t0 = time.perf_counter()
                    old, solves = _nested(h, sub, law, load, tol, max_iter)
                    t_old = time.perf_counter() - t0
                    log(_row("  nested root search", old, t_old, f"{solves} inner solves"))
                    row.update(nested_iterations=old.iterations, nested_seconds=t_old,
                               nested_solves=solves, nested_status=old.status.value)  # fmt: skip
                log(f"  ratio load/offset iterations {row['ratio']:.2f} (this grid's), "
                    f"time {row['time_ratio']:.2f} (coarse solve included)")
                out.append(row)
    return out


def paths(sizes, adhesion_lengths, path_loads, tol, max_iter, log=print, law_name="lj93smooth",
          surface="issue"):
    """Load- vs offset-controlled paths through the same states: one dict per (n, la)."""
    import roughcontact as rc

    out = []
    for n in sizes:
        h = issue_surface(n, surface)
        sub = rc.Substrate((n, n))
        for la in adhesion_lengths:
            law = make_law(law_name, la)
            t0 = time.perf_counter()
            by_load = rc.approach_retract(h, sub, law, loads=path_loads, retract=False,
                                          tol=tol, max_iter=max_iter)  # fmt: skip
            t_load = time.perf_counter() - t0
            offsets = by_load["offset"].values
            t0 = time.perf_counter()
            by_offset = rc.approach_retract(h, sub, law, offsets=offsets, retract=False,
                                            tol=tol, max_iter=max_iter)  # fmt: skip
            t_off = time.perf_counter() - t0
            its_l = [int(i) for i in by_load["iterations"].values]
            its_o = [int(i) for i in by_offset["iterations"].values]
            med_l, med_o = float(np.median(its_l[1:])), float(np.median(its_o[1:]))
            row = dict(
                n=n, law=law_name, adhesion_length=la, loads=[float(x) for x in path_loads],
                load_iterations=its_l, offset_iterations=its_o, load_seconds=t_load,
                offset_seconds=t_off, median_warm_load=med_l, median_warm_offset=med_o,
                ratio=med_l / max(med_o, 1.0),
                converged=bool(all(by_load["converged"].values)),
                load_error=float(np.max(np.abs(by_load["load"].values - path_loads))),
            )  # fmt: skip
            log(
                f"# path n={n} {law_name} la={la:g}: loads {path_loads[0]:g}..{path_loads[-1]:g} "
                f"({len(path_loads)} steps): load-controlled its {its_l} ({t_load:.2f} s), "
                f"offset-controlled its {its_o} ({t_off:.2f} s); median warm step "
                f"{med_l:.0f} vs {med_o:.0f} = {row['ratio']:.2f}x; converged "
                f"{row['converged']}, max |load error| {row['load_error']:.1e}"
            )
            out.append(row)
    return out


def add_arguments(ap, prefix=""):
    """The options (``prefix`` "lc-" inside adhesive.py, where --sizes etc. are taken)."""
    ap.add_argument(f"--{prefix}loads", type=float, nargs="+", default=[1e-3, 0.0],
                    help="loads (mean pressure / E*) of the cold solves")  # fmt: skip
    ap.add_argument(f"--{prefix}path-loads", type=float, nargs="+",
                    default=[0.0, 5e-4, 1e-3, 1.5e-3, 2e-3],
                    help="the load-controlled path's loads (mean pressure / E*)")  # fmt: skip
    ap.add_argument("--nested", action="store_true",
                    help="also time the nested root search (the method before)")  # fmt: skip
    ap.add_argument("--no-coarse-start", action="store_true",
                    help="cold load-controlled solves without the nested iteration's coarse "
                    "start (the method before it: A/B)")  # fmt: skip


def run(sizes, adhesion_lengths, loads, path_loads, tol, max_iter, nested, log=print,
        law_name="lj93smooth", coarse_start=True, surface="issue"):
    """Both parts; a 16² path first (untimed) loads what a first path imports."""
    import roughcontact as rc

    h = issue_surface(16)
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    rc.approach_retract(h, rc.Substrate((16, 16)), law, loads=[0.0, 1e-3], retract=False)
    cold = cold_cases(sizes, adhesion_lengths, loads, tol, max_iter, nested, log, law_name,
                      coarse_start, surface)  # fmt: skip
    path_loads = np.asarray(path_loads, dtype=float)
    with _CoarseCount(coarse_start):
        path = paths(sizes, adhesion_lengths, path_loads, tol, max_iter, log, law_name, surface)
    return dict(cold=cold, paths=path)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[128, 256])
    ap.add_argument("--adhesion-lengths", type=float, nargs="+", default=[0.005, 0.05])
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-iter", type=int, default=5000)
    ap.add_argument("--law", choices=("lj93smooth", "exponential", "dugdale"),
                    default="lj93smooth", help="exponential: hard core, work of adhesion la "
                    "E* a0, range a0; dugdale: Maugis-Dugdale, la E* a0, range a0/2")  # fmt: skip
    ap.add_argument("--surface", choices=("issue", "rough"), default="issue",
                    help="rough: H 0.5, h'rms 0.2, seed 5 (see above)")  # fmt: skip
    ap.add_argument("--json", metavar="OUT")
    add_arguments(ap)
    args = ap.parse_args(argv)
    out = run(args.sizes, args.adhesion_lengths, args.loads, args.path_loads, args.tol,
              args.max_iter, args.nested, log=lambda s: print(s, flush=True),
              law_name=args.law, coarse_start=not args.no_coarse_start,
              surface=args.surface)  # fmt: skip
    if args.json:
        import json

        with open(args.json, "w") as fh:
            json.dump(out, fh, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
