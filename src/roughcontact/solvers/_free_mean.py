r"""Load control inside the one minimisation of :mod:`.smooth`: the uniform mode set free.

With a rigid uniform mode the offset ``d`` is the gap's mean plus ``mean(h)``. Under a load
``N`` (mean pressure) the energy per site is

.. math:: E(g) = \tfrac12 w K w + \sum_i V(g_i) + N\, n\, d, \qquad
          w = g - (d - h),\ d = \bar g + \bar h,

so its gradient is :math:`K w - p_{int}(g) + N`: the force imbalance of the offset-controlled
solve plus its mean, :math:`N - \bar p`, the load not carried. The gap (the iterate) then
moves in all its modes, the offset with it, and the minimum is the equilibrium that carries
``N`` and is stable under load control (a minimum of the enthalpy), found in one nonlinear
CG run instead of a root search over nested solves (:mod:`.load_control`). ``K`` kills the
uniform mode (rigid), so ``K s`` and ``K w`` are those of the offset-controlled loop; only the
preconditioner needs a uniform block. It spans two directions (:meth:`FreeMean.add` with
``K z``): the uniform one and the body lifted at fixed contact, ``u = 1 - G(1_S - s)/m``
off the stiff sites ``S`` (zero on them; :func:`lift_mode`), ``z += c0 + c1 u`` with
``(c0, c1)`` the Galerkin solution of the 2x2 system of the Hessian ``K + V''+`` on the
two (:func:`.adhesive_rules.pair_coefficients`), refreshed every ``refresh_every``
iterations (two float32 convolutions) and ``K z += c1 K u``. A uniform shift alone (the
rule before, :func:`add_uniform`, ``mean(gr) / k_u`` with ``k_u`` a fraction of the
interaction's mean curvature, :func:`uniform_stiffness`) is resisted by every stiff
contact, so the load not carried fell only 10x per ~14 iterations in a path step (256²,
ℓa 0.005) against ~8 for an offset step. The block preconditioner takes the mean-free
``gr - mean(gr)`` (a block-diagonal split).

Cost (iterations, cold from first contact, ``benchmarks/adhesive_load.py``): 1.1-1.9x the
offset-controlled cold solve ending in the same state at ℓa 0.05 (128², 256²), 1.3-2x at
ℓa 0.005 up to 64², 2.1-3.5x at 128²-256²: the offset has to travel from first contact
(about one rms height) while the contacts form one after another, where the offset-
controlled solve starts at its offset. From 128² on a cold solve therefore starts from the
same load solved on the 2x2-coarsened grid (:func:`.load_control._coarse_start`): 0.5-1.5x
the offset-controlled solve's iterations on the fine grid, 0.6-1.4x its time at 256² with
the coarse solve (with the lift direction: 0.5-1.0x). A warm path step costs 1.05-1.1x
an offset step (128²-256², ℓa 0.005 and 0.05; 1.08-1.53x with the uniform shift alone).
The nested root search it replaces took 10-30x.

The bounded solver (:mod:`.bounded`, a hard core: the wall's sites are pinned) takes the
uniform mode along the body's response at fixed contact, ``u = 1 - G(1_A - a)/m``
(:func:`.adhesive_rules.contact_mode`: 1 far from the contacts, about 0 on them), with its
stiffness from the contact's Rayleigh quotient, rather than a uniform shift of the free
sites, which bends the surface at every contact's edge and left the offset creeping
(256², Exponential w = 0.005 E* a0, cold load 0: 54 -> 27 fine-grid iterations against 23
offset-controlled; hard-core cases at 128²-256² 2654 -> 1941 in all, benchmarks/README.md).

The compiled loops (:mod:`._smooth_jax`, :mod:`._bounded_jax`) take the same method with
the same rules (:mod:`.adhesive_rules`' scalar functions on 0-d device arrays) inside their
``lax.while_loop``: the same iterations on JAX heights.
"""

from __future__ import annotations

import numpy as np

from .._validate import ParameterError
from . import adhesive_rules as rules
from .fourier import compliance_operator, in_single_precision, stiffness_operator
from .reductions import dot, total
from .smooth_rules import STIFF_FRACTION

__all__ = ["FreeMean", "add_uniform", "lift_mode", "uniform_stiffness"]


class FreeMean:
    """The free uniform mode of one load-controlled minimisation (module docstring)."""

    def __init__(self, load, interaction, substrate, heights, work):
        self.load, self.law, self.substrate, self.work = float(load), interaction, substrate, work
        self.reach = max(float(np.std(heights)), substrate.pixel_size)
        self.k_u, self.detached = None, None
        self.contact = None  # the bounded solver's (wall sites, u, k): add_on
        self.lift = None  # the smooth solver's (u, K u, h): add
        self.peak = rules.attraction_peak_gap(interaction) if self.load < 0 else 0.0

    @classmethod
    def of(cls, load, interaction, substrate, heights, work, periodic_rigid):
        """The free mode for ``load`` (None: offset control, no free mode); it needs a
        periodic substrate with a rigid mean."""
        if load is None:
            return None
        if not periodic_rigid:
            raise ParameterError(
                "load in minimize_energy needs a periodic substrate with a rigid mean "
                "(else solve(load=...) takes the nested search)"
            )
        return cls(load, interaction, substrate, heights, work)

    def mean_free(self, gr):
        """``gr - mean(gr)``: what the block preconditioner takes."""
        return gr - np.mean(gr)

    def add(self, z, gr, gap, it, refresh_every, kz=None):
        """``z`` with its uniform block; ``k_u`` refreshed with the preconditioner's stiff
        sites. With ``kz`` (``K z``, updated in place) the block spans two directions, the
        uniform one and the body's lift at fixed contact (:func:`lift_mode`, refreshed
        with ``k_u``): ``z + c0 + c1 u``, ``K z + c1 K u``
        (:func:`.adhesive_rules.pair_coefficients`); without it :func:`add_uniform`. None,
        with ``detached`` the message, once a tensile load has pulled every site beyond
        the law's cutoff (no force left to balance it: the surfaces separate for good)."""
        if self._lost(gap, it):
            return None
        if self.k_u is None or it % refresh_every == 1:
            self.k_u = uniform_stiffness(self.law, gap, self.substrate, self.work)
            self.lift = None if kz is None else lift_mode(self.law, gap, self.substrate,
                                                         self.work)  # fmt: skip
        if kz is None or self.lift is None:
            return add_uniform(z, gr, self.k_u, self.reach, self.work)
        u, ku, h = self.lift
        n = gap.shape[0]
        c0, c1 = rules.pair_coefficients(*h, total(gr) / n, dot(u, gr) / n, self.reach)
        z += float(c0) + float(c1) * u
        kz += (float(c1) * ku).astype(kz.dtype, copy=False)
        return z

    def add_on(self, z, rr, gap, free, it, green=None):
        """The bounded solver's uniform block (:mod:`.bounded`): ``z + c u`` on the free
        sites, ``u`` the body's shape lifted at fixed contact and ``c = (u . rr) / (n k)``
        (:func:`.adhesive_rules.contact_mode`; ``green``: the float32 compliance, which
        computes ``u`` when :func:`.adhesive_rules.contact_stale` says; ``c`` at most
        ``reach``; on the wall's active face the caller zeroes ``z``). Without ``green``
        the rule before: a uniform shift of the free sites by their mean of ``rr`` over
        :func:`.adhesive_rules.wall_uniform_stiffness`. None, with ``detached``, as in
        :meth:`add`."""
        if self._lost(gap, it):
            return None
        n, sub = free.shape[0], self.substrate
        n_free = int(np.count_nonzero(free))
        floor = rules.wall_uniform_stiffness(0.0, sub.self_stiffness, sub.contact_modulus,
                                             max(sub.shape) * sub.pixel_size)  # fmt: skip
        if green is None:
            k_u = rules.wall_uniform_stiffness(1.0 - n_free / n, sub.self_stiffness,
                                               sub.contact_modulus,
                                               max(sub.shape) * sub.pixel_size)  # fmt: skip
            mean = float(np.sum(rr)) / max(n_free, 1)  # rr is 0 off the free sites
            return z + float(rules.uniform_shift(mean, k_u, self.reach))
        active = ~free
        if self.contact is None or rules.contact_stale(
                int(np.count_nonzero(active != self.contact[0])), n - n_free):  # fmt: skip
            a = (n - n_free) / n
            v = green(np.where(active, 1.0 - a, -a).astype(rr.dtype))
            self.contact = (active, *rules.contact_mode(v, active, floor))
        _, u, k = self.contact
        c = float(rules.uniform_shift(dot(np.where(free, u, 0.0), rr) / n, k, self.reach))
        z += np.where(free, c * u, 0.0)
        return z

    def _lost(self, gap, it) -> bool:
        """Whether the tensile load is lost (:func:`.adhesive_rules.tension_lost`); then
        ``detached`` says so."""
        if self.load >= 0:
            return False
        min_gap = float(np.min(gap))
        if not rules.tension_lost(self.law, self.load, min_gap, self.peak):
            return False
        self.detached = (
            f"no state reached carries load {self.load:g}: at iteration {it} the surfaces separate "
            f"(smallest gap {min_gap:.3g}, beyond the attraction's peak, where no site pulls "
            "that hard): beyond the pull-off force"
        )
        return True

    def moved(self, offset, gap, base):
        """The offset and ``base`` (``d - h``) of the final gap: moved with its mean."""
        shift = float(np.mean(gap - base))
        return offset + shift, base + shift


def uniform_stiffness(interaction, gap, substrate, work) -> float:
    """``k_u`` (pressure/length) of the state ``gap`` by the shared rule
    :func:`.adhesive_rules.uniform_stiffness` (module docstring)."""
    near = work.interacting(gap, interaction.cutoff)
    curvature = interaction.curvature(gap if near is None else gap[near])
    total = float(np.sum(np.where(curvature > 0, curvature, 0.0)))
    size = max(substrate.shape) * substrate.pixel_size
    return rules.uniform_stiffness(total / gap.shape[0], substrate.contact_modulus, size)


def lift_mode(interaction, gap, substrate, work):
    """The smooth solver's second uniform direction in the state ``gap``: ``(u, K u, h)``
    (:func:`.adhesive_rules.lift_shape` on the preconditioner's stiff sites, ``V'' >
    STIFF_FRACTION K_ii``; ``h = (h00, h01, h11)`` of
    :func:`.adhesive_rules.pair_coefficients`), or None when it has none (no stiff site,
    every site stiff). Two float32 convolutions."""
    near = work.interacting(gap, interaction.cutoff)
    curvature = interaction.curvature(gap if near is None else gap[near])
    curvature = np.where(curvature > 0, curvature, 0.0)  # (a NaN counts as 0, as in k_u)
    if near is None:
        d = curvature
    else:
        d = np.zeros_like(gap)
        d[near] = curvature
    stiff = d > STIFF_FRACTION * substrate.self_stiffness
    n, count = gap.shape[0], int(np.count_nonzero(stiff))
    if count in (0, n):
        return None
    a = count / n
    green = in_single_precision(compliance_operator(substrate, work_grid=True))
    u, ok = rules.lift_shape(green(np.where(stiff, 1.0 - a, -a).astype(gap.dtype)), stiff)
    if not ok:
        return None
    ku = in_single_precision(stiffness_operator(substrate, work_grid=True))(u)
    floor = substrate.contact_modulus * np.pi / (max(substrate.shape) * substrate.pixel_size)
    return u, ku, tuple(float(x) for x in rules.lift_block(d, u, ku, floor, total, dot))


def add_uniform(z, gr, k_u, reach, work):
    """The preconditioned gradient with its uniform block: ``z + mean(gr)/k_u``, that shift
    at most ``reach`` (length) in magnitude. ``z`` is the block preconditioner's of the
    mean-free ``gr - mean(gr)`` (a block-diagonal split, positive definite), and its
    ``K z`` holds for the sum (``K`` has no uniform mode).

    The shift and its bound are :func:`.adhesive_rules.uniform_shift`'s."""
    z += float(rules.uniform_shift(float(np.mean(gr)), k_u, reach))
    return z
