"""Hard-wall benchmark: roughcontact against tamaas and ContactMechanics (benchmarks/README.md).

One self-affine surface per size (H = 0.8, h'rms = 0.1, lambda_s = 8, lambda_L = n/2,
fixed seed), pushed onto a periodic elastic half-space (E* = 1, a0 = 1) at a mean
pressure of 1e-3 E* (about 2 % contact), solved by each code to the same tolerance in
its own convergence measure. Prints one row per code and size; see README.md here.

    python benchmarks/hardwall.py --sizes 256 512 1024 --repeats 3 --json results.json

The peers are test/benchmark-only dependencies (``pip install tamaas ContactMechanics``);
they are imported inside functions, so a missing peer is reported and skipped.

What is timed (wall clock, ``time.perf_counter``; median over ``--repeats`` cold solves):

* roughcontact: the ``polonsky_keer`` call (what ``rc.solve`` runs for a hard wall,
  including its coarse-grid start; with ``--plain`` also ``rc-1grid``, the same on the
  fine grid alone, and ``rc-plain``, plain Polonsky-Keer on the fine grid). The ``Substrate``
  (stiffness array) is built once beforehand and reused; the result record (observables)
  is included.
* tamaas: ``PolonskyKeerRey.solve`` only. The model (``ModelFactory.createModel``, its
  FFT plans) and the solver object are built fresh for every repeat, outside the timer.
* ContactMechanics: ``constrained_conjugate_gradients`` only. The
  ``PeriodicFFTElasticHalfSpace`` (FFT engine, Green's function) and the ``Topography``
  are built once beforehand and reused; each solve starts cold.

Surface generation and imports are never timed. BLAS and OpenMP pools run on their
libraries' defaults (the figures in README.md) unless ``--blas-threads N`` is given, which
is then enforced and verified (``_threads.py``); the header and the JSON
(``meta.threads``) record the threads per library, CPUs and versions either way.
"""

from __future__ import annotations

import sys

if __name__ == "__main__":  # before NumPy, SciPy or a peer loads its BLAS: see _threads.py
    import _threads

    _threads.preset_from_argv(sys.argv[1:], "--blas-threads", default=None)

import argparse
import contextlib
import json
import os
import platform
import tempfile
import time

import _threads
import numpy as np

PEERS = ("tamaas", "contactmechanics")


# ------------------------------------------------------------------------------ helpers
def n_cores() -> int:
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def machine_meta() -> dict:
    """Where and with what a benchmark ran (JSON-ready; shared by the scripts here)."""
    import scipy

    import roughcontact

    return dict(
        machine=platform.machine(),
        processor=platform.processor(),
        cores=n_cores(),
        python=platform.python_version(),
        numpy=np.__version__,
        scipy=scipy.__version__,
        roughcontact=roughcontact.__version__,
    )


def surface(n: int, seed: int) -> np.ndarray:
    """The benchmark surface, roughcontact's convention (summits = maxima of h)."""
    import roughcontact as rc

    return rc.self_affine(
        (n, n), hurst=0.8, rms_slope=0.1, short_cutoff=8, long_cutoff=n / 2, seed=seed
    )


def fft_pair_seconds(n: int, workers: int, repeats: int = 7) -> float:
    """Median wall time of one forward + inverse real FFT pair on an n x n float64 grid.

    The best pair this machine does: the faster of one thread and ``workers`` threads
    (on small grids starting threads costs more than they save), and of
    ``scipy.fft.irfft2``, roughcontact's own inverse (the same transform one axis at a
    time, 1.6-1.8x faster in double precision with scipy 1.17) and the pair the solvers'
    convolutions run (``_backend.convolve``: scipy's pocketfft binding into arrays kept
    between calls, with a multiplication by ones in between; up to 2x faster at
    256²-512², where fresh result arrays page-fault).
    """
    import scipy.fft

    from roughcontact import _backend

    x = np.random.default_rng(0).standard_normal((n, n))
    ones = np.ones((n, n // 2 + 1))
    spectrum, out = np.empty(ones.shape, dtype=complex), np.empty_like(x)
    pairs = (
        lambda w: scipy.fft.irfft2(scipy.fft.rfft2(x, workers=w), s=x.shape, workers=w),
        lambda w: _backend.irfft2(scipy.fft.rfft2(x, workers=w), x.shape, workers=w),
        lambda w: _backend.convolve(x, ones, spectrum=spectrum, out=out, workers=w),
    )
    best = np.inf
    for w in sorted({1, workers}):
        for pair in pairs:
            pair(w)
            times = []
            for _ in range(repeats):
                t0 = time.perf_counter()
                pair(w)
                times.append(time.perf_counter() - t0)
            best = min(best, float(np.median(times)))
    return best


@contextlib.contextmanager
def capture_stderr_fd():
    """Capture what C/C++ code writes to file descriptor 2 (tamaas logs there)."""
    import ctypes

    sys.stderr.flush()
    box: dict[str, str] = {}
    with tempfile.TemporaryFile(mode="w+b") as tmp:
        saved = os.dup(2)
        os.dup2(tmp.fileno(), 2)
        try:
            yield box
        finally:
            with contextlib.suppress(Exception):
                ctypes.CDLL(None).fflush(None)
            sys.stderr.flush()
            os.dup2(saved, 2)
            os.close(saved)
            tmp.seek(0)
            box["text"] = tmp.read().decode(errors="replace")


# ------------------------------------------------------------------------------ solvers
# Each takes heights in roughcontact's convention (rigid surface at z = d - h, summits
# are maxima of h) and a mean pressure in units of E* (E* = 1, a0 = 1), and returns a
# dict with the pressure field (> 0 compressive), offset d, time, iterations.


def solve_rc(
    h: np.ndarray, load: float, tol: float, repeats: int, precondition=True, nested=True
) -> dict:
    import roughcontact as rc
    from roughcontact.solvers import polonsky_keer

    sub = rc.Substrate(h.shape, contact_modulus=1.0, pixel_size=1.0)
    times, res = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = polonsky_keer(h, sub, load=load, tol=tol, precondition=precondition, nested=nested)
        times.append(time.perf_counter() - t0)
    return dict(
        pressure=np.asarray(res.pressure),
        offset=float(res.offset),
        times=times,
        iterations=int(res.iterations),
        converged=bool(res.converged),
        residual=float(res.residual),
    )


def solve_tamaas(h: np.ndarray, load: float, tol: float, repeats: int) -> dict:
    """tamaas 2.9 PolonskyKeerRey (pressure primal), load control.

    Conventions (checked against roughcontact on a paraboloid): tamaas' surface heights
    point at the elastic body like ours (no sign flip); ``model.E``/``model.nu`` give
    E* = E/(1 - nu^2) (nu = 0 here, so E = E*); ``solve(p)`` takes the mean pressure;
    ``model.traction`` is the pressure (> 0 compressive); ``model.displacement`` is
    ``d + w`` (gap = displacement - h), so d = mean(displacement). Tolerance: tamaas'
    complementarity error ``sum(p * g) / (sum(p) * std(h))``. Its Green's function is
    the continuum k = E*|q|/2 on the FFT grid, identical to ours.
    """
    import tamaas as tm

    n0, n1 = h.shape
    heights = np.ascontiguousarray(h, dtype=np.float64)
    times, iters, err = [], None, None
    for _ in range(repeats):
        model = tm.ModelFactory.createModel(
            tm.model_type.basic_2d, [float(n0), float(n1)], [n0, n1]
        )
        model.E = 1.0
        model.nu = 0.0
        solver = tm.PolonskyKeerRey(model, heights, tol)
        solver.dump_freq = 10**9  # tamaas still logs the last iteration: parse it
        solver.max_iter = 100_000
        with capture_stderr_fd() as box:
            t0 = time.perf_counter()
            err = solver.solve(load)
            times.append(time.perf_counter() - t0)
        rows = [line.split() for line in box["text"].splitlines()]
        counts = [int(r[0]) for r in rows if r and r[0].isdigit()]
        iters = counts[-1] if counts else None
    pressure = np.array(model.traction, copy=True)
    disp = np.array(model.displacement, copy=True)
    return dict(
        pressure=pressure,
        offset=float(disp.mean()),
        times=times,
        iterations=iters,
        converged=bool(err is not None and err <= tol),
        residual=float(err),
    )


def solve_contactmechanics(h: np.ndarray, load: float, tol: float, repeats: int) -> dict:
    """ContactMechanics 1.8 constrained conjugate gradients, load control.

    Conventions: heights point at the substrate like ours (no sign flip); the gap is
    ``u - h - offset_CM`` with u the displacement (positive into the substrate, = our
    w plus its mean), so our d = mean(u) - offset_CM. Forces (not pressures) are
    returned in ``result.jac`` (> 0 compressive); with a0 = 1 they equal pressures.
    The q = 0 stiffness is set to that of the lowest mode (``stiffness_q0=None``); it
    only shifts mean(u) and is absorbed into the offset (``stiffness_q0=0`` breaks load
    control: the solver "converges" in one step to a uniform pressure). Tolerance
    mapping (CM has three absolute/relative criteria): ``pentol = tol * std(h)``
    (max/rms penetration), ``forcetol = tol * load * a0^2`` (max tensile pixel force),
    ``thermotol = tol`` (relative change of total force / rigid-body position).
    """
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization.ConstrainedConjugateGradients import (
        constrained_conjugate_gradients,
    )
    from SurfaceTopography import Topography

    n0, n1 = h.shape
    size = (float(n0), float(n1))
    sub = PeriodicFFTElasticHalfSpace((n0, n1), 1.0, physical_sizes=size)
    topo = Topography(np.asarray(h, dtype=np.float64), physical_sizes=size)
    force = load * n0 * n1
    times, res = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        res = constrained_conjugate_gradients(
            sub,
            topo,
            external_force=force,
            pentol=tol * float(np.std(h)),
            forcetol=tol * load,
            thermotol=tol,
            maxiter=100_000,
        )
        times.append(time.perf_counter() - t0)
    u = np.asarray(res.x)
    return dict(
        pressure=np.array(res.jac, copy=True),
        offset=float(u.mean() - res.offset),
        times=times,
        iterations=int(res.nit),
        converged=bool(res.success),
        residual=float("nan"),
    )


SOLVERS = {
    "roughcontact": solve_rc,
    # the same solver on the fine grid alone (no coarse-grid start): its iterations are
    # all the work, so its ms/it is the cost of one iteration
    "rc-1grid": lambda *args: solve_rc(*args, nested=False),
    # plain Polonsky-Keer (no preconditioner, no coarse-grid start), for comparison
    "rc-plain": lambda *args: solve_rc(*args, precondition=False, nested=False),
    "tamaas": solve_tamaas,
    "contactmechanics": solve_contactmechanics,
}


# ------------------------------------------------------------------------------ main
def run(sizes, repeats, tol, peers, load, seed, fft_workers, log=print, plain=False):
    rows = []
    for n in sizes:
        h = surface(n, seed)
        # the FFT reference before and after the solves (the machine's load drifts)
        fft_before = fft_pair_seconds(n, fft_workers)
        results = {}
        for code in ("roughcontact", *(["rc-1grid", "rc-plain"] if plain else []), *peers):
            try:
                out = SOLVERS[code](h, load, tol, repeats)
            except ImportError as exc:
                log(f"# {code}: not available ({exc}); skipped")
                continue
            results[code] = out
        fft = float(np.median([fft_before, fft_pair_seconds(n, fft_workers)]))
        ref = results.get("roughcontact")
        peer_times = [np.median(results[c]["times"]) for c in peers if c in results]
        for code, out in results.items():
            t = float(np.median(out["times"]))
            it = out["iterations"]
            per_it = t / it if it else float("nan")
            row = dict(
                code=code,
                n=n,
                seconds=t,
                all_seconds=[float(x) for x in out["times"]],
                iterations=it,
                seconds_per_iteration=per_it,
                fft_pair_seconds=fft,
                iteration_over_fft=per_it / fft,
                contact_fraction=float(np.mean(out["pressure"] > 0)),
                mean_pressure=float(np.mean(out["pressure"])),
                offset=out["offset"],
                converged=out["converged"],
                residual=out["residual"],
            )
            if code == "roughcontact" and peer_times:
                row["ratio_to_fastest_peer"] = t / float(min(peer_times))
            if ref is not None:
                p, pr = out["pressure"], ref["pressure"]
                row["rel_l2_vs_roughcontact"] = float(np.linalg.norm(p - pr) / np.linalg.norm(pr))
                row["offset_diff_vs_roughcontact"] = out["offset"] - ref["offset"]
            rows.append(row)
            log(format_row(row))
    return rows


HEADER = (
    f"{'code':<17}{'n':>6}{'time[s]':>10}{'iters':>7}{'ms/it':>9}{'fft[ms]':>9}"
    f"{'it/fft':>8}{'rc/peer':>9}{'area':>8}{'L2 vs rc':>10}{'conv':>6}"
)


def format_row(r: dict) -> str:
    ratio = r.get("ratio_to_fastest_peer")
    l2 = r.get("rel_l2_vs_roughcontact")
    return (
        f"{r['code']:<17}{r['n']:>6}{r['seconds']:>10.3f}{r['iterations'] or -1:>7}"
        f"{1e3 * r['seconds_per_iteration']:>9.2f}{1e3 * r['fft_pair_seconds']:>9.2f}"
        f"{r['iteration_over_fft']:>8.2f}"
        f"{(f'{ratio:.2f}' if ratio is not None else '-'):>9}"
        f"{100 * r['contact_fraction']:>7.2f}%"
        f"{(f'{l2:.1e}' if l2 is not None else '-'):>10}"
        f"{('yes' if r['converged'] else 'NO'):>6}"
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024, 2048])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--peers", nargs="*", default=list(PEERS), choices=PEERS)
    ap.add_argument("--load", type=float, default=1e-3, help="mean pressure in units of E*")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument(
        "--fft-workers",
        type=int,
        default=n_cores(),
        help="threads for the FFT-pair reference (the faster of this and one is used)",
    )
    ap.add_argument(
        "--blas-threads",
        type=int,
        default=None,
        help="BLAS/OpenMP threads per library, set before NumPy loads and verified (default: "
        "the libraries' own, as measured in README.md; recorded either way)",
    )
    ap.add_argument(
        "--plain",
        action="store_true",
        help="also time roughcontact on the fine grid alone (rc-1grid) and plain (rc-plain)",
    )
    ap.add_argument("--json", metavar="OUT", help="write all figures to this JSON file")
    args = ap.parse_args(argv)

    meta = dict(
        machine_meta(),
        fft_workers=args.fft_workers,
        tol=args.tol,
        load=args.load,
        seed=args.seed,
        repeats=args.repeats,
        surface=dict(hurst=0.8, rms_slope=0.1, short_cutoff=8, long_cutoff="n/2"),
    )
    for name, mod in (("tamaas", "tamaas"), ("contactmechanics", "ContactMechanics")):
        with contextlib.suppress(ImportError):
            meta[name] = __import__(mod).__version__
    preload = ("scipy.fft", "tamaas", "ContactMechanics")
    with _threads.enforced(args.blas_threads, preload=preload) as threads:
        meta["threads"] = threads
        print(
            f"# hard wall, mean pressure {args.load:g} E*, tol {args.tol:g}, "
            f"median of {args.repeats}, {meta['cores']} cores, FFT workers {args.fft_workers}\n"
            + _threads.describe(threads)
        )
        print(HEADER, flush=True)
        rows = run(
            args.sizes,
            args.repeats,
            args.tol,
            args.peers,
            args.load,
            args.seed,
            args.fft_workers,
            log=lambda s: print(s, flush=True),
            plain=args.plain,
        )
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(dict(meta=meta, rows=rows), fh, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
