"""Contact solvers and the result record."""

from .path import PathError, PathInterrupted, approach_retract
from .polonsky_keer import polonsky_keer
from .result import ContactResult
from .smooth import minimize_energy
from .solve import solve

__all__ = [
    "ContactResult",
    "PathError",
    "PathInterrupted",
    "approach_retract",
    "minimize_energy",
    "polonsky_keer",
    "solve",
]
