"""Elastic substrates: periodic FFT Green's functions (half-space, layers on a rigid base),
the free-boundary half-space (Hockney's zero padding), and the operator the solvers use."""

from .attrs import register_substrate_kind, substrate_from_attrs, substrate_kind
from .free_boundary import free_compliance, love_rectangle, pixel_response
from .operator import ElasticOperator, FourierMultipliers
from .stiffness import (
    bonded_layer_stiffness,
    frictionless_layer_stiffness,
    half_space_stiffness,
    uniaxial_layer_stiffness,
)
from .substrate import Substrate, wavevectors

__all__ = [
    "ElasticOperator",
    "FourierMultipliers",
    "Substrate",
    "bonded_layer_stiffness",
    "free_compliance",
    "frictionless_layer_stiffness",
    "half_space_stiffness",
    "love_rectangle",
    "pixel_response",
    "register_substrate_kind",
    "substrate_from_attrs",
    "substrate_kind",
    "uniaxial_layer_stiffness",
    "wavevectors",
]
