"""The one registry of interaction laws: name, class, parameters, and :func:`make_law`.

Every place that names a law -- the command line's ``--interaction`` choices, the study
file's ``[interaction] law``, the law's own ``name`` -- reads :data:`REGISTRY`, and every
law is built from its parameters by :func:`make_law` (which checks them: a parameter the
law does not take, or a required one missing, is a one-line :class:`ParameterError`
naming the parameter and the law).

Parameters (all optional keywords of :func:`make_law`, ``None`` = not given):
``work_of_adhesion`` (w), ``adhesion_length`` (ℓa = w/E*, instead of w: every law that
takes w takes ℓa), ``range``, ``stiffness``, ``core_stiffness``; and the context every law
may use, ``contact_modulus`` (E*, default 1) and ``pixel_size`` (a0, default 1: the
equilibrium distance of the Lennard-Jones laws).

Registering a new law
---------------------
1. Write the class (the :class:`~roughcontact.interactions._base.Interaction` protocol;
   derive from :class:`~roughcontact.interactions._base.GapLaw` for a potential), with
   ``name`` set to its registry name.
2. Add one :class:`LawEntry` to :data:`REGISTRY`: the name, the class, the parameters it
   takes (:class:`Parameter`, ``required=True`` where it cannot do without) and
   ``build(w, given, contact_modulus, pixel_size)`` returning the law (``w`` is the work
   of adhesion from either w or ℓa, ``given`` the other parameters given).
3. Nothing else: ``--interaction`` and the study schema's ``law`` take their choices
   from here. A study file can only pass the parameters of :data:`PARAMETERS`.

The law parameter names themselves are listed once, in :data:`LAW_PARAMETERS`: the
command line's options, the study schema's ``[interaction]`` keys, the attributes a path
records (``roughcontact.pathdata``, ``solvers.path.provenance``) and the plots' keys are
derived from it. A new parameter is one :class:`LawParameter` there (and its argument in
the commands that build laws).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from ..errors import ParameterError
from ._base import Interaction
from .dugdale import MaugisDugdale
from .exponential import Exponential
from .hardwall import HardWall
from .lj93 import LennardJones93
from .lj93smooth import SmoothLJ93

__all__ = [
    "LAW_ATTRIBUTES",
    "LAW_PARAMETERS",
    "PARAMETERS",
    "REGISTRY",
    "Interaction",
    "LawEntry",
    "LawParameter",
    "Parameter",
    "law_parameters",
    "lookup",
    "make_law",
    "names",
]


@dataclass(frozen=True)
class LawParameter:
    """One law parameter name, written once for every place that spells it.

    ``name`` is the keyword of :func:`make_law`, the study file's key, the command
    line's option (``--`` + name with ``-``) and the key of the path's attributes;
    ``unit`` and ``meaning`` describe it there, ``option_help`` in ``--help``.
    ``given``: a parameter one gives (:data:`PARAMETERS`); ``recorded``: a number a built
    law carries, recorded with every path (:data:`LAW_ATTRIBUTES`).
    """

    name: str
    unit: str
    meaning: str
    option_help: str = ""
    given: bool = True
    recorded: bool = True


#: Every law parameter name of the package: the one list the others derive from (the
#: command line's options, the study schema, the path's attributes, the plots' keys).
LAW_PARAMETERS = (
    LawParameter(
        "adhesion_length", "length", "ℓa = w/E*",
        "ℓa = w/E* (length, > 0): w = ℓa x --modulus; instead of --work-of-adhesion.",
        recorded=False,  # a law carries w; ℓa follows from w and E*
    ),
    LawParameter(
        "work_of_adhesion", "pressure*length", "w (adhesive laws)",
        "w (energy per area, units of E* x length).",
    ),
    LawParameter(
        "range", "length", "the law's range (Δr, ρ or δ)",
        "Δr (lj93smooth), ρ (exponential), cohesive width (dugdale).",
    ),
    LawParameter(
        "stiffness", "pressure/length", "k = V''(a0) (Lennard-Jones walls)",
        "lj93smooth site stiffness per area k = V''(a0) (default E*/(2 a0)).",
    ),
    # a0 of the Lennard-Jones walls is the pixel size (make_law's context), not a parameter
    LawParameter(
        "equilibrium_distance", "length", "a0 of the Lennard-Jones walls", given=False
    ),
    LawParameter(
        "core_stiffness", "pressure/length", "soft core of the exponential law",
        "exponential: soft repulsive core k_c for g < 0 (default: hard wall).",
    ),
)  # fmt: skip

#: The law parameters make_law accepts, in the order they are checked and reported.
PARAMETERS = tuple(p.name for p in LAW_PARAMETERS if p.given)
#: The numeric members a law may have, as the results record them (:func:`law_parameters`).
LAW_ATTRIBUTES = tuple(p.name for p in LAW_PARAMETERS if p.recorded)


@dataclass(frozen=True)
class Parameter:
    """One parameter a law takes: its keyword, meaning, whether required, its default.

    ``default`` is what the law uses when the parameter is not given (``None``: the law
    derives it, as ``meaning`` says).
    """

    name: str
    meaning: str = ""
    required: bool = False
    default: object = None


@dataclass(frozen=True)
class LawEntry:
    """A registered law: name, class, the parameters it takes and how it is built."""

    name: str
    cls: type
    parameters: tuple[Parameter, ...]
    build: Callable[..., Interaction]
    summary: str = ""

    @property
    def takes(self) -> tuple[str, ...]:
        """The keywords of :data:`PARAMETERS` it takes (ℓa wherever w is taken)."""
        own = {p.name for p in self.parameters}
        if "work_of_adhesion" in own:
            own.add("adhesion_length")
        return tuple(k for k in PARAMETERS if k in own)

    @property
    def required(self) -> tuple[str, ...]:
        """The parameters it needs (``work_of_adhesion``: w or ℓa)."""
        return tuple(p.name for p in self.parameters if p.required)

    def parameter(self, name: str) -> Parameter | None:
        return next((p for p in self.parameters if p.name == name), None)


_W = Parameter("work_of_adhesion", "w (pressure × length), or adhesion_length ℓa = w/E*", True)

# the command line lists them in this order
REGISTRY: dict[str, LawEntry] = {
    e.name: e
    for e in (
        LawEntry(
            "hardwall",
            HardWall,
            (),
            lambda w, given, es, a0: HardWall(),
            "non-adhesive hard wall (a constraint)",
        ),
        LawEntry(
            "lj93smooth",
            SmoothLJ93,
            (
                Parameter("work_of_adhesion", "w; any two of stiffness, range, w"),
                Parameter("range", "Δr; any two of stiffness, range, w"),
                Parameter("stiffness", "k = V''(a0); default E*/(2 a0)"),
            ),
            lambda w, given, es, a0: SmoothLJ93(
                contact_modulus=es,
                pixel_size=a0,
                stiffness=given.get("stiffness"),
                range=given.get("range"),
                work_of_adhesion=w,
            ),
            "the paper's smoothly truncated 9-3 Lennard-Jones wall (a0 = pixel_size)",
        ),
        LawEntry(
            "lj93",
            LennardJones93,
            (_W,),
            lambda w, given, es, a0: LennardJones93(work_of_adhesion=w, equilibrium_distance=a0),
            "untruncated 9-3 Lennard-Jones wall (a0 = pixel_size)",
        ),
        LawEntry(
            "exponential",
            Exponential,
            (
                _W,
                Parameter("range", "decay length ρ", True),
                Parameter("core_stiffness", "soft core k_c for g < 0; default: hard wall"),
            ),
            lambda w, given, es, a0: Exponential(
                work_of_adhesion=w,
                range=given["range"],
                core_stiffness=given.get("core_stiffness"),
            ),
            "exponential adhesion -w exp(-g/ρ)",
        ),
        LawEntry(
            "dugdale",
            MaugisDugdale,
            (_W, Parameter("range", "cohesive-zone width; σ0 = W/DR", True)),
            lambda w, given, es, a0: MaugisDugdale(work_of_adhesion=w, range=given["range"]),
            "Maugis-Dugdale cohesive zone on a hard wall",
        ),
    )
}


def names() -> tuple[str, ...]:
    """The registered law names, in registry order."""
    return tuple(REGISTRY)


def lookup(name) -> LawEntry:
    """The registry entry of a law name (a ParameterError listing the names if unknown)."""
    try:
        return REGISTRY[name]
    except (KeyError, TypeError):
        raise ParameterError(
            f"interaction must be one of {', '.join(REGISTRY)}, got {name!r}"
        ) from None


def law_parameters(law) -> dict[str, float]:
    """The numeric parameters a law has (of :data:`LAW_ATTRIBUTES`), as floats."""
    out = {}
    for key in LAW_ATTRIBUTES:
        value = getattr(law, key, None)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            out[key] = float(value)
    return out


# -- how messages name parameters and laws: the Python API, the CLI, a study file --------


class _Python:
    order = PARAMETERS

    def both(self):
        return "give adhesion_length (ℓa = w/E*) or work_of_adhesion (w), not both"

    def bad_adhesion_length(self, value):
        return f"adhesion_length must be > 0 and finite (length), got {value!r}"

    def unexpected(self, law, key, value):
        return f"{key} does not apply to interaction {law!r}"

    def none_given(self, law):
        return None  # the law's own message

    def missing(self, law, key, meaning):
        if key == "work_of_adhesion":
            return f"interaction {law!r} needs work_of_adhesion (or adhesion_length)"
        return f"interaction {law!r} needs {key} ({meaning})"


class _Cli(_Python):
    order = ("adhesion_length", "stiffness", "core_stiffness", "work_of_adhesion", "range")

    @staticmethod
    def option(key):
        return "--" + key.replace("_", "-")

    def both(self):
        return "give --adhesion-length (ℓa = w/E*) or --work-of-adhesion (w), not both"

    def bad_adhesion_length(self, value):
        return f"--adhesion-length must be > 0 and finite (length), got {value!r}"

    def unexpected(self, law, key, value):
        if law == "hardwall" and key in ("work_of_adhesion", "range"):
            return "--interaction hardwall takes no --work-of-adhesion/--range"
        if law == "hardwall" and key == "adhesion_length":
            return "--interaction hardwall takes no --adhesion-length"
        why = " (untruncated)" if law == "lj93" and key == "range" else ""
        return f"{self.option(key)} does not apply to --interaction {law}{why}"

    def missing(self, law, key, meaning):
        if key == "work_of_adhesion":
            return f"--interaction {law} needs --work-of-adhesion (or --adhesion-length)"
        return f"--interaction {law} needs {self.option(key)} ({meaning})"


class _Study(_Python):
    def both(self):
        return "give adhesion_length or work_of_adhesion, not both"

    def unexpected(self, law, key, value):
        return f"{key} = {value!r} does not apply to law = {law!r}"

    def none_given(self, law):
        return (
            f"law = {law!r} needs adhesion_length (or any two of stiffness, range, "
            "work_of_adhesion)"
        )

    def missing(self, law, key, meaning):
        if key == "work_of_adhesion":
            return f"law = {law!r} needs adhesion_length (or work_of_adhesion)"
        return f"law = {law!r} needs {key} (> 0, length)"


_SPELLINGS = {"python": _Python(), "cli": _Cli(), "study": _Study()}


def make_law(
    name, *, contact_modulus=1.0, pixel_size=1.0, spelling="python", **params
) -> Interaction:
    """The law ``name`` of the registry, built from its parameters after checking them.

    ``params`` are keywords of :data:`PARAMETERS` (``None`` = not given). A parameter the
    law does not take, a missing required one, or both ``adhesion_length`` and
    ``work_of_adhesion`` give a one-line :class:`ParameterError` naming the parameter and
    the law; the law's class checks the values. ``spelling`` -- ``"python"``, ``"cli"``
    or ``"study"`` -- names them as keywords, options (``--range``) or study keys.
    """
    words = _SPELLINGS[spelling]
    entry = lookup(name)
    unknown = [k for k in params if k not in PARAMETERS]
    if unknown:
        raise ParameterError(
            f"{unknown[0]} is not a parameter of interaction {name!r}: "
            f"accepted {', '.join(entry.takes) or 'none'}"
        )
    given = {k: v for k, v in params.items() if v is not None}
    ell = given.get("adhesion_length")
    if ell is not None:
        if "work_of_adhesion" in given:
            raise ParameterError(words.both())
        if not (isinstance(ell, (int, float)) and math.isfinite(ell) and ell > 0):
            raise ParameterError(words.bad_adhesion_length(ell))
    for key in words.order:
        if key in given and key not in entry.takes:
            raise ParameterError(words.unexpected(name, key, given[key]))
    if entry.takes and not entry.required and not given:  # lj93smooth: any two of ...
        message = words.none_given(name)
        if message is not None:
            raise ParameterError(message)
    w = ell * contact_modulus if ell is not None else given.get("work_of_adhesion")
    for key in entry.required:
        if (w if key == "work_of_adhesion" else given.get(key)) is None:
            raise ParameterError(words.missing(name, key, entry.parameter(key).meaning))
    return entry.build(w, given, contact_modulus, pixel_size)
