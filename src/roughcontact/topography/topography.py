"""The :class:`Topography` record: a measured (or saved) height map or line scan.

Lengths are in metres when the file says what its units are (instrument files) or the
caller does (``pixel_size=``, ``height_unit=``); a ``.npy`` or text file read without
them stays in lattice units (``a0 = 1``, heights in the same unit), and
``info["length_unit"]`` says which of the two (``"m"`` or ``"a0"``).
"""

from __future__ import annotations

import datetime as _dt
import enum
import math
from dataclasses import dataclass, field

import numpy as np

from .._validate import real_array
from ..errors import ParameterError
from ..units import LENGTH_UNITS, length_factor

__all__ = ["LENGTH_UNITS", "Topography", "length_factor", "pixel_sizes"]

# The length-unit table and its parser live in roughcontact.units (one table for every
# reader of units); LENGTH_UNITS and length_factor stay importable here.


def pixel_sizes(value, ndim: int) -> tuple:
    """``value`` (one number, or one per axis) as a tuple of ``ndim`` floats > 0."""
    px = (value,) * ndim if np.ndim(value) == 0 else tuple(np.ravel(value))
    if len(px) != ndim:
        raise ParameterError(
            f"pixel_size must be one number or one per axis ({ndim}), got {value!r}"
        )
    out = []
    for p in px:
        try:
            v = float(p)
        except (TypeError, ValueError):
            v = math.nan
        if not (math.isfinite(v) and v > 0) or isinstance(p, (bool, np.bool_, str)):
            raise ParameterError(f"pixel_size must be > 0 and finite, got {value!r}")
        out.append(v)
    return tuple(out)


def _jsonable(obj):
    """``obj`` made JSON-serialisable: datetimes as ISO text, NumPy scalars as numbers.

    Anything else that JSON cannot hold (arrays, objects) is dropped, so ``info`` never
    breaks ``json.dumps``; non-finite floats become None.
    """
    if isinstance(obj, dict):
        out = {}
        for k, v in obj.items():
            v = _jsonable(v)
            if v is not _DROP:
                out[str(k)] = v
        return out
    if isinstance(obj, (list, tuple)):
        return [v for v in (_jsonable(v) for v in obj) if v is not _DROP]
    if obj is None or isinstance(obj, (bool, str)):
        return obj
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        v = float(obj)
        return v if math.isfinite(v) else None
    if isinstance(obj, (_dt.datetime, _dt.date, _dt.time)):
        return obj.isoformat()
    if isinstance(obj, enum.Enum):
        return _jsonable(obj.value)
    return _DROP


_DROP = object()


@dataclass(frozen=True, eq=False)
class Topography:
    """Heights on a uniform grid, with the file's metadata.

    Parameters
    ----------
    heights : ndarray of float64, shape (nx,) or (nx, ny)
        Finite heights (metres, or lattice units: see ``info["length_unit"]``); stored
        read-only. ``heights[i, j]`` is at ``x = i * pixel_size[0]``,
        ``y = j * pixel_size[1]``; larger heights are higher (summits are maxima).
    pixel_size : tuple of float
        Grid spacing along each axis (same length unit as the heights), one per axis.
    periodic : bool
        Whether the heights are one period of a periodic surface (measured scans are not).
    channel : str
        Name of the channel read (``"heights"`` for ``.npy`` and text files).
    source : str
        The file read.
    height_unit : str
        The unit the file stored heights in (``"a0"`` for lattice units).
    info : dict
        JSON-serialisable metadata: instrument, ``tip_radius`` (m) when stored, scan size,
        what reading and preparation did (``resampled``, ``missing_data``, ``detrend``).

    Notes
    -----
    The physical size is ``n * pixel_size`` along each axis, the convention of
    SurfaceTopography and of a periodic grid (the period).
    """

    heights: np.ndarray
    pixel_size: tuple
    periodic: bool = False
    channel: str = "heights"
    source: str = ""
    height_unit: str = "a0"
    info: dict = field(default_factory=dict)

    def __post_init__(self):
        # a copy (the record owns its data); bool, complex, object arrays never convert
        h = np.array(real_array("heights", self.heights), dtype=np.float64)
        if h.ndim not in (1, 2) or min(h.shape, default=0) < 2:
            raise ParameterError(
                f"heights must be a 1D (nx,) or 2D (nx, ny) array with at least 2 points "
                f"per axis, got shape {h.shape}"
            )
        if not np.all(np.isfinite(h)):
            raise ParameterError(
                f"heights must be finite everywhere (found {int(np.sum(~np.isfinite(h)))} "
                "NaN or inf)"
            )
        h.setflags(write=False)
        object.__setattr__(self, "heights", h)
        object.__setattr__(self, "pixel_size", pixel_sizes(self.pixel_size, h.ndim))
        object.__setattr__(self, "periodic", bool(self.periodic))
        object.__setattr__(self, "channel", str(self.channel))
        object.__setattr__(self, "source", str(self.source))
        object.__setattr__(self, "height_unit", str(self.height_unit))
        object.__setattr__(self, "info", _jsonable(dict(self.info)))

    @property
    def dim(self) -> int:
        """1 for a line scan, 2 for a map."""
        return self.heights.ndim

    @property
    def shape(self) -> tuple:
        """Grid points per axis."""
        return self.heights.shape

    @property
    def physical_size(self) -> tuple:
        """Size along each axis, ``n * pixel_size`` (same length unit as the heights)."""
        return tuple(n * p for n, p in zip(self.heights.shape, self.pixel_size, strict=True))

    @property
    def length_unit(self) -> str:
        """``"m"`` (SI) or ``"a0"`` (lattice units): the unit of heights and pixel size."""
        return self.info.get("length_unit", "a0")

    def to_dict(self) -> dict:
        """A JSON-ready summary (no heights): shape, sizes, units, channel, source, info.

        ``rms_height`` is the root mean square of the heights about their mean (same
        length unit), ``min_height`` / ``max_height`` the extremes.
        """
        h = self.heights
        return {
            "source": self.source,
            "channel": self.channel,
            "dim": self.dim,
            "shape": list(h.shape),
            "pixel_size": list(self.pixel_size),
            "physical_size": list(self.physical_size),
            "length_unit": self.length_unit,
            "height_unit": self.height_unit,
            "periodic": self.periodic,
            "rms_height": float(np.sqrt(np.mean((h - h.mean()) ** 2))),
            "min_height": float(h.min()),
            "max_height": float(h.max()),
            "info": self.info,
        }
