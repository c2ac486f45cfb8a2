"""Geometry of contact maps: area, perimeter, patches (periodic boundaries).

All functions take a boolean map (True = site in the set, e.g. repulsive) on a periodic
grid and are exact counts, not estimates.
"""

from __future__ import annotations

import numpy as np

from .._backend import to_numpy

__all__ = ["area_fraction", "contact_patches", "perimeter", "perimeter_edges"]


def area_fraction(mask) -> float:
    """Fraction of sites in ``mask`` (A/A0)."""
    m = to_numpy(mask)
    return float(np.count_nonzero(m)) / m.size


def perimeter_edges(mask) -> int:
    """Number of nearest-neighbour bonds that cross the boundary of ``mask``.

    Bonds are counted on the periodic square lattice in both directions; for a convex
    region this is the 'Manhattan' perimeter in units of a0.
    """
    m = np.asarray(to_numpy(mask), dtype=bool)
    return int(
        np.count_nonzero(m != np.roll(m, 1, axis=0)) + np.count_nonzero(m != np.roll(m, 1, axis=1))
    )


def perimeter(mask, pixel_size: float = 1.0) -> float:
    r"""Perimeter (length) of ``mask``: edge count × π/4 × a0.

    The π/4 factor corrects the lattice's Manhattan length for isotropic boundaries
    (a disc of radius R has 8R/a0 edges and perimeter 2πR); Pastewka & Robbins 2014,
    Methods, and Yastrebov et al., Tribol. Lett. 56, 171 (2014).
    """
    return perimeter_edges(mask) * np.pi / 4.0 * pixel_size


def contact_patches(mask, *, periodic: bool = True):
    """Label connected patches (4-neighbour connectivity) with periodic wrap-around.

    Parameters
    ----------
    mask : 2D bool array
    periodic : bool
        Merge patches that touch across the periodic boundaries.

    Returns
    -------
    labels : ndarray of int
        0 outside, 1..n inside, numbered by decreasing size.
    sizes : ndarray of int
        Number of sites of each patch, ``sizes[i]`` for label ``i + 1`` (descending).
    """
    from scipy import ndimage

    m = np.asarray(to_numpy(mask), dtype=bool)
    labels, n = ndimage.label(m)
    if n == 0:
        return labels, np.zeros(0, dtype=int)
    parent = np.arange(n + 1)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    if periodic:
        pairs = [(labels[0, :], labels[-1, :]), (labels[:, 0], labels[:, -1])]
        for a, b in pairs:
            both = (a > 0) & (b > 0)
            for i, j in set(zip(a[both].tolist(), b[both].tolist(), strict=True)):
                ri, rj = find(i), find(j)
                if ri != rj:
                    parent[max(ri, rj)] = min(ri, rj)
    roots = np.array([find(i) for i in range(n + 1)])
    merged = roots[labels]
    uniq, inverse, counts = np.unique(merged, return_inverse=True, return_counts=True)
    # uniq[0] is 0 (background) because the mask is not full... unless it is
    keep = uniq > 0
    order = np.argsort(-counts[keep], kind="stable")
    relabel = np.zeros(uniq.size, dtype=int)
    relabel[np.flatnonzero(keep)[order]] = np.arange(1, order.size + 1)
    return relabel[inverse].reshape(m.shape), counts[keep][order]
