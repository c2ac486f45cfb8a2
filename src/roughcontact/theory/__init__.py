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

# Rough-surface theories: Pastewka & Robbins (2014) Eqs. 4-10 and the stickiness
# criterion (:mod:`.pastewka_robbins`); Persson (2001) and Bush-Gibson-Thomas (1975)
# area-load laws (:mod:`.persson`); Greenwood-Williamson with Hertz, DMT and JKR
# (Fuller-Tabor 1975) summits from Nayak/McCool summit statistics
# (:mod:`.greenwood_williamson`).
from .greenwood_williamson import (  # noqa: E402
    GreenwoodWilliamsonCurve,
    SummitStatistics,
    fuller_tabor_parameter,
    greenwood_williamson,
    spectral_moments,
    summit_statistics,
    summit_statistics_from_heights,
)
from .pastewka_robbins import (  # noqa: E402
    AREA_RATIO_PREFACTOR,
    KAPPA_REP,
    NECESSARY_CONDITION_CONSTANT,
    STICKINESS_THRESHOLD,
    PastewkaRobbinsPrediction,
    area_ratio,
    asperity_radius,
    attractive_load,
    height_change,
    kappa_att,
    kappa_att_from_area_ratio,
    kappa_from_components,
    necessary_condition,
    predict,
    predicted_d_rep,
    stickiness_margin,
    stickiness_parameter,
)
from .persson import BGT_KAPPA, PERSSON_KAPPA, bgt_area, persson_area, persson_load  # noqa: E402

__all__ += [
    "AREA_RATIO_PREFACTOR",
    "BGT_KAPPA",
    "KAPPA_REP",
    "NECESSARY_CONDITION_CONSTANT",
    "PERSSON_KAPPA",
    "STICKINESS_THRESHOLD",
    "GreenwoodWilliamsonCurve",
    "PastewkaRobbinsPrediction",
    "SummitStatistics",
    "area_ratio",
    "asperity_radius",
    "attractive_load",
    "bgt_area",
    "fuller_tabor_parameter",
    "greenwood_williamson",
    "height_change",
    "kappa_att",
    "kappa_att_from_area_ratio",
    "kappa_from_components",
    "necessary_condition",
    "persson_area",
    "persson_load",
    "predict",
    "predicted_d_rep",
    "spectral_moments",
    "stickiness_margin",
    "stickiness_parameter",
    "summit_statistics",
    "summit_statistics_from_heights",
]
