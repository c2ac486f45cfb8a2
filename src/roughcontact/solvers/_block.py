"""The smooth solver's block preconditioner and its search direction off NumPy.

See :mod:`.smooth` (the method); split from it to keep each module short.
"""

from __future__ import annotations

from .._backend import array_device, in_background
from ._inplace import Workspace
from .reductions import total, vdot, vtotal
from .smooth_rules import STIFF_FRACTION

__all__ = ["STIFF_FRACTION"]


def _stiff_sites(interaction, gap, self_stiffness, work=None):
    """The preconditioner's stiff sites, V'' > STIFF_FRACTION K_ii, and 1/(K_ii + V'') there.

    Returns ``(sites, diagonal)`` (see :mod:`._inplace` for sites; ``diagonal`` holds the
    values on them, in their order), or ``(None, None)`` when no site is stiff (then the
    preconditioner is the Green's function alone).
    """
    work = work or Workspace(gap)
    xp = work.xp
    # V'' = 0 beyond the cutoff (and off the patch): only sites inside it can be stiff
    near = work.interacting(gap, interaction.cutoff)
    curvature = interaction.curvature(gap if near is None else gap[near])
    stiff = curvature > STIFF_FRACTION * self_stiffness
    if not bool(xp.any(stiff)):
        return None, None
    if near is None and not work.inplace:  # on the whole grid, zero off the stiff sites
        # (a GPU: no boolean gather, which syncs on CuPy)
        inverse = 1.0 / (self_stiffness + xp.where(stiff, curvature, 0.0))
        return stiff, xp.where(stiff, inverse, 0.0)
    diagonal = 1.0 / (self_stiffness + curvature[stiff])
    if near is None:
        return work.sites(stiff), diagonal
    if work.inplace:
        return near[stiff], diagonal
    sites = xp.zeros_like(near)  # a mask over the grid
    sites[near] = stiff
    return sites, diagonal


def _direction_on_device(xp, work, gr, z, z_old, s, gz_old, restart):
    """The PR+ direction ``s = -z + beta s`` of the main loop, its slope ``gr.s``, ``beta``
    and ``gr.z``, with the scalars as 0-d device arrays (a GPU: no host sync).

    The same values as the host branches: ``beta = 0`` (a restart, ``gz_old = 0``, or
    PR+'s clip) gives ``0 s - z = -z`` exactly (``s`` is finite: zero before the first
    direction), and a direction that does not descend is replaced by ``-z``.
    """
    zero = xp.zeros((), dtype=xp.float64, device=array_device(gr))
    gz = vdot(gr, z)
    if restart:
        beta = zero
    else:
        pr = (gz - vdot(gr, z_old)) / xp.where(gz_old == zero, 1.0, gz_old)
        beta = xp.where(gz_old == zero, zero, xp.maximum(pr, zero))
    s = work.scale_sub(s, beta, z)
    slope0 = vdot(gr, s)
    ascent = slope0 >= zero  # not a descent direction: along the preconditioned -gr
    s = xp.where(ascent, -z, s)
    return s, xp.where(ascent, -gz, slope0), xp.where(ascent, zero, beta), gz


def _direction_stiffness(work, ks, beta, kz):
    """``K s`` for ``s = -z + beta s_old``: ``-K z + beta ks`` (in place on NumPy). ``kz``
    may be a function that waits for ``K z``."""
    kz = kz() if callable(kz) else kz
    if not work.inplace:  # beta a device scalar (0: -K z exactly; ks is finite)
        return work.scale_sub(ks, beta, kz)
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
):
    """Block-preconditioned gradient ``z`` and its elastic pressure ``K z``.

    ``z = diagonal * gr`` on the stiff sites and ``K^-1 (gr on the other sites)`` there;
    both blocks are symmetric positive definite, so is the preconditioner (restricted
    to mean-free fields when the uniform mode is rigid). With ``fast`` (a float32 array
    of the grid's size) both convolutions run in single precision: the Green's-function
    block only steers the search direction, and ``K z`` (then returned in float32) only
    updates the elastic pressure incrementally (see the module docstring). ``out``
    receives ``z`` where the backend allows; ``result`` (NumPy, float32, with ``fast``)
    receives both convolutions, one after the other (``K z`` is returned in it). With
    ``background`` (NumPy, with ``fast``) ``K z`` is computed on the background thread
    and a function of no arguments that waits for it is returned in its place.
    """
    work = work or Workspace(gr)
    xp = work.xp
    if stiff is None:
        # K K^-1 is the identity on the non-uniform modes, and gr has no uniform mode
        # when it is rigid: no second convolution
        return compliance(gr), gr
    if not work.inplace and diagonal.shape == gr.shape:  # the whole grid's (_stiff_sites)
        return _precondition_masked(
            gr, stiff, diagonal, compliance, elastic_pressure, rigid, work, fast
        )
    soft = work.cast(fast, gr) if fast is not None else xp.asarray(gr, copy=True)
    soft[stiff] = 0.0
    soft_block = compliance(soft, out=result)
    z_stiff = gr[stiff] * diagonal
    shift = 0.0
    if rigid:  # the mean of z, without a pass of its own
        shift = (total(soft_block) - total(soft_block[stiff]) + total(z_stiff)) / gr.shape[0]
    z = work.shifted(out if out is not None else xp.empty_like(gr), soft_block, shift)
    z[stiff] = z_stiff - shift
    z_fast = work.cast(fast, z) if fast is not None else z
    if background and fast is not None:
        return z, in_background(elastic_pressure, z_fast, out=result)
    return z, elastic_pressure(z_fast, out=result)


def _precondition_masked(gr, stiff, diagonal, compliance, elastic_pressure, rigid, work, fast):
    """:func:`_precondition` with ``stiff`` a mask and ``diagonal`` on the whole grid (zero
    off it): ``where`` in place of gathers and scatters, sums as device scalars."""
    xp = work.xp
    soft = work.cast(fast, gr) if fast is not None else gr
    soft_block = compliance(xp.where(stiff, 0.0, soft))
    z_stiff = gr * diagonal  # zero off the stiff sites
    shift = 0.0
    if rigid:  # the mean of z, without a pass of its own
        stiff_block = vtotal(xp.where(stiff, soft_block, 0.0))
        shift = (vtotal(soft_block) - stiff_block + vtotal(z_stiff)) / gr.shape[0]
    z = xp.where(stiff, z_stiff - work.scalar(shift, z_stiff), work.shifted(gr, soft_block, shift))
    return z, elastic_pressure(work.cast(fast, z) if fast is not None else z)
