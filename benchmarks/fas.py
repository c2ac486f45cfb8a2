"""A two-level full approximation scheme (FAS) for the adhesive path step, measured.

Issue 39's item 3 asks for fewer iterations per path step at strong adhesion (ℓa 0.05) and
for iterations that grow at most 1.3x from 256² to 1024². Linear coarse corrections of the
fine Hessian did not get there (``spectrum.py --coarse-block``, ``warm_start.py``). This
script measures the nonlinear alternative on the benchmark approach of ``adhesive.py``:
every step of the approach from the same warm start (the plain solver's previous state,
paired), once by the plain solver and once by cycles of

1. pre-smoothing: ``nu`` iterations of the solver itself on the fine grid;
2. the coarse problem of FAS on the 2x2-coarsened grid (``Substrate.coarsened()``, block
   means of the heights): find ``W`` with ``g_H(W) = g_H(R w) - R g_h(w)``, where
   ``g = K w - p(d - h + w)`` is the force imbalance and ``R`` the block mean. The
   right-hand side ``b`` is taken into the heights, ``H' = H - K_H^-1 b`` (so the coarse
   problem is an ordinary solve: ``K W' - p(d - H' + W') = 0`` with ``W = W' + K_H^-1 b``),
   solved by the same solver to a tenth of the fine residual;
3. the correction ``P (W - R w)`` (``P``: each block's value on its four sites, or with
   ``--prolongation linear`` the bilinear interpolation), taken with the step length
   among 1, 1/2, 1/4, 0 that lowers the fine energy most,

until the fine solve converges. It reports the fine and the coarse iterations per step
(a coarse iteration costs about a quarter of a fine one). ``--widen F`` gives the coarse
level a law with the same work of adhesion and F times the range, a first guess at a
coarse-grained law.

    python benchmarks/fas.py --size 256 --adhesion-length 0.05
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from adhesive import A0, ES, approach_offsets, make_law, surface  # noqa: E402


def block_mean(x):
    """``R``: the 2x2 block means (n x n -> n/2 x n/2)."""
    n, m = x.shape
    return x.reshape(n // 2, 2, m // 2, 2).mean(axis=(1, 3))


def spread(x, kind="constant"):
    """``P``: each coarse value on its block's four sites (``constant``), or the periodic
    bilinear interpolation between the blocks' centres (``linear``)."""
    if kind == "constant":
        return np.kron(x, np.ones((2, 2)))
    out = np.kron(x, np.ones((2, 2)))
    # a fine site lies a quarter of a coarse pixel from its block's centre: 3/4 of its
    # block and 1/4 of the neighbour on that side, along each axis
    for axis in (0, 1):
        lo = np.roll(out, 2, axis=axis)
        hi = np.roll(out, -2, axis=axis)
        idx = np.arange(out.shape[axis]) % 2
        shape = [1, 1]
        shape[axis] = -1
        first = (idx == 0).reshape(shape)
        out = 0.75 * out + 0.25 * np.where(first, lo, hi)
    return out


def imbalance(sub, law, heights, offset, w):
    """The force imbalance ``K w - p(d - h + w)`` (pressure)."""
    return sub.pressure(w) - law.pressure(offset - heights + w)


def energy(sub, law, heights, offset, w):
    """The total energy per area (elastic plus interaction)."""
    return float(sub.energy(w)) + float(np.mean(law.energy(offset - heights + w)))


def fas_step(h, sub, law, offset, w, tol, nu, max_cycles=200, kind="constant", coarse_law=None):
    """One path step by FAS cycles from the deflection ``w``: ``(result, fine, coarse,
    cycles, accepted step lengths)``."""
    import roughcontact as rc

    coarse_sub = sub.coarsened()
    coarse_h = block_mean(h)
    coarse_law = coarse_law or law
    fine = coarse = 0
    steps = []
    res = None
    for cycle in range(max_cycles):
        res = rc.solve(h, sub, law, offset=offset, initial=w, tol=tol, max_iter=nu)
        fine += res.iterations
        w = np.asarray(res.deflection)
        if res.converged:
            return res, fine, coarse, cycle, steps
        w0 = block_mean(w)
        b = imbalance(coarse_sub, coarse_law, coarse_h, offset, w0) - block_mean(
            imbalance(sub, law, h, offset, w)
        )
        shift = coarse_sub.deflection(b - b.mean())  # K_H^-1 b (the mean is the load's)
        sol = rc.solve(
            coarse_h - shift, coarse_sub, coarse_law, offset=offset, initial=w0 - shift,
            tol=max(tol, 0.1 * float(res.residual)), max_iter=2000,
        )  # fmt: skip
        coarse += sol.iterations
        e = spread(np.asarray(sol.deflection) + shift - w0, kind)
        e -= e.mean()
        base = energy(sub, law, h, offset, w)
        trials = {a: energy(sub, law, h, offset, w + a * e) for a in (1.0, 0.5, 0.25)}
        alpha = min(trials, key=trials.get)
        if trials[alpha] < base:
            w = w + alpha * e
            steps.append(alpha)
        else:
            steps.append(0.0)
    return res, fine, coarse, max_cycles, steps


def run(size, la, seed, tol, nu, steps, kind="constant", widen=1.0, log=print):
    import roughcontact as rc

    h = surface(size, seed)
    law = make_law(la, None)
    sub = rc.Substrate(h.shape, contact_modulus=ES, pixel_size=A0)
    offsets = approach_offsets(h, steps, 5e-4)["offsets"]
    # the coarse level's law: the same w, its range widened (``widen`` times Delta_r)
    coarse_law = law if widen == 1.0 else rc.SmoothLJ93(
        contact_modulus=ES, pixel_size=A0, work_of_adhesion=law.work_of_adhesion,
        range=widen * law.range)  # fmt: skip
    rows, prev = [], None
    for k, d in enumerate(offsets, 1):
        plain = rc.solve(h, sub, law, offset=float(d), initial=prev, tol=tol)
        row = dict(step=k, offset=float(d), plain=int(plain.iterations))
        if prev is not None:  # step 1 starts cold: the same solve in both
            res, fine, coarse, cycles, taken = fas_step(
                h, sub, law, float(d), np.asarray(prev.deflection), tol, nu, kind=kind,
                coarse_law=coarse_law,
            )
            pixels = round(abs(res.repulsive_area - plain.repulsive_area) * h.size)
            row.update(fine=fine, coarse=coarse, cycles=cycles, steps=taken,
                       converged=bool(res.converged), area_diff_pixels=pixels)  # fmt: skip
        log(json.dumps(row))
        rows.append(row)
        prev = plain
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--adhesion-length", type=float, default=0.05)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--tol", type=float, default=1e-6)
    ap.add_argument("--nu", type=int, default=5, help="fine iterations per cycle")
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--prolongation", choices=("constant", "linear"), default="constant")
    ap.add_argument("--widen", type=float, default=1.0,
                    help="the coarse level's law: the same w, the range times this")  # fmt: skip
    args = ap.parse_args(argv)
    rows = run(args.size, args.adhesion_length, args.seed, args.tol, args.nu, args.steps,
               args.prolongation, args.widen)
    done = [r for r in rows if "fine" in r]
    print(
        f"# steps 2-{args.steps}: plain {sum(r['plain'] for r in done)} iterations; FAS "
        f"{sum(r['fine'] for r in done)} fine + {sum(r['coarse'] for r in done)} coarse "
        f"(nu {args.nu}, {args.prolongation}, coarse range x{args.widen:g}); all converged: "
        f"{all(r['converged'] for r in done)}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
