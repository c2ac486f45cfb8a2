"""How the sites that jump into contact during one approach step join, iteration by iteration.

A diagnostic of the smooth solver's long steps (``benchmarks/README.md``): the approach of
``adhesive.py`` (same surface, potential and offsets, each step warm-started, tol 1e-6)
up to ``--step``; that step is then solved again from the same warm start with
``max_iter = 1, 2, ...`` (the iterates of one solve: the solver is deterministic), and for
each iteration it prints the residual and how many sites became repulsive (g < a0) for
the first time in this step, and to how many of the step's final clusters of new
repulsive sites (4-connected) they belong. Whether the new contact arrives as many small
clusters at once or as one cluster growing by a front over many iterations tells which
kind of method could shorten the step.

    python benchmarks/front.py --size 256 --adhesion-length 0.05 --step 5

Costs about iterations²/2 solver iterations.
"""

from __future__ import annotations

import argparse

import numpy as np
from adhesive import A0, approach_state


def front(n, la, step, seed=1, tol=1e-6):
    """Per-iteration record of one approach step; returns (rows, cluster sizes, spans)."""
    from scipy import ndimage

    import roughcontact as rc

    h, law, sub, offsets, prev = approach_state(n, la, seed, step - 1, tol)
    offset = float(offsets[step - 1])
    full = rc.solve(h, sub, law, offset=offset, initial=prev, tol=tol)
    if not full.converged:
        raise RuntimeError(f"step {step} did not converge: {full.message}")
    before = np.zeros(h.shape, bool) if prev is None else np.asarray(prev.gap) < A0
    new = (np.asarray(full.gap) < A0) & ~before
    labels, _ = ndimage.label(new)
    first = np.zeros(h.shape, int)  # iteration at which a site first became repulsive
    rows = []
    for k in range(1, full.iterations + 1):
        r = rc.solve(h, sub, law, offset=offset, initial=prev, tol=tol, max_iter=k)
        joined = (np.asarray(r.gap) < A0) & ~before & (first == 0)
        first[joined] = k
        clusters = np.unique(labels[joined])
        rows.append((k, r.residual, int(joined.sum()), int((clusters > 0).sum())))
    sizes = np.bincount(labels.ravel())[1:]
    spans = []
    for c in np.argsort(sizes)[::-1][:3]:
        its = first[(labels == c + 1) & (first > 0)]
        spans.append((int(sizes[c]), int(its.min()), int(its.max())) if its.size else None)
    return rows, sizes, spans


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--adhesion-length", type=float, default=0.05)
    ap.add_argument("--step", type=int, default=5, help="approach step (1-10)")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args(argv)
    if not 1 <= args.step <= 10:
        ap.error(f"--step must be in 1..10, got {args.step}")
    rows, sizes, spans = front(args.size, args.adhesion_length, args.step, args.seed)
    print("iteration  residual  new-repulsive-sites  final-clusters-touched")
    for k, residual, joined, touched in rows:
        print(f"{k:9d}  {residual:8.2e}  {joined:19d}  {touched:22d}")
    print(
        f"# {sizes.sum()} new repulsive sites in {sizes.size} clusters; "
        f"the largest (sites, first and last iteration it grew):",
        ", ".join(str(s) for s in spans if s is not None),
    )


if __name__ == "__main__":
    main()
