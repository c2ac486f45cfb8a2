r"""The hard-wall reference of a path: κ_rep of the same surface without a soft wall.

The paper's smoothed 9-3 wall (Pastewka & Robbins, PNAS 111, 3298 (2014)) has the site
stiffness :math:`k = E^*/(2a_0)` per area, softer than the substrate's on-site stiffness
(:math:`\approx 1.2\,E^*/a_0` for a half-space). Sites in a band of width δ around every
contact therefore carry a small repulsive force and count in :math:`A_{rep}` (the
paper's definition, :math:`g < a_0`). Its :math:`\kappa_{rep}` exceeds the continuum
hard-wall value by about :math:`1 + \pi\delta/d_{rep}`; δ is set by the wall, not by the
grid, so a larger grid does not remove it, a stiffer wall does. The paper reports κ_rep
close to 2 for its own simulations with this wall; that the difference is the wall's
finite stiffness is our explanation, and the hard-wall value computed here is its test.

This module solves the non-adhesive hard wall (:func:`roughcontact.solve` with
:class:`~roughcontact.HardWall`, constrained conjugate gradients) on the same surface and
substrate under load control, a few cheap warm-started solves, and reports

* ``kappa_rep`` :math:`= h'_{rms}E^* A/N` at the load where the hard-wall site count
  :math:`A_{rep}` equals the target area;
* ``kappa_rep_corrected``: the same where the perimeter-corrected area of Yastrebov,
  Anciaux & Molinari, Tribol. Int. 114, 161 (2017) equals the target (the estimate of
  the continuum area: it removes the lattice's bias, proportional to the perimeter);
* ``area_at_load``: the hard-wall :math:`A_{rep}` at a given load (the soft wall's
  :math:`N_{rep}`), from which :func:`band_width` gives
  :math:`\delta = (A_{rep} - A_{rep}^{hw})/P` at the same repulsive load.

Areas are fractions of :math:`A_0`, loads mean pressures :math:`N/A_0` (units of E*),
lengths in the substrate's units.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, in_range, json_ready, positive

__all__ = ["HardWallReference", "band_width", "hard_wall_reference"]

# κ of a self-affine hard-wall contact at small areas lies around 2-3: the first load
# tried is the one giving the target area for this value
_KAPPA_GUESS = 2.4
# bracketing states of the interpolation are accepted this close in load (relative):
# A_rep(N) is linear to far better than this over a few per cent of load
_BRACKET_WIDTH = 0.02


@dataclass(frozen=True)
class HardWallReference:
    """Hard-wall κ_rep of one surface at ``target_area`` (module docstring).

    ``load`` and ``corrected_load`` [N/A0, units of E*] carry ``target_area`` as raw and
    corrected area; ``kappa_rep``, ``kappa_rep_corrected`` [dimensionless];
    ``area_at_load`` the hard-wall A_rep/A0 at ``given_load`` (NaN if none was given);
    ``loads``/``areas``/``corrected_areas`` every state solved; ``converged`` whether
    every solve converged; ``solves`` how many were needed.
    """

    target_area: float
    rms_slope: float
    contact_modulus: float
    load: float
    kappa_rep: float
    corrected_load: float
    kappa_rep_corrected: float
    given_load: float
    area_at_load: float
    loads: tuple[float, ...]
    areas: tuple[float, ...]
    corrected_areas: tuple[float, ...]
    converged: bool
    solves: int

    def to_dict(self) -> dict:
        return json_ready(self)


def _bracket(loads, values, target):
    """Indices (lo, hi) of the closest states with values below / at-or-above target."""
    below = [i for i, v in enumerate(values) if v < target]
    above = [i for i, v in enumerate(values) if v >= target]
    lo = max(below, key=lambda i: loads[i]) if below else None
    hi = min(above, key=lambda i: loads[i]) if above else None
    return lo, hi


def _next_load(loads, values, target):
    """The load to try next for ``values(load) = target``, or None when bracketed."""
    lo, hi = _bracket(loads, values, target)
    if lo is not None and hi is not None:
        if values[hi] == target or loads[hi] - loads[lo] <= _BRACKET_WIDTH * loads[hi]:
            return None
        # regula falsi inside the bracket, nudged off its ends so that it shrinks
        frac = (target - values[lo]) / (values[hi] - values[lo])
        frac = min(max(frac, 0.1), 0.9)
        return loads[lo] + frac * (loads[hi] - loads[lo])
    # no bracket yet: A_rep grows about in proportion to the load at small areas;
    # step past the target by a little so that the next state closes the bracket
    i = hi if hi is not None else lo
    scale = target / values[i] if values[i] > 0 else 4.0
    scale = min(max(scale, 0.25), 4.0)
    return loads[i] * scale * (0.99 if hi is not None else 1.01)


def _interpolate(loads, values, target):
    lo, hi = _bracket(loads, values, target)
    if lo is None or hi is None:
        return math.nan
    if values[hi] == target:
        return loads[hi]
    return float(np.interp(target, [values[lo], values[hi]], [loads[lo], loads[hi]]))


def hard_wall_reference(
    heights,
    substrate,
    *,
    target_area: float = 0.01,
    rms_slope: float | None = None,
    load: float | None = None,
    tol: float = 1e-8,
    max_solves: int = 16,
    device: str | None = None,
) -> HardWallReference:
    r"""κ_rep of the non-adhesive hard wall on ``heights`` at ``target_area``.

    Parameters
    ----------
    heights : (nx, ny) array
        The rigid surface's heights (length), as for :func:`roughcontact.solve`.
    substrate : Substrate
        The elastic substrate of the path.
    target_area : float
        :math:`A_{rep}/A_0` in (0, 1) at which κ_rep is measured (the paper: 0.01).
    rms_slope : float, optional
        :math:`h'_{rms}` in :math:`\kappa_{rep} = h'_{rms}E^*A_{rep}/N_{rep}`; default:
        the spectral value of :func:`roughcontact.statistics` (what the path analysis uses).
    load : float, optional
        A load N/A0 (the soft wall's repulsive load at the target area) at which the
        hard-wall area is also solved for (``area_at_load``).
    tol : float
        Tolerance of each hard-wall solve (largest Signorini violation / h_rms).
    max_solves : int
        Cap on the number of solves of the bracketing search.
    device : {None, "cpu", "cuda", "cuda:N"}, optional
        Where the solves compute (default: where ``heights`` live); the heights are
        moved there once and every warm start stays there.

    Returns
    -------
    HardWallReference
        ``kappa_rep`` is NaN, and ``converged`` False, if the search did not bracket
        the target within ``max_solves`` solves.
    """
    from .._accelerator import place
    from ..interactions import HardWall
    from ..solvers import solve
    from ..surfaces.statistics import statistics

    target = in_range("target_area", target_area, 1e-12, 1.0)
    stats = statistics(heights, pixel_size=substrate.pixel_size, periodic=substrate.periodic)
    slope = stats.rms_slope
    slope = slope if rms_slope is None else positive("rms_slope", rms_slope)
    modulus = substrate.contact_modulus
    states, converged = [], True
    # moved once (device="cuda": a JAX array on that GPU, the compiled loop's heights)
    h = place(heights, device)

    def run(n):
        nonlocal converged
        nearest = min(states, key=lambda s: abs(s.load - n)) if states else None
        res = solve(h, substrate, HardWall(), load=n, initial=nearest, tol=tol)
        converged &= bool(res.converged)
        states.append(res)

    def columns():
        return (
            [s.load for s in states],
            [s.repulsive_area for s in states],
            [s.corrected_repulsive_area for s in states],
        )

    run(slope * modulus * target / _KAPPA_GUESS)
    while len(states) < max_solves:
        loads, areas, corrected = columns()
        wanted = [_next_load(loads, v, target) for v in (areas, corrected)]
        wanted = [w for w in wanted if w is not None]
        if not wanted:
            break
        run(wanted[0])
    loads, areas, corrected = columns()
    at_load = math.nan
    if load is not None:
        run(positive("load", load))
        at_load = states[-1].repulsive_area
    n_raw, n_corr = _interpolate(loads, areas, target), _interpolate(loads, corrected, target)
    scale = slope * modulus * target
    bracketed = math.isfinite(n_raw) and math.isfinite(n_corr)
    return HardWallReference(
        target_area=target,
        rms_slope=slope,
        contact_modulus=modulus,
        load=n_raw,
        kappa_rep=scale / n_raw,
        corrected_load=n_corr,
        kappa_rep_corrected=scale / n_corr,
        given_load=math.nan if load is None else float(load),
        area_at_load=at_load,
        loads=tuple(s.load for s in states),
        areas=tuple(s.repulsive_area for s in states),
        corrected_areas=tuple(s.corrected_repulsive_area for s in states),
        converged=converged and bracketed,
        solves=len(states),
    )


def band_width(repulsive_area: float, hard_wall_area: float, perimeter: float) -> float:
    r"""Width δ of the soft wall's repulsive band: :math:`(A_{rep} - A_{rep}^{hw})/P`.

    ``repulsive_area`` and ``hard_wall_area`` are :math:`A/A_0` at the same repulsive
    load, ``perimeter`` is :math:`P/A_0` (1/length) of the soft wall's repulsive area;
    the result is a length. For a contact of mean diameter :math:`d_{rep} = \pi A/P`
    the band raises :math:`\kappa_{rep}` by about :math:`1 + \pi\delta/d_{rep}`.
    """
    p = float(perimeter)
    if not p > 0:
        raise ParameterError(f"perimeter must be > 0, got {perimeter!r}")
    return (float(repulsive_area) - float(hard_wall_area)) / p


#: πδ/d_rep above which the soft wall's repulsive band is reported as a warning.
BAND_WARNING = 0.1


def reference_fields(ds, heights, substrate, target, at, kappa_rep, d_rep, device=None) -> dict:
    """The hard-wall reference's fields of a path analysis (and its warnings).

    ``ds`` is the path dataset, ``at`` its observables interpolated to the target area;
    the substrate is rebuilt from the path's attributes when ``substrate`` is None.
    """
    if heights is None and "heights" in ds.variables:
        heights = np.asarray(ds["heights"].values, dtype=float)
    if heights is None:
        return {
            "warnings": [
                "hard-wall reference not computed: the path holds no heights (pass heights=, "
                "or write the path with this version of roughcontact)"
            ]
        }
    if substrate is None:
        from ..elastic import substrate_from_attrs

        substrate = substrate_from_attrs(ds.attrs)
    ref = hard_wall_reference(
        heights,
        substrate,
        target_area=target,
        rms_slope=float(ds.attrs["rms_slope"]),
        load=at["repulsive_load"],
        device=device,
    )
    delta = band_width(target, ref.area_at_load, at["perimeter"])
    out = {
        "kappa_rep_hard_wall": ref.kappa_rep,
        "kappa_rep_hard_wall_corrected": ref.kappa_rep_corrected,
        "hard_wall_repulsive_area": ref.area_at_load,
        "band_width": delta,
        "band_fraction": math.pi * delta / d_rep,
        "warnings": [],
    }
    if not ref.converged:
        out["warnings"].append(
            f"the hard-wall reference did not converge in {ref.solves} solves: its values are "
            "approximate"
        )
    if out["band_fraction"] > BAND_WARNING:
        out["warnings"].append(_band_warning(ds, kappa_rep, delta, out["band_fraction"], ref))
    return out


def _hard_core(attrs) -> bool:
    """Whether the path's interaction has a hard core (no soft repulsion to blame)."""
    name = str(attrs.get("interaction_name", ""))
    if name in ("dugdale", "hardwall"):
        return True
    if name == "exponential":  # hard unless a core stiffness was recorded
        k = attrs.get("core_stiffness")
        return k is None or not math.isfinite(float(k))
    return False


def _band_warning(ds, kappa_rep, delta, fraction, ref) -> str:
    """The kappa_rep band warning, naming the cause that applies to the path's law: a
    soft wall's finite stiffness, or (a hard core, no soft repulsion) the adhesion."""
    head = (
        f"kappa_rep = {kappa_rep:.3g} includes a band of width delta = {delta:.3g} around "
        f"every contact (pi delta/d_rep = {fraction:.0%}); a hard wall on the same surface "
        f"without adhesion gives kappa_rep = {ref.kappa_rep:.3g} "
        f"({ref.kappa_rep_corrected:.3g} with the corrected area). "
    )
    if _hard_core(ds.attrs):
        law = str(ds.attrs.get("interaction_name", "the interaction"))
        return head + (
            f"The law ({law}) has a hard core, so no soft repulsion widens the contacts: the "
            "band comes from the adhesion, whose attraction around each contact deforms "
            "the surface and changes the repulsive area and load at this target area; "
            "it is a property of the adhesive contact, not of the wall model or the grid"
        )
    k = float(ds.attrs.get("stiffness", math.nan)) * float(ds.attrs["pixel_size"])
    wall = (
        f"its site stiffness k = {k / float(ds.attrs['contact_modulus']):.3g} E*/a0 per area"
        if math.isfinite(k)
        else "its finite stiffness"
    )
    return head + (
        f"The band is where the wall is weakly repulsive: it comes from the wall model "
        f"({wall}, softer than the substrate's on-site stiffness), not from adhesion or "
        "the grid: a larger grid keeps it, a stiffer wall removes it"
    )
