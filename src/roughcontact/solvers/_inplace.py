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

__all__ = ["BAND_MARGIN", "BAND_MARGIN_CAP", "BAND_SKIP", "StickyBand", "Workspace"]

#: The sticky band (:class:`StickyBand`) holds the sites with ``gap < cutoff + margin``,
#: ``margin = BAND_MARGIN * range`` (the law's range, or its cutoff without one), or the
#: largest approach ``reach * max(-s)`` of the search direction where that is larger, up
#: to ``BAND_MARGIN_CAP`` margins (beyond it: the line search's own band).
#: After a step beyond that, the next ``BAND_SKIP`` line searches take their own band
#: (fast approaches come in runs: a jump into contact).
BAND_MARGIN = 0.25
BAND_MARGIN_CAP = 4.0
BAND_SKIP = 3


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


class StickyBand:
    """The line search's sites, kept from one iteration to the next (NumPy loop).

    The line search of :func:`.line_search.line_minimum` needs the sites that can feel a
    law of range ``cutoff`` along ``gap + alpha s`` for ``0 <= alpha <= reach``: its own
    band (:meth:`Workspace.band`) is selected afresh on every call (five passes over the
    grid and two gathers). This set ``S``, the sites with ``gap < cutoff + margin``, is
    a superset of that band for as long as no site outside it can have come within
    ``cutoff``: its ``slack`` is the margin less the largest approach of an outside site
    since it was selected (``alpha`` times the outside sites' most negative ``s``: one
    pass per iteration, two where the bound of every site is not enough), and it is
    selected afresh when ``slack + reach min(s)`` would fall below 0 (with the margin,
    or wider where sites outside it approach faster; beyond ``BAND_MARGIN_CAP`` margins
    the line search takes its own band). On ``S`` the gap after a step is the line
    search's last trial gap (the same values as the grid's ``gap + alpha s``) and its
    curvature comes with that trial's pressure (``pressure_and_curvature``), so the
    next line search needs no gather of the gap and no evaluation of its own at
    ``alpha = 0``. The interaction is zero beyond ``cutoff``: sums over ``S`` are those
    over the band plus zeros (equal up to the order of summation).

    Parameters
    ----------
    work : Workspace
    cutoff : float
        The law's cutoff (length; finite).
    margin : float
        The margin (length) beyond the cutoff.
    """

    def __init__(self, work, cutoff: float, margin: float):
        self.work, self.cutoff, self.margin = work, cutoff, margin
        self.sites = None  # S (index array); None: to be selected
        self.outside = None  # 1 on the patch's sites outside S, else 0
        self.slack = self.low = 0.0
        self.skip = 0  # selections left to the line search's own band
        self.gap = self.curvature = None  # on S at the current iterate (curvature: or None)

    def select(self, gap, s, reach: float, curvature):
        """``(sites, s[sites], gap[sites], V''(gap[sites]))`` covering ``alpha <= reach``
        along ``s``, or None (then the line search selects its own band).
        ``curvature(g)``: the law's V'' (called when S is selected afresh)."""
        if self.sites is not None:
            self.low = min(float(np.minimum.reduce(s)), 0.0)  # every site's: a bound
            if self.slack + reach * self.low < 0.0:  # the outside sites' (a pass more)
                self.low = self._approach(s, self.outside)
            if self.slack + reach * self.low >= 0.0:
                return self.sites, s[self.sites], self.gap, self.curvature
        if self.skip:  # after a fast approach: the line search's own band for a while
            self.skip -= 1
            self.sites = None
            return None
        margin = self.margin
        inside, outside = self._split(gap, margin)
        self.low = min(float(np.minimum.reduce(s)), 0.0)
        if margin + reach * self.low < 0.0:
            self.low = self._approach(s, outside)
            if margin + reach * self.low < 0.0:
                # wider: fewer sites outside, none of which approaches by more than that
                margin = -reach * self.low
                if margin > BAND_MARGIN_CAP * self.margin:
                    self.sites, self.skip = None, BAND_SKIP
                    return None
                inside, outside = self._split(gap, margin)
        self.sites, self.outside, self.slack = inside, outside, margin
        self.gap = gap[inside]
        self.curvature = curvature(self.gap)
        return self.sites, s[self.sites], self.gap, self.curvature

    def _approach(self, s, outside) -> float:
        """``min(s)`` over the sites where ``outside`` is 1 (or 0 if larger)."""
        return min(float(np.minimum.reduce(np.multiply(s, outside, out=self.work.tmp))), 0.0)

    def _split(self, gap, margin):
        """The sites of the patch with ``gap < cutoff + margin`` (an index array), and 1
        on the others of the patch, else 0 (a factor of the grid's dtype)."""
        inside = gap < self.cutoff + margin
        patch = self.work.patch_mask
        if patch is not None:
            inside &= patch
            return np.flatnonzero(inside), np.logical_and(~inside, patch).astype(gap.dtype)
        return np.flatnonzero(inside), np.logical_not(inside).astype(gap.dtype)

    def forget(self):
        """The gap changed other than along a step (float32's exact refresh re-forms it):
        select anew."""
        self.sites = None

    def moved(self, alpha: float, sites, trial):
        """After the step ``alpha`` whose line search ran on ``sites`` and left its last
        trial (``trial``: "gap" and "curvature" there) in its state."""
        if sites is None or sites is not self.sites or "curvature" not in trial:
            self.sites = None  # a search beyond the band, or on its own band: select anew
            return
        self.slack += alpha * self.low
        self.gap, self.curvature = trial["gap"], trial["curvature"]
