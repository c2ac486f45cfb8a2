"""roughcontact: contact of rough elastic surfaces with adhesion.

Implements Pastewka & Robbins, PNAS 111, 3298 (2014): self-affine surfaces, FFT
Green's-function substrates, surface interactions and contact solvers.
Conventions and units: see the README (lattice units a0 = 1, E* = 1 unless given).
"""

# first: under the command line, Ctrl-C while the modules load exits 130 in one line
from . import _startup  # noqa: F401
from ._accelerator import to_device
from ._validate import ParameterError
from .analysis import (
    area_fraction,
    contact_patches,
    corrected_area,
    perimeter,
    perimeter_edges,
)
from .elastic import ElasticOperator, Substrate
from .interactions import Exponential, HardWall, LennardJones93, MaugisDugdale, SmoothLJ93
from .solvers import (
    ContactResult,
    PathError,
    PathInterrupted,
    SolveStatus,
    approach_retract,
    first_contact_offset,
    polonsky_keer,
    relative_offsets,
    solve,
)
from .surfaces import (
    egg_box,
    flat,
    load_heights,
    power_spectrum,
    save_heights,
    self_affine,
    sinusoid,
    sphere,
    statistics,
)
from .topography import load_topography, stick
from .workflows import run_path

__version__ = "0.1.0"

__all__ = [
    "ContactResult",
    "ElasticOperator",
    "Exponential",
    "HardWall",
    "LennardJones93",
    "MaugisDugdale",
    "ParameterError",
    "PathError",
    "PathInterrupted",
    "SmoothLJ93",
    "SolveStatus",
    "Substrate",
    "approach_retract",
    "area_fraction",
    "contact_patches",
    "corrected_area",
    "egg_box",
    "first_contact_offset",
    "flat",
    "load_heights",
    "load_topography",
    "perimeter",
    "perimeter_edges",
    "polonsky_keer",
    "power_spectrum",
    "relative_offsets",
    "run_path",
    "save_heights",
    "self_affine",
    "sinusoid",
    "solve",
    "sphere",
    "statistics",
    "stick",
    "to_device",
]
