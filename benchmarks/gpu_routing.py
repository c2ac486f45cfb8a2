"""CuPy in, CuPy out: the accelerator route's cost against JAX heights (issue 38, item 3).

The same warm hard-wall solve (1024², load 2e-3 E*, median of 5) on JAX heights, on CuPy
heights (to the compiled program through DLPack, the fields back as CuPy) and on NumPy
heights with ``device="cuda"``; the CuPy result against the NumPy loops' (relative L2),
and whether the heights reach JAX without a copy (the same device buffer).

    python benchmarks/gpu_routing.py            # on a GPU with CuPy and JAX's CUDA backend
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import roughcontact as rc


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args(argv)
    import cupy
    import jax
    import jax.numpy as jnp

    n = args.size
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1)
    sub = rc.Substrate((n, n))
    hc = cupy.asarray(h)
    with jax.enable_x64(True):
        hj = jnp.asarray(h)

    def timed(x, **kw):
        rc.solve(x, sub, rc.HardWall(), load=2e-3, **kw)  # compiles / warms up
        times = []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            res = rc.solve(x, sub, rc.HardWall(), load=2e-3, **kw)
            times.append(time.perf_counter() - t0)
        return res, float(np.median(times))

    rj, tj = timed(hj)
    rcu, tc = timed(hc)
    rd, td = timed(h, device="cuda")
    print(f"{n}² hard wall, load 2e-3, median of {args.repeats} warm solves: JAX heights "
          f"{tj:.4f} s, CuPy heights {tc:.4f} s, NumPy + device='cuda' {td:.4f} s; iterations "
          f"{rj.iterations} / {rcu.iterations} / {rd.iterations}; fields "
          f"{type(rcu.pressure).__module__}.{type(rcu.pressure).__name__}, "
          f"{type(rd.pressure).__module__}.{type(rd.pressure).__name__}")  # fmt: skip
    ref = rc.solve(h, sub, rc.HardWall(), load=2e-3)
    rel = np.linalg.norm(cupy.asnumpy(rcu.pressure) - ref.pressure) / np.linalg.norm(ref.pressure)
    print(f"CuPy result against the NumPy loops: pressure relative L2 {rel:.2e}")
    with jax.enable_x64(True):
        shared = jnp.from_dlpack(hc).unsafe_buffer_pointer() == hc.data.ptr
    print(f"CuPy heights reach JAX without a copy: {shared}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
