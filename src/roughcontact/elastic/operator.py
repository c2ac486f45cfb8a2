r"""The elastic operator: what a substrate offers the solvers (the extension point).

Every solver reaches the substrate through the members of :class:`ElasticOperator` and
nothing else, so a new substrate (another Green's function, a graded layer, a measured
response) works with all of them once it provides these. :class:`~roughcontact.Substrate`
(periodic or free-boundary half-space, periodic layer) is the reference implementation.

The operator is linear and diagonal in Fourier space on its *work grid*: the pressure
``p`` and deflection ``w`` of the *patch* (the heights' grid, ``shape``) are embedded in
the work grid (``work_shape``) at its corner ``[:nx, :ny]``, zero elsewhere (``embed``),
and read back from there (``crop``). On the work grid

.. math:: \tilde w(\mathbf q) = c(\mathbf q)\,\tilde p(\mathbf q), \qquad
          \tilde p(\mathbf q) = k(\mathbf q)\,\tilde w(\mathbf q)

with real multipliers ``c`` (compliance, length/pressure) and ``k`` (stiffness,
pressure/length) on the ``rfft2`` layout of the work grid (:meth:`multipliers`).

* Periodic substrates: the work grid is the patch, ``c = 1/k``. A rigid uniform mode
  (``rigid_mean``) has ``k(0) = inf``, stored as ``k = c = 0``: the mean deflection is
  zero and the mean pressure (the load) is carried through the offset.
* A free boundary (Hockney's zero padding, work grid ``2 nx × 2 ny``): ``crop(c * embed(p))``
  is the exact free-space deflection of a pressure on the patch; ``k = 1/c`` is the
  stiffness of the padded periodic problem. Solvers in the pressure (Polonsky–Keer) use
  ``crop ∘ c ∘ embed``; solvers in the deflection (smooth and hard-core adhesive laws)
  minimise over a deflection on the whole work grid with the energy
  :math:`\tfrac12 w^T k w` and the interaction on the patch only, whose equilibrium
  leaves no pressure on the padding and is then the free-space solution.

An operator describes itself in flat, NetCDF- and JSON-safe attributes (:meth:`to_attrs`,
written into every path file), among them the *kind tag* ``substrate``: a text that begins
with the kind's name followed by ``(`` (the operator's ``repr``).
:func:`~roughcontact.elastic.attrs.substrate_from_attrs` reads the tag and rebuilds the
operator through its kind's ``from_attrs``, so analysing a path needs no knowledge of the
substrate's parameters.
"""

from __future__ import annotations

from typing import NamedTuple, Protocol, runtime_checkable

__all__ = ["ElasticOperator", "FourierMultipliers"]


class FourierMultipliers(NamedTuple):
    """The operator's multipliers on the ``rfft2`` layout of the work grid,
    ``(work_shape[0], work_shape[1] // 2 + 1)``, real, in one namespace, device, dtype."""

    #: :math:`k(\mathbf q)` (pressure / length); 0 for a rigid uniform mode.
    stiffness: object
    #: :math:`c(\mathbf q)` (length / pressure); 0 for a rigid uniform mode.
    compliance: object


@runtime_checkable
class ElasticOperator(Protocol):
    """A linear-elastic substrate as the solvers see it (module docstring).

    Attributes
    ----------
    shape : (int, int)
        The patch: the grid of heights, pressures and deflections (sites).
    work_shape : (int, int)
        The grid the Fourier multipliers live on; ``shape`` when periodic, larger with
        padding. The patch is its corner ``[:shape[0], :shape[1]]``.
    periodic : bool
        Whether the patch is one period of a periodic surface (``work_shape == shape``).
    contact_modulus : float
        :math:`E^*` (pressure); the solvers' residuals are in its units.
    pixel_size : float
        :math:`a_0` (length).
    nominal_area : float
        The patch's area :math:`A_0 = n_x n_y a_0^2` (length²): loads are per A0.
    rigid_mean : bool
        The uniform mode is rigid (``k(0) = inf``): zero mean deflection, the load is
        carried through the offset.
    self_stiffness : float
        Diagonal :math:`K_{ii}` of the stiffness on the work grid (pressure / length):
        the mean of ``k`` over all modes, a rigid mode counting as zero.
    """

    shape: tuple[int, int]
    work_shape: tuple[int, int]
    periodic: bool
    contact_modulus: float
    pixel_size: float

    @property
    def nominal_area(self) -> float: ...

    @property
    def rigid_mean(self) -> bool: ...

    @property
    def self_stiffness(self) -> float: ...

    def multipliers(self, like) -> FourierMultipliers:
        """Stiffness and compliance on the namespace, device and dtype of array ``like``."""
        ...

    def embed(self, field, out=None):
        """A patch field (``shape``) on the work grid, zero outside the patch; into
        ``out`` (a work-grid array whose outside is already zero) when given."""
        ...

    def crop(self, field):
        """The patch ``[:nx, :ny]`` of a work-grid field (a view where the backend has them)."""
        ...

    def deflection(self, pressure):
        """Deflection (length) of the patch under a pressure on the patch (pressure)."""
        ...

    def pressure(self, deflection):
        """Pressure on the patch (zero outside) that deflects the patch by ``deflection``."""
        ...

    def energy(self, deflection) -> float:
        r"""Elastic energy :math:`\tfrac12 a_0^2 \sum p\,w` (pressure × length³) of a
        deflection of the patch."""
        ...

    def to_attrs(self) -> dict:
        """Flat attributes that rebuild this operator through :meth:`from_attrs`.

        Values are scalars, strings or short integer lists (NetCDF- and JSON-safe); they
        include ``contact_modulus`` (pressure), ``pixel_size`` (length), ``grid`` (the
        patch, ``[nx, ny]``), ``nominal_area`` (length²), ``periodic`` (1/0) and the kind
        tag ``substrate`` (the module docstring).
        """
        ...

    @classmethod
    def from_attrs(cls, attrs) -> ElasticOperator:
        """The operator described by ``attrs`` (a mapping, e.g. a path dataset's attrs),
        as written by :meth:`to_attrs` or by earlier versions of it."""
        ...

    def coarsened(self) -> ElasticOperator:
        """The same substrate on the patch coarsened 2 × 2 (twice the pixel size); used by
        the hard-wall solver's nested iteration."""
        ...
