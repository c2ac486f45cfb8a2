"""Elastic substrates: periodic FFT Green's functions (half-space, layers on a rigid base)."""

from .stiffness import (
    bonded_layer_stiffness,
    frictionless_layer_stiffness,
    half_space_stiffness,
    uniaxial_layer_stiffness,
)
from .substrate import Substrate, wavevectors

__all__ = [
    "Substrate",
    "bonded_layer_stiffness",
    "frictionless_layer_stiffness",
    "half_space_stiffness",
    "uniaxial_layer_stiffness",
    "wavevectors",
]
