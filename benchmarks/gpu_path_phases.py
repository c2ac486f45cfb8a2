"""Where the time of a path on JAX heights goes: the solves against the per-state work.

The path of ``gpu.py`` (``--states`` states, the paper's potential at ℓa/a0 =
``--adhesion-length``, from the first contact to the offset where the hard wall carries
5e-4 E* and back, each state warm-started on the device) runs twice after an untimed
2-state path compiles it: as it is (``path_seconds``), then with each state's solve and
patch count synchronised and timed apart (``phases``, seconds summed over the states).
Then the compiled patch count alone on the deepest state's repulsive map (median of 3,
``count_seconds``). On a GPU, float64 (``jax_enable_x64`` switched on here).

    python benchmarks/gpu_path_phases.py --size 4096            # on a GPU
    python benchmarks/gpu_path_phases.py --size 128 --states 9  # a dry run on the CPU
"""

from __future__ import annotations

import argparse
import functools
import json
import time

import numpy as np
from hardwall import surface

import roughcontact as rc


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=4096)
    ap.add_argument("--states", type=int, default=41, help="odd: approach and retract")
    ap.add_argument("--adhesion-length", type=float, default=0.005, help="ℓa / a0")
    ap.add_argument("--json", metavar="OUT")
    args = ap.parse_args(argv)
    import jax
    import jax.numpy as jnp

    jax.config.update("jax_enable_x64", True)
    from roughcontact.analysis._patches_jax import count_patches_jax
    from roughcontact.solvers import path

    n = args.size
    h = surface(n, 1)
    sub = rc.Substrate((n, n))
    law = rc.SmoothLJ93.from_adhesion_length(args.adhesion_length)
    hj = jnp.asarray(h)
    d_end = rc.solve(hj, sub, rc.HardWall(), load=5e-4).offset + 1.0
    half = (args.states - 1) // 2
    d_start = float(h.max()) + 1.0
    offsets = d_start - (d_start - d_end) * np.arange(half + 1) / half
    rc.approach_retract(hj, sub, law, offsets=offsets[:2], retract=False)  # compiles
    out = {"n": n, "device": str(jax.devices()[0]), "jax": jax.__version__}
    t0 = time.perf_counter()
    ds = rc.approach_retract(hj, sub, law, offsets=offsets)
    out |= {"path_seconds": time.perf_counter() - t0, "states": int(ds.sizes["step"]),
            "iterations": int(ds["iterations"].sum())}  # fmt: skip
    phases = {}

    def timed(name, f):
        @functools.wraps(f)
        def g(*a, **k):
            t = time.perf_counter()
            r = f(*a, **k)
            jax.block_until_ready(getattr(r, "pressure", r))
            phases[name] = phases.get(name, 0.0) + time.perf_counter() - t
            return r

        return g

    solve, count = path.solve, path.patch_count
    path.solve, path.patch_count = timed("solve", solve), timed("patch_count", count)
    try:
        t0 = time.perf_counter()
        last = rc.approach_retract(hj, sub, law, offsets=offsets, fields_at=[half])
        out["synchronised_seconds"] = time.perf_counter() - t0
    finally:
        path.solve, path.patch_count = solve, count
    out["phases"] = phases
    mask = jnp.asarray(last["pressure"].values[0] > 0)  # the one field step kept
    count_patches_jax(mask, True).block_until_ready()
    times = []
    for _ in range(3):
        t0 = time.perf_counter()
        count_patches_jax(mask, True).block_until_ready()
        times.append(time.perf_counter() - t0)
    out["count_seconds"] = float(np.median(times))
    print(json.dumps(out, indent=1))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
