"""The non-adhesive hard wall: gap >= 0, pressure >= 0, pressure * gap = 0."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["HardWall"]


@dataclass(frozen=True)
class HardWall:
    """Non-adhesive, impenetrable contact (a constraint, not a potential).

    Sites with gap ``g = 0`` carry a compressive pressure ``p >= 0``; sites with
    ``g > 0`` carry none (Signorini conditions). Solved by constrained conjugate
    gradients (:func:`roughcontact.solvers.polonsky_keer`). A site is *repulsive* when
    ``p > 0``; there are no attractive sites.
    """

    name: str = "hardwall"
    adhesive: bool = False
