"""Preparing a measured topography: detrending and the tip-radius reliability cutoff.

Pure functions: each returns a new record and never changes its argument; what a
function did is recorded in the result's ``info`` (e.g. ``info["detrend"] = "plane"``).
Lengths are in the topography's unit (metres for instrument files, see
``Topography.length_unit``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .._validate import positive
from ..errors import ParameterError
from .topography import Topography

__all__ = [
    "DETREND_MODES",
    "ReliabilityCutoff",
    "detrend",
    "reliability_cutoff",
    "scale_dependent_curvature",
]

#: Modes of :func:`detrend`: the polynomial removed by least squares.
DETREND_MODES = ("none", "height", "plane", "curvature")
_TERMS = {
    1: {"height": ["1"], "plane": ["1", "x"], "curvature": ["1", "x", "x^2"]},
    2: {
        "height": ["1"],
        "plane": ["1", "x", "y"],
        "curvature": ["1", "x", "y", "x^2", "x*y", "y^2"],
    },
}


def detrend(topo: Topography, mode: str = "plane") -> Topography:
    """Remove the least-squares mean, plane (tilt) or second-order polynomial.

    The heights ``h`` are fitted by ``sum_k c_k b_k(x, y)`` over the basis of the mode
    (``height``: 1; ``plane``: 1, x, y; ``curvature``: 1, x, y, x², xy, y²; in 1D the
    terms in x only) with coordinates measured from the centre of the scan, and the fit
    is subtracted: the residual is orthogonal to every basis function (the normal
    equations ``B^T (h - B c) = 0``). Tilt and curvature are artefacts of mounting and
    of scanners (piezo bow) that would otherwise dominate slopes and curvatures of a
    measured scan (Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001
    (2017)).

    Parameters
    ----------
    topo : Topography
        The scan (any length unit).
    mode : {"plane", "height", "curvature", "none"}
        What to remove.

    Returns
    -------
    Topography
        The residual heights; ``info["detrend"]`` is the mode and
        ``info["detrend_coefficients"]`` the fitted ``c_k`` by term name (``"1"``,
        ``"x"``, ``"x*y"``, ...; heights per length**order, coordinates from the scan
        centre). Removing a tilt or a curvature makes a periodic record non-periodic;
        removing the mean keeps it.
    """
    if mode not in DETREND_MODES:
        raise ParameterError(f"mode must be one of {', '.join(DETREND_MODES)}, got {mode!r}")
    if mode == "none":
        return dataclasses.replace(topo, info={**topo.info, "detrend": "none"})
    h = topo.heights
    terms = _TERMS[topo.dim][mode]
    columns, scales = _basis(h.shape, topo.pixel_size, terms)
    coef, *_ = np.linalg.lstsq(columns, h.ravel(), rcond=None)
    residual = (h.ravel() - columns @ coef).reshape(h.shape)
    coefficients = {t: float(c / s) for t, c, s in zip(terms, coef, scales, strict=True)}
    info = {**topo.info, "detrend": mode, "detrend_coefficients": coefficients}
    periodic = topo.periodic and mode == "height"
    return dataclasses.replace(topo, heights=residual, periodic=periodic, info=info)


def _basis(shape, pixel_size, terms):
    """Columns of the basis on the grid (coordinates from the centre, scaled to [-1, 1]).

    Scaling keeps the least-squares problem well conditioned whatever the length unit;
    ``scales`` turn the coefficients back into physical ones.
    """
    axes = []
    half = []
    for n, p in zip(shape, pixel_size, strict=True):
        c = (np.arange(n) - (n - 1) / 2) * p
        half.append(max(float(np.max(np.abs(c))), p))
        axes.append(c / half[-1])
    grids = np.meshgrid(*axes, indexing="ij")
    u = grids[0].ravel()
    v = grids[1].ravel() if len(grids) > 1 else None
    hx = half[0]
    hy = half[1] if len(half) > 1 else 1.0
    table = {
        "1": (np.ones_like(u), 1.0),
        "x": (u, hx),
        "x^2": (u * u, hx * hx),
    }
    if v is not None:
        table.update({"y": (v, hy), "x*y": (u * v, hx * hy), "y^2": (v * v, hy * hy)})
    columns = np.stack([table[t][0] for t in terms], axis=1)
    return columns, [table[t][1] for t in terms]


@dataclass(frozen=True)
class ReliabilityCutoff:
    """The scale below which a scanning-probe measurement is dominated by its tip.

    Attributes
    ----------
    cutoff : float or None
        Scale ``l_c`` (topography's length unit): below it the scale-dependent curvature
        of the summits exceeds ``safety_factor / tip_radius``; every larger scale is
        reliable. None when no cutoff applies (tip radius unknown, or no artefact at the
        smallest scale, two pixels: see ``message``).
    tip_radius : float or None
        The radius used (same unit), None if unknown.
    tip_radius_source : str
        ``"argument"``, ``"file"`` (the instrument's metadata) or ``"unknown"``.
    safety_factor : float
        ``f`` in the criterion ``-h''_l >= f / R``.
    all_scales : bool
        True if the criterion is violated up to the largest scale examined (then
        ``cutoff`` is that scale: no reliable data).
    message : str
        The outcome in words.
    """

    cutoff: float | None
    tip_radius: float | None
    tip_radius_source: str
    safety_factor: float
    all_scales: bool
    message: str

    def to_dict(self) -> dict:
        """A JSON-ready dict of the fields."""
        return dataclasses.asdict(self)


def scale_dependent_curvature(topo: Topography, half_width: int, axis: int = 0) -> np.ndarray:
    """Second differences of the heights at the scale ``l = 2 * half_width * pixel_size``.

    ``h''_l(x) = [h(x + l/2) - 2 h(x) + h(x - l/2)] / (l/2)²`` along ``axis``: the
    3-point stencil of overall width ``l`` (the scale of Sanner et al., Appl. Surf. Sci.
    Adv. 7, 100190 (2022), and of SurfaceTopography's ``derivative(n=2, distance=l)``),
    at the points ``l/2`` or more inside a non-periodic scan, at every point of a
    periodic one (wrapping around). Units: 1/length.
    """
    h = topo.heights
    n = h.shape[axis]
    m = int(half_width)
    spacing = m * topo.pixel_size[axis]
    if topo.periodic:
        return (np.roll(h, -m, axis) - 2 * h + np.roll(h, m, axis)) / spacing**2
    ahead, centre, behind = (
        np.take(h, np.arange(a, n - 2 * m + a), axis=axis) for a in (2 * m, m, 0)
    )
    return (ahead - 2 * centre + behind) / spacing**2


def _summit_curvature(topo, half_width, axes) -> float:
    """The largest ``-h''_l`` (summits) over the scan along ``axes``."""
    worst = -math.inf
    for axis in axes:
        c = scale_dependent_curvature(topo, half_width, axis)
        if c.size:
            worst = max(worst, float(-np.min(c)))
    return worst


def reliability_cutoff(
    topo: Topography, tip_radius=None, *, safety_factor: float = 0.5, axis: int | None = 0
) -> ReliabilityCutoff:
    """The smallest lateral scale at which a scan is not dominated by tip artefacts.

    A spherical tip of radius ``R`` rides over summits sharper than itself and images
    them with its own curvature, ``-1/R``: at scales ``l`` where the scale-dependent
    curvature of the summits, ``C(l) = max_x -h''_l(x)`` (the 3-point stencil of width
    ``l``, :func:`scale_dependent_curvature`), reaches ``f / R`` the data show the tip
    rather than the surface. The cutoff ``l_c`` is the largest scale with
    ``C(l) >= f / R``, found on the scales ``l = 2 m * pixel_size`` (m = 1, 2, ...)
    and interpolated log-log between the two that bracket the crossing. For a sinusoid
    ``A sin(2 pi x / lambda)`` sampled at its summit,
    ``C(l) = 4 A sin²(pi l / (2 lambda)) / (l/2)²``, which tends to its curvature
    ``A (2 pi / lambda)²`` as ``l -> 0`` and falls monotonically up to ``l = 2 lambda``.

    Parameters
    ----------
    topo : Topography
        The scan (e.g. from :func:`roughcontact.load_topography`).
    tip_radius : float, optional
        Tip radius R (topography's length unit, > 0). Default: the radius stored in the
        file's metadata (``topo.info["tip_radius"]``, metres), if any.
    safety_factor : float
        ``f`` (> 0); Sanner et al. calibrate ``f = 1/2`` on simulated tips (default);
        ``f = 1`` is the bare geometric bound ``1/R``.
    axis : int or None
        Axis of the differences in a 2D map: 0 (x, default, as SurfaceTopography), 1,
        or None for both (the larger curvature; square pixels only).

    Returns
    -------
    ReliabilityCutoff
        ``cutoff`` None with ``message`` "no reliability cutoff (tip radius unknown)"
        when no radius is given or stored.

    References
    ----------
    T. D. B. Jacobs, T. Junge and L. Pastewka, Surf. Topogr.: Metrol. Prop. 5, 013001
    (2017); A. Sanner, W. G. Nöhring, L. A. Thimons, T. D. B. Jacobs and L. Pastewka,
    "Scale-dependent roughness parameters for topography analysis", Appl. Surf. Sci.
    Adv. 7, 100190 (2022) (the tip-radius criterion and ``f = 1/2``).
    """
    f = positive("safety_factor", safety_factor)
    radius, source = _radius(topo, tip_radius)
    if radius is None:
        return ReliabilityCutoff(
            None, None, source, f, False, "no reliability cutoff (tip radius unknown)"
        )
    axes = _axes(topo, axis)
    target = f / radius
    spacing = topo.pixel_size[axes[0]]
    n = min(topo.shape[a] for a in axes)
    largest = n // 2 if topo.periodic else (n - 1) // 2  # the largest half-width m
    known: dict[int, float] = {}

    def curvature(m: int) -> float:
        if m not in known:
            known[m] = _summit_curvature(topo, m, axes)
        return known[m]

    # every half-width up to 16 pixels, then geometrically spaced ones, refined below
    grid = np.unique(np.concatenate([np.arange(1, 17), np.geomspace(1, largest, 48).round()]))
    grid = [int(m) for m in grid if 1 <= m <= largest]
    bad = [m for m in grid if curvature(m) >= target]

    def length(x):  # metres in words for an SI record, the number otherwise
        if topo.length_unit == "m":
            from ._text import length_text

            return length_text(x)
        return f"{x:.4g}"

    how = f"tip radius {length(radius)} from the {source}, f = {f:g}"
    if not bad:
        message = (
            f"no tip artefacts: the summit curvature stays below f/R = {target:.4g} "
            f"1/{'m' if topo.length_unit == 'm' else 'length'} down to "
            f"the smallest scale, {length(2 * spacing)} ({how})"
        )
        return ReliabilityCutoff(None, radius, source, f, False, message)
    m = bad[-1]
    if m == grid[-1]:
        cutoff = 2 * largest * spacing
        message = (
            f"tip artefacts at every scale up to {length(cutoff)}: no reliable data ({how})"
        )
        return ReliabilityCutoff(cutoff, radius, source, f, True, message)
    for k in range(m + 1, grid[grid.index(m) + 1]):  # the largest violation in between
        if curvature(k) >= target:
            m = k
    cutoff = 2 * spacing * _crossing(m, curvature(m), m + 1, curvature(m + 1), target)
    message = f"reliable above {length(cutoff)} (tip artefacts below; {how})"
    return ReliabilityCutoff(cutoff, radius, source, f, False, message)


def _radius(topo, tip_radius):
    """(radius, where it came from): the argument, else the file's (SI records only)."""
    if tip_radius is not None:
        return positive("tip_radius", tip_radius), "argument"
    if topo.info.get("tip_radius") is not None and topo.length_unit == "m":
        return positive("tip_radius", topo.info["tip_radius"]), "file"
    return None, "unknown"


def _axes(topo, axis) -> tuple:
    if axis is None:
        axes = tuple(range(topo.dim))
    elif (
        isinstance(axis, (int, np.integer)) and not isinstance(axis, bool) and 0 <= axis < topo.dim
    ):
        axes = (int(axis),)
    else:
        raise ParameterError(f"axis must be None or in [0, {topo.dim - 1}], got {axis!r}")
    if any(not math.isclose(topo.pixel_size[a], topo.pixel_size[axes[0]]) for a in axes):
        raise ParameterError(
            f"axis=None needs square pixels, got pixel_size {topo.pixel_size}; give axis=0 or 1"
        )
    if min(topo.shape[a] for a in axes) < 3:
        raise ParameterError(f"topo must have at least 3 points per axis, got {topo.shape}")
    return axes


def _crossing(m0, c0, m1, c1, target) -> float:
    """Half-width between ``m0`` and ``m1`` where the curvature crosses ``target``.

    Log-log linear (summit curvatures of rough surfaces are power laws in the scale)
    when both values are positive, else linear.
    """
    if c1 > 0:
        t = (math.log(c0) - math.log(target)) / (math.log(c0) - math.log(c1))
        return math.exp(math.log(m0) + t * (math.log(m1) - math.log(m0)))
    return m0 + (c0 - target) / (c0 - c1) * (m1 - m0)
