"""Where a compiled loop's time goes on the device: a profiler trace, summarised.

One warm solve of ``gpu.py``'s surface at ``--size`` runs under ``jax.profiler.trace``
(float64, ``jax_enable_x64`` switched on here): ``hardwall_loop`` (load 1e-3 E* from a
uniform pressure: no coarse grids), ``adhesive`` (the 9-3 wall at ℓa/a0 = 0.005, the
hard wall's 5e-4 E* offset + a0, cold) or ``bounded`` (Maugis-Dugdale, w = 0.005 E* a0,
the same range, at that offset). From the trace's device events: the span from the first
to the last kernel, the time the device was busy, its idle gaps, the device-to-host
copies per iteration (each ``lax.cond`` and each ``lax.while_loop`` round reads its
predicate on the host), and the kernels by total time (cuFFT, XLA's fusions, copies).
On the CPU the trace has no device events: only the solve's time is reported.

    python benchmarks/gpu_trace.py --solver hardwall_loop --size 4096   # on a GPU
    python benchmarks/gpu_trace.py --size 128 --keep trace.json.gz      # a CPU dry run
"""

from __future__ import annotations

import argparse
import collections
import glob
import gzip
import json
import os
import shutil
import tempfile
import time

from hardwall import surface

import roughcontact as rc


def summarise(trace: dict, iterations: int, top: int = 12) -> dict:
    """Device busy time, idle gaps, D2H copies and the top kernels of a trace (µs → ms)."""
    events = trace["traceEvents"]
    names = {e["pid"]: e["args"]["name"] for e in events
             if e.get("ph") == "M" and e.get("name") == "process_name"}  # fmt: skip
    device = sorted((e for e in events if e.get("ph") == "X" and "GPU" in names.get(e["pid"], "")),
                    key=lambda e: e["ts"])  # fmt: skip
    if not device:
        return {"device_events": 0}
    kernels = collections.defaultdict(lambda: [0, 0.0])
    idle, end = 0.0, device[0]["ts"]
    for e in device:
        idle += max(e["ts"] - end, 0.0)
        end = max(end, e["ts"] + e["dur"])
        kernels[e["name"][:90]][0] += 1
        kernels[e["name"][:90]][1] += e["dur"]
    ranked = sorted(kernels.items(), key=lambda kv: -kv[1][1])[:top]
    return {
        "device_events": len(device),
        "span_ms": (end - device[0]["ts"]) / 1e3,
        "busy_ms": sum(e["dur"] for e in device) / 1e3,
        "idle_ms": idle / 1e3,
        "d2h_per_iteration": kernels["MemcpyD2H"][0] / max(iterations, 1),
        "kernels": [{"name": k, "calls": c, "ms": t / 1e3} for k, (c, t) in ranked],
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=4096)
    ap.add_argument("--solver", choices=["hardwall_loop", "adhesive", "bounded"],
                    default="hardwall_loop")  # fmt: skip
    ap.add_argument("--keep", metavar="FILE", help="also keep the trace (.trace.json.gz)")
    ap.add_argument("--json", metavar="OUT")
    args = ap.parse_args(argv)
    import jax
    import jax.numpy as jnp

    jax.config.update("jax_enable_x64", True)
    n = args.size
    h = jnp.asarray(surface(n, 1))
    sub = rc.Substrate((n, n))
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offset = rc.solve(h, sub, rc.HardWall(), load=5e-4).offset
    solves = {
        "hardwall_loop": lambda: rc.solve(h, sub, rc.HardWall(), load=1e-3,
                                          initial=jnp.full((n, n), 1e-3)),
        "adhesive": lambda: rc.solve(h, sub, law, offset=offset + 1.0),
        "bounded": lambda: rc.solve(h, sub, rc.MaugisDugdale(0.005, law.range), offset=offset),
    }  # fmt: skip
    solve = solves[args.solver]
    solve()  # compiles
    with tempfile.TemporaryDirectory() as tmp:
        with jax.profiler.trace(tmp):
            t0 = time.perf_counter()
            res = solve()
            seconds = time.perf_counter() - t0
        (path,) = glob.glob(os.path.join(tmp, "**", "*.trace.json.gz"), recursive=True)
        with gzip.open(path) as f:
            trace = json.load(f)
        if args.keep:
            shutil.copyfile(path, args.keep)
    out = {"n": n, "solver": args.solver, "device": str(jax.devices()[0]),
           "iterations": res.iterations, "seconds": seconds}  # fmt: skip
    out |= summarise(trace, res.iterations)
    print(json.dumps(out, indent=1))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
