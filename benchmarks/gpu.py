"""GPU benchmark (issue 6): roughcontact on CuPy against its own FFT floor and the CPU.

For every grid size n (default 1024 2048 4096 8192) on one surface per size (H = 0.8,
h'rms = 0.1, lambda_s = 8, lambda_L = n/2, fixed seed; E* = a0 = 1):

* ``fft``: median time of one forward + inverse real FFT pair (``rfft2`` + ``irfft2``)
  of an n x n float array on the device, synchronised -- the floor of one iteration;
* ``hardwall``: the Polonsky-Keer solve at mean pressure ``--load`` (default 1e-3 E*),
  cold start; time, iterations, ms per iteration and that divided by the FFT pair
  (target <= 2);
* ``adhesive``: one displacement-controlled state of the paper's potential
  (``rc.SmoothLJ93.from_adhesion_length(--adhesion-length)``) at the offset where the
  hard wall carries ``--end-load``, cold start; the same columns;
* peak device memory, in units of one n x n float64 array (JAX's allocator peak so far
  in the process: the CuPy heights go to the compiled loops through DLPack; on the CPU:
  not measured).

Then the paper-scale path (``--path-size``, default 4096): approach in ``--path-steps``/2
equal offset steps from first contact (summit at the equilibrium distance a0) to the
offset where the hard wall carries ``--end-load`` plus a0, and back (40 steps, 41 states
by default), each warm-started, with the paper's potential; total wall time
(target: under 2 minutes on one H100). ``--cpu-sizes`` reruns the single solves on the
CPU (NumPy, scipy.fft on all cores) for the GPU/CPU ratio; ``--cpu-path`` also the path.

    python benchmarks/gpu.py                                  # on a GPU: everything
    python benchmarks/gpu.py --device cpu --sizes 256 --path-size 256 --cpu-sizes
                                                              # dry run without a GPU
    python benchmarks/gpu.py --dtype float32 --json gpu32.json
    python benchmarks/gpu.py --backend jax --sizes 1024 2048 4096 --path-size 0
                                       # the compiled loops (jax.jit), JAX's device

``--backend jax`` times the compiled loops (``--solvers``: the hard wall at ``--load``,
``adhesive``: the smoothed 9-3 wall at the offset above, ``bounded``: Maugis-Dugdale with
the same w and range at the hard wall's ``--end-load`` offset; ``adhesive_load`` /
``bounded_load``: the same two laws under load control at ``--load``, cold, the load inside
the one minimisation in the compiled loop, not in the default list): the heights as a JAX array
on JAX's default device (``--device cpu``: its CPU), float64 with ``jax_enable_x64``
switched on by this script; the first solve at each size (XLA compilation, and the
solve) is reported apart (``first_seconds``), ``it/fft`` is the time per iteration over
one compiled ``rfft2`` + ``irfft2`` pair, and the same problem solved by the NumPy loop
on the CPU (``*_numpy``, and ``speedup_over_cpu`` on an accelerator) when the size is in
``--cpu-sizes`` or the device is the CPU. On a GPU ``peak_arrays`` is JAX's allocator
peak so far in the process (monotone over the rows) in n x n float64 arrays; on any device
``loop_arrays`` is XLA's own account of the compiled loop program (arguments + outputs -
aliased + temporaries; ``--no-footprint`` skips it: it compiles the loop once more).
``hardwall_loop`` is the hard wall warm-started from a uniform pressure, which skips the
nested coarse-grid solves of a cold start: every iteration on the n x n grid, the cost of
one iteration of the compiled loop (``hardwall``'s ms/it divides the whole nested solve by
the fine grid's iterations alone). The path
(``--path-size``) then runs on JAX heights, after an untimed 2-state path compiles it.

Surface generation and the hard-wall solve that fixes the offsets are never timed; each
timed solve follows an untimed warm-up run of the same solve, at the same size and dtype
(CUDA context, cuFFT plans of every grid the solve uses, kernel compilation; on the CPU
:data:`WARMUP_ITER` iterations of it), so ``--repeats 1`` times a warm solve. BLAS and OpenMP pools
run on their libraries' defaults unless ``--blas-threads N`` is given, which is then
enforced and verified (``_threads.py``); the header and the JSON (``meta.threads``)
record the threads per library, CPUs and versions.
"""

from __future__ import annotations

import sys

if __name__ == "__main__":  # before NumPy or SciPy loads its BLAS: see _threads.py
    import _threads

    _threads.preset_from_argv(sys.argv[1:], "--blas-threads", default=None)

import argparse
import contextlib
import functools
import json
import time

import _threads
import numpy as np
from hardwall import machine_meta, surface

import roughcontact as rc

A0 = ES = 1.0
#: iterations of the untimed warm-up solve before each timed one on the CPU (no kernels
#: to compile there; a GPU warms up with the whole solve)
WARMUP_ITER = 5


def _xp(device: str):
    if device == "cpu":
        return None
    import cupy

    return cupy


def sync(device: str) -> None:
    if device != "cpu":
        import cupy

        cupy.cuda.Stream.null.synchronize()


def fft_pair_seconds(n: int, device: str, dtype: str, repeats: int = 9) -> float:
    """Median time of one rfft2 + irfft2 pair of an n x n array on ``device``."""
    from roughcontact._backend import irfft2, rfft2

    x = rc.to_device(np.random.default_rng(0).standard_normal((n, n)), device, dtype)
    irfft2(rfft2(x), (n, n))
    sync(device)
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        irfft2(rfft2(x), (n, n))
        sync(device)
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def jax_peak_bytes(device: str):
    """JAX's allocator peak so far on the GPU (bytes; the compiled loops run there since
    the accelerator route), None on the CPU. (A solver ``callback`` would send the solve to
    the NumPy loops on the host: the compiled loops take none.)"""
    if device == "cpu":
        return None
    import jax

    return (jax.devices()[0].memory_stats() or {}).get("peak_bytes_in_use")


def timed_solve(h, sub, law, device, dtype, **control) -> dict:
    sync(device)
    t0 = time.perf_counter()
    res = rc.solve(h, sub, law, device=device, dtype=dtype, **control)
    seconds = time.perf_counter() - t0  # the scalars read from the device: it has finished
    return {
        "seconds": seconds,
        "iterations": res.iterations,
        "converged": res.converged,
        "repulsive_area": res.repulsive_area,
        "peak_bytes": jax_peak_bytes(device),
    }


def bench_size(n: int, args, device: str) -> dict:
    h = surface(n, args.seed)
    sub = rc.Substrate((n, n), contact_modulus=ES, pixel_size=A0)
    law = rc.SmoothLJ93.from_adhesion_length(args.adhesion_length)
    # untimed, on the device (on a 16-core CPU it took longer than the timed GPU solves)
    d_hw = rc.solve(h, sub, rc.HardWall(), load=args.end_load, device=device).offset
    h_dev = rc.to_device(h, device, args.dtype)
    row = {"n": n, "device": device, "dtype": args.dtype}
    row["fft_seconds"] = fft_pair_seconds(n, device, args.dtype)
    grid_bytes = n * n * 8
    for name, lw, control in (
        ("hardwall", rc.HardWall(), {"load": args.load}),
        ("adhesive", law, {"offset": d_hw + A0}),
    ):
        # untimed warm-up at the measured size and dtype (a few iterations of the same
        # solve, its nested coarse grids included): kernel compilation and FFT plans
        # (on a GPU the whole solve: a few iterations may not reach every kernel, e.g. a
        # projection's point corrections, whose first use compiles them)
        warmup = {} if device != "cpu" else {"max_iter": WARMUP_ITER}
        rc.solve(h_dev, sub, lw, device=device, dtype=args.dtype, **warmup, **control)
        repeats = args.cpu_repeats if device == "cpu" else args.repeats
        runs = [timed_solve(h_dev, sub, lw, device, args.dtype, **control) for _ in range(repeats)]
        r = dict(runs[0])
        r["seconds"] = float(np.median([x["seconds"] for x in runs]))
        r["ms_per_iteration"] = 1e3 * r["seconds"] / max(r["iterations"], 1)
        r["iteration_over_fft"] = r["ms_per_iteration"] / (1e3 * row["fft_seconds"])
        r["peak_arrays"] = r["peak_bytes"] / grid_bytes if r["peak_bytes"] else None
        row[name] = r
    return row


def _jax_device(device: str, dtype: str):
    import jax

    if dtype == "float64":  # this script's choice; roughcontact never flips it
        jax.config.update("jax_enable_x64", True)
    return jax.devices("cpu")[0] if device == "cpu" else jax.devices()[0]


def jax_fft_pair_seconds(n: int, device, dtype: str, repeats: int = 9) -> float:
    """Median time of one compiled rfft2 + irfft2 pair of an n x n array (JAX)."""
    import jax
    import jax.numpy as jnp

    x = jax.device_put(jnp.asarray(np.random.default_rng(0).standard_normal((n, n)), dtype), device)
    pair = jax.jit(lambda a: jnp.fft.irfft2(jnp.fft.rfft2(a), s=a.shape))
    pair(x).block_until_ready()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        pair(x).block_until_ready()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


@contextlib.contextmanager
def loop_footprints(record: list):
    """Spy on the compiled loops (``run`` of the three JAX modules): for each call, XLA's
    memory analysis of the compiled loop -- arguments + outputs - aliased + temporaries,
    bytes -- appended to ``record``. The analysis compiles the loop once more (untimed)."""
    from roughcontact.solvers import _bounded_jax, _pk_jax, _smooth_jax

    originals = {m: m.run for m in (_pk_jax, _smooth_jax, _bounded_jax)}

    def spy(*a, _run, **kw):
        ma = _run.lower(*a, **kw).compile().memory_analysis()
        if ma is not None:
            record.append(ma.argument_size_in_bytes + ma.output_size_in_bytes
                          - ma.alias_size_in_bytes + ma.temp_size_in_bytes)  # fmt: skip
        return _run(*a, **kw)

    for module, run in originals.items():
        module.run = functools.partial(spy, _run=run)
    try:
        yield record
    finally:
        for module, run in originals.items():
            module.run = run


def bench_size_jax(n: int, args, device: str) -> dict:
    """Every compiled loop on a JAX array (hard wall under load control; the smoothed 9-3
    wall and Maugis-Dugdale at an offset) and, on the CPU, the NumPy loops beside them."""
    import jax
    import jax.numpy as jnp

    dev = _jax_device(device, args.dtype)
    h = surface(n, args.seed)
    sub = rc.Substrate((n, n), contact_modulus=ES, pixel_size=A0)
    law = rc.SmoothLJ93.from_adhesion_length(args.adhesion_length)
    dugdale = rc.MaugisDugdale(args.adhesion_length * ES, law.range)
    d_hw = rc.solve(h, sub, rc.HardWall(), load=args.end_load).offset  # untimed (NumPy)
    hj = jax.device_put(jnp.asarray(h, dtype=args.dtype), dev)
    # a warm start skips the nested coarse-grid solves: every iteration on the n x n grid
    uniform = jax.device_put(jnp.full((n, n), args.load, dtype=args.dtype), dev)
    row = {"n": n, "device": f"jax:{dev.platform}", "dtype": args.dtype}
    row["fft_seconds"] = jax_fft_pair_seconds(n, dev, args.dtype)
    solvers = {"hardwall": (rc.HardWall(), {"load": args.load}),
               "hardwall_loop": (rc.HardWall(), {"load": args.load, "initial": uniform}),
               "adhesive": (law, {"offset": d_hw + A0}),
               "bounded": (dugdale, {"offset": d_hw}),
               "adhesive_load": (law, {"load": args.load}),
               "bounded_load": (dugdale, {"load": args.load})}  # fmt: skip
    numpy_too = device == "cpu" or n in (args.cpu_sizes or [])
    for name in args.solvers:
        lw, control = solvers[name]

        def one(heights, lw=lw, control=control):  # the record's scalars reach the host:
            if "initial" in control and isinstance(heights, np.ndarray):  # the solve has
                control = dict(control, initial=np.full((n, n), args.load))  # finished
            t0 = time.perf_counter()
            res = rc.solve(heights, sub, lw, **control)
            return time.perf_counter() - t0, {  # no field is kept
                "iterations": res.iterations, "converged": res.converged,
                "repulsive_area": res.repulsive_area, "message": res.message}  # fmt: skip

        first, _ = one(hj)  # compiles the loop (every grid of the hard wall's nested solves)
        jobs = [(name, [one(hj) for _ in range(args.repeats)])]
        if numpy_too:
            h_np = h.astype(args.dtype)
            one(h_np)  # warm-up (FFT plans)
            jobs.append((f"{name}_numpy", [one(h_np) for _ in range(args.cpu_repeats)]))
        for key, runs in jobs:
            res = runs[0][1]
            seconds = float(np.median([t for t, _ in runs]))
            row[key] = dict(res, seconds=seconds, peak_bytes=None, peak_arrays=None,
                            ms_per_iteration=1e3 * seconds / max(res["iterations"], 1),
                            iteration_over_fft=seconds / max(res["iterations"], 1)
                            / row["fft_seconds"], all_seconds=[t for t, _ in runs])  # fmt: skip
        row[name]["first_seconds"] = first
        if numpy_too and device != "cpu":  # the accelerator against the NumPy loop here
            row[name]["speedup_over_cpu"] = row[f"{name}_numpy"]["seconds"] / row[name]["seconds"]
        sizes = []
        if args.footprint:  # the compiled loop's own memory (any device)
            with loop_footprints(sizes):
                one(hj)
        if sizes:
            row[name]["loop_bytes"] = max(sizes)
            row[name]["loop_arrays"] = max(sizes) / (n * n * 8)
        stats = dev.memory_stats() or {}  # a GPU's allocator; the process's peak so far
        if stats.get("peak_bytes_in_use"):
            row[name]["peak_bytes"] = stats["peak_bytes_in_use"]
            row[name]["peak_arrays"] = stats["peak_bytes_in_use"] / (n * n * 8)
    return row


def bench_path(n: int, args, device: str) -> dict:
    h = surface(n, args.seed)
    sub = rc.Substrate((n, n), contact_modulus=ES, pixel_size=A0)
    law = rc.SmoothLJ93.from_adhesion_length(args.adhesion_length)
    if args.backend == "jax":  # the compiled loops, each state warm-started on the device
        import jax
        import jax.numpy as jnp

        dev = _jax_device(device, args.dtype)  # x64 first: then asarray keeps float64
        h_dev = jax.device_put(jnp.asarray(h, dtype=args.dtype), dev)
        d_hw = rc.solve(h_dev, sub, rc.HardWall(), load=args.end_load).offset  # untimed
    else:
        h_dev = rc.to_device(h, device, args.dtype)
        d_hw = rc.solve(h, sub, rc.HardWall(), load=args.end_load, device=device).offset
    d_start, d_end = float(h.max()) + A0, d_hw + A0
    half = args.path_steps // 2
    offsets = d_start - (d_start - d_end) * np.arange(0, half + 1) / half  # 2 half + 1 states
    if args.backend == "jax":
        rc.approach_retract(h_dev, sub, law, offsets=offsets[:2], retract=False)  # compiles
    sync(device)
    t0 = time.perf_counter()
    ds = rc.approach_retract(h_dev, sub, law, offsets=offsets, dtype=args.dtype)
    seconds = time.perf_counter() - t0
    return {
        "n": n,
        "device": f"jax:{device}" if args.backend == "jax" else device,
        "dtype": args.dtype,
        "steps": int(ds.sizes["step"]),
        "seconds": seconds,
        "iterations": int(ds["iterations"].sum()),
        "all_converged": bool(ds.attrs["all_converged"]),
        "pull_off": float(ds.attrs["pull_off"]),
        "max_repulsive_area": float(ds["repulsive_area"].max()),
    }


def fmt(row: dict) -> list[str]:
    out = []
    for name in ("hardwall", "hardwall_numpy", "hardwall_loop", "hardwall_loop_numpy",
                 "adhesive", "adhesive_numpy", "bounded",
                 "bounded_numpy", "adhesive_load", "adhesive_load_numpy", "bounded_load",
                 "bounded_load_numpy"):  # fmt: skip
        r = row.get(name)
        if r is None:
            continue
        peak = f"{r['peak_arrays']:.1f}" if r["peak_arrays"] else "-"
        if r.get("loop_arrays"):
            peak += f" (loop {r['loop_arrays']:.1f})"
        out.append(
            f"{row['device']:>5} {row['dtype']:>7} {row['n']:>6}² {name:>9} "
            f"{r['seconds']:9.3f} s {r['iterations']:>6} it {r['ms_per_iteration']:9.3f} ms/it "
            f"fft {1e3 * row['fft_seconds']:8.3f} ms  it/fft {r['iteration_over_fft']:5.2f}  "
            f"peak {peak} arrays  conv={r['converged']}"
            + (f"  first {r['first_seconds']:.2f} s" if "first_seconds" in r else "")
        )
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="*", default=[1024, 2048, 4096, 8192])
    ap.add_argument("--device", default="cuda")
    ap.add_argument(
        "--backend",
        choices=["roughcontact", "jax"],
        default="roughcontact",
        help="jax: the hard wall's compiled loop on JAX arrays (see the module docstring)",
    )
    ap.add_argument("--dtype", choices=["float64", "float32"], default="float64")
    ap.add_argument(
        "--solvers",
        nargs="+",
        choices=[
            "hardwall",
            "hardwall_loop",
            "adhesive",
            "bounded",
            "adhesive_load",
            "bounded_load",
        ],
        default=["hardwall", "adhesive", "bounded"],
        help="--backend jax: the compiled loops to time (bounded: Maugis-Dugdale; *_load: "
        "under load control at --load)",
    )
    ap.add_argument("--cpu-sizes", type=int, nargs="*", default=[1024, 2048])
    ap.add_argument("--path-size", type=int, default=4096, help="0 skips the path")
    ap.add_argument("--path-steps", type=int, default=40)
    ap.add_argument("--cpu-path", action="store_true", help="also run the path on the CPU")
    ap.add_argument("--load", type=float, default=1e-3, help="hard-wall mean pressure / E*")
    ap.add_argument("--end-load", type=float, default=5e-4, help="sets the deepest offset")
    ap.add_argument("--adhesion-length", type=float, default=0.005, help="ℓa / a0")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cpu-repeats", type=int, default=3, help="repeats of the CPU solves")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument(
        "--blas-threads",
        type=int,
        default=None,
        help="BLAS/OpenMP threads per library, set before NumPy loads and verified (default: "
        "the libraries' own; recorded either way)",
    )
    ap.add_argument(
        "--no-footprint",
        dest="footprint",
        action="store_false",
        help="--backend jax: skip XLA's memory account of each compiled loop (one more "
        "compilation and solve per row)",
    )
    ap.add_argument("--json", metavar="OUT")
    args = ap.parse_args(argv)
    with _threads.enforced(args.blas_threads, preload=("scipy.fft",)) as threads:
        meta, rows, paths = _main(args, threads)
    if args.json:  # after the block: with the pools as they were at the end
        with open(args.json, "w") as f:
            json.dump({"meta": meta, "solves": rows, "paths": paths}, f, indent=1)
    return 0


def _main(args, threads: dict):
    meta = machine_meta()
    if args.backend == "jax":
        import jax

        meta["jax"] = jax.__version__
    elif args.device != "cpu":
        cupy = _xp(args.device)
        props = cupy.cuda.runtime.getDeviceProperties(0)
        meta |= {"gpu": props["name"].decode(), "cupy": cupy.__version__}
    meta["threads"] = threads
    print(json.dumps({k: v for k, v in meta.items() if k != "threads"}))
    print(_threads.describe(threads), flush=True)
    rows, paths = [], []
    for n in args.sizes:
        bench = bench_size_jax if args.backend == "jax" else bench_size
        rows.append(bench(n, args, args.device))
        print("\n".join(fmt(rows[-1])), flush=True)
    for n in [] if args.backend == "jax" else args.cpu_sizes or []:  # (jax: beside each size)
        rows.append(bench_size(n, args, "cpu"))
        print("\n".join(fmt(rows[-1])), flush=True)
    for a in rows:  # GPU/CPU ratios where both ran
        for b in rows:
            if a["n"] == b["n"] and a["device"] != "cpu" and b["device"] == "cpu":
                for name in ("hardwall", "adhesive"):
                    ratio = b[name]["seconds"] / a[name]["seconds"]
                    a[name]["speedup_over_cpu"] = ratio
                    print(f"{a['n']:>6}² {name:>9}: GPU {ratio:.1f}x faster than the CPU")
    if args.path_size:
        devices = [args.device] + (["cpu"] if args.cpu_path and args.device != "cpu" else [])
        for device in devices:
            paths.append(bench_path(args.path_size, args, device))
            p = paths[-1]
            print(
                f"path {p['n']}² on {p['device']} ({p['dtype']}): {p['steps']} steps in "
                f"{p['seconds']:.1f} s, {p['iterations']} iterations, all converged: "
                f"{p['all_converged']}, pull-off {p['pull_off']:.3e} E*, max A_rep/A0 "
                f"{p['max_repulsive_area']:.4f}  (targets on one H100: < 120 s CuPy, <= 15 s JAX)",
                flush=True,
            )
    return meta, rows, paths


if __name__ == "__main__":
    raise SystemExit(main())
