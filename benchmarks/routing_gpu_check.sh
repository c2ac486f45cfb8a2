#!/usr/bin/env bash
# One short device check of the accelerator route (roughcontact/_accelerator.py): the GPU
# tests of tests/backends/test_routing.py and test_cupy.py, then CuPy in -> CuPy out
# zero-copy and its cost against JAX heights at 1024² (hard wall, warm). Writes to $OUT
# (or /tmp) only.
#     bash benchmarks/routing_gpu_check.sh
set -u
OUT=${OUT:-/tmp}
PY=${PY:-python}
export PYTHONPATH=$PWD/src${PYTHONPATH:+:$PYTHONPATH}
$PY -c "import jax, sys; print('jax', jax.__version__, jax.devices()); import cupy; print('cupy', cupy.__version__)"
timeout 240 $PY -m pytest -o addopts="" -p no:cacheprovider -q -x --no-header \
    tests/backends/test_routing.py tests/backends/test_cupy.py 2>&1 | tail -15
timeout 120 $PY - <<'PYEOF' 2>&1 | tee "$OUT/routing_gpu.txt"
import time
import cupy, jax, jax.numpy as jnp, numpy as np
import roughcontact as rc

n = 1024
h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1)
sub = rc.Substrate((n, n))
hc = cupy.asarray(h)
with jax.enable_x64(True):
    hj = jnp.asarray(h)
def timed(x, **kw):
    rc.solve(x, sub, rc.HardWall(), load=2e-3, **kw)  # compile / warm
    t = []
    for _ in range(5):
        t0 = time.perf_counter(); r = rc.solve(x, sub, rc.HardWall(), load=2e-3, **kw)
        t.append(time.perf_counter() - t0)
    return r, float(np.median(t))
rj, tj = timed(hj)
rcu, tc = timed(hc)
rd, td = timed(h, device="cuda")
print(f"{n}^2 hard wall, load 2e-3, median of 5 warm solves: JAX heights {tj:.4f} s, "
      f"CuPy heights {tc:.4f} s, NumPy + device='cuda' {td:.4f} s; iterations "
      f"{rj.iterations} / {rcu.iterations} / {rd.iterations}; fields {type(rcu.pressure).__name__}, "
      f"{type(rd.pressure).__name__}")
rn = rc.solve(h, sub, rc.HardWall(), load=2e-3)
rel = np.linalg.norm(rcu.pressure.get() - rn.pressure) / np.linalg.norm(rn.pressure)
print(f"CuPy vs NumPy pressure relative L2 {rel:.2e}")
# zero-copy: CuPy heights as JAX share the buffer
with jax.enable_x64(True):
    j = jnp.from_dlpack(hc)
print("heights zero-copy:", j.unsafe_buffer_pointer() == hc.data.ptr)
PYEOF
