"""CPU proxy of a GPU iteration's overheads: host syncs and arrays created per iteration.

On a GPU every conversion of a device array to a Python scalar (``float(x)``, ``if x``,
``int(x)``, an index) waits for the device (a host sync), and every array the step
creates is a kernel launch and an allocation. Both are counted here without a GPU, on
``array_api_strict`` arrays (a strict array-API library on the CPU, standing for CuPy):
calls of ``Array.__float__``/``__bool__``/``__int__``/``__index__``/``__complex__`` and
conversions to NumPy (``__array__``, ``__dlpack__``: several scalars fetched at once) are
"syncs"; those conversions of more than a few elements are also "host copies"; and every
array created (``Array._new``) is counted, those of more than a few elements also as
"fields" (a pass over a field: the others are scalars, among them the one or two arrays
array_api_strict makes for each Python or 0-d scalar operand of a field operation,
which CuPy passes to the kernel instead).

"Per iteration" is the marginal count: the same solve run to ``--iterations`` and to
twice that many iterations (``--iterations``, default 6; ``--tol`` 1e-15, which none of
these problems meets in 12 iterations at 128²: with 20 and 40, as before, several
converged before 40 and the difference was over a few iterations), the difference
divided by the extra iterations, so the set-up and the final result record are not
counted. The
"whole" columns count a whole solve at the default tolerance (set-up, exact refreshes,
the convergence test and the result record included) per iteration. Load control's
outer search runs whole inner solves; its count is per inner iteration.

    python benchmarks/host_syncs.py                 # every solver, 128²
    python benchmarks/host_syncs.py --size 64 --json syncs.json
    python benchmarks/host_syncs.py --only smooth --by-line   # per source line

``--by-line`` charges every array, field and sync to the innermost frame in
roughcontact's source that is not a helper (``file:line``; a helper's own line follows
"via"), so that the counts can be attributed to the operations of the method (an array
made inside array_api_strict or array_api_compat is charged to the solver line that
called it); ``--top`` lines are shown per solver, and ``--json`` keeps them all.

Targets (issue 34): at most 2 syncs and 40 arrays per iteration for every solver.
"""

from __future__ import annotations

import argparse
import collections
import contextlib
import json
import os
import sys

import roughcontact as rc

SYNCS = ("__float__", "__bool__", "__int__", "__index__", "__complex__")
COPIES = ("__array__", "__dlpack__")
#: conversions of arrays of more than this many elements count as host copies; arrays
#: created of more elements count as "fields" too (the others are scalars: array_api_strict
#: makes one or two for each Python or 0-d scalar operand of an operation on a field,
#: where CuPy passes the scalar to the one kernel)
SMALL = 16
#: the counts measured
KEYS = ("syncs", "copies", "arrays", "fields")


#: the package's source folder: frames there are the solver code an array is charged to
PACKAGE = os.path.dirname(os.path.abspath(rc.__file__)) + os.sep


#: helpers charged to their caller (with themselves named: "caller:line via helper:line")
HELPERS = ("_backend.py", os.path.join("solvers", "reductions.py"))


def _site():
    """``file:line`` of the innermost frame in roughcontact's code that is not a helper
    (:data:`HELPERS`): the solver line that made the array or the sync; where a helper
    made it, ``... via helper:line`` names the helper's line too."""
    frame, via = sys._getframe(2), None
    while frame is not None:
        path = frame.f_code.co_filename
        if path.startswith(PACKAGE):
            here = f"{path[len(PACKAGE) :]}:{frame.f_lineno}"
            if not path.endswith(HELPERS):
                return here if via is None else f"{here} via {via}"
            via = via or here
        frame = frame.f_back
    return via or "(outside roughcontact)"


@contextlib.contextmanager
def counting(by_line: bool = False):
    """Counts of syncs, host copies and arrays created by array_api_strict in the block;
    ``by_line``: also ``counts["lines"][kind][file:line]`` (see :func:`_site`)."""
    from array_api_strict._array_object import Array

    counts = {"syncs": 0, "copies": 0, "arrays": 0, "fields": 0}
    lines = {kind: collections.Counter() for kind in ("syncs", "arrays", "fields")}
    saved = {name: Array.__dict__[name] for name in (*SYNCS, *COPIES, "_new")}

    def wrap(name, copy=False):
        original = saved[name]

        def hook(self, *args, **kwargs):
            # any transfer waits for the device; more than a few elements is also a copy
            counts["syncs"] += 1
            if by_line:
                lines["syncs"][_site()] += 1
            if copy and (self.size is None or self.size > SMALL):
                counts["copies"] += 1
            return original(self, *args, **kwargs)

        return hook

    for name in SYNCS:
        setattr(Array, name, wrap(name))
    for name in COPIES:
        setattr(Array, name, wrap(name, copy=True))
    new = saved["_new"].__func__

    def counted_new(cls, *args, **kwargs):
        counts["arrays"] += 1
        site = _site() if by_line else None
        if by_line:
            lines["arrays"][site] += 1
        out = new(cls, *args, **kwargs)
        if out.size is None or out.size > SMALL:  # a pass over a field, not a scalar
            counts["fields"] += 1
            if by_line:
                lines["fields"][site] += 1
        return out

    Array._new = classmethod(counted_new)
    try:
        yield counts
    finally:
        for name, value in saved.items():
            setattr(Array, name, value)
        if by_line:
            counts["lines"] = lines


def problems(n: int):
    """(name, solve(max_iter, tol) -> result) for every solver, on array_api_strict heights."""
    import array_api_strict as xp

    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    hs = xp.asarray(h)
    sub = rc.Substrate((n, n))
    top = float(h.max())
    smooth = rc.SmoothLJ93.from_adhesion_length(0.005)
    exponential = rc.Exponential(work_of_adhesion=0.01, range=0.4)
    sphere = xp.asarray(rc.sphere((n, n), 0.6 * n))

    def solve(heights, law, **control):
        return lambda max_iter, tol: rc.solve(
            heights, sub, law, max_iter=max_iter, tol=tol, **control
        )

    return [
        ("hardwall-load", solve(hs, rc.HardWall(), load=2e-3), False),
        ("hardwall-offset", solve(hs, rc.HardWall(), offset=top - 0.3 * float(h.std())), False),
        ("smooth", solve(hs, smooth, offset=top + 0.6), False),
        ("bounded", solve(hs, exponential, offset=top - 0.1), False),
        ("load-control", solve(sphere, exponential, load=2e-4), True),
    ]


def _fresh(run, *args):
    """``run(*args)`` with no operands cached from an earlier run (``_backend.constant``'s
    arrays: each run makes its own, so that they cancel in the marginal counts and count
    as set-up in a whole solve)."""
    from roughcontact import _backend

    getattr(_backend, "_CONSTANTS", {}).clear()
    return run(*args)


def _per_line(b, a, divisor):
    """The per-line counters of ``b`` less those of ``a`` (or none), per ``divisor``."""
    out = {}
    for kind, counter in b["lines"].items():
        diff = counter.copy()
        if a is not None:
            diff.subtract(a["lines"][kind])
        out[kind] = {k: v / divisor for k, v in diff.most_common() if v}
    return out


def measure_whole(run, iterations: int, by_line: bool = False) -> dict:
    """Counts per iteration of a whole solve at the default tolerance."""
    with counting(by_line) as c:
        res = _fresh(run, iterations * 40, None)
    its = max(res.iterations, 1)
    got = {k: c[k] / its for k in KEYS} | {"iterations": res.iterations}
    if by_line:
        got["lines"] = _per_line(c, None, its)
    return got


def measure(run, iterations: int, whole: bool, tol: float = 1e-15, by_line: bool = False) -> dict:
    """Marginal counts per iteration (``whole``: per inner iteration of a full solve);
    ``by_line``: also per source line (``result["lines"][kind]``, see :func:`counting`)."""
    if whole:  # load control: whole inner solves, counted per inner iteration
        return measure_whole(run, iterations, by_line)
    with counting(by_line) as a:
        ra = _fresh(run, iterations, tol)
    with counting(by_line) as b:
        rb = _fresh(run, 2 * iterations, tol)
    extra = rb.iterations - ra.iterations
    if extra <= 0:
        raise RuntimeError(f"no extra iterations ({ra.iterations} -> {rb.iterations})")
    got = {k: (b[k] - a[k]) / extra for k in KEYS} | {"iterations": rb.iterations}
    if by_line:
        got["lines"] = _per_line(b, a, extra)
    return got


def print_lines(name: str, lines: dict, top: int) -> None:
    """The ``top`` source lines of each kind, per iteration, largest first."""
    for kind, per in lines.items():
        shown = list(per.items())[:top]
        rest = sum(per.values()) - sum(v for _, v in shown)
        print(f"  {name} {kind} per iteration by line ({sum(per.values()):.2f} in all):")
        for site, v in shown:
            print(f"    {v:7.2f}  {site}")
        if len(per) > top:
            print(f"    {rest:7.2f}  ({len(per) - top} more lines)")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--iterations", type=int, default=6)
    ap.add_argument("--only", nargs="*", help="solver names to run (default: all)")
    ap.add_argument("--tol", type=float, default=1e-15, help="tolerance of the marginal runs")
    ap.add_argument("--json", metavar="OUT")
    ap.add_argument(
        "--by-line",
        action="store_true",
        help="also the counts per roughcontact source line (file:line that made each array "
        "or sync), marginal and whole",
    )
    ap.add_argument("--top", type=int, default=25, help="lines shown per solver with --by-line")
    args = ap.parse_args(argv)
    rows = {}
    print(f"array_api_strict, {args.size}², marginal counts per iteration")
    head = f"{'solver':>16} {'syncs':>7} {'copies':>7} {'arrays':>7} {'fields':>7}"
    print(head + "   whole: syncs arrays fields  its")
    for name, run, whole in problems(args.size):
        if args.only and name not in args.only:
            continue
        rows[name] = r = measure(run, args.iterations, whole, args.tol, args.by_line)
        r["whole"] = w = measure_whole(run, args.iterations, args.by_line)
        line = f"{name:>16} {r['syncs']:7.2f} {r['copies']:7.2f} {r['arrays']:7.1f} "
        line += f"{r['fields']:7.1f}   {w['syncs']:12.2f} {w['arrays']:6.1f} {w['fields']:6.1f}"
        print(line + f" {w['iterations']:4d}", flush=True)
        if args.by_line:
            if not whole:
                print_lines(f"{name} (marginal)", r["lines"], args.top)
            print_lines(f"{name} (whole)", w["lines"], args.top)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"size": args.size, "per_iteration": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
