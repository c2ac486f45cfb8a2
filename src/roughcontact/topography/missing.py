"""Missing points of a measured scan: fill a few, refuse many (the policy of every reader).

Instruments mark points they could not measure (interferometers: no fringe contrast on
steep or dark spots; AFMs: saturated lines) as NaN or masked. The analysis needs a full
grid, so they are filled by harmonic interpolation (each missing point the mean of its
neighbours, :func:`~roughcontact.topography._grid.harmonic_fill`): the smoothest surface
through the points around them, which keeps a plane exactly and adds no roughness.

**Threshold.** A filled point carries no roughness of its own, so filling a fraction f
of the scan lowers the mean-square slope and curvature by about f (they are averages
over the area; measured in ``tests/topography/test_missing.py``). Up to
:data:`MISSING_FILL_MAX` = 1 % this bias (at most 1 % in ``h'_rms^2``, 0.5 % in
``h'_rms``) is well below the uncertainty of the Hurst fit and the scatter between
scans of one surface, and isolated dropouts are the common case: such scans are filled
by default, with a line saying how many points and how. Above it the statistics describe
the interpolation as much as the surface: the scan is refused unless the user asks for
the filling (``fill_missing=True``, CLI ``--fill-missing``), and then the fraction is
stated next to the result.
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError
from ._grid import harmonic_fill

__all__ = ["MISSING_FILL_MAX", "fill_note", "missing_policy"]

#: Largest fraction of missing points filled without being asked (module docstring).
MISSING_FILL_MAX = 0.01


def _option_text() -> str:
    return "--fill-missing (Python: fill_missing=True)"


def slope_change(values, missing, filled) -> float:
    """How filling changed the rms slope: ``rms(filled) / rms(measured) - 1``.

    The slope is the difference of neighbouring pixels along every axis, less its mean
    (the tilt); "measured" takes only the pairs of two measured points, "filled" every
    pair of the filled scan. Negative: the filled area is smoother than the scan (the
    usual case of harmonic filling); positive: it is rougher (e.g. isolated pixels
    pinned inside a filled region). NaN when no pair is measured.
    """
    ms_measured = ms_filled = 0.0
    for axis in range(values.ndim):
        d_all = np.diff(filled, axis=axis)
        pair = ~(np.delete(missing, 0, axis=axis) | np.delete(missing, -1, axis=axis))
        d = np.diff(values, axis=axis)[pair]
        if d.size < 2:
            return float("nan")
        ms_measured += float(np.var(d))
        ms_filled += float(np.var(d_all))
    if not ms_measured > 0:
        return float("nan")
    return float(np.sqrt(ms_filled / ms_measured) - 1.0)


def missing_policy(name, data, fill_missing, periodic, info, *, outliers: int = 0):
    """Fill or refuse the missing points (NaN or masked) of ``data``.

    Parameters
    ----------
    name : str
        How the data are named in messages (``"path 'scan.frt'"``).
    data : array or masked array
        Heights, 1D or 2D (any unit).
    fill_missing : bool or None
        None: fill up to :data:`MISSING_FILL_MAX`, refuse more; True: fill any fraction;
        False: refuse any.
    periodic : bool
        Whether the data wrap around (the filling's neighbours do too).
    info : dict
        Metadata; a copy gets ``missing_data`` (``points``, ``fraction``, ``filled``,
        ``asked``, ``outliers``: how many of the points are outliers removed by
        :mod:`~roughcontact.topography.outliers`, ``slope_change``: the measured effect
        of the filling on the rms slope, :func:`slope_change`).
    outliers : int
        How many of the missing points are outliers removed (for the messages).

    Returns
    -------
    (ndarray, dict or None)
        The heights (float64) and the new info, or None when nothing was missing.

    Raises
    ------
    ParameterError
        One line with the count, the fraction and the option that fills them.
    """
    missing = np.ma.getmaskarray(data) | ~np.isfinite(np.ma.getdata(data))
    values = np.array(np.ma.getdata(data), dtype=np.float64)
    count = int(missing.sum())
    if count == 0:
        return values, None
    fraction = count / missing.size
    if count == missing.size:
        raise ParameterError(f"{name}: every point is missing; no heights to read")
    of_them = (
        f", {outliers} of them outliers removed (--outliers keep keeps them)" if outliers else ""
    )
    if fill_missing is None and fraction > MISSING_FILL_MAX:
        raise ParameterError(
            f"{name}: {_percent(fraction)} of the points ({count} of {missing.size}) are "
            f"missing (NaN or masked by the instrument{of_them}), more than the "
            f"{MISSING_FILL_MAX:.0%} filled by default; {_option_text()} fills them by "
            "harmonic interpolation, which removes the roughness of the filled area"
        )
    if fill_missing is not None and not fill_missing:
        raise ParameterError(
            f"{name}: {count} of {missing.size} points ({fraction:.3%}) are missing (NaN or "
            f"masked by the instrument{of_them}) and fill_missing=False; {_option_text()} fills "
            "them by harmonic interpolation"
        )
    measured = values
    values = harmonic_fill(values, missing, periodic=periodic)
    info = dict(info)
    info["missing_data"] = {
        "points": count,
        "fraction": fraction,
        "filled": "harmonic",
        "asked": bool(fill_missing),
        "outliers": int(outliers),
        "slope_change": slope_change(measured, missing, values),
    }
    return values, info


def fill_note(missing: dict, total: int | None = None) -> str:
    """One line on what was filled (``info["missing_data"]``), for every text output."""
    f = float(missing["fraction"])
    count = int(missing["points"])
    of = f" of {total}" if total else ""
    how = missing.get("filled", "harmonic")
    how = (
        "harmonic interpolation (each the mean of its neighbours)"
        if how == "harmonic"
        else str(how)
    )
    line = f"filled {count}{of} missing points ({f:.3%} of the scan) by {how}"
    if missing.get("outliers"):
        line += f" ({int(missing['outliers'])} of them outliers removed)"
    change = missing.get("slope_change")
    large = f > MISSING_FILL_MAX
    if change is not None and np.isfinite(change) and (large or abs(change) >= 0.01):
        more = "higher" if change > 0 else "lower"
        why = "" if change > 0 else " (the filled area has no roughness of its own)"
        line += (
            f"; the filled scan's rms slope (pixel differences) is {abs(change):.1%} {more} "
            f"than that of the measured points alone{why}"
        )
    if large:
        line += f"; {_percent(f)} is more than the {MISSING_FILL_MAX:.0%} filled by default"
    return line


def _percent(fraction: float, limit: float = MISSING_FILL_MAX) -> str:
    """``fraction`` in percent with the digits that tell it from ``limit`` and keep it
    within 1 % of its value (1.05 %, not the 1.0 % that reads as the limit itself)."""
    for digits in range(1, 7):
        text = f"{fraction:.{digits}%}"
        close = abs(float(text[:-1]) - 100 * fraction) <= 0.01 * 100 * fraction
        if close and (fraction == limit or text != f"{limit:.{digits}%}"):
            return text
    return f"{fraction:.7%}"
