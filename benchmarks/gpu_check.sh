#!/usr/bin/env bash
# Issue 34's and 38's GPU check in one script: the GPU tests (the compiled JAX loops'
# included), benchmarks/gpu.py at 1024²-4096² (float64 and float32, ms per iteration and
# cuFFT pairs, GPU/CPU at 2048²; the compiled loops of every solver, --backend jax:
# hard wall, smoothed 9-3 wall, Maugis-Dugdale, per iteration / rfft2+irfft2 pair, their
# GPU/CPU ratio at 2048², JAX's peak memory, float32), the 4096² paper task with its
# analysis, a 512² task on the GPU against one CPU core, the 41-state 4096² path (CuPy and
# JAX heights) and the task through the real Dask path. Each step has its own time limit,
# so a slow one does not take the rest with it; everything goes to $LOG.
#
#   benchmarks/gpu_check.sh                         # on a GPU machine, from the repo root
#   DEVICE=cpu SIZES="64 128" TASK_SIZE=128 SMALL=64 PATH_SIZE=128 CPU_SIZE=128 \
#       benchmarks/gpu_check.sh                     # a dry run on the CPU
#   PART=quick benchmarks/gpu_check.sh              # tests + float64 sizes only
#   PART=second benchmarks/gpu_check.sh             # GPU side only: tests, float64 and
#                                                   # float32 sizes, 4096² task and path
#   PART=jax benchmarks/gpu_check.sh                # issue 38 (<= 9 min): the compiled
#                                                   # loops' tests, float64/float32 sizes
#                                                   # (GPU/CPU at CPU_SIZE), JAX path
#   PART=one benchmarks/gpu_check.sh              # issue 38's item 5 in one call of
#                                                   # <= 8 min (a session's whole device
#                                                   # budget is 15 min), then PART=two
#                                                   # (<= 9 min): GPU/CPU at CPU_SIZE², the
#                                                   # Dask study, float32's floor, the
#                                                   # path's phases, a loop's trace
# The two device calls to make: PART=one, then PART=two (both ran 2026-11-27 on an H200,
# PART=two's steps in separate calls; see benchmarks/README.md). The older split,
# PART=jax + PART=second (the paper task and the 512² task on the GPU; PART=all adds the
# 512² task on one CPU core and the Dask study), measures the same with wider limits.
set -u -o pipefail
export PYTHONUNBUFFERED=1
PY=${PY:-python3}
DEVICE=${DEVICE:-cuda}
SIZES=${SIZES:-1024 2048 4096}
CPU_SIZE=${CPU_SIZE:-2048}
TASK_SIZE=${TASK_SIZE:-4096}
SMALL=${SMALL:-512}
PATH_SIZE=${PATH_SIZE:-4096}
PART=${PART:-all}
OUTDIR=${OUT:-/tmp/gpu_check}
mkdir -p "$OUTDIR"
LOG=${LOG:-$OUTDIR/log}
TMP=$(mktemp -d)
step() {  # step SECONDS TITLE COMMAND...: run with a limit, log the time it took
    local limit=$1 title=$2
    shift 2
    echo "=== $title ($(date -u +%T), limit ${limit}s)"
    local t0=$SECONDS
    timeout "$limit" "$@"
    echo "=== $title: rc=$? in $((SECONDS - t0)) s"
}
{
    echo "=== gpu_check $(date -u) device=$DEVICE sizes=$SIZES part=$PART"
    if [ "$DEVICE" != cpu ]; then
        nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv
    fi
    $PY -c "import sys, numpy, scipy, array_api_compat, roughcontact; print(sys.version.split()[0], 'numpy', numpy.__version__, 'scipy', scipy.__version__, 'array_api_compat', array_api_compat.__version__, roughcontact.__file__)"
    [ "$DEVICE" != cpu ] && $PY -c "import cupy; print('cupy', cupy.__version__)"
    $PY -c "import jax; print('jax', jax.__version__, jax.devices())"
    cpu=(--cpu-sizes)
    [ -n "$CPU_SIZE" ] && [ "$PART" != second ] && cpu=(--cpu-sizes "$CPU_SIZE" --cpu-repeats 1)
    if [ "$PART" = two ]; then  # the second call: GPU/CPU at CPU_SIZE², the Dask study,
        # float32's floor, where the path's time goes (limits sum to 500 s)
        for solver in hardwall adhesive; do
            step 140 "GPU/CPU at ${CPU_SIZE}²: $solver (NumPy on every core)" $PY \
                benchmarks/gpu.py --backend jax --device "$DEVICE" --sizes "$CPU_SIZE" \
                --cpu-sizes "$CPU_SIZE" --cpu-repeats 1 --path-size 0 --repeats 2 \
                --no-footprint --solvers $solver --json "$OUTDIR/gpu_cpu_$solver.json"
        done
        $PY benchmarks/gpu_task.py --write-study "$TMP/one.toml" --size "$SMALL"
        step 60 "study run ${SMALL}² through Dask on $DEVICE" $PY -c \
            "from roughcontact.cli.main import main; main()" study run "$TMP/one.toml" \
            -o "$TMP/study" --device "$DEVICE" --workers 1 --no-progress
        step 40 "float32's residual floor at ${PATH_SIZE}²" $PY benchmarks/float32_floor.py \
            --size "$PATH_SIZE" --json "$OUTDIR/float32_floor.json"
        step 75 "the ${PATH_SIZE}² path's solves and per-state work" $PY \
            benchmarks/gpu_path_phases.py --size "$PATH_SIZE" --states 41 \
            --json "$OUTDIR/path_phases.json"
        step 45 "the hard wall loop's profiler trace at ${PATH_SIZE}²" $PY \
            benchmarks/gpu_trace.py --solver hardwall_loop --size "$PATH_SIZE" \
            --json "$OUTDIR/trace_hardwall.json"
        echo "=== done $(date -u)"
        exit 0
    fi
    if [ "$PART" = one ]; then  # issue 38's item 5 in one call (limits sum to 460 s),
        # the steps in the order of what matters most, each with its own limit
        step 75 "GPU tests: compiled loops, memory, DLPack/CuPy routing" $PY -m pytest -q \
            -n 0 -p no:cacheprovider tests/solvers/test_pk_jax.py \
            tests/solvers/test_smooth_jax.py tests/solvers/test_bounded_jax.py \
            tests/solvers/test_jax_memory.py tests/backends/test_routing.py \
            tests/backends/test_cupy.py -k "no_host_transfer or same_answer or gpu or cupy or \
            dlpack or holds or donated or cuda"
        # shellcheck disable=SC2086
        step 100 "gpu.py jax float64: every compiled loop, per iteration, memory" $PY \
            benchmarks/gpu.py --backend jax --device "$DEVICE" --sizes ${ONE_SIZES:-1024 4096} \
            --cpu-sizes --path-size 0 --repeats 2 --json "$OUTDIR/gpu_jax.json" --solvers \
            hardwall_loop adhesive bounded
        step 60 "41-state path ${PATH_SIZE}² on JAX heights" $PY benchmarks/gpu.py \
            --backend jax --device "$DEVICE" --sizes --cpu-sizes --path-size "$PATH_SIZE" \
            --json "$OUTDIR/path_jax.json"
        step 85 "paper task ${TASK_SIZE}² on $DEVICE, with its analysis (compiles, then warm)" \
            $PY benchmarks/gpu_task.py --device "$DEVICE" --size "$TASK_SIZE" --runs 2 \
            --json "$OUTDIR/task.json"
        step 35 "gpu.py jax float32 at ${PATH_SIZE}²" $PY benchmarks/gpu.py --backend jax \
            --device "$DEVICE" --sizes "$PATH_SIZE" --cpu-sizes --path-size 0 --repeats 2 \
            --dtype float32 --no-footprint --solvers hardwall_loop adhesive \
            --json "$OUTDIR/gpu_jax32.json"
        step 35 "task ${SMALL}² on $DEVICE (compiles, then warm)" $PY benchmarks/gpu_task.py \
            --device "$DEVICE" --size "$SMALL" --runs 2 --json "$OUTDIR/task_small.json"
        step 45 "task ${SMALL}² on one CPU core" $PY benchmarks/gpu_task.py --device cpu \
            --threads 1 --size "$SMALL" --json "$OUTDIR/task_small_cpu.json"
        [ "$DEVICE" != cpu ] && step 25 "CuPy in, CuPy out (DLPack)" $PY benchmarks/gpu_routing.py \
            --repeats 3
        echo "=== done $(date -u)"
        exit 0
    fi
    if [ "$PART" = jax ] || [ "$PART" = all ]; then  # issue 38: the compiled loops (JAX)
        step 120 "GPU tests, compiled loops" $PY -m pytest -q -p no:cacheprovider \
            tests/solvers/test_pk_jax.py tests/solvers/test_smooth_jax.py \
            tests/solvers/test_bounded_jax.py -k "no_host_transfer or same_answer"
        # shellcheck disable=SC2086
        step 210 "gpu.py jax float64 (every compiled loop, GPU/CPU at $CPU_SIZE²)" $PY \
            benchmarks/gpu.py --backend jax --device "$DEVICE" --sizes $SIZES "${cpu[@]}" \
            --path-size 0 --repeats 3 --json "$OUTDIR/gpu_jax.json"
        # shellcheck disable=SC2086
        step 120 "gpu.py jax float32 (every compiled loop)" $PY benchmarks/gpu.py \
            --backend jax --device "$DEVICE" --sizes $SIZES --cpu-sizes --path-size 0 \
            --repeats 2 --dtype float32 --json "$OUTDIR/gpu_jax32.json"
        step 90 "41-state path ${PATH_SIZE}² on JAX heights" $PY benchmarks/gpu.py \
            --backend jax --device "$DEVICE" --sizes --cpu-sizes --path-size "$PATH_SIZE" \
            --json "$OUTDIR/path_jax.json"
        [ "$PART" = jax ] && echo "=== done $(date -u)" && exit 0
    fi
    step 90 "GPU tests" $PY -m pytest -q -p no:cacheprovider \
        tests/backends/test_cupy.py tests/backends/test_device_detection.py tests/solvers/test_pk_jax.py
    cpu=(--cpu-sizes)
    [ -n "$CPU_SIZE" ] && [ "$PART" = all ] && cpu=(--cpu-sizes "$CPU_SIZE" --cpu-repeats 1)
    # shellcheck disable=SC2086
    step 150 "gpu.py float64" $PY benchmarks/gpu.py --device "$DEVICE" --sizes $SIZES \
        "${cpu[@]}" --path-size 0 --repeats 3 --json "$OUTDIR/gpu64.json"
    [ "$PART" = quick ] && exit 0
    if [ "$PART" = second ]; then  # a later, shorter run: the GPU side only
        step 100 "paper task ${TASK_SIZE}² on $DEVICE" $PY benchmarks/gpu_task.py \
            --device "$DEVICE" --size "$TASK_SIZE" --json "$OUTDIR/task.json"
        step 90 "41-state path ${PATH_SIZE}²" $PY benchmarks/gpu.py --device "$DEVICE" \
            --sizes --cpu-sizes --path-size "$PATH_SIZE" --json "$OUTDIR/path.json"
        # shellcheck disable=SC2086
        step 40 "gpu.py float32" $PY benchmarks/gpu.py --device "$DEVICE" --sizes $SIZES \
            --cpu-sizes --path-size 0 --repeats 2 --dtype float32 --json "$OUTDIR/gpu32.json"
        step 30 "task ${SMALL}² on $DEVICE" $PY benchmarks/gpu_task.py --device "$DEVICE" \
            --size "$SMALL" --json "$OUTDIR/task_small.json"
        echo "=== done $(date -u)"
        exit 0
    fi
    step 120 "paper task ${TASK_SIZE}² on $DEVICE" $PY benchmarks/gpu_task.py \
        --device "$DEVICE" --size "$TASK_SIZE" --json "$OUTDIR/task.json"
    # shellcheck disable=SC2086
    step 60 "gpu.py float32" $PY benchmarks/gpu.py --device "$DEVICE" --sizes $SIZES \
        --cpu-sizes --path-size 0 --repeats 2 --dtype float32 --json "$OUTDIR/gpu32.json"
    step 45 "task ${SMALL}² on $DEVICE" $PY benchmarks/gpu_task.py --device "$DEVICE" \
        --size "$SMALL" --json "$OUTDIR/task_small.json"
    step 60 "task ${SMALL}² on one CPU core" $PY benchmarks/gpu_task.py --device cpu \
        --threads 1 --size "$SMALL" --json "$OUTDIR/task_small_cpu.json"
    step 90 "41-state path ${PATH_SIZE}²" $PY benchmarks/gpu.py --device "$DEVICE" \
        --sizes --cpu-sizes --path-size "$PATH_SIZE" --json "$OUTDIR/path.json"
    $PY benchmarks/gpu_task.py --write-study "$TMP/one.toml" --size "$SMALL"
    step 60 "study run ${SMALL}² through Dask on $DEVICE" $PY -c "from roughcontact.cli.main import main; main()" study run \
        "$TMP/one.toml" -o "$TMP/study" --device "$DEVICE" --workers 1 --no-progress
    $PY -c "
import glob, xarray as xr
for f in sorted(glob.glob('$TMP/study/*.nc')):
    try:
        a = xr.open_dataset(f).attrs
    except Exception as err:
        print(f, err); continue
    print(f.split('/')[-1], {k: round(float(a[k]), 2) for k in a if k.endswith('_seconds')})
"
    echo "=== done $(date -u)"
} 2>&1 | tee "$LOG"
