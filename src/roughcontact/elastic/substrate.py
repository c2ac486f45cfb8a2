r"""Linear-elastic substrates: deflection from pressure and back, elastic energy.

The substrate is flat and undeformed at z = 0; its deflection ``w`` is positive into
the substrate and pressure ``p`` is positive when compressive (the README's conventions).
Both live on the patch, an ``nx × ny`` grid of spacing ``pixel_size``.

Periodic (the default): the patch is one period; in Fourier space
:math:`\tilde w(\mathbf q) = \tilde p(\mathbf q)/k(q)` with :math:`k` from
:mod:`roughcontact.elastic.stiffness`. The uniform (q = 0) mode: for a half-space and for
an incompressible (ν = 1/2) layer it is rigid — the mean deflection stays zero and the
load is carried through the offset of the rigid surface (the usual convention of periodic
FFT contact codes, Stanley & Kato, J. Tribol. 119, 481 (1997)). For a compressible layer
it has the finite stiffness :math:`k(0) = M/t` of uniaxial strain.

Free boundary (``periodic=False``, half-space only): the patch is a finite piece of the
surface of a half-space with no load outside it, e.g. a measured scan pressed as
measured, without periodic images. The deflection is the linear convolution of the
pressure with the response of one loaded pixel (Love's rectangle,
:mod:`roughcontact.elastic.free_boundary`), computed exactly by FFT on the zero-padded
``2nx × 2ny`` work grid (Hockney's method). No mode is rigid: the deflection is measured
from the undeformed surface far away (where it vanishes), so a load moves the mean
deflection; the offset ``d`` of the rigid surface is measured from there too (gap
``g = d - h + w`` as ever), the load is the total force over the patch area,
:math:`N/A_0 = \bar p`, and the elastic energy is the work of the pressure,
:math:`\tfrac12 a_0^2 \sum_x p(x) w(x)`. The members the solvers use are those of
:class:`~roughcontact.elastic.operator.ElasticOperator`.
"""

from __future__ import annotations

import dataclasses
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
from .free_boundary import free_compliance
from .operator import FourierMultipliers
from .stiffness import (
    bonded_layer_stiffness,
    frictionless_layer_stiffness,
    half_space_stiffness,
    uniaxial_layer_stiffness,
)

__all__ = ["Substrate", "wavevectors"]

_BASES = ("bonded", "frictionless")

#: Relative residual :math:`\|G p - w\|/\|w\|` at which :meth:`Substrate.pressure` of a
#: free-boundary substrate stops (float64; 100 eps in float32), and its iteration cap.
FREE_PRESSURE_RTOL = 1e-12
FREE_PRESSURE_MAX_ITER = 2000


def wavevectors(shape: tuple[int, int], pixel_size: float = 1.0) -> np.ndarray:
    """Magnitudes ``|q|`` (rad/length) on the ``rfft2`` layout ``(nx, ny//2 + 1)``."""
    nx, ny = shape
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=pixel_size)
    qy = 2 * np.pi * np.fft.rfftfreq(ny, d=pixel_size)
    return np.sqrt(qx[:, None] ** 2 + qy[None, :] ** 2)


@dataclass(frozen=True)
class Substrate:
    r"""A linear-elastic substrate: periodic half-space or layer, or free half-space.

    Parameters
    ----------
    shape : int or (int, int)
        Grid size ``(nx, ny)`` of the patch; rectangular grids are allowed.
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
    periodic : bool
        True (default): the patch is one period of a periodic surface. False: a free
        boundary, the patch alone pressed on a half-space with no periodic images (see
        the module docstring); only for a half-space (``thickness=None``).

    Notes
    -----
    Stiffness per mode :math:`k(q) = E^* q/2` for the periodic half-space; finite-thickness
    formulas are in :mod:`roughcontact.elastic.stiffness`; the free half-space's compliance
    is in :mod:`roughcontact.elastic.free_boundary`. ``stiffness`` and ``compliance``
    hold the multipliers (float64, NumPy) on the ``rfft2`` layout of the work grid
    (``work_shape``: the patch when periodic, ``2nx × 2ny`` for a free boundary).
    Energies are in pressure × length³ (``contact_modulus * pixel_size**3`` in lattice
    units). Implements :class:`~roughcontact.elastic.operator.ElasticOperator`.
    """

    shape: tuple[int, int]
    contact_modulus: float = 1.0
    pixel_size: float = 1.0
    thickness: float | None = None
    poisson: float = 0.5
    base: str = "bonded"
    periodic: bool = True
    stiffness: np.ndarray = field(init=False, repr=False, compare=False)
    compliance: np.ndarray = field(init=False, repr=False, compare=False)
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
        if not isinstance(self.periodic, (bool, np.bool_)):
            raise ParameterError(f"periodic must be True or False, got {self.periodic!r}")
        set_(self, "periodic", bool(self.periodic))
        if not self.periodic and self.thickness is not None:
            raise ParameterError(
                f"periodic=False needs thickness=None (a free boundary is implemented for "
                f"the half-space only), got thickness={self.thickness!r}"
            )
        stiffness, compliance = self._make_multipliers()
        set_(self, "stiffness", stiffness)
        set_(self, "compliance", compliance)

    def __repr__(self) -> str:
        # the dataclass repr, with periodic only when it is not the default (a periodic
        # substrate keeps the repr, recorded in path files, it had before the keyword)
        shown = [f for f in dataclasses.fields(self) if f.repr and f.name != "periodic"]
        text = ", ".join(f"{f.name}={getattr(self, f.name)!r}" for f in shown)
        return f"Substrate({text}{'' if self.periodic else ', periodic=False'})"

    # ------------------------------------------------------------------ description
    def to_attrs(self) -> dict:
        """Flat attributes that rebuild this substrate (:meth:`from_attrs`); path files hold them.

        ``contact_modulus`` (pressure), ``pixel_size`` (length), ``grid`` ``[nx, ny]``,
        ``nominal_area`` (length²), ``thickness`` (length; inf for a half-space), ``poisson``,
        ``base`` ("" for a half-space), ``periodic`` (1, or 0 for a free boundary) and the
        kind tag ``substrate`` (the ``repr``). The names and values are those every earlier
        version wrote, so old and new path files read alike.
        """
        half_space = self.thickness is None
        return {
            "contact_modulus": self.contact_modulus,
            "pixel_size": self.pixel_size,
            "grid": list(self.shape),
            "nominal_area": self.nominal_area,
            "thickness": math.inf if half_space else self.thickness,
            "poisson": self.poisson,
            "base": "" if half_space else self.base,
            "periodic": int(self.periodic),
            "substrate": repr(self),
        }

    @classmethod
    def from_attrs(cls, attrs) -> Substrate:
        """The substrate described by ``attrs`` (a mapping: :meth:`to_attrs`, a path's attrs).

        ``grid``, ``contact_modulus`` and ``pixel_size`` are required; files of earlier
        versions may lack the rest, which then take the values those versions implied: a
        half-space (``thickness`` absent, inf or NaN), ``poisson`` 0.5, ``base`` "bonded"
        (also for ""), periodic (``periodic`` absent). Values may be NumPy scalars or
        arrays as read back from NetCDF.
        """
        for key in ("grid", "contact_modulus", "pixel_size"):
            if key not in attrs:
                raise ParameterError(
                    f"substrate attributes need {key!r} (grid, contact_modulus, pixel_size); "
                    f"got only {sorted(attrs)}"
                )
        thickness = float(attrs.get("thickness", math.inf))
        return cls(
            tuple(int(n) for n in np.atleast_1d(attrs["grid"])),
            contact_modulus=float(attrs["contact_modulus"]),
            pixel_size=float(attrs["pixel_size"]),
            thickness=thickness if math.isfinite(thickness) else None,
            poisson=float(attrs.get("poisson", 0.5)),
            base=str(attrs.get("base") or "bonded"),
            periodic=bool(int(attrs.get("periodic", 1))),
        )

    def _make_multipliers(self):
        if not self.periodic:
            c = free_compliance(self.shape, self.pixel_size, self.contact_modulus)
            return 1.0 / c, c
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
        with np.errstate(divide="ignore"):
            c = np.where(np.isinf(k), 0.0, 1.0 / k)
        return k, c

    # ------------------------------------------------------------------ properties
    @property
    def work_shape(self) -> tuple[int, int]:
        """The grid of the Fourier multipliers: ``shape``, or ``(2nx, 2ny)`` when free."""
        nx, ny = self.shape
        return self.shape if self.periodic else (2 * nx, 2 * ny)

    @property
    def nominal_area(self) -> float:
        """Projected area of the patch :math:`A_0 = n_x n_y a_0^2`."""
        return self.shape[0] * self.shape[1] * self.pixel_size**2

    @property
    def rigid_mean(self) -> bool:
        """True if the uniform mode is rigid (periodic half-space, or ν = 1/2 layer)."""
        return math.isinf(self.stiffness[0, 0])

    @property
    def self_stiffness(self) -> float:
        r"""Diagonal :math:`K_{ii}` of the stiffness operator on the work grid (pressure /
        length): the pressure at a site per unit deflection of that site alone, the mean
        of :math:`k(q)` over all Fourier modes (a rigid uniform mode counts as zero).
        About :math:`1.20\,E^*/a_0` for the periodic half-space, :math:`1.16\,E^*/a_0` on
        a free boundary's padded grid."""
        cached = self._cache.get("self_stiffness")
        if cached is None:  # (48 ms at 4096², and every solve asks: computed once)
            k = np.where(np.isinf(self.stiffness), 0.0, self.stiffness)
            nx, ny = self.work_shape
            cached = self._cache["self_stiffness"] = float(_sum_over_modes(np, k, ny)) / (nx * ny)
        return cached

    def multipliers(self, like) -> FourierMultipliers:
        """Stiffness and compliance multipliers on the namespace, device and dtype of ``like``.

        On the ``rfft2`` layout of the work grid; a rigid uniform mode is stored as 0 in
        both. Cached per (backend, device, dtype), so the solvers' loops never copy them.
        """
        numpy = is_numpy_array(like)
        key = ("numpy", "cpu") if numpy else (type(like).__module__, str(array_device(like)))
        key += (str(like.dtype),)
        if key not in self._cache:
            c = self.compliance
            kf = np.where(np.isinf(self.stiffness), 0.0, self.stiffness)
            if numpy:
                c, kf = c.astype(like.dtype, copy=False), kf.astype(like.dtype, copy=False)
            else:
                xp = array_namespace(like)
                c = xp.asarray(c, dtype=like.dtype, device=array_device(like))
                kf = xp.asarray(kf, dtype=like.dtype, device=array_device(like))
            self._cache[key] = FourierMultipliers(kf, c)
        return self._cache[key]

    def embed(self, field, out=None):
        """``field`` (the patch's shape) on the work grid at ``[:nx, :ny]``, zero elsewhere.

        Periodic: ``field`` itself (or copied into ``out``). ``out``: a work-grid array of
        ``field``'s backend whose outside of the patch is already zero; it is returned.
        """
        if out is None:
            if self.periodic:
                return field
            xp = array_namespace(field)
            out = xp.zeros(self.work_shape, dtype=field.dtype, device=array_device(field))
        nx, ny = self.shape
        out[:nx, :ny] = field
        return out

    def crop(self, field):
        """The patch ``[:nx, :ny]`` of a work-grid field (``field`` itself when periodic)."""
        if self.periodic:
            return field
        nx, ny = self.shape
        return field[:nx, :ny]

    def coarsened(self) -> Substrate:
        """The same substrate on the patch coarsened 2 × 2 (``nx//2 × ny//2``, 2 a0)."""
        coarse = self._cache.get("coarsened")
        if coarse is None:  # kept: a nested solve asks for every level each time, and a new
            # substrate would compute and upload its multipliers again (the substrate is frozen)
            nx, ny = self.shape
            coarse = dataclasses.replace(
                self, shape=(nx // 2, ny // 2), pixel_size=2 * self.pixel_size
            )
            self._cache["coarsened"] = coarse
        return coarse

    def _check(self, name, field_):
        if tuple(field_.shape) != self.shape:
            raise ParameterError(
                f"{name} must have the substrate's shape {self.shape}, got {tuple(field_.shape)}"
            )

    def _apply(self, x, multiplier):
        """``crop(irfft2(rfft2(embed(x)) * multiplier))``, a fresh array."""
        if self.periodic:
            return convolve(x, multiplier)
        xp = array_namespace(x)
        return xp.asarray(self.crop(convolve(self.embed(x), multiplier)), copy=True)

    # ------------------------------------------------------------------ operators
    def deflection(self, pressure):
        r"""Deflection ``w`` (length) of the patch from a pressure field (pressure units).

        Periodic: :math:`w = \mathcal F^{-1}[\tilde p/k]`; with a rigid uniform mode the
        mean deflection is zero whatever the mean pressure. Free boundary: the exact
        free-space convolution :math:`w = G * p` of the pressure on the patch (zero
        outside) with the response of one loaded pixel (module docstring).
        """
        self._check("pressure", pressure)
        return self._apply(pressure, self.multipliers(pressure).compliance)

    def pressure(self, deflection):
        r"""Pressure (pressure units) on the patch that produces a deflection field (length).

        Periodic: :math:`p = \mathcal F^{-1}[k \tilde w]`. With a rigid uniform mode the
        mean pressure is not determined by the deflection (it is the load, carried through
        the offset); it is returned as zero and the mean deflection is ignored.

        Free boundary: the pressure on the patch, zero outside it, whose free-space
        deflection on the patch is ``deflection``: the solution of :math:`G p = w`
        (symmetric positive definite) by conjugate gradients preconditioned with the
        padded grid's stiffness, to the relative residual :data:`FREE_PRESSURE_RTOL`
        (some tens of FFT pairs). Outside the patch the surface then deflects freely.
        """
        self._check("deflection", deflection)
        if self.periodic:
            return convolve(deflection, self.multipliers(deflection).stiffness)
        return self._free_pressure(deflection)

    def _free_pressure(self, w):
        xp = array_namespace(w)
        if not bool(xp.all(xp.isfinite(w))):
            raise ParameterError("deflection must be finite to give a pressure")
        k, c = self.multipliers(w)
        eps = 2.220446049250313e-16 if w.dtype == xp.float64 else 1.1920929e-07
        rtol = max(FREE_PRESSURE_RTOL, 100.0 * eps)

        def norm(x):
            return math.sqrt(float(xp.sum(x * x, dtype=xp.float64)))

        def inner(x, y):
            return float(xp.sum(x * y, dtype=xp.float64))

        scale = norm(w)
        p = self._apply(w, k)  # the padded stiffness: the starting guess and preconditioner
        r = w - self._apply(p, c)
        z = self._apply(r, k)
        s, rz = z, inner(r, z)
        for _ in range(FREE_PRESSURE_MAX_ITER):
            if norm(r) <= rtol * scale:
                return p
            gs = self._apply(s, c)
            alpha = rz / inner(s, gs)
            p = p + alpha * s
            r = r - alpha * gs
            z = self._apply(r, k)
            rz, rz_old = inner(r, z), rz
            s = z + (rz / rz_old) * s
        raise ArithmeticError(  # not seen: the preconditioned system is well conditioned
            f"free-boundary pressure: no convergence to {rtol:g} in "
            f"{FREE_PRESSURE_MAX_ITER} iterations"
        )

    def energy(self, deflection) -> float:
        r"""Elastic energy :math:`E_{el} = \tfrac12 a_0^2 \sum_x p(x) w(x)`.

        Periodic: computed in Fourier space, :math:`E_{el} = \frac{a_0^2}{2 n_x n_y}
        \sum_{\mathbf q} k(q) |\tilde w(\mathbf q)|^2` (Parseval), in pressure × length³.
        With a rigid uniform mode the mean deflection is ignored. Free boundary: with the
        pressure of :meth:`pressure` (the work done on the half-space).
        """
        self._check("deflection", deflection)
        xp = array_namespace(deflection)
        if not self.periodic:
            p = self._free_pressure(deflection)
            work = float(xp.sum(p * deflection, dtype=xp.float64))
            return 0.5 * self.pixel_size**2 * work
        k = self.multipliers(deflection).stiffness
        wq = rfft2(deflection)
        e = k * (xp.real(wq) ** 2 + xp.imag(wq) ** 2)
        total = _sum_over_modes(xp, e, self.shape[1])
        return float(0.5 * self.pixel_size**2 * total / (self.shape[0] * self.shape[1]))


def _sum_over_modes(xp, e, ny):
    """Sum over all Fourier modes of a field given on the ``rfft2`` layout.

    rfft stores only ny//2+1 columns: the interior columns stand for two modes each.
    """
    return 2.0 * xp.sum(e) - xp.sum(e[:, 0]) - (xp.sum(e[:, -1]) if ny % 2 == 0 else 0.0)
