"""The keys of a study file: type, accepted range, default, and whether a list sweeps.

Sections ``[study]``, ``[surface]``, ``[substrate]``, ``[interaction]``, ``[path]``,
``[solver]``, ``[analysis]``, ``[output]`` and ``[[cases]]``; see ``studies/smoke.toml``
and the README. Lengths in units of the pixel size a0, moduli and pressures in units of E*.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._validate import (
    CONTACT_MODULUS,
    FIT_MAX_AREA,
    HURST,
    MAX_ITER,
    PIXEL_SIZE,
    POISSON,
    SEED,
    TARGET_AREA,
    TOL,
    ParameterError,  # noqa: F401 (importable from here, as before)
    Range,
)
from ..interactions.registry import PARAMETERS, make_law
from ..interactions.registry import names as law_names
from ..pathdata import FIELDS  # the field maps a path file can keep (one owner)

__all__ = ["SCHEMA", "SWEEP_KEYS", "find", "make_interaction"]

DEFAULT_LAW = "lj93smooth"
# the registry's laws, the default first (as the schema has always listed them)
LAWS = (DEFAULT_LAW, *(n for n in law_names() if n != DEFAULT_LAW))
UNITS = {
    "offset": ("length", "rms_height", "bearing_area"),
    "load": ("modulus", "rms_slope_modulus"),
}
KINDS = {float: "a number", int: "an integer", bool: "true or false", str: "a string"}


@dataclass(frozen=True)
class _Key:
    """One TOML key: type, accepted range (text and test), default, and whether it sweeps."""

    kind: type
    accepted: str = ""
    test: object = None
    default: object = None
    sweep: bool = False
    is_list: bool = False


def _k(kind, accepted="", test=None, default=None, sweep=True, is_list=False):
    return _Key(kind, accepted, test, default, sweep, is_list)


_POS = ("> 0 and finite", lambda v: 0 < v < math.inf)


def _shared(rng: Range):
    """(accepted, test) of a range defined once in :mod:`roughcontact._validate`."""
    return rng.accepted, rng.contains


_NUM = ("finite", math.isfinite)
#: the largest grid of a study (sites per axis)
MAX_SIZE = 16384
# what a surface of float64 heights can carry and a solver resolve (lattice units): far
# beyond these the heights under- or overflow and every task would fail after the start
_RMS_SLOPE = ("in [1e-8, 1e4]", lambda v: 1e-8 <= v <= 1e4)
_RMS_HEIGHT = ("in [1e-8, 1e8] (units of pixel_size)", lambda v: 1e-8 <= v <= 1e8)
# E* in a study's units: the solvers' states overflow beyond about 1e±30 (every task would
# fail after the start), so a study takes the API's range narrowed to [1e-20, 1e20]
_MODULUS = (
    "in [1e-20, 1e20]",
    lambda v: CONTACT_MODULUS.contains(v) and 1e-20 <= v <= 1e20,
)
SCHEMA = {
    "study": {"name": _k(str, sweep=False), "description": _k(str, sweep=False, default="")},
    "surface": {
        # 16384² sites: a few GiB per field map; larger grids do not fit a worker
        "size": _k(int, f"an integer >= 8 and <= {MAX_SIZE}", lambda v: 8 <= v <= MAX_SIZE),
        "pixel_size": _k(float, *_shared(PIXEL_SIZE), default=1.0),
        "hurst": _k(float, *_shared(HURST)),
        "rms_slope": _k(float, *_RMS_SLOPE),
        "rms_height": _k(float, *_RMS_HEIGHT),
        "short_cutoff": _k(float, ">= 2 * pixel_size", lambda v: 0 < v < math.inf),
        "long_cutoff": _k(float, "in (short_cutoff, size * pixel_size]", lambda v: v > 0),
        "rolloff": _k(bool, default=True),
        "seeds": _k(
            int,
            f"a non-empty list of distinct integers {SEED.accepted.removeprefix('an integer ')}",
            SEED.contains,
            sweep=False,
            is_list=True,
        ),
    },
    "substrate": {
        "contact_modulus": _k(float, *_MODULUS, default=1.0),
        "thickness": _k(float, *_POS),
        "poisson": _k(float, *_shared(POISSON), default=0.5),
        "base": _k(
            str,
            "'bonded' or 'frictionless'",
            lambda v: v in ("bonded", "frictionless"),
            default="bonded",
        ),
        # false: a free boundary (no periodic images; a half-space only). Left at the
        # default it is not part of the task keys (studies/spec.py: _keyed)
        "periodic": _k(bool, default=True),
    },
    "interaction": {
        "law": _k(str, "one of " + ", ".join(LAWS), lambda v: v in LAWS, default=DEFAULT_LAW),
        # the registry's parameters, each a positive number
        **{k: _k(float, *_POS) for k in PARAMETERS},
        "adhesion_length": _k(float, "> 0; law = 'hardwall' for no adhesion", _POS[1]),
    },
    "path": {
        "control": _k(str, "'offset' or 'load'", lambda v: v in UNITS, "offset", False),
        "values": _k(float, *_NUM, sweep=False, is_list=True),
        "start": _k(float, *_NUM, sweep=False),
        "stop": _k(float, *_NUM, sweep=False),
        "step": _k(
            float, "non-zero and finite", lambda v: v != 0 and math.isfinite(v), sweep=False
        ),
        "num": _k(int, "an integer in [2, 100000]", lambda v: 2 <= v <= 100_000, sweep=False),
        "spacing": _k(
            str, "'linear' or 'geometric'", lambda v: v in ("linear", "geometric"), "linear", False
        ),
        "unit": _k(
            str,
            "'length', 'rms_height' or 'bearing_area' (offsets), 'modulus' or "
            "'rms_slope_modulus' (loads)",
            None,
            None,
            False,
        ),
        "lead_in": _k(float, "a list of lengths > 0", lambda v: 0 < v < math.inf, (), False, True),
        "retract": _k(bool, default=True, sweep=False),
    },
    "solver": {
        "tol": _k(float, *_shared(TOL), 1e-8, False),
        "max_iter": _k(int, *_shared(MAX_ITER), 5000, False),
        "dtype": _k(
            str, "'float64' or 'float32'", lambda v: v in ("float64", "float32"), "float64", False
        ),
    },
    "analysis": {
        "target_area": _k(float, *_shared(TARGET_AREA), 0.01, False),
        "fit_max_area": _k(float, *_shared(FIT_MAX_AREA), 0.05, False),
        "branch": _k(
            str,
            "'approach' or 'retract'",
            lambda v: v in ("approach", "retract"),
            "approach",
            False,
        ),
        # an explicit opt-in: analyse across unconverged steps, marked unreliable
        "allow_unconverged": _k(bool, default=False, sweep=False),
        # κ_rep of a hard wall on the same surface beside the paper's (a few cheap solves)
        "hard_wall_reference": _k(bool, default=True, sweep=False),
    },
    "output": {
        "fields_at": _k(
            int,
            "a list of step indices in [-steps, steps) (negative: from the end)",
            None,
            (),
            False,
            True,
        ),
        "fields_at_area": _k(
            float,
            f"a list of A_rep/A0 {TARGET_AREA.accepted}",
            TARGET_AREA.contains,
            (),
            False,
            True,
        ),
        "fields": _k(
            str, "a list from " + ", ".join(FIELDS), lambda v: v in FIELDS, FIELDS, False, True
        ),
    },
}
SWEEP_KEYS = tuple(k for s in SCHEMA.values() for k, d in s.items() if d.sweep)
_SECTION = {k: s for s, keys in SCHEMA.items() for k in keys}


def find(key) -> _Key:
    """The schema entry of a parameter key (any section)."""
    return SCHEMA[_SECTION[key]][key]


LAW_KEYS = PARAMETERS  # adhesion_length, work_of_adhesion, range, stiffness, core_stiffness


def make_interaction(p):
    """The interaction law of a parameter set (ℓa = w/E*; lengths in the units of a0).

    Reads ``p["law_inputs"]`` (the interaction parameters as given) when present.

    ``lj93smooth`` takes ``adhesion_length`` (k = E*/(2 a0), Δr = √(24 a0 ℓa)) or any two
    of stiffness, range, work_of_adhesion; ``lj93`` a work of adhesion or ℓa;
    ``exponential`` and ``dugdale`` ℓa (or w) and a range; ``hardwall`` none. The checks
    and the construction are the registry's (:func:`~roughcontact.interactions.registry.make_law`).
    """
    src = p.get("law_inputs", p)  # the values as given; p holds the derived ones too
    return make_law(
        p["law"],
        contact_modulus=p["contact_modulus"],
        pixel_size=p["pixel_size"],
        spelling="study",
        **{k: src.get(k) for k in LAW_KEYS},
    )
