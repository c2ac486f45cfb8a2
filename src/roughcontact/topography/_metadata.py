"""The metadata of an instrument file read by SurfaceTopography: JSON-ready, with the tip
or stylus radius the file states (in any spelling of its unit).

Lengths in metres.
"""

from __future__ import annotations

import math
import re

from ..errors import ParameterError
from .topography import length_factor

__all__ = ["instrument_info"]


def _format(reader) -> str:
    try:
        return str(reader.name())
    except Exception:  # noqa: BLE001
        return type(reader).__name__


def instrument_info(reader, ch, topo_info) -> dict:
    """JSON-ready metadata: the format, the channels, the instrument, the tip radius (m)."""
    try:
        from SurfaceTopography import __version__ as version
    except ImportError:  # pragma: no cover - imported already
        version = "?"
    meta = {**(getattr(ch, "info", {}) or {}), **topo_info}
    raw = meta.pop("raw_metadata", None)  # vendor key/value dumps: large, not always JSON
    info = {
        "format": _format(reader),
        "reader": f"SurfaceTopography {version}",
        "length_unit": "m",
        "channel_index": int(ch.index),
        "channels": [c.name for c in reader.channels],
        "height_scale_factor": getattr(ch, "height_scale_factor", None),
        **meta,
    }
    if getattr(ch, "channel_id", None) is not None:
        info["channel_id"] = str(ch.channel_id)
    radius, where, stated = _tip_radius(meta, raw if isinstance(raw, dict) else None)
    if radius is not None:
        info["tip_radius"] = radius
        info["tip_radius_stated"] = {"text": stated, "key": where}
    elif stated is not None:  # stated, but its unit is no length we know
        info["tip_radius_stated"] = {"text": stated, "key": "", "unreadable": True}
    return info


#: Spellings of "micro" that a unit reaches us in: the micro sign, the Greek mu, and the
#: micro sign of a UTF-8 file read as Latin-1 ("Âµ") or with its byte lost (U+FFFD).
_MICRO = ("\u00c2\u00b5", "\u00b5", "\u03bc", "\ufffd")
#: A number and a unit in a vendor's metadata value ("Radius: 2 µm", "2.5um").
_RADIUS_VALUE = re.compile(r"([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)\s*([^\s,;:()]+)")


def _unit_text(unit) -> str:
    """A length unit's text with every spelling of micro as ``u``."""
    text = str(unit).strip()
    for micro in _MICRO:
        text = text.replace(micro, "u")
    return text


def _micro_sign(text) -> str:
    """``text`` with the micro sign in place of its mis-decoded spellings ("Âµ", "μ")."""
    return str(text).replace("\u00c2\u00b5", "\u00b5").replace("\u03bc", "\u00b5")


def _radius_metres(value, unit) -> float | None:
    try:
        r = float(value) * length_factor("tip radius unit", _unit_text(unit))
    except (ParameterError, TypeError, ValueError):
        return None
    return r if math.isfinite(r) and r > 0 else None


def _flat(d, depth=0):
    """(key, value) pairs of a nested metadata dict, leaves only (4 levels at most)."""
    for key, value in d.items():
        if isinstance(value, dict):
            if depth < 4:
                yield from _flat(value, depth + 1)
        elif isinstance(value, (str, int, float)):
            yield key, value


def _tip_radius(meta, raw=None) -> tuple:
    """The tip or stylus radius the file states: ``(metres or None, where, as written)``.

    First SurfaceTopography's reading (``instrument.parameters.tip_radius``: value and
    unit, the unit's "µ" in any of its spellings, :data:`_MICRO`), then the vendor's own
    key/value pairs (``raw``): a key naming a tip, stylus, probe or cantilever radius,
    or a value of the form "Radius: 2 µm". ``where`` says which; ``as written`` is the
    file's text. A stated radius whose unit is not a length gives None with its text.
    """
    stated = None
    try:
        r = meta["instrument"]["parameters"]["tip_radius"]
        stated = f"{r['value']} {_micro_sign(r['unit'])}"
        value = _radius_metres(r["value"], r["unit"])
        if value is not None:
            return value, "instrument.parameters.tip_radius", stated
    except (KeyError, TypeError):
        pass
    for key, text in _flat(raw or {}):
        k, v = str(key), str(text)
        named = re.search(r"(tip|stylus|probe|needle).*radius|radius.*(tip|stylus|probe)", k, re.I)
        if not (named or v.lower().lstrip().startswith("radius")):
            continue
        if "cantilever" in k.lower():
            continue  # a cantilever's radius is not the tip's
        found = _RADIUS_VALUE.search(v.split(":", 1)[-1] if ":" in v else v)
        if found is None:
            continue
        value = _radius_metres(*found.groups())
        stated = f"{k}: {_micro_sign(v.strip())}"
        if value is not None:
            return value, f"metadata {k!r}", stated
    return None, "", stated
