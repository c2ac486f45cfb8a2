"""Warm starts of an adhesive path's steps: the previous state against two predictors.

The benchmark approach of ``adhesive.py`` (same surface, potential and offsets), each step
solved from one of three starting deflections:

* ``previous``: the last step's state (what ``approach_retract`` does);
* ``secant``: the last two states extrapolated to the new offset,
  ``w_k + (d - d_k) / (d_k - d_{k-1}) (w_k - w_{k-1})`` (a continuation predictor);
* ``coarse``: the same approach followed beside it on the grid coarsened 2 × 2 (block
  means of the heights, ``Substrate.coarsened()``), the previous fine state plus the coarse
  step's change of the deflection interpolated to the fine grid (Fourier interpolation:
  the coarse spectrum zero-padded; ``--interpolation constant`` repeats each coarse pixel).

Prints, per start, the iterations of every step, their sum over steps 2-10 (step 1 is
cold in all three), the coarse grid's iterations (a quarter of the cost each), the time,
and the repulsive areas: a start that ends a step in another metastable state shows there.

    python benchmarks/warm_start.py --size 256 --adhesion-length 0.05
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from adhesive import A0, ES, approach_offsets, make_law, surface


def interpolate(coarse: np.ndarray, how: str) -> np.ndarray:
    """A coarse field on the grid twice as fine (periodic)."""
    if how == "constant":
        return np.repeat(np.repeat(coarse, 2, axis=0), 2, axis=1)
    m, n = coarse.shape
    spectrum = np.fft.rfft2(coarse)
    fine = np.zeros((2 * m, n + 1), complex)
    fine[: m // 2, : n // 2 + 1] = spectrum[: m // 2, : n // 2 + 1]
    fine[-m // 2 :, : n // 2 + 1] = spectrum[-m // 2 :, : n // 2 + 1]
    return np.fft.irfft2(4 * fine, s=(2 * m, 2 * n))


def approach(h, law, offsets, start: str, tol: float, how: str) -> dict:
    import roughcontact as rc

    sub = rc.Substrate(h.shape, contact_modulus=ES, pixel_size=A0)
    n = h.shape[0]
    coarse_h = h.reshape(n // 2, 2, n // 2, 2).mean(axis=(1, 3))
    coarse_sub = sub.coarsened()
    states, coarse, iterations, coarse_iterations, seconds = [], None, [], [], 0.0
    for d in offsets:
        t0 = time.perf_counter()
        initial = states[-1] if states else None
        if start == "secant" and len(states) >= 2:
            a, b = states[-2], states[-1]
            r = (d - b.offset) / (b.offset - a.offset)
            initial = np.asarray(b.deflection) + r * (b.deflection - a.deflection)
        if start == "coarse":
            state = rc.solve(coarse_h, coarse_sub, law, offset=float(d), initial=coarse, tol=tol)
            coarse_iterations.append(state.iterations)
            if states and coarse is not None:
                change = interpolate(state.deflection - coarse.deflection, how)
                initial = np.asarray(states[-1].deflection) + change
            coarse = state
        res = rc.solve(h, sub, law, offset=float(d), initial=initial, tol=tol)
        seconds += time.perf_counter() - t0
        if not res.converged:
            raise RuntimeError(f"{start}: the step at d = {d:g} did not converge: {res.message}")
        states.append(res)
        iterations.append(int(res.iterations))
    return dict(
        iterations=iterations,
        coarse_iterations=coarse_iterations,
        seconds=seconds,
        repulsive_area=[float(s.repulsive_area) for s in states],
    )


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--adhesion-length", type=float, default=0.05)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--interpolation", choices=["fourier", "constant"], default="fourier")
    args = ap.parse_args(argv)
    if args.size < 16 or args.size % 4:
        ap.error(f"--size must be a multiple of 4, at least 16, got {args.size}")
    h = surface(args.size, args.seed)
    law = make_law(args.adhesion_length, None)
    offsets = approach_offsets(h, 10, 5e-4)["offsets"]
    print(f"# n={args.size}, la={args.adhesion_length:g}, tol {args.tol:g}")
    for start in ("previous", "secant", "coarse"):
        r = approach(h, law, offsets, start, args.tol, args.interpolation)
        coarse = f", coarse {sum(r['coarse_iterations'])}" if r["coarse_iterations"] else ""
        print(
            f"{start:<9s} iterations {r['iterations']} (steps 2-10: {sum(r['iterations'][1:])}"
            f"{coarse}), {r['seconds']:.2f} s; A_rep/A0 "
            + " ".join(f"{a:.4f}" for a in r["repulsive_area"])
        )


if __name__ == "__main__":
    main()
