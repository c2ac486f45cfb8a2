r"""Periodic elastic substrate: deflection from pressure and back, elastic energy.

The substrate is flat and undeformed at z = 0; its deflection ``w`` is positive into
the substrate and pressure ``p`` is positive when compressive (the README's conventions). Both are
periodic on an ``nx × ny`` grid of spacing ``pixel_size``; in Fourier space
:math:`\tilde w(\mathbf q) = \tilde p(\mathbf q)/k(q)` with :math:`k` from
:mod:`roughcontact.elastic.stiffness`.

The uniform (q = 0) mode: for a half-space and for an incompressible (ν = 1/2) layer it
is rigid — the mean deflection stays zero and the load is carried through the offset of
the rigid surface (the usual convention of periodic FFT contact codes, Stanley & Kato,
J. Tribol. 119, 481 (1997)). For a compressible layer it has the finite stiffness
:math:`k(0) = M/t` of uniaxial strain.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._backend import array_device, array_namespace, convolve, is_numpy_array, rfft2
from .._validate import (
    CONTACT_MODULUS,
    PIXEL_SIZE,
    ParameterError,
    in_range,
    layer_thickness,
    shape2d,
)
from .stiffness import (
    bonded_layer_stiffness,
    frictionless_layer_stiffness,
    half_space_stiffness,
    uniaxial_layer_stiffness,
)

__all__ = ["Substrate", "wavevectors"]

_BASES = ("bonded", "frictionless")


def wavevectors(shape: tuple[int, int], pixel_size: float = 1.0) -> np.ndarray:
    """Magnitudes |q| (rad/length) on the ``rfft2`` layout ``(nx, ny//2 + 1)``."""
    nx, ny = shape
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=pixel_size)
    qy = 2 * np.pi * np.fft.rfftfreq(ny, d=pixel_size)
    return np.sqrt(qx[:, None] ** 2 + qy[None, :] ** 2)


@dataclass(frozen=True)
class Substrate:
    r"""A periodic linear-elastic substrate (half-space or layer on a rigid base).

    Parameters
    ----------
    shape : int or (int, int)
        Grid size ``(nx, ny)``; rectangular grids are allowed.
    contact_modulus : float
        Contact modulus :math:`E^* = E/(1-\nu^2)` (pressure units; 1 in lattice units),
        in [1e-100, 1e100].
    pixel_size : float
        Grid spacing :math:`a_0` (length units), in [1e-25, 1e25]. The period is
        ``L = n * pixel_size``.
    thickness : float or None
        Layer thickness ``t`` (length), in [1e-6, 1e100] x pixel_size; None for a
        half-space.
    poisson : float
        Poisson ratio ν in [0, 0.5]; only used for a finite thickness.
    base : {"bonded", "frictionless"}
        How the layer is attached to its rigid base.

    Notes
    -----
    Stiffness per mode :math:`k(q) = E^* q/2` for the half-space; finite-thickness
    formulas are in :mod:`roughcontact.elastic.stiffness`. Energies are in
    pressure × length³ (``contact_modulus * pixel_size**3`` in lattice units).
    """

    shape: tuple[int, int]
    contact_modulus: float = 1.0
    pixel_size: float = 1.0
    thickness: float | None = None
    poisson: float = 0.5
    base: str = "bonded"
    stiffness: np.ndarray = field(init=False, repr=False, compare=False)
    _cache: dict = field(init=False, repr=False, compare=False, default_factory=dict)

    def __post_init__(self):
        set_ = object.__setattr__
        set_(self, "shape", shape2d("shape", self.shape))
        modulus = CONTACT_MODULUS.check("contact_modulus", self.contact_modulus)
        set_(self, "contact_modulus", modulus)
        set_(self, "pixel_size", PIXEL_SIZE.check("pixel_size", self.pixel_size))
        set_(self, "poisson", in_range("poisson", self.poisson, 0.0, 0.5))
        if self.base not in _BASES:
            raise ParameterError(f"base must be one of {_BASES}, got {self.base!r}")
        if self.thickness is not None:
            set_(self, "thickness", layer_thickness("thickness", self.thickness, self.pixel_size))
        set_(self, "stiffness", self._make_stiffness())

    def _make_stiffness(self) -> np.ndarray:
        q = wavevectors(self.shape, self.pixel_size)
        es, t, nu = self.contact_modulus, self.thickness, self.poisson
        if t is None:
            k = half_space_stiffness(q, es)
            k[0, 0] = math.inf
        else:
            if self.base == "bonded":
                k = bonded_layer_stiffness(q, t, es, nu)
            else:
                k = frictionless_layer_stiffness(q, t, es)
            k[0, 0] = uniaxial_layer_stiffness(t, es, nu)
        return k

    # ------------------------------------------------------------------ properties
    @property
    def nominal_area(self) -> float:
        """Projected area :math:`A_0 = n_x n_y a_0^2`."""
        return self.shape[0] * self.shape[1] * self.pixel_size**2

    @property
    def rigid_mean(self) -> bool:
        """True if the uniform mode is rigid (half-space, or ν = 1/2 layer)."""
        return math.isinf(self.stiffness[0, 0])

    @property
    def self_stiffness(self) -> float:
        r"""Diagonal :math:`K_{ii}` of the stiffness operator (pressure / length): the
        pressure at a site per unit deflection of that site alone, the mean of
        :math:`k(q)` over all Fourier modes (a rigid uniform mode counts as zero).
        About :math:`1.2\,E^*/a_0` for a half-space."""
        k = np.where(np.isinf(self.stiffness), 0.0, self.stiffness)
        return float(_sum_over_modes(np, k, self.shape[1])) / (self.shape[0] * self.shape[1])

    def _arrays(self, like):
        """Stiffness and compliance on the namespace, device and precision of ``like``.

        Cached per (backend, device, dtype), so the loops never copy them.
        """
        numpy = is_numpy_array(like)
        key = ("numpy", "cpu") if numpy else (type(like).__module__, str(array_device(like)))
        key += (str(like.dtype),)
        if key not in self._cache:
            k = self.stiffness
            with np.errstate(divide="ignore"):
                c = np.where(np.isinf(k), 0.0, 1.0 / k)
            kf = np.where(np.isinf(k), 0.0, k)
            if numpy:
                c, kf = c.astype(like.dtype, copy=False), kf.astype(like.dtype, copy=False)
            else:
                xp = array_namespace(like)
                c = xp.asarray(c, dtype=like.dtype, device=array_device(like))
                kf = xp.asarray(kf, dtype=like.dtype, device=array_device(like))
            self._cache[key] = (kf, c)
        return self._cache[key]

    def _check(self, name, field_):
        if tuple(field_.shape) != self.shape:
            raise ParameterError(
                f"{name} must have the substrate's shape {self.shape}, got {tuple(field_.shape)}"
            )

    # ------------------------------------------------------------------ operators
    def deflection(self, pressure):
        r"""Deflection ``w`` (length) from a pressure field (pressure units).

        :math:`w = \mathcal F^{-1}[\tilde p/k]`; with a rigid uniform mode the mean
        deflection is zero whatever the mean pressure.
        """
        self._check("pressure", pressure)
        _, c = self._arrays(pressure)
        return convolve(pressure, c)

    def pressure(self, deflection):
        r"""Pressure (pressure units) that produces a deflection field (length).

        :math:`p = \mathcal F^{-1}[k \tilde w]`. With a rigid uniform mode the mean
        pressure is not determined by the deflection (it is the load, carried through
        the offset); it is returned as zero and the mean deflection is ignored.
        """
        self._check("deflection", deflection)
        k, _ = self._arrays(deflection)
        return convolve(deflection, k)

    def energy(self, deflection) -> float:
        r"""Elastic energy :math:`E_{el} = \tfrac12 a_0^2 \sum_x p(x) w(x)`.

        Computed in Fourier space, :math:`E_{el} = \frac{a_0^2}{2 n_x n_y}
        \sum_{\mathbf q} k(q) |\tilde w(\mathbf q)|^2` (Parseval), in pressure × length³.
        With a rigid uniform mode the mean deflection is ignored.
        """
        self._check("deflection", deflection)
        k, _ = self._arrays(deflection)
        xp = array_namespace(deflection)
        wq = rfft2(deflection)
        e = k * (xp.real(wq) ** 2 + xp.imag(wq) ** 2)
        total = _sum_over_modes(xp, e, self.shape[1])
        return float(0.5 * self.pixel_size**2 * total / (self.shape[0] * self.shape[1]))


def _sum_over_modes(xp, e, ny):
    """Sum over all Fourier modes of a field given on the ``rfft2`` layout.

    rfft stores only ny//2+1 columns: the interior columns stand for two modes each.
    """
    return 2.0 * xp.sum(e) - xp.sum(e[:, 0]) - (xp.sum(e[:, -1]) if ny % 2 == 0 else 0.0)
