"""Spectrum of the smooth solver's preconditioned Hessian at the end of the benchmark approach.

For each size and ℓa: the approach of ``adhesive.py`` (same surface, potential and
offsets, each step warm-started, tol 1e-8), then at its last state the extreme
eigenvalues of ``B H`` on mean-free deflections, with ``H = K + diag V''(g)`` the Hessian
of the energy and ``B`` either the substrate's Green's function alone or the solver's
block preconditioner (``roughcontact.solvers.smooth``). ``B H`` is self-adjoint in the
``B^-1`` inner product, so its eigenvalues are real; ARPACK finds the largest, then the
smallest ones as the largest of ``1.05 lambda_max - B H`` (the smallest is the rigid
uniform mode's 0, reported is the next). ``kappa`` = lambda_max / lambda_min bounds the
conjugate-gradient iteration count like sqrt(kappa) on a fixed Hessian.

    python benchmarks/spectrum.py --sizes 256 512 --adhesion-lengths 0.005 0.05
    python benchmarks/spectrum.py --sizes 256 --adhesion-lengths 0.05 --step 5 --lowest 12

Prints one line per case and preconditioner; where the largest and the smallest
eigenvectors live (their shares on repulsive g < a0 and attractive sites; the rest is on
free sites) shows which sites limit the preconditioner. ``--step`` takes the state after
an earlier step of the approach; ``--lowest`` prints that many of the smallest
eigenvalues (a few isolated ones could be deflated; a dense band cannot).
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from adhesive import A0, approach_state


def extremes(apply, m, lowest=1):
    """Extreme eigenpairs of the operator ``apply`` on R^m.

    Returns ``(lambda_max, its eigenvector, lows, their eigenvectors)``: ``lows`` are the
    ``lowest`` smallest eigenvalues above the uniform mode's 0, ascending.
    """
    from scipy.sparse.linalg import LinearOperator, eigs

    op = LinearOperator((m, m), matvec=lambda x: apply(np.ravel(x)), dtype=float)
    vals, vecs = eigs(op, k=1, which="LR", tol=1e-4)
    lam_max = float(vals.real[0])
    shifted = LinearOperator(
        (m, m), matvec=lambda x: 1.05 * lam_max * np.ravel(x) - apply(np.ravel(x)), dtype=float
    )
    low, low_vecs = eigs(shifted, k=lowest + 1, which="LR", tol=1e-4)
    order = np.argsort(1.05 * lam_max - low.real)[1:]  # [0]: the uniform mode's 0
    return lam_max, vecs[:, 0].real, 1.05 * lam_max - low.real[order], low_vecs[:, order].real


def case(n, la, seed, step=10, lowest=1):
    from roughcontact.solvers import smooth
    from roughcontact.solvers.fourier import compliance_operator, stiffness_operator

    _, law, sub, _, res = approach_state(n, la, seed, step, tol=1e-8)
    gap = np.ravel(res.gap)
    curvature = law.curvature(gap)
    stiffness, green = stiffness_operator(sub), compliance_operator(sub)
    stiff, diagonal = smooth._stiff_sites(law, gap, sub.self_stiffness)

    def hessian(v):
        v = v - v.mean()
        f = curvature * v
        return stiffness(v) + f - f.mean()

    def block(r):
        return smooth._precondition(r, stiff, diagonal, green, stiffness, True)[0]

    repulsive, attractive = gap < A0, (gap >= A0) & (gap < law.cutoff)

    def weights(vec):
        """Shares of the mode's squared amplitude on repulsive and attractive sites."""
        weight = vec**2 / (vec**2).sum()
        return float(weight[repulsive].sum()), float(weight[attractive].sum())

    out = dict(
        n=n,
        la=la,
        stiff=0 if stiff is None else len(stiff),
        repulsive=float(repulsive.mean()),
        attractive=float(attractive.mean()),
    )
    for name, precondition in (("green", green), ("block", block)):
        lam_max, vec, lows, low_vecs = extremes(
            lambda v, p=precondition: p(hessian(v)), gap.size, lowest
        )
        out[name] = dict(
            lam_max=lam_max,
            lam_min=float(lows[0]),
            lows=lows,
            kappa=lam_max / lows[0],
            weight_max=weights(vec),
            weight_min=weights(low_vecs[:, 0]),
        )
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512])
    ap.add_argument("--adhesion-lengths", type=float, nargs="+", default=[0.005, 0.05])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument(
        "--step", type=int, default=10, help="the state after this approach step (1-10)"
    )
    ap.add_argument(
        "--lowest", type=int, default=1, help="how many of the smallest eigenvalues to print"
    )
    args = ap.parse_args(argv)
    if not 1 <= args.step <= 10:
        ap.error(f"--step must be in 1..10, got {args.step}")
    if args.lowest < 1:
        ap.error(f"--lowest must be >= 1, got {args.lowest}")
    print(
        "n      la     preconditioner  lam_max  lam_min  kappa   "
        "mode weight rep / att: largest, smallest"
    )
    for la in args.adhesion_lengths:
        for n in args.sizes:
            t0 = time.perf_counter()
            r = case(n, la, args.seed, args.step, args.lowest)
            for name in ("green", "block"):
                s = r[name]
                (rmax, amax), (rmin, amin) = s["weight_max"], s["weight_min"]
                print(
                    f"{n:<6d} {la:<6g} {name:<15s} {s['lam_max']:7.2f}  {s['lam_min']:7.3f}"
                    f"  {s['kappa']:6.1f}  {rmax:.2f} / {amax:.2f}, {rmin:.2f} / {amin:.2f}"
                )
                if args.lowest > 1:
                    print("#   lowest:", " ".join(f"{v:.3f}" for v in s["lows"]))
            print(
                f"#   step {args.step}: {r['stiff']} stiff sites, repulsive / attractive "
                f"sites {r['repulsive']:.3f} / {r['attractive']:.3f} of the grid, "
                f"{time.perf_counter() - t0:.0f} s"
            )


if __name__ == "__main__":
    main()
