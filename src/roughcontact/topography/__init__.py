"""Measured topographies: instrument files in SI units, detrending, tip-radius reliability.

:func:`load_topography` reads AFM, interferometer and stylus profilometer files through
SurfaceTopography (optional: ``pip install "roughcontact[topography]"``, imported only
when such a file is read) as well as ``.npy`` and text files, into a
:class:`Topography` (heights and pixel size in metres, the channel, the instrument's
metadata). :func:`detrend` and :func:`reliability_cutoff` prepare it for analysis.
"""

from .prepare import (
    DETREND_MODES,
    ReliabilityCutoff,
    detrend,
    reliability_cutoff,
    scale_dependent_curvature,
)
from .read import file_kind, load_topography
from .statistics import (
    HurstFit,
    PowerSpectrum,
    ScaleStatistics,
    fit_hurst,
    power_spectrum_1d,
    power_spectrum_2d,
    scale_dependent_rms,
    scale_statistics,
)
from .topography import LENGTH_UNITS, Topography
from .verdict import StickResult, Verdict, stick, stickiness_verdict

__all__ = [
    "DETREND_MODES",
    "LENGTH_UNITS",
    "HurstFit",
    "PowerSpectrum",
    "ReliabilityCutoff",
    "ScaleStatistics",
    "StickResult",
    "Topography",
    "Verdict",
    "detrend",
    "file_kind",
    "fit_hurst",
    "load_topography",
    "power_spectrum_1d",
    "power_spectrum_2d",
    "reliability_cutoff",
    "scale_dependent_curvature",
    "scale_dependent_rms",
    "scale_statistics",
    "stick",
    "stickiness_verdict",
]
