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


def missing_policy(name, data, fill_missing, periodic, info):
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
        ``asked``).

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
    if fill_missing is None and fraction > MISSING_FILL_MAX:
        raise ParameterError(
            f"{name}: {_percent(fraction)} of the points ({count} of {missing.size}) are missing "
            "(NaN or masked by the instrument), more than the "
            f"{MISSING_FILL_MAX:.0%} filled by default; {_option_text()} fills them by "
            "harmonic interpolation, which removes the roughness of the filled area"
        )
    if fill_missing is not None and not fill_missing:
        raise ParameterError(
            f"{name}: {count} of {missing.size} points ({fraction:.3%}) are missing (NaN or "
            f"masked by the instrument) and fill_missing=False; {_option_text()} fills "
            "them by harmonic interpolation"
        )
    values = harmonic_fill(values, missing, periodic=periodic)
    info = dict(info)
    info["missing_data"] = {
        "points": count,
        "fraction": fraction,
        "filled": "harmonic",
        "asked": bool(fill_missing),
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
    if f > MISSING_FILL_MAX:
        line += (
            f"; {_percent(f)} is more than the {MISSING_FILL_MAX:.0%} filled by default: slope and "
            f"curvature may be low by about {f:.0%} (the filled area has no roughness)"
        )
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
