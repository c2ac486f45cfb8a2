"""Cold hard-core load-controlled solves against offset-controlled ones (issue 39, item 2).

For every surface × law × load: ``rc.solve(h, sub, law, load=N)`` from the undeformed
substrate, then the cold offset-controlled solve ``rc.solve(h, sub, law, offset=d)`` at the
offset ``d`` that the load solve reached. Printed per case: the load solve's iterations on
the fine grid (``result.iterations``; its nested start's coarse grid is not counted, as for
the hard wall), whether it started again from a hard-wall state (its message says so),
the offset-controlled solve's iterations, the ratio (load / offset-controlled, the
latter at least 1), the state the offset-controlled solve ends in (``same``: within
:data:`SAME_STATE` of the load solve's gap; ``full``: full contact at offset mean(h), where
it takes 0-1 iterations; ``other``: another equilibrium at that offset) with the largest gap
difference, and for a restarted solve the offset-controlled solve from the same hard-wall
state (hard-wall + adhesive iterations, and whether it ends in the load solve's state).
The summary per size: the iterations in all, the restarts, and over the cases where both
converged the median and largest ratio and the cases above issue 39's 2× by state.

The surfaces: ``self_affine((n, n), hurst=H, rms_slope=s, short_cutoff=4, seed=k)`` with
(H, s, k) = (0.8, 0.1, 7), (0.5, 0.2, 3), (0.3, 0.05, 4), (0.8, 0.3, 11). The laws:
Maugis–Dugdale and hard-core Exponential with (work of adhesion / E* a0, range / a0) =
(0.01, 0.5), (0.002, 0.2), (0.05, 1.0) and (0.01, 0.5), (0.002, 0.2), (0.05, 0.2). E* = a0 = 1.

    python benchmarks/cold_load_sweep.py --sizes 128 256          # 144 cold solves, ~1 min
    python benchmarks/cold_load_sweep.py --sizes 128 --laws exp --json sweep.json

Iteration counts are the figures (the machine may be shared); seconds are printed beside
them.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time

import numpy as np

SURFACES = ((0.8, 0.1, 7), (0.5, 0.2, 3), (0.3, 0.05, 4), (0.8, 0.3, 11))
LAWS = (
    ("md", 0.01, 0.5),
    ("md", 0.002, 0.2),
    ("md", 0.05, 1.0),
    ("exp", 0.01, 0.5),
    ("exp", 0.002, 0.2),
    ("exp", 0.05, 0.2),
)
#: Largest gap difference (a0) of two states called the same.
SAME_STATE = 1e-6


def make_law(kind: str, work: float, reach: float):
    """Maugis–Dugdale (``md``) or hard-core Exponential (``exp``)."""
    import roughcontact as rc

    cls = rc.MaugisDugdale if kind == "md" else rc.Exponential
    return cls(work_of_adhesion=work, range=reach)


def one_case(h, substrate, law, load: float, tol: float, max_iter: int) -> dict:
    """The load-controlled cold solve and the offset-controlled ones at its offset: cold,
    and, where the load solve started again from a hard-wall state, from that same state
    (the offset-controlled solve that can end in the same state: the unloading branch)."""
    import roughcontact as rc
    from roughcontact.solvers.load_control import RESTARTED, hard_wall_start_load

    t0 = time.perf_counter()
    by_load = rc.solve(h, substrate, law, load=load, tol=tol, max_iter=max_iter)
    t1 = time.perf_counter()
    row = {
        "load_status": by_load.status.value,
        "load_iterations": by_load.iterations,
        "restarted": RESTARTED in by_load.message,
        "load_seconds": t1 - t0,
        "offset": by_load.offset,
        "load_reached": by_load.load,
        "repulsive_area": by_load.repulsive_area,
        # a hard core at offset mean(h) is in full contact: every gap zero, any load from
        # the least wall reaction up holds there (the offset-controlled solve takes 0-1)
        "full_contact_at_mean": bool(abs(by_load.offset - float(np.mean(h))) <= 1e-9),
    }
    if by_load.status.value != "converged":
        return row
    gap = np.asarray(by_load.gap)
    by_offset = rc.solve(h, substrate, law, offset=by_load.offset, tol=tol, max_iter=max_iter)
    row.update(
        offset_status=by_offset.status.value,
        offset_iterations=by_offset.iterations,
        offset_seconds=time.perf_counter() - t1,
        ratio=by_load.iterations / max(by_offset.iterations, 1),
        max_gap_difference=float(np.max(np.abs(gap - by_offset.gap))),
        offset_repulsive_area=by_offset.repulsive_area,
    )
    if row["restarted"]:
        start = rc.polonsky_keer(h, substrate, load=hard_wall_start_load(load, law))
        again = rc.solve(h, substrate, law, offset=by_load.offset, initial=start, tol=tol,
                         max_iter=max_iter)  # fmt: skip
        row.update(
            hard_wall_iterations=start.iterations,
            unloading_status=again.status.value,
            unloading_iterations=again.iterations,
            unloading_gap_difference=float(np.max(np.abs(gap - again.gap))),
        )
    return row


def state_kind(row: dict) -> str:
    """``same`` (the cold offset-controlled solve ends in the load solve's state),
    ``full`` (full contact at offset mean(h): a trivial offset-controlled solve) or
    ``other`` (another equilibrium at that offset)."""
    if row["full_contact_at_mean"]:
        return "full"
    return "same" if row["max_gap_difference"] <= SAME_STATE else "other"


def unloading_ratio(row: dict) -> float | None:
    """Load solve / the offset-controlled solve from the same hard-wall state (its
    hard-wall iterations counted), where that ends in the load solve's state."""
    if row.get("unloading_status") != "converged":
        return None
    if row["unloading_gap_difference"] > SAME_STATE:
        return None
    offset_controlled = row["hard_wall_iterations"] + row["unloading_iterations"]
    return row["load_iterations"] / max(offset_controlled, 1)


def summary(rows: list[dict]) -> dict:
    """Totals and the ratio's distribution over the cases where both solves converged;
    the cases above 2x by :func:`state_kind`, and the unloading comparison's ratios."""
    both = [r for r in rows if r.get("offset_status") == "converged"]
    ratios = [r["ratio"] for r in both]
    above = [r for r in both if r["ratio"] > 2.0]
    return {
        "cases": len(rows),
        "load_iterations": sum(r["load_iterations"] for r in rows),
        "restarts": sum(r["restarted"] for r in rows),
        "both_converged": len(both),
        "median_ratio": statistics.median(ratios) if ratios else None,
        "largest_ratio": max(ratios) if ratios else None,
        "above_2x": len(above),
        "above_2x_by_state": {k: sum(state_kind(r) == k for r in above)
                              for k in ("same", "full", "other")},  # fmt: skip
        "unloading_ratios": [round(x, 2) for r in rows if (x := unloading_ratio(r)) is not None],
        "statuses": sorted({r["load_status"] for r in rows}),
    }


def case_line(row: dict) -> str:
    """One printed line per case."""
    head = (f"{row['n']:4d} {row['hurst']:4.1f} {row['rms_slope']:5.2f} {row['law']:>4} "
            f"{row['work']:5.3f}/{row['range']:3.1f} {row['load']:+8.1e} "
            f"{row['load_status'][:10]:>10} {row['load_iterations']:5d} "
            f"{'yes' if row['restarted'] else 'no':>3}")  # fmt: skip
    seconds = row["load_seconds"] + row.get("offset_seconds", 0.0)
    if "ratio" not in row:
        return f"{head} {'-':>6} {'-':>6} {'-':>5} {'-':>9} {'-':>12} {seconds:6.2f}"
    unloading = "-"
    if "unloading_iterations" in row:
        same = "same" if row["unloading_gap_difference"] <= SAME_STATE else "other"
        unloading = f"{row['hard_wall_iterations']}+{row['unloading_iterations']} {same}"
    return (f"{head} {row['offset_iterations']:6d} {row['ratio']:6.2f} {state_kind(row):>5} "
            f"{row['max_gap_difference']:9.1e} {unloading:>12} {seconds:6.2f}")  # fmt: skip


def summary_line(n: int, s: dict) -> str:
    """The summary of one size."""
    spread = "no ratio"
    if s["both_converged"]:
        by = s["above_2x_by_state"]
        spread = (f"median ratio {s['median_ratio']:.2f}, largest {s['largest_ratio']:.2f}, "
                  f"{s['above_2x']} above 2x ({by['same']} in the same state, {by['full']} in "
                  f"full contact at mean(h), {by['other']} ending in another state than the "
                  f"cold offset-controlled solve)")  # fmt: skip
    unloading = ", ".join(f"{x:.2f}" for x in s["unloading_ratios"]) or "none"
    return (f"# n={n}: {s['cases']} cold load solves, {s['load_iterations']} fine-grid "
            f"iterations, {s['restarts']} restarted from a hard-wall state; where both "
            f"converged ({s['both_converged']}): {spread}; restarted solves against the "
            f"offset-controlled solve from the same hard-wall state, where it ends in the "
            f"same state: {unloading}; load-solve statuses {', '.join(s['statuses'])}")  # fmt: skip


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[128, 256])
    parser.add_argument("--loads", type=float, nargs="+", default=[-1e-4, 0.0, 1e-3],
                        help="mean pressures / E* (default -1e-4 0 1e-3)")  # fmt: skip
    parser.add_argument("--laws", choices=("md", "exp", "all"), default="all")
    parser.add_argument("--tol", type=float, default=1e-8)
    parser.add_argument("--max-iter", type=int, default=5000)
    parser.add_argument("--json", metavar="OUT", help="write every case and the summaries")
    args = parser.parse_args(argv)
    for name, values in (("--sizes", args.sizes), ("--max-iter", [args.max_iter])):
        if min(values) < 8:
            parser.error(f"{name} must be >= 8, got {min(values)}")
    if not 0 < args.tol < 1:
        parser.error(f"--tol must lie in (0, 1), got {args.tol}")
    if args.json and os.path.lexists(args.json):
        parser.error(f"--json {args.json} exists: name a new file (nothing is replaced)")
    import roughcontact as rc

    laws = [law for law in LAWS if args.laws in ("all", law[0])]
    out = {"cases": [], "summaries": {}}
    print(f"{'n':>4} {'H':>4} {'hrms':>5} {'law':>14} {'load':>8} {'status':>10} {'it':>5} "
          f"{'rst':>3} {'off it':>6} {'ratio':>6} {'state':>5} {'max dgap':>9} "
          f"{'unloading':>12} {'t[s]':>6}")  # fmt: skip
    for n in args.sizes:
        rows = []
        for hurst, slope, seed in SURFACES:
            h = rc.self_affine((n, n), hurst=hurst, rms_slope=slope, short_cutoff=4, seed=seed)
            substrate = rc.Substrate(h.shape)
            for kind, work, reach in laws:
                law = make_law(kind, work, reach)
                for load in args.loads:
                    row = one_case(h, substrate, law, load, args.tol, args.max_iter)
                    row.update(n=n, hurst=hurst, rms_slope=slope, seed=seed, law=kind,
                               work=work, range=reach, load=load)  # fmt: skip
                    rows.append(row)
                    print(case_line(row), flush=True)
        s = summary(rows)
        out["cases"] += rows
        out["summaries"][str(n)] = s
        print(summary_line(n, s), flush=True)
    if args.json:
        with open(args.json, "x") as f:  # never replaces a file
            json.dump(out, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
