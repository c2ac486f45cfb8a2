r"""The adhesive solvers' rules on physical scales: what a stall means, where load control stops.

One place for the decisions that the NumPy loops (:mod:`.smooth`, :mod:`.load_control`) and
a compiled loop share: plain functions of host floats and of the law, no arrays of the
loop's backend.

**The physical pressure scale.** An elastic half-space pressed onto a rough surface of rms
slope :math:`h'_{rms}` needs pressures of order :math:`E^* h'_{rms}` to flatten it (full
contact of a hard wall, Persson's and Johnson's estimates, ~0.5-1 E* h'rms); an adhesive
law adds its largest attraction :math:`\sigma_{max}` (the tensile stress the surfaces can
hold). So an equilibrium under a load ``N`` has pressures of order
:math:`P = \max(E^* h'_{rms}, \sigma_{max}) + |N|`; a state with pressures many orders of
magnitude above that is not an equilibrium of linear elasticity but a runaway (two
surfaces pushed through each other by an offset far beyond full contact: 1e13 E* in the
9-3 core).

**Stall or runaway.** float64 resolves a force balance on pressures of size ``p`` only to
``eps p`` (``eps = 2**-52``). A solve whose residual stops falling at the floor of its
*own* largest pressure is therefore

* *stalled* (:attr:`SolveStatus.STALLED`) only if that residual is also within
  :data:`FLOOR_ULPS` floors of the *physical* scale, :math:`\epsilon P / E^*` (``tol``
  below what float64 resolves: the state is an equilibrium to that floor);
* a *runaway* (:attr:`SolveStatus.RUNAWAY`) if its pressures exceed
  :data:`RUNAWAY_RATIO` physical scales: they are beyond any elastic equilibrium, and
  the residual it stalls at is not a force balance on the physical scale;
* in between (a few sites deep in a repulsive core at tens of E*, ``tol`` below their
  rounding) stalled, with a message that says at which local pressure, never "as
  accurate as float64 allows".

**Where load control looks.** For a law without a hard core the load
:math:`\bar p(d)` grows without bound as the offset goes below full contact; an
equilibrium carrying ``N`` has its gaps where the law's pressure is at most
:math:`N + C P` (:data:`FULL_CONTACT_MARGIN` ``= C``), so its mean gap (``d - mean(h)``
with a rigid mean) lies above the gap :math:`g_N` where the law's repulsion equals
:math:`N + C P`. :func:`lowest_smooth_offset` gives ``mean(h) + g_N``: the bracketing
of the offset never goes below it, and the load there exceeds ``N`` (the core's pressure
is convex in the gap: the mean of ``p(g_i)`` is at least ``p`` of the mean gap), so the
bracket closes there, in full contact, rather than doubling into a runaway.

**Load in the one minimisation** (:mod:`._free_mean`): the uniform mode's preconditioner
block, :func:`uniform_stiffness` and :func:`uniform_shift`, scalar rules written for any
array namespace's scalars (``xp``: NumPy floats by default, 0-d device arrays in a
compiled loop).
"""

from __future__ import annotations

import contextlib
import contextvars
import math

import numpy as np

from .._backend import array_namespace, is_numpy_array, to_numpy
from .result import SolveStatus

__all__ = [
    "FLOOR_ULPS",
    "EPS64",
    "attraction_peak_gap",
    "CONTACT_FRACTION",
    "CONTACT_REFRESH",
    "contact_mode",
    "contact_stale",
    "FULL_CONTACT_MARGIN",
    "NESTED_MIN_SIZE",
    "NESTED_TOL",
    "RUNAWAY_RATIO",
    "carrying",
    "floor_verdict",
    "gap_at_pressure",
    "largest_attraction",
    "lift_block",
    "lift_shape",
    "pair_coefficients",
    "lowest_smooth_offset",
    "nests",
    "physical_pressure_scale",
    "rms_slope",
    "runaway_message",
    "state_verdict",
    "tension_lost",
    "uniform_shift",
    "uniform_stiffness",
    "wall_uniform_stiffness",
]

#: A float64 residual within this many floors ``eps p / E*`` is "at the rounding floor".
FLOOR_ULPS = 256
#: float64 machine epsilon, 2**-52.
EPS64 = 2.220446049250313e-16
#: Pressures above this many physical scales are a runaway (measured: states through
#: full contact reach 1e9-1e14 E*; legitimate equilibria have a few core sites at <= 1e2 E*).
RUNAWAY_RATIO = 1e6
#: Load control's lowest offset: the law's repulsion there is the load plus this many
#: physical pressure scales (a full-contact state's pressures vary by ~1 scale).
FULL_CONTACT_MARGIN = 10.0

#: Nested iteration of a cold load-controlled solve (:mod:`.load_control`): on a grid of at
#: least NESTED_MIN_SIZE sites with even sides it starts from the same load solved on the
#: grid coarsened 2x2 (one level, never recursively: a coarse grid of a surface whose
#: shortest wavelength is 4 pixels holds it on 2; two levels, 256² -> 64², ended at load 0
#: in another state), to NESTED_TOL (or ``tol`` if larger). Measured (issue surface, ℓa
#: 0.005 / 0.05, loads 1e-3 / 0, benchmarks/README.md): the fine grid's iterations 0.5-1.5x
#: the offset-controlled cold solve's instead of 1.1-3.2x, the same states.
NESTED_MIN_SIZE = 1 << 14
NESTED_TOL = 1e-3


def nests(shape) -> bool:
    """Whether a cold load-controlled solve on a grid of ``shape`` starts from the coarse
    grid's state (:data:`NESTED_MIN_SIZE`)."""
    nx, ny = shape
    return nx * ny >= NESTED_MIN_SIZE and nx % 2 == 0 and ny % 2 == 0


def rms_slope(heights, pixel_size: float, periodic: bool = True) -> float:
    """Root-mean-square slope of 2-D ``heights`` (dimensionless; forward differences,
    periodic wrap when ``periodic``); a NumPy computation on the host, or for periodic
    device heights (JAX, CuPy) on their device, one scalar read (not the grid)."""
    xp = None if is_numpy_array(heights) else array_namespace(heights)
    if periodic and xp is not None and hasattr(xp, "roll"):
        h = heights
        dx, dy = xp.roll(h, -1, axis=0) - h, xp.roll(h, -1, axis=1) - h
        return float(xp.sqrt(xp.mean(dx * dx) + xp.mean(dy * dy))) / float(pixel_size)
    h = np.asarray(to_numpy(heights), dtype=float)
    if periodic:
        dx, dy = np.roll(h, -1, 0) - h, np.roll(h, -1, 1) - h
        squares = np.mean(dx * dx) + np.mean(dy * dy)
    else:
        dx, dy = np.diff(h, axis=0), np.diff(h, axis=1)
        squares = (np.mean(dx * dx) if dx.size else 0.0) + (np.mean(dy * dy) if dy.size else 0.0)
    return float(math.sqrt(squares)) / float(pixel_size)


def _sample_gaps(law) -> np.ndarray:
    """Gaps (length) spanning the law's attractive range: 0 to its cutoff (or to ten
    equilibrium distances / ranges when the cutoff is infinite)."""
    top = float(law.cutoff)
    if not math.isfinite(top):
        eq = getattr(law, "equilibrium_distance", None) or 0.0
        top = eq + 10.0 * float(getattr(law, "range", None) or eq or 1.0)
    return np.linspace(0.0, top, 4097)[1:]


def largest_attraction(law) -> float:
    """The law's largest tensile stress (pressure, >= 0): ``-min p(g)`` over its range."""
    with np.errstate(all="ignore"):
        p = np.asarray(law.pressure(_sample_gaps(law)), dtype=float)
    p = p[np.isfinite(p)]
    return float(max(0.0, -p.min())) if p.size else 0.0


#: The load (pressure) that load control's inner solves are to carry, or None.
_LOAD: contextvars.ContextVar = contextvars.ContextVar("adhesive_load", default=None)


@contextlib.contextmanager
def carrying(load):
    """Within the block, :func:`physical_pressure_scale` adds ``|load|`` (pressure): load
    control's inner solves judge their floor on the load asked for too."""
    token = _LOAD.set(float(load))
    try:
        yield
    finally:
        _LOAD.reset(token)


def attraction_peak_gap(law) -> float:
    """The gap (length) of the law's largest tension (0 if it has none): beyond it the
    attraction falls with the gap (the laws here: one well)."""
    gaps = _sample_gaps(law)
    with np.errstate(all="ignore"):
        p = np.asarray(law.pressure(gaps), dtype=float)
    p = np.where(np.isfinite(p), p, np.inf)
    return float(gaps[int(np.argmin(p))]) if p.min() < 0 else 0.0


def tension_lost(law, load, min_gap, peak_gap, xp=None) -> bool:
    """Whether a tensile ``load`` (< 0, pressure) can no longer be carried as the surfaces
    separate: every gap beyond the law's range, or beyond its attraction's peak
    (``peak_gap``) with less tension at the smallest gap ``min_gap`` than ``-load`` (no
    site can then pull harder, and separating further pulls less). With ``xp`` (a compiled
    loop's namespace) the same rule on 0-d arrays, a boolean 0-d array."""
    if xp is not None:
        tension = -law.pressure(xp.reshape(min_gap, (1,)))[0]
        beyond = (min_gap >= law.cutoff) | ((min_gap > peak_gap) & (tension < -load))
        return (load < 0) & beyond
    if load >= 0:
        return False
    if min_gap >= law.cutoff:
        return True
    if min_gap <= peak_gap:
        return False
    tension = -float(np.asarray(law.pressure(np.array([min_gap], dtype=float)))[0])
    return tension < -load


def physical_pressure_scale(heights, substrate, law) -> float:
    """:math:`\\max(E^* h'_{rms}, \\sigma_{max})` (pressure), plus ``|N|`` inside
    :func:`carrying`: the scale of an elastic equilibrium's pressures on these heights
    with this law (module docstring)."""
    periodic = getattr(substrate, "periodic", True)
    slope = rms_slope(heights, substrate.pixel_size, periodic)
    load = _LOAD.get()
    extra = 0.0 if load is None else abs(load)
    return max(substrate.contact_modulus * slope, largest_attraction(law)) + extra


def floor_verdict(best, own_pressure, physical_scale, contact_modulus, tol, patience):
    """Why a float64 solve whose residual stopped falling at its own rounding floor stops:
    ``(kind, message)``, ``kind`` "stalled" or "runaway" (module docstring).

    ``best``: its best residual (units of E*); ``own_pressure``: its largest ``|p|``;
    ``physical_scale``: :func:`physical_pressure_scale`. Within :data:`FLOOR_ULPS` floors
    of the physical scale the state is an equilibrium to float64's floor ("stalled ... as
    accurate as float64 allows"); with pressures above :data:`RUNAWAY_RATIO` physical
    scales it is a runaway; in between (a few sites deep in a repulsive core, tens of E*)
    it is stalled at the rounding of those sites' pressures, and the message says so
    instead of calling the state as accurate as float64 allows.
    """
    scale = max(physical_scale, 1e-300)
    floor = EPS64 * scale / contact_modulus
    if best <= FLOOR_ULPS * floor:
        return "stalled", (
            f"stalled at the float64 rounding floor: residual {best:.3g} (units of E*), "
            f"pressure scale P = {physical_scale:.3g} (E*·h'rms or the law's largest "
            f"attraction, plus |load|), floor ~P·eps/E* = {floor:.3g}; no progress in "
            f"{patience} iterations: the state is as accurate as float64 allows (tol {tol:g} "
            "is below what float64 resolves at this pressure)"
        )
    ratio = own_pressure / scale
    if ratio <= RUNAWAY_RATIO:
        return "stalled", (
            f"stalled: residual {best:.3g} E* is float64's rounding of the largest local "
            f"pressure, {own_pressure / contact_modulus:.3g} E* ({ratio:.2g} times the "
            f"pressure scale P = {physical_scale:.3g}: sites deep in the repulsive core); no "
            f"progress in {patience} iterations; tol {tol:g} is not reached (use tol >= "
            f"{2 * best:.1g})"
        )
    return "runaway", runaway_message(own_pressure, physical_scale, contact_modulus, best)


def runaway_message(own_pressure, physical_scale, contact_modulus, residual):
    """The message of a runaway: pressures ``own_pressure`` (largest ``|p|``) above
    :data:`RUNAWAY_RATIO` times ``physical_scale`` (:func:`physical_pressure_scale`), beyond
    any elastic equilibrium, whatever the residual says (in float32 the force balance of
    1e13 E* pressures can round to exactly 0). None when the pressures are physical."""
    ratio = own_pressure / max(physical_scale, 1e-300)
    if not ratio > RUNAWAY_RATIO:
        return None
    return (
        f"runaway: pressures reach {own_pressure / contact_modulus:.3g} E* (max |p|), "
        f"{ratio:.2g} times the physical scale P = {physical_scale:.3g} (E*·h'rms or the "
        "law's largest attraction, plus |load|): beyond any elastic equilibrium. The "
        f"residual stopped at {residual:.3g} E* (the rounding floor at those pressures), far "
        "above a force balance on the scale P; the offset pushes the surfaces through each "
        "other (below full contact): not an equilibrium"
    )


def state_verdict(status, message, own_pressure, law, physical, contact_modulus, residual,
                  tol, eps):
    """``(status, message)`` of a smooth-law solve, judged on its largest ``|p|``
    (``own_pressure``, pressure) once it has stopped; the rule of the NumPy loop
    (:mod:`.smooth`) and the compiled one (:mod:`._adhesive_jax`), stated once.

    *Runaway.* A solve that claims a state (``status`` stalled at its precision's floor,
    or converged with a residual below ``tol``, units of E*, that its precision cannot
    resolve: the rounding floor ``eps * own_pressure / E*`` above ``tol``, ``eps`` the
    machine epsilon of the solve's precision) with pressures above :data:`RUNAWAY_RATIO`
    times the law's largest attraction and :data:`RUNAWAY_RATIO` physical scales
    (``physical()``, only then evaluated: :func:`physical_pressure_scale`) was pushed
    through full contact and rounded its force balance to zero (64², offset below the
    surface's mean: uniform p = 6e12 E*, residual 0, yet 1e-2 E* recomputed): it becomes
    :attr:`SolveStatus.RUNAWAY`. A cap, a callback or a failed line search already say the
    state is not an equilibrium.

    *Beyond linear elasticity.* A converged state whose force balance is resolved is an
    equilibrium of the model however deep in the core (1e3 E* at a mean gap of 0.38 a0),
    but the elastic half-space holds for pressures far below E* (small strains; states of
    an approach reach ~0.2 E* even at a mean gap of a0): above E* the message says so.
    """
    converged = status is SolveStatus.CONVERGED
    claims = status is SolveStatus.STALLED or (
        converged and eps * own_pressure / contact_modulus > tol
    )
    if claims and own_pressure > RUNAWAY_RATIO * largest_attraction(law):
        runaway = runaway_message(own_pressure, physical(), contact_modulus, residual)
        if runaway is not None:
            return SolveStatus.RUNAWAY, runaway
    if converged and own_pressure > contact_modulus:
        message = (
            f"{message}; note: pressures reach {own_pressure / contact_modulus:.3g} E*, "
            "beyond the linear-elastic half-space (valid for |p| << E*): the surfaces are "
            "pressed deep into the interaction's repulsive core"
        )
    return status, message


def gap_at_pressure(law, target: float, start: float) -> float:
    """The gap (length) at or below ``start`` where the law's pressure reaches ``target``
    (pressure, > its value at ``start``), by doubling steps down and bisection; -inf if
    it never does (a bounded repulsion)."""

    def p(g):
        return float(np.asarray(law.pressure(np.array([g], dtype=float)))[0])

    hi, step = float(start), max(abs(float(start)), 1.0) * 1e-3
    lo = hi - step
    for _ in range(200):
        if p(lo) >= target:
            break
        hi, step = lo, 2.0 * step
        lo = hi - step
    else:
        return -math.inf
    for _ in range(200):  # p(lo) >= target > p(hi)
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        lo, hi = (mid, hi) if p(mid) >= target else (lo, mid)
    return lo


def lowest_smooth_offset(law, mean_height, load, physical_scale) -> float:
    """The lowest offset (length) load control tries for a law without a hard core on a
    substrate with a rigid mean: ``mean(h) + g`` with ``p(g) = max(load, 0) + C P``
    (:data:`FULL_CONTACT_MARGIN`; module docstring); -inf for a law whose repulsion is
    bounded."""
    eq = getattr(law, "equilibrium_distance", None) or 0.0
    target = max(float(load), 0.0) + FULL_CONTACT_MARGIN * physical_scale
    return float(mean_height) + gap_at_pressure(law, target, eq)


#: ``k_u`` is this fraction of the mean repulsive curvature: the sites' springs act in
#: series with the substrate, so the contact stiffness is below their mean (measured: 11x
#: below at 128², ℓa 0.005, 1.2x at ℓa 0.05); cold load control from first contact, 128²
#: and 256², ℓa 0.005 and 0.05: 1.0 -> 105/118/214/163/136 iterations, 0.3 -> 92/112/196/
#: 143/120, 0.1 -> 94/128/216/164/142.
UNIFORM_FRACTION = 0.3


def uniform_stiffness(mean_curvature, contact_modulus, size, xp=np):
    """The uniform mode's stiffness ``k_u`` (pressure/length): :data:`UNIFORM_FRACTION` of
    the mean over the grid of ``max(V''(g), 0)`` (``mean_curvature``), at least the
    longest wavelength's elastic stiffness ``E* pi / size`` (``size``: the longer side,
    length). One mode mis-scaled costs conjugate gradients about one iteration."""
    return xp.maximum(UNIFORM_FRACTION * mean_curvature, contact_modulus * math.pi / size)


#: The bounded solver's ``k_u``: this fraction of the self-stiffness times the fraction of
#: sites on the wall (the contact pins them; the free sites' curvature is attractive).
#: Measured, cold load 1e-3 / path steps, Exponential(w = la, range a0), 128² and 256²:
#: 0 (the elastic floor alone) 31/44/51/74 its, steps 24-26/30-35/40-42/42-53; 0.1
#: 31/29/46/44, 24-26/20-22/39-42/28-30; 0.3 33/33/41/66; 1.0 72/54/97/93.
WALL_FRACTION = 0.1


def wall_uniform_stiffness(wall_fraction, self_stiffness, contact_modulus, size, xp=np):
    """``k_u`` (pressure/length) of the bounded solver's uniform block: :data:`WALL_FRACTION`
    x the fraction of sites on the wall (``wall_fraction``) x the substrate's
    self-stiffness (pressure/length), at least ``E* pi / size``."""
    floor = contact_modulus * math.pi / size
    return xp.maximum(WALL_FRACTION * wall_fraction * self_stiffness, floor)


#: The bounded solver's uniform block follows the contact's response (:func:`contact_mode`),
#: recomputed (one float32 convolution) when more than this fraction of the wall's sites
#: changed since it was last computed. Measured (Exponential w = 0.005 E* a0, range a0,
#: 256², cold load 0, benchmarks/README.md): 0 (every change) 32 iterations and 38
#: convolutions, 0.02 33 and 23, 0.1 35 and 16.
CONTACT_REFRESH = 0.1
#: :func:`contact_mode`'s stiffness is this fraction of its Rayleigh quotient (which bounds
#: the contact stiffness from above: the uniform pressure is a trial field). Measured
#: (cold load -1e-3 / 0 / 1e-3, Exponential w 0.005 and 0.05 range a0, MaugisDugdale w 0.05
#: range a0 and w 0.01 range a0/2; fine-grid iterations summed over the 12 cases): 256²
#: 0.25 661, 0.5 661, 1.0 738, the rule before (:func:`wall_uniform_stiffness`) 938; 128²
#: 475, 361, 390, before 441.
CONTACT_FRACTION = 0.5


def contact_stale(changed, n_active, xp=np):
    """Whether the contact's response is to be recomputed: ``changed`` sites entered or left
    the wall since, of ``n_active`` there now (:data:`CONTACT_REFRESH`; ``xp`` as in
    :func:`contact_mode`)."""
    return changed > CONTACT_REFRESH * xp.maximum(n_active, 1)


def contact_mode(v, active, floor, xp=np):
    r"""The bounded solver's uniform mode under load control: ``(u, k)``.

    ``v = G (1_A - a)`` (length) is the deflection of a uniform pressure on the wall's
    sites ``active`` (``a`` their fraction; ``G`` the compliance, which takes no mean), so
    ``u = 1 - v / m`` (``m`` the mean of ``v`` over the wall) is the shape of the body
    lifted at fixed contact: 1 far from it, about 0 on it. A uniform shift of the free
    sites alone (the rule before, :func:`wall_uniform_stiffness`) bends the surface at
    every contact's edge; ``u`` does not, and its stiffness per site is
    :math:`u K u / n = a / m` (``K u = -(1_A - a)/m``, ``sum_A u = 0``): the Rayleigh
    quotient of the contact stiffness under a uniform contact pressure; ``k`` is
    :data:`CONTACT_FRACTION` of it. That can be far below the longest wavelength's
    stiffness :math:`E^* \pi / L` (256², 5 % on the wall: 0.003 against 0.012), which
    the rule before used as its floor. No site on the wall: ``u = 1``, ``k = floor``
    (:math:`E^* \pi / L`).
    ``xp``: NumPy, or a compiled loop's namespace (then ``v`` and ``active`` are its
    arrays, the result too).
    """
    count = xp.sum(active)
    if xp is np and not count:
        return np.ones_like(v), floor
    lifted, m, touching = _lifted(v, active, count, xp)
    u = xp.where(touching, lifted, 1.0)
    k = xp.where(touching, CONTACT_FRACTION * count / active.size / m, floor)
    return u, k


def _lifted(v, sites, count, xp):
    """``(1 - v / m, m, ok)``: ``m`` the mean of ``v`` over the ``count`` ``sites`` (1 where
    not ``ok``: no site, or ``m <= 0``); the body lifted at fixed contact of
    :func:`contact_mode` and :func:`lift_shape`."""
    m = xp.sum(xp.where(sites, v, 0.0)) / xp.maximum(count, 1)
    ok = (count > 0) & (m > 0)
    safe = xp.where(ok, m, 1.0)
    return 1.0 - v / safe.astype(v.dtype), safe, ok


def uniform_shift(mean_gradient, k_u, reach, xp=np):
    """The preconditioned gradient's uniform part (length): ``mean(gr) / k_u``, at most
    ``reach`` (the heights' rms) in magnitude.

    The bound keeps a load far beyond the state's stiffness (out of contact ``k_u`` is the
    elastic floor ``E* pi / L``; 1e9 E* then asks for a 1e10 a0 step) from a step that only
    the line search's tiny ``alpha`` can hold, which then stalls every other mode."""
    return xp.clip(mean_gradient / k_u, -reach, reach)


def lift_shape(v, stiff, xp=np):
    """The smooth solver's second uniform direction under load control: ``(u, ok)`` with
    ``u = 1 - v / m`` off the ``stiff`` sites (zero on them), ``v = G (1_S - s)`` the
    deflection of a uniform pressure on them and ``m`` its mean there: the body lifted
    at fixed contact (:func:`contact_mode`, whose sites are pinned; here the stiff sites
    move with the block preconditioner's diagonal). ``ok``: some site is stiff and
    ``m > 0``; else ``u`` is zero. ``xp`` as in :func:`contact_mode`."""
    count = xp.sum(stiff)
    lifted, _, ok = _lifted(v, stiff, count, xp)
    ok = ok & (count < stiff.size)
    return xp.where(stiff | ~ok, 0.0, lifted), ok


def lift_block(d, u, ku, floor, total, dot, xp=np):
    """``(h00, h01, h11)`` of :func:`pair_coefficients` (per site, pressure/length): the
    Hessian ``K + V''+`` on the directions ``1`` and ``u`` (:func:`lift_shape`), ``d`` the
    curvature ``V''+``, ``ku`` = ``K u``, ``floor`` = ``E* pi / L``; ``total`` and ``dot``
    the caller's sums (NumPy's or a compiled loop's accumulating ones)."""
    n = d.size
    du = d * u
    return xp.maximum(total(d) / n, floor), total(du) / n, (dot(u, ku) + dot(du, u)) / n


def pair_coefficients(h00, h01, h11, g0, g1, reach, xp=np):
    r"""The preconditioner's block on the two uniform directions ``1`` and ``u``
    (:func:`lift_shape`): ``(c0, c1)`` solving the Galerkin system
    :math:`\begin{pmatrix} h_{00} & h_{01} \\ h_{01} & h_{11} \end{pmatrix} c = g`
    (per site: ``h00 = max(mean V''+, E* pi / L)``, ``h01 = mean(V''+ u)``,
    ``h11 = (u K u)/n + mean(V''+ u^2)``, ``V''+`` the interaction's curvature where
    positive; ``g = (mean gr, mean u gr)``), each at most ``reach`` (length) in magnitude
    (:func:`uniform_shift`). ``h`` is positive definite by Cauchy-Schwarz when ``u K u > 0``;
    a determinant that is not positive gives ``c1 = 0``, ``c0 = g0 / h00``."""
    det = h00 * h11 - h01 * h01
    good = det > 0
    safe = xp.where(good, det, 1.0)
    c0 = xp.where(good, (h11 * g0 - h01 * g1) / safe, g0 / h00)
    c1 = xp.where(good, (h00 * g1 - h01 * g0) / safe, 0.0)
    return xp.clip(c0, -reach, reach), xp.clip(c1, -reach, reach)
