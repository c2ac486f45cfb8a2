"""Rough and reference surfaces: generation, geometry, statistics and file I/O.

Heights ``h(x, y)`` belong to the rigid surface at ``z = d - h``: larger ``h`` is closer
to the substrate (summits are maxima). Grids are periodic, ``x = i * pixel_size`` along
axis 0 and ``y = j * pixel_size`` along axis 1.

Note: the function :func:`statistics` shadows the submodule of the same name as an
attribute of this package; import the module's other names with
``from roughcontact.surfaces.statistics import ...``.
"""

from .generate import self_affine
from .geometry import egg_box, flat, sinusoid, sphere
from .io import load_heights, save_heights
from .statistics import (
    SurfaceStatistics,
    power_spectrum,
    rms_curvature,
    rms_height,
    rms_slope,
    statistics,
)

__all__ = [
    "SurfaceStatistics",
    "egg_box",
    "flat",
    "load_heights",
    "power_spectrum",
    "rms_curvature",
    "rms_height",
    "rms_slope",
    "save_heights",
    "self_affine",
    "sinusoid",
    "sphere",
    "statistics",
]
