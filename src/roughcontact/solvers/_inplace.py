"""Vector updates of the smooth solver's NumPy loop that reuse preallocated arrays.

An iteration of the smooth solver at 256²-512² spends more time in NumPy's vector work
than in its two FFT convolutions, and much of that work was allocating (and, for arrays
above glibc's mmap threshold, page-faulting) a temporary per expression. On NumPy these
helpers write into arrays that live as long as the solve (ufuncs with ``out=``): the same
values as the plain expressions (same operations, same order).

Sites: a set of grid sites is an index array (``flatnonzero``; cheap gathers and scatters
on a few per cent of the grid).

The patch: on a free boundary's work grid (:mod:`roughcontact.elastic.operator`) the
interaction acts only on the sites of the patch; the site sets of the interaction
(:meth:`Workspace.interacting`, :meth:`Workspace.band`) then never leave it.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["Workspace"]


class Workspace:
    """Scratch arrays of one solve and the in-place updates that use them.

    Parameters
    ----------
    like : flat float ndarray
        A field of the solve (its size and dtype are used).
    patch : flat bool ndarray, optional
        The sites where the interaction acts (the patch of a free boundary's work grid);
        None (default): every site.

    Attributes
    ----------
    patch : index array or None
        The patch as sites; None: every site.
    """

    def __init__(self, like, patch=None):
        self.tmp = np.empty_like(like)
        self.dense_band = False  # whether the last band held more than 1/8 of the sites
        self.patch_mask = patch
        self.patch = None if patch is None else self.sites(patch)

    @staticmethod
    def sites(mask):
        """The sites where ``mask`` is true (an index array)."""
        return np.flatnonzero(mask)

    def on_patch(self, sites):
        """``sites`` without those off the patch (``sites`` itself when all are on it)."""
        if self.patch_mask is None:
            return sites
        return sites[self.patch_mask[sites]]

    def interacting(self, gap, cutoff: float):
        """Sites where a law of range ``cutoff`` acts at ``gap``: on the patch, with
        ``gap < cutoff`` (None: every site, for an unbounded law without a patch)."""
        if not math.isfinite(cutoff):
            return self.patch
        return self.on_patch(self.sites(gap < cutoff))

    def axpy(self, y, a: float, x):
        """``y += a * x`` in place; returns ``y``."""
        y += np.multiply(x, a, out=self.tmp)
        return y

    def difference(self, x, y):
        """``x - y`` in the scratch array (valid until the next helper call)."""
        return np.subtract(x, y, out=self.tmp)

    @staticmethod
    def scale_sub(y, beta: float, x):
        """``y = beta * y - x`` in place (``x`` may be of lower precision); returns ``y``."""
        y *= beta
        y -= x
        return y

    @staticmethod
    def negative(out, x):
        """``-x`` in ``out``'s dtype, into ``out`` (None: a new array of ``x``'s dtype)."""
        return -x if out is None else np.negative(x, out=out)

    @staticmethod
    def cast(out, x):
        """``x`` converted to ``out``'s dtype, written into ``out``."""
        np.copyto(out, x, casting="same_kind")
        return out

    @staticmethod
    def shifted(out, x, shift: float):
        """``x - shift`` in ``out``'s dtype, computed in that dtype, into ``out``."""
        return np.subtract(x, shift, out=out, dtype=out.dtype)

    def band(self, gap, s, reach: float, cutoff: float):
        """Sites where ``min(gap, gap + reach s) < cutoff``: all that can feel a law
        of range ``cutoff`` along ``gap + alpha s`` for ``0 <= alpha <= reach`` (on the
        patch)."""
        if self.patch_mask is not None:
            return self.on_patch(self._band(gap, s, reach, cutoff))
        return self._band(gap, s, reach, cutoff)

    def _band(self, gap, s, reach, cutoff):
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
