"""Contact solvers and the result record."""

from .offsets import first_contact_offset, relative_offsets
from .path import PathError, PathInterrupted, approach_retract
from .polonsky_keer import polonsky_keer
from .result import ContactResult, SolveStatus
from .smooth import minimize_energy
from .solve import solve

__all__ = [
    "ContactResult",
    "PathError",
    "PathInterrupted",
    "SolveStatus",
    "approach_retract",
    "first_contact_offset",
    "minimize_energy",
    "polonsky_keer",
    "relative_offsets",
    "solve",
]
