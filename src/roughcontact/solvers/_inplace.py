"""Vector updates that reuse preallocated arrays on NumPy, plain expressions elsewhere.

An iteration of the smooth solver at 256²-512² spends more time in NumPy's vector work
than in its two FFT convolutions, and much of that work was allocating (and, for arrays
above glibc's mmap threshold, page-faulting) a temporary per expression. On NumPy these
helpers write into arrays that live as long as the solve (ufuncs with ``out=``); on other
array-API backends (array_api_strict has no ``out=``; CuPy allocates from a pool) they
are the plain expressions. Both give the same values: same operations, same order.

Sites: a set of grid sites is an index array on NumPy (``flatnonzero``; cheap gathers and
scatters on a few per cent of the grid) and a boolean mask elsewhere (the array API has no
integer-array assignment); ``x[sites]`` and ``x[sites] = v`` read the same either way.

The patch: on a free boundary's work grid (:mod:`roughcontact.elastic.operator`) the
interaction acts only on the sites of the patch; the site sets of the interaction
(:meth:`Workspace.interacting`, :meth:`Workspace.band`) then never leave it.
"""

from __future__ import annotations

import math

import numpy as np

from .._backend import array_namespace, is_numpy_array

__all__ = ["Workspace"]


class Workspace:
    """Scratch arrays of one solve and the in-place updates that use them.

    Parameters
    ----------
    like : flat float array
        A field of the solve (its backend, device, size and dtype are used).
    patch : flat bool array, optional
        The sites where the interaction acts (the patch of a free boundary's work grid);
        None (default): every site.

    Attributes
    ----------
    patch : sites or None
        The patch as sites (index array on NumPy, mask elsewhere); None: every site.
    """

    def __init__(self, like, patch=None):
        self.xp = array_namespace(like)
        self.inplace = is_numpy_array(like)
        self.tmp = np.empty_like(like) if self.inplace else None
        self.dense_band = False  # whether the last band held more than 1/8 of the sites
        self.patch_mask = patch
        self.patch = None if patch is None else self.sites(patch)

    def sites(self, mask):
        """The sites where ``mask`` is true (index array on NumPy, the mask elsewhere)."""
        return np.flatnonzero(mask) if self.inplace else mask

    def on_patch(self, sites):
        """``sites`` without those off the patch (``sites`` itself when all are on it)."""
        if self.patch_mask is None:
            return sites
        return sites[self.patch_mask[sites]] if self.inplace else sites & self.patch_mask

    def interacting(self, gap, cutoff: float):
        """Sites where a law of range ``cutoff`` acts at ``gap``: on the patch, with
        ``gap < cutoff`` (None: every site, for an unbounded law without a patch)."""
        if not math.isfinite(cutoff) or not self.inplace:
            # elsewhere (a GPU) every site of the patch: a law vanishes exactly beyond its
            # cutoff, and a subset would cost a boolean gather (on CuPy a host sync)
            return self.patch
        return self.on_patch(self.sites(gap < cutoff))

    def scalar(self, a, like):
        """A scalar (Python float, or a 0-d array of this backend) in ``like``'s dtype, as
        a Python float is used with an array (a float64 0-d array would promote it)."""
        if isinstance(a, float) or a.dtype == like.dtype:
            return a
        return self.xp.astype(a, like.dtype)

    def axpy(self, y, a: float, x):
        """``y += a * x`` in place (``y = y + a * x`` off NumPy); returns ``y``."""
        if self.inplace:
            y += np.multiply(x, a, out=self.tmp)
            return y
        return y + self.scalar(a, y) * x

    def difference(self, x, y):
        """``x - y``, on NumPy in the scratch array (valid until the next helper call)."""
        return np.subtract(x, y, out=self.tmp) if self.inplace else x - y

    def scale_sub(self, y, beta: float, x):
        """``y = beta * y - x`` in place (``x`` may be of lower precision); returns ``y``."""
        if not self.inplace:
            return self.scalar(beta, y) * y - x
        y *= beta
        y -= x
        return y

    def negative(self, out, x):
        """``-x`` in ``out``'s dtype (into ``out`` on NumPy; ``out`` may be None)."""
        if self.inplace and out is not None:
            return np.negative(x, out=out)
        neg = -x
        return neg if out is None or neg.dtype == out.dtype else self.xp.astype(neg, out.dtype)

    def cast(self, out, x):
        """``x`` converted to ``out``'s dtype (written into ``out`` on NumPy)."""
        if self.inplace:
            np.copyto(out, x, casting="same_kind")
            return out
        return self.xp.astype(x, out.dtype)

    def shifted(self, out, x, shift: float):
        """``x - shift`` in ``out``'s dtype, computed in that dtype (into ``out`` on NumPy)."""
        if self.inplace:
            return np.subtract(x, shift, out=out, dtype=out.dtype)
        x = x if x.dtype == out.dtype else self.xp.astype(x, out.dtype)
        return x - self.scalar(shift, out)

    def band(self, gap, s, reach: float, cutoff: float):
        """Sites where ``min(gap, gap + reach s) < cutoff``: all that can feel a law
        of range ``cutoff`` along ``gap + alpha s`` for ``0 <= alpha <= reach`` (on the
        patch)."""
        if not self.inplace:  # every site of the patch (see interacting)
            return self.patch
        if self.patch_mask is not None:
            return self.on_patch(self._band(gap, s, reach, cutoff))
        return self._band(gap, s, reach, cutoff)

    def _band(self, gap, s, reach, cutoff):
        if not self.inplace:
            return self.xp.minimum(gap, gap + reach * s) < cutoff
        if not self.dense_band:
            # few sites near the cutoff (a short-ranged law): the test on the gap alone
            # with the largest approach, min(s), is two passes instead of four
            candidates = np.flatnonzero(gap < cutoff - reach * min(float(s.min()), 0.0))
            if 4 * candidates.size < gap.size:
                g, d = gap[candidates], s[candidates]
                return candidates[np.minimum(g, g + reach * d) < cutoff]
            self.dense_band = True
        t = np.multiply(s, reach, out=self.tmp)
        t += gap
        np.minimum(t, gap, out=t)
        sites = np.flatnonzero(t < cutoff)
        self.dense_band = 8 * sites.size > gap.size
        return sites
