"""Offsets of a path aimed relative to the first contact of the rough surface.

The rigid surface sits at ``z = d - h``; with an undeformed substrate the highest summit
first touches (gap ``g = d - max(h)`` equal to the law's equilibrium distance ``d0``) at

    d_first = max(h) + d0,

``d0`` being a0 (the equilibrium distance) for the Lennard-Jones walls and 0 for the
hard-core laws (hard wall, exponential, Maugis-Dugdale). Offsets given relative to it are
in units of length, of the surface's rms height, or as a bearing-area fraction (see
:func:`relative_offsets`). The single owner of this convention: the studies'
``[path] unit`` and ``roughcontact path --offset-unit`` both use it; and of the stepped
ranges ``START STOP STEP`` of both (:func:`stepped_values`).
"""

from __future__ import annotations

import numpy as np

from .._backend import array_namespace, to_numpy
from .._validate import MAX_PATH_STEPS, ParameterError
from ..interactions.hardwall import HardWall

__all__ = ["OFFSET_UNITS", "first_contact_offset", "relative_offsets", "stepped_values"]

#: The units of :func:`relative_offsets`.
OFFSET_UNITS = ("length", "rms_height", "bearing_area")


def _host_heights(heights) -> np.ndarray:
    from .._validate import heights2d

    return np.asarray(to_numpy(heights2d("heights", heights)), dtype=np.float64)


def _equilibrium_distance(interaction) -> float:
    """d0 (length): a0 of the Lennard-Jones walls; 0 for the hard wall and hard cores."""
    if interaction is None or isinstance(interaction, HardWall):
        return 0.0
    return float(interaction.equilibrium_distance or 0.0)


def first_contact_offset(heights, interaction=None) -> float:
    """Offset ``d`` (length) at which the undeformed surfaces first touch.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights h of the rigid surface (length), any backend.
    interaction : interaction law, optional
        Its ``equilibrium_distance`` d0 (length; a0 for the Lennard-Jones walls) is the
        gap at contact; laws without one (hard wall, exponential, Dugdale; None) have 0.

    Returns
    -------
    float
        ``max(h) + d0`` (length); the maximum is taken on the heights' device.
    """
    from .._validate import heights2d

    h = heights2d("heights", heights)
    return float(array_namespace(h).max(h)) + _equilibrium_distance(interaction)


def relative_offsets(heights, values, unit="length", interaction=None, pixel_size=1.0):
    """Absolute offsets ``d`` (length) from values given relative to the first contact.

    Parameters
    ----------
    heights : (nx, ny) array
        Heights h of the rigid surface (length), any backend.
    values : float or sequence of float
        The offsets in ``unit``; finite.
    unit : {"length", "rms_height", "bearing_area"}
        ``"length"``: ``d = max(h) + d0 + v`` (v in length units, negative v pushes
        into contact); ``"rms_height"``: ``d = max(h) + d0 + v h_rms`` with
        ``h_rms = <(h - <h>)^2>^(1/2)``; ``"bearing_area"``: fractions v in [0, 1] of the
        nominal area, growing into contact, ``d = d0 + quantile(h, 1 - v)`` (linear
        interpolation), where the undeformed rigid surface would overlap (``h > d - d0``)
        a fraction v of the substrate (to within one site; exactly k sites for
        v = k/(nx ny) on distinct heights). v = 0 is the first contact.
    interaction : interaction law, optional
        Gives ``d0``, its ``equilibrium_distance`` (length; a0 for the Lennard-Jones
        walls, 0 for the hard-core laws and for None).
    pixel_size : float
        a0 (length), > 0; the rms height does not depend on it (kept for the statistics'
        signature and future units).

    Returns
    -------
    numpy.ndarray
        float64 offsets ``d`` (length), one per value, in the order given.

    Raises
    ------
    ParameterError
        For an unknown unit, non-finite values, bearing-area fractions outside [0, 1], or
        flat heights with ``"rms_height"`` or ``"bearing_area"`` (no scale to step by).
    """
    from ..surfaces.statistics import rms_height

    if unit not in OFFSET_UNITS:
        raise ParameterError(
            f"unit must be one of {', '.join(map(repr, OFFSET_UNITS))}, got {unit!r}"
        )
    try:
        v = np.atleast_1d(np.asarray(values, dtype=np.float64))
    except (TypeError, ValueError):
        raise ParameterError(f"values must be finite numbers, got {values!r}") from None
    if not np.all(np.isfinite(v)):
        raise ParameterError(f"values must be finite numbers, got {values!r}")
    h = _host_heights(heights)
    d0 = _equilibrium_distance(interaction)
    if unit != "length" and h.size and not float(np.ptp(h)) > 1e-9 * float(np.max(np.abs(h))):
        # every value would give the same d: a path of identical steps
        raise ParameterError(
            f"unit {unit!r} needs a rough surface: the heights are flat (all "
            f"{float(np.mean(h)):.6g} up to rounding), so every value gives the same offset; "
            "use unit 'length' (or absolute offsets)"
        )
    if unit == "bearing_area":
        if np.any((v < 0) | (v > 1)):
            raise ParameterError(
                f"values must be in [0, 1] for unit 'bearing_area' (fractions of A0), "
                f"got {values!r}"
            )
        if v.size == 0:
            return v
        return d0 + np.quantile(h, 1.0 - v)  # the undeformed surfaces overlap on v
    scale = rms_height(h, pixel_size=pixel_size) if unit == "rms_height" else 1.0
    return float(h.max()) + d0 + scale * v


def stepped_values(start, stop, step, *, name="the path"):
    """``start, start ± |step|, ...`` up to ``stop`` (inclusive): a stepped path's values.

    Parameters
    ----------
    start, stop : float
        The first value and the last one (reached when ``|stop - start|/|step|`` is an
        integer to within 1e-9, so that decimal steps such as 0.1 hit it); any unit
        (offsets: length or ``unit``; loads: pressure).
    step : float
        Non-zero; its sign is ignored (the values go from ``start`` towards ``stop``).
    name : str
        How messages name the three numbers (``"--offsets"``, ``"[path]"``).

    Returns
    -------
    numpy.ndarray
        float64 ``start + sign(stop - start) |step| k``, ``k = 0 ... floor(|stop - start|
        / |step| + 1e-9)``; ``[start]`` when ``stop == start``.

    Raises
    ------
    ParameterError
        For non-finite numbers, a zero step, or more than
        :data:`~roughcontact._validate.MAX_PATH_STEPS` values.
    """
    try:
        start, stop, step = float(start), float(stop), float(step)
    except (TypeError, ValueError):
        raise ParameterError(
            f"{name} START STOP STEP must be numbers, got {start!r} {stop!r} {step!r}"
        ) from None
    if not all(np.isfinite(v) for v in (start, stop, step)):
        raise ParameterError(
            f"{name} START STOP STEP must be finite numbers, got {start:g} {stop:g} {step:g}"
        )
    if step == 0:
        raise ParameterError(f"{name} STEP must be non-zero")
    span = abs(stop - start) / abs(step)
    if not span < MAX_PATH_STEPS:
        raise ParameterError(
            f"{name} {start:g} {stop:g} {step:g} gives more than {MAX_PATH_STEPS} steps "
            f"(accepted: at most {MAX_PATH_STEPS}); use a larger STEP"
        )
    count = int(np.floor(span + 1e-9)) + 1
    return start + np.sign(stop - start or 1) * abs(step) * np.arange(count)
