"""Surface interactions: laws that depend only on the local gap (see ``_base``)."""

from .dugdale import MaugisDugdale
from .exponential import Exponential
from .hardwall import HardWall
from .lj93 import LennardJones93
from .lj93smooth import SmoothLJ93

__all__ = ["Exponential", "HardWall", "LennardJones93", "MaugisDugdale", "SmoothLJ93"]
