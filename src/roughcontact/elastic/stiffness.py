r"""Fourier stiffness of periodic elastic substrates.

A sinusoidal pressure :math:`\tilde p(\mathbf q)` on the surface of a linear elastic body
produces a deflection :math:`\tilde w(\mathbf q) = \tilde p(\mathbf q) / k(q)` with a
stiffness per unit area :math:`k(q)` (units of pressure per length, i.e. of
``contact_modulus / pixel_size``).  All functions take ``q = |q|`` in rad per length unit.

References
----------
K. L. Johnson, *Contact Mechanics* (CUP 1985), ch. 13 (half-space).
C. Carbone, L. Mangialardi, J. Mech. Phys. Solids 56, 684 (2008), Eq. (A.30) (layer
bonded to a rigid base); the frictionless base follows by symmetry from a free plate of
thickness 2t.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "bonded_layer_stiffness",
    "frictionless_layer_stiffness",
    "half_space_stiffness",
    "uniaxial_layer_stiffness",
]


def half_space_stiffness(q, contact_modulus: float):
    r"""Half-space stiffness :math:`k(q) = E^* q / 2` (Johnson 1985, §13.2).

    Parameters
    ----------
    q : array_like
        Wavevector magnitude (1/length).
    contact_modulus : float
        :math:`E^* = E/(1-\nu^2)` (pressure).
    """
    return 0.5 * contact_modulus * np.asarray(q, dtype=float)


def uniaxial_layer_stiffness(thickness: float, contact_modulus: float, poisson: float) -> float:
    r"""Stiffness of the uniform (q = 0) mode of a laterally periodic layer on a rigid base.

    A uniform pressure on a periodic layer compresses it in uniaxial strain, so
    :math:`k(0) = M/t` with the P-wave modulus
    :math:`M = E(1-\nu)/((1+\nu)(1-2\nu)) = E^*(1-\nu)^2/(1-2\nu)`. It is infinite for
    :math:`\nu = 1/2` (incompressible: the mean deflection cannot change). This equals the
    :math:`q \to 0` limit of the bonded-layer stiffness (Carbone & Mangialardi 2008).
    """
    if poisson >= 0.5:
        return float("inf")
    return contact_modulus * (1.0 - poisson) ** 2 / ((1.0 - 2.0 * poisson) * thickness)


def bonded_layer_stiffness(q, thickness: float, contact_modulus: float, poisson: float):
    r"""Stiffness of a layer of thickness ``t`` bonded to a rigid base, for q > 0.

    .. math::
        k(q) = \frac{E^* q}{2}\,
        \frac{(3-4\nu)\cosh 2qt + 2(qt)^2 + (1-2\nu)^2 + 4(1-\nu)^2}
             {(3-4\nu)\sinh 2qt - 2qt}

    (Carbone & Mangialardi 2008, Eq. A.30).  Evaluated in a form scaled by
    :math:`e^{-2qt}` so that it cannot overflow and tends smoothly to the half-space
    value :math:`E^* q/2` for :math:`qt \gg 1`.  Entries with ``q == 0`` are returned as
    NaN; the caller supplies the uniform mode (:func:`uniaxial_layer_stiffness`).
    """
    q = np.asarray(q, dtype=float)
    x = q * thickness
    e2 = np.exp(-2.0 * x)
    a = 3.0 - 4.0 * poisson
    c = (1.0 - 2.0 * poisson) ** 2 + 4.0 * (1.0 - poisson) ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        # numerator and denominator multiplied by 2 e^{-2x}
        num = a * (1.0 + e2 * e2) + 2.0 * e2 * (2.0 * x * x + c)
        den = -a * np.expm1(-4.0 * x) - 4.0 * x * e2
        k = 0.5 * contact_modulus * q * num / den
    return np.where(q > 0, k, np.nan)


def frictionless_layer_stiffness(q, thickness: float, contact_modulus: float):
    r"""Stiffness of a layer of thickness ``t`` on a frictionless rigid base, for q > 0.

    .. math:: k(q) = \frac{E^* q}{2}\,\frac{\sinh 2qt + 2qt}{\cosh 2qt - 1}

    Scaled by :math:`e^{-2qt}` to avoid overflow; :math:`\to E^* q/2` for
    :math:`qt \gg 1` and :math:`\to E^*/t` for :math:`qt \ll 1` (plate of thickness 2t
    in plane strain). ``q == 0`` entries are NaN (see :func:`uniaxial_layer_stiffness`).
    """
    q = np.asarray(q, dtype=float)
    x = q * thickness
    e2 = np.exp(-2.0 * x)
    with np.errstate(divide="ignore", invalid="ignore"):
        num = -np.expm1(-4.0 * x) + 4.0 * x * e2  # 2 e^{-2x} (sinh 2x + 2x)
        den = (1.0 - e2) ** 2  # 2 e^{-2x} (cosh 2x - 1)
        k = 0.5 * contact_modulus * q * num / den
    return np.where(q > 0, k, np.nan)
