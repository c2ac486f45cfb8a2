"""Spectrum of the smooth solver's preconditioned Hessian at the end of the SPEC §5 approach.

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

Prints one line per case; where the largest eigenvector lives (repulsive g < a0,
attractive, free sites) shows which sites limit the preconditioner.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from adhesive import A0, ES, approach_offsets, make_law
from hardwall import surface


def extremes(apply, m):
    """(lambda_max, its eigenvector, lambda_min > 0) of the operator ``apply`` on R^m."""
    from scipy.sparse.linalg import LinearOperator, eigs

    op = LinearOperator((m, m), matvec=lambda x: apply(np.ravel(x)), dtype=float)
    vals, vecs = eigs(op, k=1, which="LR", tol=1e-4)
    lam_max = float(vals.real[0])
    shifted = LinearOperator(
        (m, m), matvec=lambda x: 1.05 * lam_max * np.ravel(x) - apply(np.ravel(x)), dtype=float
    )
    low = np.sort(1.05 * lam_max - eigs(shifted, k=2, which="LR", tol=1e-4)[0].real)
    return lam_max, vecs[:, 0].real, float(low[1])  # low[0]: the uniform mode's 0


def case(n, la, seed):
    import roughcontact as rc
    from roughcontact.solvers import smooth
    from roughcontact.solvers._ops import compliance_operator, stiffness_operator

    h = surface(n, seed)
    law = make_law(la, None)
    sub = rc.Substrate(h.shape, contact_modulus=ES, pixel_size=A0)
    res = None
    for d in approach_offsets(h, 10, 5e-4)["offsets"]:
        res = rc.solve(h, sub, law, offset=float(d), initial=res, tol=1e-8)
        if not res.converged:
            raise RuntimeError(f"n={n}, la={la}: step at d={d} did not converge")
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

    out = dict(n=n, la=la, stiff=0 if stiff is None else len(stiff))
    for name, precondition in (("green", green), ("block", block)):
        lam_max, vec, lam_min = extremes(lambda v, p=precondition: p(hessian(v)), gap.size)
        weight = vec**2 / (vec**2).sum()
        attractive = (gap >= A0) & (gap < law.cutoff)
        out[name] = dict(
            lam_max=lam_max,
            lam_min=lam_min,
            kappa=lam_max / lam_min,
            weight_repulsive=float(weight[gap < A0].sum()),
            weight_attractive=float(weight[attractive].sum()),
        )
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[256, 512])
    ap.add_argument("--adhesion-lengths", type=float, nargs="+", default=[0.005, 0.05])
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    print("n      la     preconditioner  lam_max  lam_min  kappa   max-mode weight rep / att")
    for la in args.adhesion_lengths:
        for n in args.sizes:
            t0 = time.perf_counter()
            r = case(n, la, args.seed)
            for name in ("green", "block"):
                s = r[name]
                print(
                    f"{n:<6d} {la:<6g} {name:<15s} {s['lam_max']:7.2f}  {s['lam_min']:7.3f}"
                    f"  {s['kappa']:6.1f}  {s['weight_repulsive']:.2f} / "
                    f"{s['weight_attractive']:.2f}"
                )
            print(f"#   {r['stiff']} stiff sites, {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()
