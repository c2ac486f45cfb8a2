"""What every interaction law provides (the Interaction protocol).

A law depends on the local gap ``g`` only and is evaluated per unit area:

* ``energy(g)`` -- V(g), energy per area (pressure × length);
* ``pressure(g)`` -- p = -V'(g) (pressure; > 0 repulsive, < 0 attractive);
* ``curvature(g)`` -- V''(g) (pressure / length);
* ``classify(g)`` -- (repulsive, attractive) boolean masks;
* ``cutoff`` -- gap beyond which V = 0 exactly (``inf`` for unbounded laws);
* ``hard_core`` -- True if the law is only defined for g >= 0 and the non-penetration
  constraint g >= 0 is enforced by the solver (bound-constrained minimisation); the
  solver then also decides which contact sites are repulsive (the README's model: the site's net
  force pushes the surfaces apart).

:class:`Interaction` states this as a :class:`typing.Protocol`: it is the extension point
of the package. A new law is a class that provides these members (deriving from
:class:`GapLaw` gives ``energy``/``pressure``/``curvature``/``classify`` from one
``_evaluate``); it is made available by name to the command line (``--interaction``) and
to study files (``[interaction] law``) by one entry in
:data:`roughcontact.interactions.registry.REGISTRY` (see that module).
"""

from __future__ import annotations

from typing import ClassVar, Protocol, runtime_checkable

import numpy as np

from .._backend import array_namespace, is_array

__all__ = ["GapLaw", "Interaction"]


@runtime_checkable
class Interaction(Protocol):
    """What an interaction law provides (the extension point; see the module docstring).

    Required of every law:

    * ``name`` -- its registry name (``"lj93smooth"``, ...);
    * ``adhesive`` -- False for a law without attraction (then no tensile load exists);
    * ``hard_core`` -- True if the solver enforces g >= 0 (bound-constrained minimiser);
    * ``cutoff`` -- gap beyond which V = 0 exactly (``inf`` for unbounded laws);
    * ``energy(g)``, ``pressure(g)``, ``curvature(g)`` -- V, -V', V'' per unit area;
    * ``classify(g)`` -- the (repulsive, attractive) masks.

    Required too, read directly by the solvers, with defaults on :class:`GapLaw` for a
    law without them:

    * ``equilibrium_distance`` -- a0, the gap of the energy minimum (length; the
      Lennard-Jones walls), at which the undeformed surfaces first touch; default None:
      a hard core, touching at g = 0 (the solvers take d0 = 0);
    * ``range`` -- the law's range (length: Δr, ρ or δ; default None: no range
      parameter, e.g. the untruncated 9-3 wall);
    * ``work_of_adhesion`` -- w (pressure × length; default None);
    * ``stiffness`` -- k = V''(a0) (pressure / length; default None).

    Optional, read by name where a law has it (the registry's
    :func:`~roughcontact.interactions.registry.law_parameters` collects the parameters):
    ``core_stiffness`` (pressure / length; default None on :class:`GapLaw`).

    :class:`~roughcontact.interactions.HardWall` is the one law that is a constraint, not
    a potential: it provides ``name`` and ``adhesive`` only and the solvers treat it apart.
    """

    name: str
    adhesive: bool
    hard_core: bool
    equilibrium_distance: float | None
    range: float | None
    work_of_adhesion: float | None
    stiffness: float | None

    @property
    def cutoff(self) -> float: ...

    def energy(self, gap): ...

    def pressure(self, gap): ...

    def curvature(self, gap): ...

    def classify(self, gap): ...


class _Default:
    """The value of a law member that a law does not define itself (read on an instance).

    A non-data descriptor, so the law's own value (a dataclass field, a property) wins.
    On the class it is an AttributeError: a dataclass field of the same name without a
    default of its own (``work_of_adhesion: float``) stays required.
    """

    def __init__(self, default):
        self.default = default

    def __set_name__(self, owner, name):
        self.name = name

    def __get__(self, instance, owner=None):
        if instance is None:
            raise AttributeError(self.name)
        return self.default


class GapLaw:
    """Mixin: ``energy``/``pressure``/``curvature`` from one ``_evaluate(g) -> (V, V', V'')``.

    Also the defaults of the :class:`Interaction` members a law may lack (see there):
    None, so that the parameters a law records (the registry's ``law_parameters``, a
    path's attributes) are the ones it has.
    """

    hard_core: bool = False
    adhesive: ClassVar[bool] = True
    equilibrium_distance = _Default(None)
    range = _Default(None)
    work_of_adhesion = _Default(None)
    stiffness = _Default(None)
    core_stiffness = _Default(None)

    def _evaluate(self, gap):  # pragma: no cover - abstract
        raise NotImplementedError

    def energy(self, gap):
        """V(g), energy per area (pressure × length)."""
        return self._evaluate(gap)[0]

    def pressure(self, gap):
        """p(g) = -V'(g) (pressure; > 0 repulsive)."""
        return -self._evaluate(gap)[1]

    def curvature(self, gap):
        """V''(g) (pressure / length)."""
        return self._evaluate(gap)[2]

    def classify(self, gap):
        """(repulsive, attractive) masks: the site's force pushes apart / pulls together."""
        p = self.pressure(gap)
        return p > 0, p < 0


def as_gap(gap):
    """``(xp, g)``: the array namespace of ``gap`` and the gap as a float array of it.

    float32 gaps stay float32 (the solvers' single-precision option); anything else
    becomes float64.
    """
    if not is_array(gap):  # lists, Python scalars: float64 NumPy
        gap = np.asarray(gap, dtype=float)
    xp = array_namespace(gap)
    if gap.dtype in (xp.float64, xp.float32):
        return xp, gap
    return xp, xp.astype(gap, xp.float64)
