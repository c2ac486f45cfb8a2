"""The smooth solver's block preconditioner (its NumPy loop).

See :mod:`.smooth` (the method); split from it to keep each module short.
"""

from __future__ import annotations

import numpy as np

from .._backend import in_background
from ._inplace import Workspace
from .reductions import total
from .smooth_rules import STIFF_FRACTION

__all__ = ["DENSE_FRACTION", "STIFF_FRACTION"]

#: Above this fraction of stiff sites the NumPy loop applies the block preconditioner with
#: grid-sized factors (:func:`_dense_blocks`: a mask of the soft sites and the diagonal,
#: zero off the stiff sites) instead of gathers and scatters on the stiff sites' indices
#: (ℓa = 0.05: 37 % of the grid is stiff; four indexed passes and three sums cost more than
#: four plain passes and one sum: 256², median step -4 %). Not where ``K z`` runs beside
#: the line search (:func:`roughcontact._backend.overlaps_fft`, 2^17 points and more): at
#: 512² the two ways took the same time.
DENSE_FRACTION = 0.125


def _stiff_sites(interaction, gap, self_stiffness, work=None, known=None):
    """The preconditioner's stiff sites, V'' > STIFF_FRACTION K_ii, and 1/(K_ii + V'') there.

    Returns ``(sites, diagonal)`` (index arrays, see :mod:`._inplace`; ``diagonal`` holds
    the values on them, in their order), or ``(None, None)`` when no site is stiff (then
    the preconditioner is the Green's function alone). ``known``: ``(sites, V'' there)``
    at ``gap``, sites (ascending) that hold every one inside the cutoff on the patch, when
    the caller has them (:class:`._inplace.StickyBand`; the same result).
    """
    work = work or Workspace(gap)
    if known is not None:
        near, curvature = known
    else:
        # V'' = 0 beyond the cutoff (and off the patch): only sites inside it can be stiff
        near = work.interacting(gap, interaction.cutoff)
        curvature = interaction.curvature(gap if near is None else gap[near])
    stiff = curvature > STIFF_FRACTION * self_stiffness
    if not bool(np.any(stiff)):
        return None, None
    diagonal = 1.0 / (self_stiffness + curvature[stiff])
    if near is None:
        return work.sites(stiff), diagonal
    return near[stiff], diagonal


def _dense_blocks(stiff, diagonal, like, out=None):
    """``(soft, diagonal)`` on the grid: 1 on the soft sites and 0 on the stiff ones, and
    the stiff sites' diagonal with 0 elsewhere (``like``'s size and dtype; into ``out``,
    a pair of such arrays, when given)."""
    soft, full = out if out is not None else (np.empty_like(like), np.empty_like(like))
    soft.fill(1.0)
    soft[stiff] = 0.0
    full.fill(0.0)
    full[stiff] = diagonal
    return soft, full


def _direction_stiffness(work, ks, beta, kz):
    """``K s`` for ``s = -z + beta s_old``: ``-K z + beta ks``, in place. ``kz`` may be a
    function that waits for ``K z``."""
    kz = kz() if callable(kz) else kz
    return work.scale_sub(ks, beta, kz) if beta > 0 else work.negative(ks, kz)


def _precondition(
    gr,
    stiff,
    diagonal,
    compliance,
    elastic_pressure,
    rigid,
    *,
    out=None,
    work=None,
    fast=None,
    result=None,
    background=False,
    dense=None,
):
    """Block-preconditioned gradient ``z`` and its elastic pressure ``K z``.

    ``z = diagonal * gr`` on the stiff sites and ``K^-1 (gr on the other sites)`` there;
    both blocks are symmetric positive definite, so is the preconditioner (restricted
    to mean-free fields when the uniform mode is rigid). With ``fast`` (a float32 array
    of the grid's size) both convolutions run in single precision: the Green's-function
    block only steers the search direction, and ``K z`` (then returned in float32) only
    updates the elastic pressure incrementally (see the module docstring). ``out``
    receives ``z``; ``result`` (float32, with ``fast``) receives both convolutions, one
    after the other (``K z`` is returned in it). With ``background`` (with ``fast``)
    ``K z`` is computed on the background thread and a function of no arguments that
    waits for it is returned in its place. ``dense``: the blocks as grid-sized factors
    (:func:`_dense_blocks` of ``stiff`` and ``diagonal``; the same ``z`` up to rounding).
    """
    work = work or Workspace(gr)
    if stiff is None:
        # K K^-1 is the identity on the non-uniform modes, and gr has no uniform mode
        # when it is rigid: no second convolution
        return compliance(gr), gr
    if dense is not None:
        soft_sites, full_diagonal = dense
        if fast is not None:
            soft = np.multiply(gr, soft_sites, out=fast, casting="same_kind")
        else:
            soft = gr * soft_sites
        soft_block = compliance(soft, out=result)
        z = np.multiply(soft_block, soft_sites, out=out)
        z += np.multiply(gr, full_diagonal, out=work.tmp)
        if rigid:  # mean-free
            z -= total(z) / gr.shape[0]
    else:
        soft = work.cast(fast, gr) if fast is not None else gr.copy()
        soft[stiff] = 0.0
        soft_block = compliance(soft, out=result)
        z_stiff = gr[stiff] * diagonal
        shift = 0.0
        if rigid:  # the mean of z, without a pass of its own
            shift = (total(soft_block) - total(soft_block[stiff]) + total(z_stiff)) / gr.shape[0]
        z = work.shifted(out if out is not None else np.empty_like(gr), soft_block, shift)
        z[stiff] = z_stiff - shift
    z_fast = work.cast(fast, z) if fast is not None else z
    if background and fast is not None:
        return z, in_background(elastic_pressure, z_fast, out=result)
    return z, elastic_pressure(z_fast, out=result)

