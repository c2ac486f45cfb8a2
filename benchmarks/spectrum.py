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
eigenvalues (a few isolated ones could be deflated; a dense band cannot). ``--coarse-block
B`` adds a two-level preconditioner, the block preconditioner plus an additive Galerkin
coarse correction ``P (P^T H P)^+ P^T`` on B x B blocks, each block's indicator split on
the sites of negative curvature (V'' < 0) and the rest (dense, so for grids <= 256²):

    python benchmarks/spectrum.py --sizes 256 --adhesion-lengths 0.05 --coarse-block 8
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


def coarse_correction(hessian, curvature, n, b):
    """``r -> P (P^T H P)^+ P^T r``: block indicators split on V'' < 0, columns normalised."""
    import scipy.sparse as sp

    nb = n // b
    label = ((np.arange(n)[:, None] // b) * nb + np.arange(n)[None, :] // b).ravel()
    negative = curvature < 0
    column = label + nb * nb * negative  # two aggregates per block
    p = sp.csr_matrix((np.ones(n * n), (np.arange(n * n), column)), shape=(n * n, 2 * nb * nb))
    p = p[:, np.asarray(p.sum(axis=0)).ravel() > 0].tocsc()
    p = p @ sp.diags(1 / np.sqrt(np.asarray(p.sum(axis=0)).ravel()))
    dense = p.toarray()
    coarse = p.T @ np.column_stack([hessian(dense[:, j]) for j in range(dense.shape[1])])
    inverse = np.linalg.pinv(0.5 * (coarse + coarse.T), rcond=1e-10, hermitian=True)
    return lambda r: p @ (inverse @ (p.T @ r))


def case(n, la, seed, step=10, lowest=1, coarse_block=None):
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
    preconditioners = {"green": green, "block": block}
    if coarse_block:
        correction = coarse_correction(hessian, curvature, n, coarse_block)
        preconditioners[f"block+coarse{coarse_block}"] = lambda r: block(r) + correction(r)
    for name, precondition in preconditioners.items():
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
    ap.add_argument(
        "--coarse-block", type=int, default=None, help="also a two-level preconditioner (B x B)"
    )
    args = ap.parse_args(argv)
    if args.coarse_block is not None and (
        args.coarse_block < 2 or any(n % args.coarse_block for n in args.sizes)
    ):
        ap.error(f"--coarse-block must be >= 2 and divide every size, got {args.coarse_block}")
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
            r = case(n, la, args.seed, args.step, args.lowest, args.coarse_block)
            for name in [k for k in r if k in ("green", "block") or k.startswith("block+")]:
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
