"""Geometry of contact maps: area, perimeter, patches.

All functions take a boolean map (True = site in the set, e.g. repulsive), by default on
a periodic grid; ``periodic=False`` treats the map as a window of a larger surface (a
free-boundary solve, a measured scan): bonds and patches do not wrap around, and the
edge of the window is not a contact boundary. They are exact counts, except
:func:`corrected_area`, which is the perimeter-corrected estimate of the true contact
area of Yastrebov et al. (2017).

Maps of any array-API backend (NumPy, CuPy, ...) are counted where they live: only the
counts reach the host, so a path on a GPU does not copy its contact maps. The one
exception is :func:`contact_patches`, whose labelled map is NumPy (scipy.ndimage).
"""

from __future__ import annotations

import numpy as np
from array_api_compat import is_array_api_obj, is_jax_array  # (imports no jax)

from .._backend import array_device, array_namespace, is_numpy_array, to_numpy
from .._validate import ParameterError, positive

__all__ = [
    "area_fraction",
    "contact_patches",
    "corrected_area",
    "count_patches",
    "perimeter",
    "perimeter_edges",
]

#: Area (in units of a0²) removed per contact/non-contact bond by :func:`corrected_area`:
#: (π − 1 + ln 2)/24 ≈ 0.1181 (Yastrebov, Anciaux & Molinari, Tribol. Int. 114, 161 (2017)).
AREA_CORRECTION_PER_EDGE = (np.pi - 1.0 + np.log(2.0)) / 24.0


def _bool_map(mask):
    """``mask`` as a boolean array of its own backend (nonzero = True; lists: NumPy)."""
    if not is_array_api_obj(mask):
        return np.asarray(mask, dtype=bool)
    xp = array_namespace(mask)
    return mask if mask.dtype == xp.bool else xp.astype(mask, xp.bool)


def area_fraction(mask) -> float:
    """Fraction of sites in ``mask`` (A/A0), counted on the mask's device."""
    m = _bool_map(mask)
    return float(array_namespace(m).count_nonzero(m)) / m.size


def perimeter_edges(mask, *, periodic: bool = True) -> int:
    """Number of nearest-neighbour bonds that cross the boundary of ``mask``.

    Bonds are counted on the square lattice in both directions; for a convex region
    this is the 'Manhattan' perimeter in units of a0. A bond crosses the boundary where a
    site and its neighbour differ, counted on the mask's device (array API). With
    ``periodic`` (default) the last row and column bond to the first (``m !=
    roll(m, 1)``); without, only the bonds inside the window count, so a contact cut by
    the window's edge contributes no perimeter along it.
    """
    return int(boundary_bonds(mask, periodic=periodic))


def boundary_bonds(mask, *, periodic: bool = True):
    """:func:`perimeter_edges` as a 0-d integer array on the mask's device (no host sync:
    a caller fetches it with its other scalars)."""
    m = _bool_map(mask)
    xp = array_namespace(m)
    if periodic:
        return xp.count_nonzero(m != xp.roll(m, 1, axis=0)) + xp.count_nonzero(
            m != xp.roll(m, 1, axis=1)
        )
    return xp.count_nonzero(m[1:, :] != m[:-1, :]) + xp.count_nonzero(m[:, 1:] != m[:, :-1])


def perimeter(mask, pixel_size: float = 1.0, *, periodic: bool = True) -> float:
    r"""Perimeter (length) of ``mask``: edge count × π/4 × a0.

    The π/4 factor corrects the lattice's Manhattan length for isotropic boundaries
    (a disc of radius R has 8R/a0 edges and perimeter 2πR); Pastewka & Robbins 2014,
    Methods, and Yastrebov et al., Tribol. Lett. 56, 171 (2014). ``periodic`` as in
    :func:`perimeter_edges`.
    """
    return perimeter_edges(mask, periodic=periodic) * np.pi / 4.0 * pixel_size


def corrected_area(mask, pixel_size: float = 1.0, *, periodic: bool = True) -> float:
    r"""Perimeter-corrected true contact area of ``mask`` (length²).

    Counting the sites of a discretised contact overestimates the true contact area by
    an amount proportional to the length of the contact boundary. Yastrebov, Anciaux &
    Molinari subtract that bias on a square grid of spacing :math:`a_0`:

    .. math::

        A = a_0^2 \left[ n_c - \frac{\pi - 1 + \ln 2}{24}\, n_e \right],

    where :math:`n_c` is the number of sites in ``mask`` and :math:`n_e` the number of
    nearest-neighbour bonds joining a site in ``mask`` to one outside (both directions,
    :func:`perimeter_edges`). The coefficient
    :math:`(\pi - 1 + \ln 2)/24 \approx 0.118` is :data:`AREA_CORRECTION_PER_EDGE`.
    Since :math:`n_e \le 4 n_c` the estimate is never negative; it equals the raw count
    for an empty or a full map (no boundary).

    Parameters
    ----------
    mask : 2D bool array
        Contact map (True = in contact), e.g. ``result.pressure > 0``.
    pixel_size : float, optional
        Grid spacing :math:`a_0` (length), > 0.
    periodic : bool, optional
        Whether bonds wrap around the map's edges (default); False for a window of a
        larger surface.

    Returns
    -------
    float
        Corrected area (length²); divide by the nominal area :math:`A_0` for a fraction.

    Raises
    ------
    ParameterError
        If ``mask`` is not two-dimensional or ``pixel_size`` is not a positive number.

    References
    ----------
    V. A. Yastrebov, G. Anciaux, J.-F. Molinari, *On the accurate computation of the
    true contact-area in mechanical contact of random rough surfaces*, Tribology
    International 114, 161-171 (2017), arXiv:1701.02727.
    """
    a0 = positive("pixel_size", pixel_size)
    m = _mask2d(mask)
    n_c = int(array_namespace(m).count_nonzero(m))
    n_e = perimeter_edges(m, periodic=periodic)
    return float((n_c - AREA_CORRECTION_PER_EDGE * n_e) * a0 * a0)


def _mask2d(mask):
    m = _bool_map(mask)
    if m.ndim != 2:
        raise ParameterError(f"mask must be a 2D array, got {m.ndim} dimension(s)")
    return m


def _periodic_union(labels, n):
    """Join the patches 1..n of ``labels`` that touch across the periodic boundaries.

    Only the boundary rows and columns are read (copied to the host: O(nx + ny) labels).
    Returns ``(find, merges)``: the root of each label and the number of joins made.
    """
    parent = np.arange(n + 1)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    merges = 0
    for a, b in ((labels[0, :], labels[-1, :]), (labels[:, 0], labels[:, -1])):
        a, b = to_numpy(a), to_numpy(b)
        both = (a > 0) & (b > 0)
        for i, j in set(zip(a[both].tolist(), b[both].tolist(), strict=True)):
            ri, rj = find(i), find(j)
            if ri != rj:
                parent[max(ri, rj)] = min(ri, rj)
                merges += 1
    return find, merges


def contact_patches(mask, *, periodic: bool = True):
    """Label connected patches (4-neighbour connectivity) with periodic wrap-around.

    An edge to the host: the labelled map is NumPy (scipy.ndimage), whatever the
    backend of ``mask``. :func:`count_patches` counts them on the mask's device.

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
    if m.ndim != 2:
        raise ParameterError(f"mask must be a 2D array of booleans, got shape {m.shape}")
    labels, n = ndimage.label(m)
    if n == 0:
        return labels, np.zeros(0, dtype=int)
    find = _periodic_union(labels, n)[0] if periodic else (lambda a: a)
    roots = np.array([find(i) for i in range(n + 1)])
    merged = roots[labels]
    uniq, inverse, counts = np.unique(merged, return_inverse=True, return_counts=True)
    # uniq[0] is 0 (background) because the mask is not full... unless it is
    keep = uniq > 0
    order = np.argsort(-counts[keep], kind="stable")
    relabel = np.zeros(uniq.size, dtype=int)
    relabel[np.flatnonzero(keep)[order]] = np.arange(1, order.size + 1)
    return relabel[inverse].reshape(m.shape), counts[keep][order]


def patch_count(mask, *, periodic: bool = True):
    """:func:`count_patches`, as a 0-d integer array on the device of a JAX ``mask`` (a
    compiled count: no host sync, for a caller that fetches it with other scalars);
    an int for every other backend."""
    if is_jax_array(mask):
        from ._patches_jax import count_patches_jax

        return count_patches_jax(_mask2d(mask), bool(periodic))
    return count_patches(mask, periodic=periodic)


def count_patches(mask, *, periodic: bool = True) -> int:
    """Number of connected patches of ``mask`` (4-neighbour connectivity), on its device.

    The number of labels of :func:`contact_patches`, without labelling on the host:
    NumPy maps are labelled by scipy.ndimage and CuPy maps by cupyx.scipy.ndimage, then
    the labels that touch across the periodic boundaries are joined (the boundary rows
    and columns are read on the host); maps of any other array-API backend are counted
    by :func:`_count_components`. Only integers reach the host.

    Parameters
    ----------
    mask : 2D bool array of any array-API backend (nonzero = True)
    periodic : bool
        Count patches that touch across the periodic boundaries as one.

    Returns
    -------
    int
        The number of patches (0 for an empty map, 1 for a full one).

    Raises
    ------
    ParameterError
        If ``mask`` is not two-dimensional.
    """
    m = _mask2d(mask)
    if is_jax_array(m):  # a compiled count (:mod:`._patches_jax`)
        return int(patch_count(m, periodic=periodic))
    if is_numpy_array(m):
        from scipy.ndimage import label
    elif type(m).__module__.split(".")[0] == "cupy":
        from cupyx.scipy.ndimage import label
    else:
        return _count_components(m, periodic)
    labels, n = label(m)
    n = int(n)
    if periodic and n > 1:
        n -= _periodic_union(labels, n)[1]
    return n


def _count_components(m, periodic: bool) -> int:
    """Connected components of the 2D bool map ``m`` with array-API operations only.

    Min-label union-find by gathers, since the array API has no scatter: each round,
    every bond (u, v) inside the map hooks the larger of the labels L[u], L[v] to the
    smaller (L[max] <- min, a scatter-min done by sorting the bonds by target and reading
    each target's first entry through ``searchsorted``), then pointer jumping L <- L[L]
    makes every label a root. Labels only decrease and always name a site of the same
    component; when a round changes nothing they are equal across every bond, hence
    constant on each component, whose one root (L[i] = i) is counted. Shiloach & Vishkin,
    J. Algorithms 3, 57 (1982); a handful of rounds on contact maps (each a sort of 2n
    bonds).
    """
    xp = array_namespace(m)
    nx, ny = m.shape
    n = nx * ny
    if n == 0:
        return 0
    device = array_device(m)
    site = xp.arange(n, dtype=xp.int64, device=device)
    outside = xp.full_like(site, n)  # the label of every site outside the map: a root
    inside = xp.reshape(m, (-1,))
    grid = xp.reshape(site, (nx, ny))
    lo, hi = [], []
    for axis, wraps in ((0, site // ny == nx - 1), (1, site % ny == ny - 1)):
        neighbour = xp.reshape(xp.roll(grid, -1, axis=axis), (-1,))
        bond = inside & xp.take(inside, neighbour)
        if not periodic:
            bond = bond & ~wraps
        # bonds not inside the map join `outside` to itself: no effect
        lo.append(xp.where(bond, site, outside))
        hi.append(xp.where(bond, neighbour, outside))
    u, v = xp.concat(lo), xp.concat(hi)
    every = xp.arange(n + 1, dtype=xp.int64, device=device)
    label = xp.concat((xp.where(inside, site, outside), every[n:]))
    while True:
        lu, lv = xp.take(label, u), xp.take(label, v)
        key = xp.sort(xp.maximum(lu, lv) * (n + 1) + xp.minimum(lu, lv))
        target = key // (n + 1)
        first = xp.minimum(xp.searchsorted(target, every), key.shape[0] - 1)
        hooked = xp.where(xp.take(target, first) == every, xp.take(key % (n + 1), first), label)
        new = xp.minimum(label, hooked)
        while True:
            jumped = xp.take(new, new)
            if bool(xp.all(jumped == new)):
                break
            new = jumped
        if bool(xp.all(new == label)):
            return int(xp.count_nonzero(new[:n] == site))
        label = new
