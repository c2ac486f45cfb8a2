"""Surface interactions: laws that depend only on the local gap."""

from .hardwall import HardWall

__all__ = ["HardWall"]
