r"""Energy minimisation for smooth (non-convex) interactions, under displacement control.

Minimises the total energy per the substrate's nominal area

.. math:: E(w) = E_{el}(w) + a_0^2 \sum_i V(d - h_i + w_i)

over the deflection ``w`` at fixed offset ``d``, by nonlinear conjugate gradients
(Polak–Ribière+) preconditioned with :math:`(K + \bar k)^{-1}`: the substrate's
Green's function on a uniform Winkler foundation whose stiffness :math:`\bar k` is the
mean over the sites of the interaction's stiffness :math:`\max(V''(g), 0)`, taken at the
start of the solve (and at every restart). Without contact this is the plain Green's
function, which makes the elastic part of the Hessian the identity (the Fourier
preconditioning of Bugnicourt et al., Tribol. Int. 119, 145 (2018), and the
mass-weighting of Zhou, Moseler & Müser, Phys. Rev. B 99, 144103 (2019)); in full contact
it is the exact inverse Hessian. The iteration count still grows mildly with the grid
(the contact patches' local stiffness and the number of sites that change regime; see
``benchmarks/adhesive.py`` for measurements).

Per iteration the solver needs ONE FFT convolution, the preconditioner applied to the
gradient: the elastic pressure of the search direction follows without a second
transform because :math:`K (K + \bar k)^{-1} = 1 - \bar k (K + \bar k)^{-1}` on the
non-uniform modes. The step length is an exact line minimisation, cheap because the
elastic energy is quadratic along the line and the interaction is local. (Preconditioned
L-BFGS with the same line search was tried and took the same number of iterations.)

Convergence measure (``residual``): the largest force imbalance per unit area,
``max |K w - p_int(g)|`` (excluding the uniform mode when it is rigid), divided by the
contact modulus. Everything else in SPEC §1 conventions.
"""

from __future__ import annotations

import math
import time

from .._backend import (
    array_device,
    array_namespace,
    computes_on_heights_device,
    dtype_name,
    irfft2,
    rfft2,
    to_numpy,
)
from .._validate import ParameterError
from ._ops import StallGuard, check_problem, false_position, illinois, stiffness_operator
from ._ops import dot as _dot
from .observables import make_result

__all__ = ["minimize_energy"]


def _local_pressure(interaction, gap):
    """Interaction pressure, evaluated only where the gap is inside the cutoff."""
    cutoff = interaction.cutoff
    if not math.isfinite(cutoff):
        return interaction.pressure(gap)
    inside = gap < cutoff
    p = array_namespace(gap).zeros_like(gap)
    p[inside] = interaction.pressure(gap[inside])
    return p


@computes_on_heights_device
def minimize_energy(
    heights,
    substrate,
    interaction,
    *,
    offset,
    initial=None,
    tol=None,
    max_iter=5000,
    callback=None,
    restart_every=200,
    device=None,
    dtype=None,
):
    """Solve a smooth-interaction contact state at fixed ``offset``.

    Parameters
    ----------
    heights : (nx, ny) array
        Rigid surface heights (length).
    substrate : Substrate
    interaction : object with ``pressure(gap)``, ``curvature(gap)``, ``energy(gap)``,
        ``classify(gap)``, ``cutoff``
    offset : float
        Offset ``d`` (length); gap ``g = d - h + w``.
    initial : ContactResult or array, optional
        Warm start (its deflection).
    tol : float, optional
        Tolerance on ``max |K w - p_int| / E*`` (see module docstring).
        Default 1e-8 (float64) or 1e-6 (float32, also the smallest allowed there).
    max_iter : int
        Iteration cap; reaching it returns ``converged=False``.
    callback : callable, optional
        ``callback(iteration, residual)``; return True to stop.
    restart_every : int
        Steepest-descent restart period of the conjugate directions.
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where to compute (default: where ``heights`` live); see :func:`roughcontact.to_device`.
    dtype : {None, "float64", "float32"}, optional
        Precision of the computation (default float64). float32 halves memory and
        time on a GPU; its accuracy floor is documented in the README.

    Returns
    -------
    ContactResult
    """
    t_start = time.perf_counter()
    h, tol = check_problem(heights, substrate, tol, offset, device, dtype)
    offset = float(offset)
    shape = h.shape
    n = h.size
    es = substrate.contact_modulus
    rigid = substrate.rigid_mean
    xp = array_namespace(h)
    elastic_pressure = stiffness_operator(substrate)
    stiffness = substrate._arrays(h)[0]

    base = offset - xp.reshape(h, (-1,))  # gap = base + w
    if initial is not None:
        w = getattr(initial, "deflection", initial)
        w = w if xp is array_namespace(w) else to_numpy(w)
        w = xp.reshape(xp.asarray(w, device=array_device(h), copy=True), (-1,))
        if w.shape[0] != n:
            raise ParameterError(f"initial must have the substrate's shape {substrate.shape}")
        if rigid:
            w -= xp.mean(w)
    else:
        w = xp.zeros(n, dtype=h.dtype, device=array_device(h))
    kw = elastic_pressure(w)

    def gradient(gap):
        gr = kw - _local_pressure(interaction, gap)
        if rigid:
            gr -= xp.mean(gr)  # the uniform mode is frozen: its force is the load
        return gr

    gap = base + w
    gr = gradient(gap)
    conv = kbar = None
    s = ks = z_old = None
    gz_old = 1.0
    converged, message, residual, it = False, "iteration cap reached", math.inf, 0
    stall = StallGuard(dtype_name(h))
    while True:
        residual = float(xp.max(xp.abs(gr))) / es
        if not math.isfinite(residual):
            message = f"non-finite state at iteration {it} (check inputs and the interaction)"
            break
        if residual <= tol:
            converged, message = True, "converged"
            break
        if (stalled := stall(residual)) is not None:
            message = stalled
            break
        if it >= max_iter:
            break
        if callback is not None and it > 0 and callback(it, residual):
            message = "stopped by callback"
            break
        it += 1
        restart = s is None or it % restart_every == 0
        if restart:
            kbar = _mean_site_stiffness(interaction, gap)
            conv = _shifted_compliance(stiffness, kbar, shape, rigid)
        z = conv(gr)  # preconditioned gradient (K + kbar)^-1 gr
        gz = _dot(gr, z)
        beta = 0.0 if restart else max(0.0, (gz - _dot(gr, z_old)) / gz_old)  # PR+
        # K (K + kbar)^-1 = 1 - kbar (K + kbar)^-1 (the uniform mode of gr is projected
        # out when it is rigid), so K z = gr - kbar z needs no second convolution
        kz = z * (-kbar)
        kz += gr
        if beta > 0:  # in place: s = -z + beta s, ks = -K z + beta ks
            s *= beta
            s -= z
            ks *= beta
            ks -= kz
        else:
            s, ks = -z, -kz
        slope0 = _dot(gr, s)
        if slope0 >= 0:  # not a descent direction: restart along the preconditioned -gr
            s, ks = -z, -kz
            slope0 = -gz
        z_old, gz_old = z, gz
        alpha = _line_minimum(interaction, gap, s, kw, ks, slope0)
        if not math.isfinite(alpha):
            message = f"line search failed at iteration {it}"
            break
        w += alpha * s
        kw += alpha * ks
        if it % 50 == 0:
            kw = elastic_pressure(w)  # remove round-off drift of the incremental update
        gap = base + w
        gr = gradient(gap)

    kw = elastic_pressure(w)
    gap = base + w
    p_int = _local_pressure(interaction, gap)
    rep, att = interaction.classify(gap)
    return make_result(
        h,
        substrate,
        xp.reshape(p_int, shape),
        xp.reshape(w, shape),
        offset,
        it,
        residual,
        converged,
        message,
        tol,
        "preconditioned-cg",
        time.perf_counter() - t_start,
        repulsive=xp.reshape(rep, shape),
        attractive=xp.reshape(att, shape),
    )


def _mean_site_stiffness(interaction, gap) -> float:
    """Mean over all sites of the interaction's stiffness V''(g), its negative part dropped."""
    cutoff = interaction.cutoff
    xp = array_namespace(gap)
    g = gap[gap < cutoff] if math.isfinite(cutoff) else gap
    return float(xp.sum(xp.maximum(interaction.curvature(g), 0.0))) / gap.shape[0]


def _shifted_compliance(stiffness, kbar, shape, rigid):
    r"""x -> (K + \bar k)^{-1} x: the Green's function of the substrate on a uniform
    Winkler foundation of the sites' mean stiffness (rigid uniform mode kept rigid)."""
    xp = array_namespace(stiffness)
    denominator = stiffness + kbar
    positive = denominator > 0
    multiplier = xp.where(positive, 1.0 / xp.where(positive, denominator, 1.0), 0.0)
    if rigid:
        multiplier[0, 0] = 0.0

    def apply(x_flat):
        xq = rfft2(xp.reshape(x_flat, shape))
        xq *= multiplier
        return xp.reshape(irfft2(xq, shape, overwrite_x=True), (-1,))

    return apply


def _line_minimum(interaction, gap, s, kw, ks, slope0, rtol=1e-3, max_eval=60):
    """Step ``alpha`` minimising E along ``w + alpha s`` (a root of the directional slope).

    phi'(alpha) = s.(kw + alpha ks) - s.p_int(gap + alpha s); the elastic part is linear
    in alpha. Bracket a sign change, then safeguarded secant (Illinois) steps until
    |phi'| <= rtol |phi'(0)|.
    """
    c0, c1 = _dot(s, kw), _dot(s, ks)
    xp = array_namespace(gap)
    # sites that can feel the interaction for alpha <= 4; the others only matter beyond
    band = math.isfinite(interaction.cutoff)
    if band:
        active = xp.minimum(gap, gap + 4.0 * s) < interaction.cutoff
        sa, ga = s[active], gap[active]
    else:
        sa, ga = s, gap

    def slope(alpha):
        return c0 + alpha * c1 - _dot(sa, interaction.pressure(ga + alpha * sa))

    lo, f_lo = 0.0, slope0
    # Newton guess with the curvature at alpha = 0
    curv = c1 + _dot(sa * sa, interaction.curvature(ga))
    hi = -slope0 / curv if curv > 0 else 1.0
    hi = min(max(hi, 1e-8), 4.0)
    f_hi = slope(hi)
    n_eval = 1
    while f_hi < 0 and n_eval < max_eval:
        if hi >= 4.0 and band:
            band, sa, ga = False, s, gap  # beyond the pre-selected band: use all sites
        lo, f_lo = hi, f_hi
        hi *= 2.0
        f_hi = slope(hi)
        n_eval += 1
    if f_hi < 0:
        return math.nan
    side = 0
    alpha = hi
    while n_eval < max_eval:
        alpha = false_position(lo, f_lo, hi, f_hi)
        f = slope(alpha)
        n_eval += 1
        if abs(f) <= rtol * abs(slope0):
            return alpha
        lo, f_lo, hi, f_hi, side = illinois(lo, f_lo, hi, f_hi, alpha, f, side)
    return alpha
