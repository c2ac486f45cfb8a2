"""Adhesive benchmark: a warm-started approach against Adhesion and tamaas (benchmarks/README.md).

One self-affine surface per size (H = 0.8, h'rms = 0.1, lambda_s = 8, lambda_L = n/2,
fixed seed) on a periodic elastic half-space (E* = 1, a0 = 1), with the paper's smoothed
9-3 Lennard-Jones wall (``rc.SmoothLJ93.from_adhesion_length(la)``: k = E*/(2 a0) per
area, Delta_r = sqrt(24 a0 la), w = k Delta_r^2 / 12), brought into contact in ``--steps``
equal steps of the offset d under displacement control, each step warm-started from the
last. Prints one line per step and code and a summary per size, la and code; see
README.md here.

    python benchmarks/adhesive.py --sizes 256 512 --repeats 1 --json adhesive.json

The approach (the same offsets for every code): d_start = max(h) + a0, where the summit
sits at the equilibrium distance of the potential (first repulsive contact of the rigid
surfaces; the attraction already acts over Delta_r around it), down to
d_end = d_hw + a0 with d_hw the offset of the hard-wall solution at mean pressure
``--end-load`` (default 5e-4 E*, ~1.2 % hard-wall contact, which gives A_rep ~ 2-3 % for
la = 0.005). Step k = 1..steps solves d_k = d_start - k (d_start - d_end) / steps; step 1
starts from the undeformed substrate (cold) in every code.

Codes (peers are test/benchmark-only dependencies, imported inside functions):

* roughcontact: ``rc.solve(h, sub, law, offset=d, initial=prev, tol=tol)``; convergence
  is max |K w - p_int(g)| / E* <= tol (mean removed: the uniform mode is rigid).
* Adhesion 0.93: ``SmoothContactSystem`` with ``LJ93(eps, sigma).spline_cutoff(gamma=w)``
  (numerically identical potential, checked and printed before timing; by default with
  Adhesion's ``linearize_core()`` below a0/2, where no state goes, see adhesion_potential) on a
  ``PeriodicFFTElasticHalfSpace`` with a rigid uniform mode (``stiffness_q0=0``; the
  objective is wrapped to act on the mean-free displacement, as ours), minimised by
  ``scipy.optimize.minimize(method="L-BFGS-B", jac=True)`` from the previous step's
  displacement, ``gtol = tol * E* * a0^2``, ``ftol = 0``: its gradient is the force
  imbalance per pixel, so both codes stop on the same quantity. Skipped above
  ``--adhesion-max-size`` (default 512) and stopped after ``--adhesion-time-cap`` seconds
  per step (reported as not converged).
* tamaas 2.9: ``PolonskyKeerRey`` with gap primal and mean-gap constraint plus an
  ``ExponentialAdhesionFunctional`` (-gamma exp(-g/rho) on a hard wall) with
  gamma = w and rho = 9 Delta_r / 16 (same work of adhesion and same largest tensile
  stress 16 w / (9 Delta_r) as the smoothed LJ wall). Displacement control through the
  mean gap: target = d - mean(h) - a0 (its hard wall at g = 0 stands for our g = a0).
  Tolerance: ``tol`` in its own (complementarity) measure. Its solver keeps its state
  between solves (warm start).

Surface generation, the hard-wall solve that fixes the schedule, model construction
and imports are never timed. BLAS runs on ``--blas-threads`` (default 1):
roughcontact calls no BLAS, but Adhesion's NuMPI reductions call ``np.dot`` on every
evaluation, and a 2-thread OpenBLAS dot of 65k doubles took 12 ms instead of 9 us while
another process kept one of the two cores busy. The limit is enforced, not assumed (see
``_threads.py``): the thread variables (OPENBLAS_NUM_THREADS, OMP_NUM_THREADS, ...) are
set before NumPy is imported, threadpoolctl limits every loaded pool when installed, the
pools are verified, and the script refuses to run if the limit cannot be enforced; the
header and the JSON (``meta.threads``) record threads per library, CPUs and versions.
"""

from __future__ import annotations

import sys

if __name__ == "__main__":  # before NumPy, SciPy or a peer loads its BLAS: see _threads.py
    import _threads

    _threads.preset_from_argv(sys.argv[1:], "--blas-threads", default=1)

import argparse
import contextlib
import json
import os
import time
from importlib import metadata

import _threads
import adhesive_load
import numpy as np
from adhesive_peers import check_potential, run_adhesion, run_tamaas
from adhesive_report import (
    STEP_HEADER,
    SUMMARY_HEADER,
    format_step,
    format_summary,
    summarise,
    targets,
)
from hardwall import fft_pair_seconds, machine_meta, n_cores, surface

PEERS = ("adhesion", "tamaas")
A0 = 1.0  # pixel size = equilibrium distance (lattice units)
ES = 1.0  # contact modulus E*


# ------------------------------------------------------------------------------ set-up
def make_law(adhesion_length: float, stiffness: float | None):
    """The paper's potential at ℓa (k = E*/(2 a0)), or with site stiffness ``stiffness`` (E*/a0)."""
    import roughcontact as rc

    if stiffness is None:
        return rc.SmoothLJ93.from_adhesion_length(
            adhesion_length, contact_modulus=ES, pixel_size=A0
        )
    return rc.SmoothLJ93(
        contact_modulus=ES,
        pixel_size=A0,
        stiffness=stiffness * ES / A0,
        work_of_adhesion=adhesion_length * ES,
    )


def approach_offsets(h: np.ndarray, steps: int, end_load: float, step=None) -> dict:
    """The displacement schedule (see the module docstring); with ``step`` (length) steps
    of that size from the start, as many as reach the end (the last one shorter)."""
    import roughcontact as rc

    sub = rc.Substrate(h.shape, contact_modulus=ES, pixel_size=A0)
    hw = rc.solve(h, sub, rc.HardWall(), load=end_load, tol=1e-8)
    d_start = float(h.max()) + A0
    d_end = float(hw.offset) + A0
    if step is not None:
        steps = max(1, int(np.ceil((d_start - d_end) / step - 1e-9)))
        offsets = np.maximum(d_start - step * np.arange(1, steps + 1), d_end)
    else:
        offsets = d_start - (d_start - d_end) * np.arange(1, steps + 1) / steps
    return dict(
        offsets=offsets,
        d_start=d_start,
        d_end=d_end,
        hardwall_area=float(hw.repulsive_area),
    )


def approach_state(n: int, la: float, seed: int, steps: int, tol: float):
    """The benchmark approach's first ``steps`` steps, each warm-started from the last.

    Returns ``(h, law, substrate, offsets, state)``: the surface, potential, substrate,
    all 10 offsets, and the state after step ``steps`` (None for 0). Raises if a step
    does not converge. For the diagnostics (``spectrum.py``, ``front.py``).
    """
    import roughcontact as rc

    h = surface(n, seed)
    law = make_law(la, None)
    sub = rc.Substrate(h.shape, contact_modulus=ES, pixel_size=A0)
    offsets = approach_offsets(h, 10, 5e-4)["offsets"]
    state = None
    for d in offsets[:steps]:
        state = rc.solve(h, sub, law, offset=float(d), initial=state, tol=tol)
        if not state.converged:
            raise RuntimeError(f"n={n}, la={la}: step at d={d} did not converge")
    return h, law, sub, offsets, state


# ------------------------------------------------------------------------------ codes
# Each runs the whole approach once and returns one dict per step with: offset, seconds,
# iterations, converged, residual (max force imbalance / E*, where defined),
# repulsive_area, attractive_area, load (mean pressure / E*), plus the final fields.


def run_roughcontact(h, law, offsets, tol, max_iter, dtype="float64", **_) -> dict:
    import roughcontact as rc

    sub = rc.Substrate(h.shape, contact_modulus=ES, pixel_size=A0)
    steps, prev = [], None
    for d in offsets:
        t0 = time.perf_counter()
        res = rc.solve(
            h, sub, law, offset=float(d), initial=prev, tol=tol, max_iter=max_iter, dtype=dtype
        )
        t = time.perf_counter() - t0
        prev = res
        steps.append(
            dict(
                offset=float(d),
                seconds=t,
                iterations=int(res.iterations),
                evaluations=None,
                converged=bool(res.converged),
                residual=float(res.residual),
                message=str(res.message),
                repulsive_area=float(res.repulsive_area),
                attractive_area=float(res.attractive_area),
                load=float(res.load),
                min_gap=float(np.min(res.gap)),
            )
        )
    return dict(steps=steps, pressure=np.array(prev.pressure), gap=np.array(prev.gap))


def run_roughcontact32(*args, **kwargs) -> dict:
    """roughcontact in single precision (``dtype="float32"``, same tolerance)."""
    return run_roughcontact(*args, **kwargs, dtype="float32")


RUNNERS = {
    "roughcontact": run_roughcontact,
    "roughcontact32": run_roughcontact32,
    "adhesion": run_adhesion,
    "tamaas": run_tamaas,
}
OURS = ("roughcontact", "roughcontact32")


# ------------------------------------------------------------------------------ main
def repeat(code, repeats, *args, **kwargs) -> dict:
    """Run the approach ``repeats`` times; per-step times are the medians."""
    outs = [RUNNERS[code](*args, **kwargs) for _ in range(repeats)]
    out = outs[-1]
    for i, step in enumerate(out["steps"]):
        step["all_seconds"] = [o["steps"][i]["seconds"] for o in outs]
        step["seconds"] = float(np.median(step["all_seconds"]))
    return out


def run(args, log=print) -> dict:
    summaries, details, checks = [], [], []
    for la in args.adhesion_lengths:
        law = make_law(la, args.stiffness)
        if "adhesion" in args.peers:
            with contextlib.suppress(ImportError):
                chk = check_potential(law, args.adhesion_core)
                chk["adhesion_length"] = la
                checks.append(chk)
                log(
                    f"# potential check la={la:g} (k={law.stiffness:g}, Delta_r={law.range:.4f}, "
                    f"w={law.work_of_adhesion:g}): Adhesion ({args.adhesion_core} core) vs "
                    f"roughcontact on {chk['gaps']} gaps in [0.5 a0, a0 + 1.3 Delta_r]: "
                    f"max |dV| {chk['max_abs_energy_diff']:.1e}, "
                    f"max |dp| {chk['max_abs_pressure_diff']:.1e}, "
                    f"max rel. dV'' {chk['max_rel_curvature_diff']:.1e}; cutoff "
                    f"{chk['cutoff_adhesion']:.6f} vs {chk['cutoff_rc']:.6f}"
                )
                for g, v_rc, v_ad in chk["sample"]:
                    log(f"#   V({g:.4f}) = {v_rc:+.6e} (rc)  {v_ad:+.6e} (Adhesion)")
    for n in args.sizes:
        h = surface(n, args.seed)
        fft = fft_pair_seconds(n, args.fft_workers)
        sched = approach_offsets(h, args.steps, args.end_load, args.offset_step)
        offsets = sched["offsets"]
        log(
            f"# n={n}: h_rms {np.std(h):.4f}, offsets {sched['d_start']:.4f} -> "
            f"{sched['d_end']:.4f} in {len(offsets)} steps (hard-wall contact at the end "
            f"load {100 * sched['hardwall_area']:.2f} %), FFT pair {1e3 * fft:.2f} ms"
        )
        for la in args.adhesion_lengths:
            law = make_law(la, args.stiffness)
            results = {}
            ours = ("roughcontact", "roughcontact32") if args.float32 else ("roughcontact",)
            for code in (*ours, *args.peers):
                if code == "adhesion" and n > args.adhesion_max_size:
                    log(
                        f"# adhesion: skipped at n={n} > --adhesion-max-size "
                        f"{args.adhesion_max_size} (L-BFGS-B takes very long here)"
                    )
                    continue
                try:
                    t0 = time.perf_counter()
                    out = repeat(
                        code,
                        args.repeats if code in OURS else args.peer_repeats,
                        h,
                        law,
                        offsets,
                        args.tol,
                        args.max_iter,
                        time_cap=args.adhesion_time_cap,
                        core=args.adhesion_core,
                    )
                    wall = time.perf_counter() - t0
                except ImportError as exc:
                    log(f"# {code}: not available ({exc}); skipped")
                    continue
                results[code] = out
                log(f"# n={n} la={la:g} {code}: {wall:.1f} s wall")
            ref = results.get("roughcontact")
            log(STEP_HEADER)
            for code, out in results.items():
                for k, s in enumerate(out["steps"], 1):
                    cmp = None
                    if code == "adhesion" and ref is not None:
                        r = ref["steps"][k - 1]
                        d_area = s["repulsive_area"] - r["repulsive_area"]
                        s["dA_rep_pixels"] = int(round(d_area * n * n))
                        s["dload_rel"] = (s["load"] - r["load"]) / max(abs(r["load"]), 1e-300)
                        cmp = r
                    log(format_step(code, k, s, cmp))
            rows = {c: summarise(c, n, la, o, fft) for c, o in results.items()}
            for mine in ("roughcontact32",):  # ratios of the single-precision run too
                if mine in rows:
                    for peer in ("adhesion", "tamaas"):
                        if peer in rows:
                            rows[mine][f"{peer}_over_roughcontact"] = (
                                rows[peer]["seconds_per_step"] / rows[mine]["seconds_per_step"]
                            )
                    p32 = results[mine]["pressure"].ravel()
                    p64 = results["roughcontact"]["pressure"].ravel()
                    rows[mine]["final_pressure_rel_l2_vs_roughcontact"] = float(
                        np.linalg.norm(p32 - p64) / np.linalg.norm(p64)
                    )
            if "adhesion" in rows and "roughcontact" in rows:
                rows["roughcontact"]["adhesion_over_roughcontact"] = (
                    rows["adhesion"]["seconds_per_step"] / rows["roughcontact"]["seconds_per_step"]
                )
                p, pa = ref["pressure"].ravel(), results["adhesion"]["pressure"].ravel()
                rows["adhesion"]["final_pressure_rel_l2_vs_roughcontact"] = float(
                    np.linalg.norm(pa - p) / np.linalg.norm(p)
                )
                log(
                    f"# n={n} la={la:g}: Adhesion vs roughcontact at the last step: pressure "
                    f"rel. L2 {rows['adhesion']['final_pressure_rel_l2_vs_roughcontact']:.1e}, "
                    f"A_rep {100 * rows['adhesion']['final_repulsive_area']:.3f} % vs "
                    f"{100 * rows['roughcontact']['final_repulsive_area']:.3f} %, load "
                    f"{rows['adhesion']['final_load']:.4e} vs "
                    f"{rows['roughcontact']['final_load']:.4e}"
                    f"; smallest gap on the path {rows['adhesion']['min_gap']:.3f} vs "
                    f"{rows['roughcontact']['min_gap']:.3f} a0"
                )
            if "tamaas" in rows and "roughcontact" in rows:
                rows["roughcontact"]["tamaas_over_roughcontact"] = (
                    rows["tamaas"]["seconds_per_step"] / rows["roughcontact"]["seconds_per_step"]
                )
                rows["tamaas"]["rho"] = results["tamaas"]["rho"]
                rows["tamaas"]["surface_energy"] = results["tamaas"]["surface_energy"]
            for code, out in results.items():
                details.append(
                    dict(
                        code=code,
                        n=n,
                        adhesion_length=la,
                        schedule=dict(
                            d_start=sched["d_start"],
                            d_end=sched["d_end"],
                            hardwall_area=sched["hardwall_area"],
                        ),
                        steps=out["steps"],
                    )
                )
            for r in rows.values():
                summaries.append(r)
    return dict(summary=summaries, details=details, potential_checks=checks)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512, 1024])
    ap.add_argument("--adhesion-lengths", type=float, nargs="+", default=[0.005, 0.05])
    ap.add_argument(
        "--stiffness",
        type=float,
        default=None,
        help="site stiffness k in E*/a0 (default 0.5, the paper); Delta_r from w = k Delta_r^2/12",
    )
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument(
        "--offset-step",
        type=float,
        default=None,
        help="steps of this offset change (a0) over the same range instead of --steps "
        "(the iterations per step at equal steps across sizes: the range grows with n)",
    )
    ap.add_argument("--tol", type=float, default=1e-6, help="max force imbalance / E*")
    ap.add_argument("--peers", nargs="*", default=list(PEERS), choices=PEERS)
    ap.add_argument("--max-iter", type=int, default=5000, help="iteration cap per step")
    ap.add_argument(
        "--end-load",
        type=float,
        default=5e-4,
        help="mean pressure / E* of the hard-wall solve whose offset (+ a0) ends the approach",
    )
    ap.add_argument("--repeats", type=int, default=3, help="approaches timed for roughcontact")
    ap.add_argument("--peer-repeats", type=int, default=1, help="approaches timed for peers")
    ap.add_argument("--adhesion-max-size", type=int, default=512)
    ap.add_argument(
        "--adhesion-core",
        choices=("linear", "bare"),
        default="linear",
        help="Adhesion's LJ93 core: linearize_core() below a0/2 (default) or the bare 9-3 wall",
    )
    ap.add_argument(
        "--adhesion-time-cap", type=float, default=600.0, help="seconds per step for Adhesion"
    )
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--fft-workers", type=int, default=n_cores())
    ap.add_argument(
        "--blas-threads",
        type=int,
        default=1,
        help="BLAS/OpenMP threads per library, set before NumPy loads and verified; 1 keeps "
        "the peers' dot products sane on a busy machine",
    )
    ap.add_argument(
        "--float32",
        action="store_true",
        help="also time roughcontact with dtype='float32' (code roughcontact32)",
    )
    ap.add_argument(
        "--load-control",
        action="store_true",
        help="also the load-controlled cold solves and paths of adhesive_load.py (issue "
        "surface, --sizes and --adhesion-lengths) after the approach",
    )
    adhesive_load.add_arguments(ap, prefix="lc-")
    ap.add_argument("--json", metavar="OUT", help="write all figures to this JSON file")
    args = ap.parse_args(argv)

    meta = dict(
        machine_meta(),
        options=vars(args),
        surface=dict(hurst=0.8, rms_slope=0.1, short_cutoff=8, long_cutoff="n/2"),
    )
    with contextlib.suppress(Exception):
        import subprocess

        meta["git"] = subprocess.run(
            ["git", "describe", "--always", "--dirty"],
            capture_output=True,
            text=True,
            cwd=os.path.dirname(os.path.abspath(__file__)),
        ).stdout.strip()
    for dist in ("Adhesion", "ContactMechanics", "tamaas"):
        with contextlib.suppress(metadata.PackageNotFoundError):
            meta[dist] = metadata.version(dist)
    # the limit, and its check, cover scipy's own OpenBLAS (L-BFGS-B) and the peers' libraries:
    # load them first (threadpoolctl sees only loaded libraries)
    preload = ("scipy.optimize", "Adhesion.System", "ContactMechanics", "tamaas")
    with _threads.enforced(args.blas_threads, preload=preload) as threads:
        meta["threads"] = threads
        meta["threadpools"] = threads["threadpools"]
        print(
            f"# adhesive approach, "
            f"{f'steps of {args.offset_step:g} a0' if args.offset_step else f'{args.steps} steps'}"
            f", tol {args.tol:g} (max force imbalance / "
            f"E*), cap {args.max_iter} it/step, roughcontact median of {args.repeats}, peers "
            f"{args.peer_repeats}; Adhesion up to n={args.adhesion_max_size}, "
            f"{args.adhesion_time_cap:g} s/step cap; {meta['cores']} cores, FFT workers "
            f"{args.fft_workers}, BLAS threads {args.blas_threads}\n" + _threads.describe(threads),
            flush=True,
        )
        t0 = time.perf_counter()
        out = run(args, log=lambda s: print(s, flush=True))
        if args.load_control:  # the same process, threads and machine: beside the peers
            out["load_control"] = adhesive_load.run(
                args.sizes, args.adhesion_lengths, args.lc_loads, args.lc_path_loads, 1e-8,
                args.max_iter, args.nested, log=lambda s: print(s, flush=True),
                coarse_start=not args.no_coarse_start,
            )  # fmt: skip
    print("# summary (t/step: median over the steps; Adh/rc, tm/rc: the peer's t/step / ours)")
    print(SUMMARY_HEADER)
    for r in out["summary"]:
        print(format_summary(r))
    out["targets"] = targets(out["summary"])
    out["wall_seconds"] = time.perf_counter() - t0
    print(f"# total wall time {out['wall_seconds']:.0f} s", flush=True)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(dict(meta=meta, **out), fh, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
