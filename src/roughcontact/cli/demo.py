"""The main job on built-in defaults: a non-adhesive load path on a self-affine surface.

Generates the benchmarks' default surface (H = 0.8, h'rms = 0.1, λs = 8 a0, λL = L/2),
pushes it onto an elastic half-space (E* = 1) at increasing loads under load control,
each state warm-started from the last, and reports A_rep/A0 against N/A0 and κ_rep at
1 % repulsive area, from the site count and from the perimeter-corrected area (Pastewka &
Robbins 2014, Eq. 2; the continuum hard-wall value is κ_rep ≈ 2).
"""

from __future__ import annotations

import time

import numpy as np

from ..analysis.path import interpolate_at_area, kappa
from ..elastic import Substrate
from ..solvers import solve
from ..surfaces import self_affine, statistics

__all__ = ["demo"]


def demo(*, size: int = 512, seed: int = 2014, loads=None, tol: float = 1e-8, progress=None):
    """Run the demo path; return a JSON-ready dict.

    Parameters
    ----------
    size : int
        Grid size n (n × n sites, lattice units).
    seed : int
        Seed of the surface.
    loads : sequence of float, optional
        Mean pressures N/A0 in units of E* (default: 8 loads from 1.5e-4 to 3e-3).
    progress : callable, optional
        ``progress(step, n_steps, result)`` after each state.
    """
    hurst, rms_slope, short_cutoff = 0.8, 0.1, 8.0
    heights = self_affine(
        (size, size),
        hurst=hurst,
        rms_slope=rms_slope,
        short_cutoff=short_cutoff,
        long_cutoff=size / 2,
        seed=seed,
    )
    stats = statistics(heights)
    substrate = Substrate((size, size), contact_modulus=1.0)
    loads = np.geomspace(1.5e-4, 3e-3, 8) if loads is None else np.asarray(loads, dtype=float)
    rows, previous, t0 = [], None, time.perf_counter()
    for i, load in enumerate(loads):
        res = solve(heights, substrate, load=float(load), initial=previous, tol=tol)
        previous = res
        rows.append(
            {
                "load": res.load,
                "repulsive_area": res.repulsive_area,
                "corrected_repulsive_area": res.corrected_repulsive_area,
                "offset": res.offset,
                "perimeter": res.perimeter,
                "mean_gap": res.mean_gap,
                "iterations": res.iterations,
                "converged": res.converged,
                "solve_seconds": res.solve_seconds,
            }
        )
        if progress is not None:
            progress(i + 1, len(loads), res)
    areas = [r["repulsive_area"] for r in rows]
    out = {
        "surface": {
            "size": size,
            "hurst": hurst,
            "short_cutoff": short_cutoff,
            "long_cutoff": size / 2,
            "seed": seed,
            **stats.to_dict(),
        },
        "path": rows,
        "all_converged": all(r["converged"] for r in rows),
        "total_seconds": time.perf_counter() - t0,
    }
    try:
        load_1 = interpolate_at_area(areas, [r["load"] for r in rows], 0.01)
        out["kappa_rep"] = kappa(0.01, load_1, stats.rms_slope)
        out["load_at_1_percent"] = load_1
        # the same with the perimeter-corrected area (Yastrebov et al. 2017): the
        # estimate of the continuum area, free of the lattice's bias
        corrected = [r["corrected_repulsive_area"] for r in rows]
        out["kappa_rep_corrected"] = kappa(
            0.01, interpolate_at_area(corrected, [r["load"] for r in rows], 0.01), stats.rms_slope
        )
    except ValueError as err:
        out["kappa_rep"], out["kappa_rep_error"] = None, str(err)
    return out
