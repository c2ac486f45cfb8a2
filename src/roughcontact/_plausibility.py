"""Plausibility checks at the reading edge: absurd data is refused before any verdict.

A damaged file can be read without an error and still hold nonsense: flipped bits give
an rms height of 10^13 m, a zeroed header field makes a reader take the wrong block or
a pixel size of 10^-41 m, a constant scan has no roughness at all. Each of these used to
go on to a verdict. The bounds (generous: they refuse only what no instrument measures)
are:

* every height finite, and ``|h|`` below :data:`MAX_MAGNITUDE` (1e150: beyond it the
  squares of an rms overflow float64) in any unit;
* a surface that is not flat: the peak-to-valley height must exceed
  :data:`FLAT_RELATIVE` (1e-9) times the largest ``|h|`` (what is left below that is
  floating-point rounding of a constant) and 1e-150 (below, squares underflow);
* instrument files (their units are the file's, in metres once read): a
  peak-to-valley height in [:data:`MIN_HEIGHT_RANGE_M`, :data:`MAX_HEIGHT_RANGE_M`]
  = [1 fm, 1 m] and a pixel size in [:data:`PIXEL_SIZE_M`] = [1 pm, 1 m] (a ``.npy``
  or text file's units are the caller's, who chose them);
* the header against the data where the format allows it (Zygo MetroPro: the sizes of
  the intensity and phase blocks the header gives against each other and against the
  file's size).
"""

from __future__ import annotations

import os
import struct

import numpy as np

from .errors import ParameterError

__all__ = [
    "FLAT_RELATIVE",
    "MAX_HEIGHT_RANGE_M",
    "MAX_MAGNITUDE",
    "MIN_HEIGHT_RANGE_M",
    "PIXEL_SIZE_M",
    "check_header",
    "check_heights",
    "check_metres",
    "is_flat",
]

#: largest |height| in any unit: the squares of an rms of larger values overflow float64
MAX_MAGNITUDE = 1e150
#: peak-to-valley at or below this fraction of max |h|: a constant up to rounding
FLAT_RELATIVE = 1e-9
#: accepted peak-to-valley height in metres: from 1 fm (below any instrument's noise)
MIN_HEIGHT_RANGE_M = 1e-15
#: ... to 1 m (beyond any profilometer's range)
MAX_HEIGHT_RANGE_M = 1.0
#: accepted pixel size in metres (1 pm to 1 m)
PIXEL_SIZE_M = (1e-12, 1.0)


def is_flat(heights) -> bool:
    """True when the finite ``heights`` are constant up to floating-point rounding.

    Peak-to-valley ``<= FLAT_RELATIVE * max|h|`` (0 for exactly equal heights) or
    ``<= 1 / MAX_MAGNITUDE`` (1e-150: no roughness a float64 rms can hold).
    """
    h = np.asarray(heights, dtype=np.float64)
    top = float(np.max(np.abs(h)))
    return not float(np.ptp(h)) > max(FLAT_RELATIVE * top, 1 / MAX_MAGNITUDE)


def check_heights(heights, where: str, *, flat: bool = True) -> None:
    """Refuse non-finite heights, magnitudes past :data:`MAX_MAGNITUDE` and (``flat``) a
    flat surface, with one line starting with ``where`` (e.g. ``"path 'x.npy'"``)."""
    h = np.asarray(heights, dtype=np.float64)
    if h.size == 0:
        return
    bad = ~np.isfinite(h)
    if bad.any():
        raise ParameterError(
            f"{where}: {int(bad.sum())} of {h.size} heights are not finite (NaN or "
            "infinite); accepted finite heights"
        )
    top = float(np.max(np.abs(h)))
    if top > MAX_MAGNITUDE:
        raise ParameterError(
            f"{where}: heights up to |h| = {top:.3g} are out of range: accepted |h| <= "
            f"{MAX_MAGNITUDE:g} (their squares overflow); a damaged file or the wrong unit"
        )
    if flat and is_flat(h):
        raise ParameterError(
            f"{where}: flat surface (every height is {float(np.mean(h)):.6g} up to "
            "rounding): there is no roughness to analyse, so no contact verdict"
        )


def check_metres(heights, pixel_size, where: str) -> None:
    """Physical bounds of a topography in metres (see the module docstring)."""
    h = np.asarray(heights, dtype=np.float64)
    sizes = np.atleast_1d(np.asarray(pixel_size, dtype=np.float64))
    lo, hi = PIXEL_SIZE_M
    for s in sizes:
        if not lo <= s <= hi:
            raise ParameterError(
                f"{where}: pixel size {s:.3g} m is out of range: accepted [{lo:g}, {hi:g}] m "
                "(a damaged header, or the wrong lateral unit)"
            )
    span = float(np.ptp(h))
    if not MIN_HEIGHT_RANGE_M <= span <= MAX_HEIGHT_RANGE_M:
        raise ParameterError(
            f"{where}: peak-to-valley height {span:.3g} m is out of range: accepted "
            f"[{MIN_HEIGHT_RANGE_M:g}, {MAX_HEIGHT_RANGE_M:g}] m (a damaged file, a wrong "
            "scale factor or the wrong height unit)"
        )


def check_header(path, format_name: str, shape) -> None:
    """Header against data for the formats whose header says how large the data are."""
    name = str(format_name).lower()
    if "metropro" in name:
        _metropro(path, shape)


#: Zygo MetroPro header 1 (big-endian): ac_org_width, ac_org_height, ac_n_buckets,
#: ac_range, ac_n_bytes, cn_org_x, cn_org_y, cn_org_width, cn_org_height, cn_n_bytes
_METROPRO = struct.Struct(">HHHhIhhHHI")
_METROPRO_AT = 52


def _metropro(path, shape) -> None:
    where = f"path {str(path)!r}"
    try:
        with open(path, "rb") as f:
            head = f.read(_METROPRO_AT + _METROPRO.size)
            header_size = struct.unpack(">I", head[6:10])[0]
        size = os.path.getsize(path)
        ac_w, ac_h, buckets, _, ac_bytes, _, _, cn_w, cn_h, cn_bytes = _METROPRO.unpack(
            head[_METROPRO_AT:]
        )
    except (OSError, struct.error):
        return  # the reader has read it; nothing more to compare
    problems = []
    if ac_bytes != 2 * buckets * ac_w * ac_h:
        problems.append(
            f"intensity block of {ac_bytes} bytes, not 2 x {buckets} buckets x {ac_w} x {ac_h}"
        )
    if cn_bytes != 4 * cn_w * cn_h:
        problems.append(f"phase block of {cn_bytes} bytes, not 4 x {cn_w} x {cn_h}")
    if header_size + ac_bytes + cn_bytes > size:
        problems.append(
            f"header + blocks = {header_size + ac_bytes + cn_bytes} bytes, more than the "
            f"file's {size}"
        )
    if sorted(shape) != sorted((cn_w, cn_h)):
        problems.append(f"data of shape {tuple(shape)}, header {cn_w} x {cn_h}")
    if problems:
        raise ParameterError(
            f"{where}: MetroPro header inconsistent with its data ({'; '.join(problems)}): "
            "a damaged header; refused rather than read from the wrong place"
        )
