r"""The contact modulus of two elastic bodies (SI units).

Two bodies of Young's moduli E1, E2 and Poisson ratios nu1, nu2 in contact behave as one
elastic half-space of contact modulus E* against a rigid one (Johnson, *Contact
Mechanics*, 1985, Eq. 4.3)::

    1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2

A rigid counter-surface (E2 -> infinity, the default) gives ``E* = E1/(1 - nu1^2)``;
two equal bodies give half of that (silicon on silicon: E*/2). A body's plane-strain
modulus ``E/(1 - nu^2)`` may be given directly by leaving its Poisson ratio out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ._validate import ParameterError

__all__ = ["CompositeModulus", "composite_modulus"]


@dataclass(frozen=True)
class CompositeModulus:
    """E* of a pair of bodies and how it was formed (SI: Pa).

    Attributes
    ----------
    contact_modulus : float
        E* [Pa].
    body, counter : float
        The plane-strain moduli ``E/(1 - nu^2)`` of the body and of the counter-surface
        [Pa] (``counter`` inf: rigid).
    text : str
        The formula with the numbers, for the text output.
    """

    contact_modulus: float
    body: float
    counter: float
    text: str


def _plane_strain(name, modulus, poisson_name, poisson):
    from .criterion import parse_quantity

    E = parse_quantity(modulus, "pressure", name)
    if not (math.isfinite(E) and E > 0):
        raise ParameterError(f"{name} must be > 0 (Pa), got {modulus!r}")
    if poisson is None:
        return E
    nu = parse_quantity(poisson, "dimensionless", poisson_name)
    if not -1.0 < nu <= 0.5:
        raise ParameterError(f"{poisson_name} must be in (-1, 0.5], got {poisson!r}")
    return E / (1.0 - nu * nu)


def composite_modulus(
    modulus, poisson=None, counter_modulus=None, counter_poisson=None
) -> CompositeModulus:
    """E* from the two bodies: ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2``.

    Parameters
    ----------
    modulus : float or str
        The body's Young's modulus E1 [Pa] with ``poisson``, or its plane-strain modulus
        ``E1/(1-nu1^2)`` without (e.g. ``"160 GPa"``).
    poisson : float, optional
        nu1 in (-1, 0.5].
    counter_modulus : float or str, optional
        The counter-surface's E2 [Pa] (with ``counter_poisson``) or its plane-strain
        modulus (without). None (default): a rigid counter-surface.
    counter_poisson : float, optional
        nu2 in (-1, 0.5]; needs ``counter_modulus``.

    Returns
    -------
    CompositeModulus
    """
    body = _plane_strain("modulus", modulus, "poisson", poisson)
    if counter_modulus is None:
        if counter_poisson is not None:
            raise ParameterError("counter_poisson needs counter_modulus (the counter-surface's E)")
        text = (
            f"E* = {_pa(body)} (rigid counter-surface: 1/E* = (1-nu1^2)/E1)"
            if poisson is not None
            else f"E* = {_pa(body)} (as given; rigid counter-surface)"
        )
        return CompositeModulus(body, body, math.inf, text)
    counter = _plane_strain("counter_modulus", counter_modulus, "counter_poisson", counter_poisson)
    E = 1.0 / (1.0 / body + 1.0 / counter)
    text = f"E* = {_pa(E)} (1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 = 1/{_pa(body)} + 1/{_pa(counter)})"
    return CompositeModulus(E, body, counter, text)


def _pa(value: float) -> str:
    for factor, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if value >= factor:
            return f"{value / factor:.4g} {prefix}Pa"
    return f"{value:.4g} Pa"
