"""How low a float32 solve of the paper's potential can drive its residual.

One cold, displacement-controlled state of ``gpu.py``'s surface (H = 0.8, h'rms = 0.1,
lambda_s = 8 a0, lambda_L = n/2, seed 1) with ``rc.SmoothLJ93.from_adhesion_length(0.005)``
at the offset where the hard wall carries 5e-4 E*, plus a0; float32 heights, solved at
the float32 default tolerance and at 1e-6: status, iterations, seconds (the first
includes compilation), the repulsive area, and the residual max|K w - p| / E* of the
returned float32 state evaluated in float64 (the floor a tolerance must stay above).
``--loop jax``: the compiled loop on JAX's default device (float64 available:
``jax_enable_x64`` is switched on here); ``--loop numpy``: the NumPy loop.

    python benchmarks/float32_floor.py --size 4096            # on a GPU
    python benchmarks/float32_floor.py --size 256 --loop numpy
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np
from hardwall import surface

import roughcontact as rc


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=4096)
    ap.add_argument("--loop", choices=["jax", "numpy"], default="jax")
    ap.add_argument("--json", metavar="OUT")
    args = ap.parse_args(argv)
    n = args.size
    h = surface(n, 1)
    sub = rc.Substrate((n, n))
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offset = rc.solve(h, sub, rc.HardWall(), load=5e-4).offset + 1.0
    if args.loop == "jax":
        import jax
        import jax.numpy as jnp

        jax.config.update("jax_enable_x64", True)
        single = jnp.asarray(h, dtype=jnp.float32)
    else:
        single = h.astype(np.float32)
    rows = []
    for tol in (None, 1e-6):
        t0 = time.perf_counter()
        res = rc.solve(single, sub, law, offset=offset, dtype="float32", tol=tol)
        seconds = time.perf_counter() - t0
        w = np.asarray(res.deflection, dtype=np.float64)
        imbalance = np.asarray(sub.pressure(w)) - np.asarray(res.pressure, dtype=np.float64)
        imbalance -= imbalance.mean()  # the rigid mean: its force is the load
        rows.append({
            "n": n, "loop": args.loop, "tol": res.tol, "status": res.status.value,
            "iterations": res.iterations, "seconds": seconds,
            "repulsive_area": res.repulsive_area,
            "residual_float64": float(np.abs(imbalance).max() / sub.contact_modulus),
        })  # fmt: skip
        print(json.dumps(rows[-1]), flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
