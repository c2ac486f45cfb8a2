"""Surface interactions: laws that depend only on the local gap."""

from .hardwall import HardWall
from .lj93smooth import SmoothLJ93

__all__ = ["HardWall", "SmoothLJ93"]
