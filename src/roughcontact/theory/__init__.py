"""Closed-form reference solutions (used as test oracles).

* :mod:`.hertz` -- sphere on a half-space (Johnson 1985, ch. 4).
* :mod:`.westergaard` -- 1D sinusoid on a half-space (Westergaard 1939; Johnson 1985,
  section 13.2).
"""

from .hertz import HertzContact, hertz, hertz_load
from .westergaard import (
    westergaard_contact_fraction,
    westergaard_contact_half_width,
    westergaard_full_contact_pressure,
    westergaard_pressure,
)

__all__ = [
    "HertzContact",
    "hertz",
    "hertz_load",
    "westergaard_contact_fraction",
    "westergaard_contact_half_width",
    "westergaard_full_contact_pressure",
    "westergaard_pressure",
]
