"""Readable numbers for the text output: lengths with prefixes and ranges with "to"."""

from __future__ import annotations

import math

__all__ = ["length_text", "range_text"]


def length_text(metres: float) -> str:
    """``12.3 nm``, ``4.56 um``, ``0.3 nm``: a length with a readable prefix."""
    if metres is None or not math.isfinite(metres):
        return "n/a"
    for factor, unit in ((1e-3, "mm"), (1e-6, "um"), (1e-9, "nm")):
        if metres >= factor:
            return f"{metres / factor:.3g} {unit}"
    return f"{metres / 1e-9:.3g} nm"


def range_text(lo: float, hi: float, fmt: str = ".3g") -> str:
    """``"-0.79 to -0.58"``: a range that stays readable with negative ends."""
    return f"{lo:{fmt}} to {hi:{fmt}}"
