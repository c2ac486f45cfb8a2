"""Contact solvers and the result record."""

from .polonsky_keer import polonsky_keer
from .result import ContactResult
from .solve import solve

__all__ = ["ContactResult", "polonsky_keer", "solve"]
