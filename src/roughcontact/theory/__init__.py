"""Closed-form and semi-analytic reference solutions (used as test oracles).

* :mod:`.hertz` -- sphere on a half-space (Johnson 1985, ch. 4).
* :mod:`.westergaard` -- 1D sinusoid on a half-space (Westergaard 1939; Johnson 1985,
  section 13.2).
* :mod:`.jkr` -- adhesive sphere: JKR (Johnson, Kendall & Roberts 1971) and DMT
  (Derjaguin, Muller & Toporov 1975).
* :mod:`.maugis_dugdale` -- the JKR-DMT transition with a Dugdale cohesive zone
  (Maugis 1992; Johnson & Greenwood 1997).
* :mod:`.adhesive_sinusoid` -- Johnson's adhesive 1D sinusoid (Johnson 1995).
"""

from .adhesive_sinusoid import (
    JOHNSON_ALPHA_MAX,
    JOHNSON_FULL_CONTACT_ALPHA,
    JohnsonSinusoidThresholds,
    johnson_parameter,
    johnson_sinusoid_mean_gap,
    johnson_sinusoid_mean_pressure,
    johnson_sinusoid_pressure,
    johnson_sinusoid_pull_off_pressure,
    johnson_sinusoid_spontaneous_full_contact,
    johnson_sinusoid_thresholds,
)
from .hertz import HertzContact, hertz, hertz_load
from .jkr import (
    JKRContact,
    dmt_contact_radius,
    dmt_load,
    dmt_pull_off_force,
    jkr,
    jkr_contact_radius,
    jkr_indentation,
    jkr_load,
    jkr_pull_off,
    jkr_pull_off_force,
    jkr_zero_load_contact_radius,
)
from .maugis_dugdale import (
    MaugisDugdaleContact,
    MaugisDugdalePullOff,
    maugis_dugdale,
    maugis_dugdale_nondimensional,
    maugis_dugdale_pull_off,
    maugis_dugdale_pull_off_force,
    maugis_parameter,
    tabor_parameter,
)
from .westergaard import (
    westergaard_contact_fraction,
    westergaard_contact_half_width,
    westergaard_full_contact_pressure,
    westergaard_pressure,
)

__all__ = [
    "JOHNSON_ALPHA_MAX",
    "JOHNSON_FULL_CONTACT_ALPHA",
    "HertzContact",
    "JKRContact",
    "JohnsonSinusoidThresholds",
    "MaugisDugdaleContact",
    "MaugisDugdalePullOff",
    "dmt_contact_radius",
    "dmt_load",
    "dmt_pull_off_force",
    "hertz",
    "hertz_load",
    "jkr",
    "jkr_contact_radius",
    "jkr_indentation",
    "jkr_load",
    "jkr_pull_off",
    "jkr_pull_off_force",
    "jkr_zero_load_contact_radius",
    "johnson_parameter",
    "johnson_sinusoid_mean_gap",
    "johnson_sinusoid_mean_pressure",
    "johnson_sinusoid_pressure",
    "johnson_sinusoid_pull_off_pressure",
    "johnson_sinusoid_spontaneous_full_contact",
    "johnson_sinusoid_thresholds",
    "maugis_dugdale",
    "maugis_dugdale_nondimensional",
    "maugis_dugdale_pull_off",
    "maugis_dugdale_pull_off_force",
    "maugis_parameter",
    "tabor_parameter",
    "westergaard_contact_fraction",
    "westergaard_contact_half_width",
    "westergaard_full_contact_pressure",
    "westergaard_pressure",
]
