"""Observables of contact states."""

from .contact_geometry import (
    area_fraction,
    contact_patches,
    corrected_area,
    perimeter,
    perimeter_edges,
)
from .path import interpolate_at_area, kappa

__all__ = [
    "area_fraction",
    "contact_patches",
    "corrected_area",
    "interpolate_at_area",
    "kappa",
    "perimeter",
    "perimeter_edges",
]
