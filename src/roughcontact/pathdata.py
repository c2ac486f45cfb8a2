"""The path dataset: its layout (one table), its builder, its reader and its one writer.

A quasi-static path (:func:`roughcontact.approach_retract`; Pastewka & Robbins, PNAS 111,
3298 (2014), Methods: each state warm-started from the last) is an ``xarray.Dataset``:

* one row per step (dim ``step``): the scalars of the solved state, its branch and status;
* optionally the contact maps of some steps (dims ``field_step, x, y``);
* the rigid surface's heights (dims ``x, y``), enough to re-analyse the path;
* attributes: how the path was run and everything needed to analyse it without its inputs.

:data:`VARIABLES` and :data:`ATTRIBUTES` are the one table of names, dims, kinds and
units; everything that writes a path (the path solver, a study task, ``roughcontact
path``) builds it with :func:`path_dataset` / :func:`add_fields` and writes it with
:func:`write_path`, and everything that reads one (the analysis, the study collector,
the figures) opens it with :func:`read_path` or checks it with :func:`check_path`.
Lattice units unless given (lengths in a0, pressures in E*); loads and areas per nominal
area A0. Only NumPy is imported here; xarray when a dataset is built or read.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._validate import GRID_SIZE, PIXEL_SIZE, POISSON, ParameterError, Range
from .interactions.registry import LAW_PARAMETERS

__all__ = [
    "ATTRIBUTES",
    "FIELDS",
    "FLAGS",
    "FIELD_STEP",
    "PER_STEP",
    "REQUIRED",
    "STEP",
    "VARIABLES",
    "Attribute",
    "Variable",
    "add_fields",
    "check_path",
    "load_libraries",
    "path_dataset",
    "read_path",
    "write_path",
]

STEP = "step"
FIELD_STEP = "field_step"
_STEP = (STEP,)
_MAP = (FIELD_STEP, "x", "y")
_SURFACE = ("x", "y")


@dataclass(frozen=True)
class Variable:
    """One variable of a path dataset.

    ``kind`` is the NumPy dtype kind ("f" float64, "i" int64, "b" bool, "U" text);
    ``required``: the analysis needs it, so a path without it is refused.
    """

    name: str
    dims: tuple[str, ...]
    kind: str
    units: str
    meaning: str
    required: bool = False


@dataclass(frozen=True)
class Attribute:
    """One global attribute of a path dataset; ``accepted``: its range, checked on reading."""

    name: str
    units: str
    meaning: str
    required: bool = False
    accepted: Range | None = None


#: The variables, in the order of the dataset. The per-step scalars up to
#: ``solve_seconds`` are :data:`roughcontact.solvers.result.STATE_SCALARS`, in its order.
VARIABLES = (
    Variable("offset", _STEP, "f", "length", "offset d of the rigid surface", True),
    Variable("load", _STEP, "f", "pressure", "external load N/A0 (> 0 pushes together)", True),
    Variable("repulsive_load", _STEP, "f", "pressure", "N_rep/A0 (magnitude)", True),
    Variable("attractive_load", _STEP, "f", "pressure", "N_att/A0 (magnitude)", True),
    Variable("repulsive_area", _STEP, "f", "1", "A_rep/A0", True),
    Variable("attractive_area", _STEP, "f", "1", "A_att/A0", True),
    Variable("perimeter", _STEP, "f", "1/length", "repulsive perimeter per A0", True),
    Variable("perimeter_edges", _STEP, "i", "1", "nearest-neighbour bonds on the perimeter"),
    Variable("corrected_repulsive_area", _STEP, "f", "1", "A_rep/A0 corrected by the perimeter"),
    Variable("mean_gap", _STEP, "f", "length", "mean gap over A0"),
    Variable("iterations", _STEP, "i", "1", "iterations of the solve"),
    Variable("converged", _STEP, "b", "", "the solve met its tolerance"),
    Variable("residual", _STEP, "f", "1", "the solver's final convergence measure"),
    Variable("solve_seconds", _STEP, "f", "s", "wall time of the solve"),
    Variable("repulsive_patches", _STEP, "i", "1", "connected repulsive patches (periodic)"),
    Variable("jump", _STEP, "b", "", "an instability (jump into or out of contact)"),
    Variable("branch", _STEP, "U", "", "'approach' or 'retract'", True),
    Variable("status", _STEP, "U", "", "why the solve stopped (SolveStatus value)"),
    Variable("pressure", _MAP, "f", "pressure", "pressure p (> 0 repulsive)"),
    Variable("gap", _MAP, "f", "length", "gap g = d - h + w"),
    Variable("deflection", _MAP, "f", "length", "deflection w of the substrate"),
    Variable("heights", _SURFACE, "f", "length", "heights h of the rigid surface (float64)"),
)
_BY_NAME = {v.name: v for v in VARIABLES}
#: The per-step variables (dim ``step``), in the dataset's order.
PER_STEP = tuple(v.name for v in VARIABLES if v.dims == _STEP)
#: The contact maps kept at some steps (dims ``field_step, x, y``), in this order.
FIELDS = tuple(v.name for v in VARIABLES if v.dims == _MAP)
#: The variables a path must have to be analysed.
REQUIRED = tuple(v.name for v in VARIABLES if v.required)

_POSITIVE = Range(0, lo_open=True)
#: The global attributes of a path from :func:`roughcontact.approach_retract` (and
#: ``roughcontact path``, which adds ``offset_unit`` and ``surface_file``).
ATTRIBUTES = (
    Attribute("control", "", "'offset' or 'load': what the path steps through"),
    Attribute("pull_off", "pressure", "largest tensile load on retraction (NaN: not measured)"),
    Attribute("separated", "", "1 if the retraction ends without repulsive contact (read: bool)"),
    Attribute("all_converged", "", "1 if every step converged (read: bool)"),
    Attribute("total_seconds", "s", "wall time of the path"),
    Attribute("rms_height", "length", "spectral rms height of the surface"),
    Attribute("rms_slope", "1", "spectral rms slope h'rms", True, Range(0)),
    Attribute("rms_curvature", "1/length", "spectral rms curvature h''rms"),
    Attribute("predicted_d_rep", "length", "d_rep = 4 h'rms/h''rms"),
    Attribute("short_cutoff_estimate", "length", "shortest wavelength present"),
    Attribute("contact_modulus", "pressure", "E*", True, _POSITIVE),
    Attribute("pixel_size", "length", "a0", True, PIXEL_SIZE),
    Attribute("grid", "1", "the substrate's two grid sizes"),
    Attribute("nominal_area", "length^2", "A0", True, _POSITIVE),
    Attribute("thickness", "length", "layer thickness (inf: half-space)", False, _POSITIVE),
    Attribute("poisson", "1", "Poisson ratio of a layer", False, POISSON),
    Attribute("base", "", "a layer's base ('' for a half-space)"),
    Attribute("periodic", "", "1 for a periodic substrate, 0 for a free boundary"),
    Attribute("interaction_name", "", "the law's registry name"),
    Attribute("interaction", "", "repr of the law"),
    Attribute("substrate", "", "repr of the substrate"),
    Attribute("roughcontact_version", "", "the version that computed the path"),
    # the law's parameters: the interaction registry's one list
    *(Attribute(p.name, p.unit, p.meaning) for p in LAW_PARAMETERS if p.recorded),
    Attribute("until_area", "1", "target A_rep/A0 of the approach (NaN: none)"),
    Attribute("until_area_reached", "", "1 if the approach reached until_area"),
    Attribute("dtype", "", "floating-point precision of the computation"),
    Attribute("device", "", "where the path was computed"),
    Attribute("units", "", "the units, in words"),
    Attribute("offset_unit", "", "unit of the offsets given to 'roughcontact path'"),
    Attribute("surface_file", "", "the heights file given to 'roughcontact path'"),
    Attribute("length_unit", "", "lengths in 'm' (an instrument file) or 'a0' (the pixel size)"),
)
_UNITS = "lattice units unless given: loads and areas per nominal area A0"


def load_libraries(write: bool = False) -> None:
    """Import now what making a path dataset (and, with ``write``, writing it) imports lazily.

    A first dataset imports ~450 modules (xarray, dask and theirs: 0.4 s), a first write
    ~260 more (dask's probe of ``distributed``, h5netcdf, h5py: 0.16 s). A Ctrl-C inside
    such an import leaves the module half-made, and the partial path built or written
    after it then fails with an ``AttributeError`` traceback instead of being saved
    (measured: ``roughcontact path`` interrupted 0.8 s in). Called before a path's first
    step, a Ctrl-C here loses nothing: no step has been computed.
    """
    import xarray as xr

    tiny = xr.Dataset({"v": ("s", np.zeros(1))})
    if write:
        from ._io import netcdf_bytes

        netcdf_bytes(tiny)


def path_dataset(rows, branch, fields, control, attrs, heights, *, total_seconds):
    """The dataset of a path's finished steps.

    Parameters
    ----------
    rows : list of dict
        One per step: the per-step scalars of :data:`PER_STEP` but ``branch``.
    branch : sequence of str
        "approach"/"retract" of every step of the path planned (the first ``len(rows)``
        are used).
    fields : dict
        ``{step: (pressure, gap, deflection)}`` of the steps whose maps are kept.
    control : {"offset", "load"}
        What the path steps through.
    attrs : dict
        Provenance attributes (:data:`ATTRIBUTES`).
    heights : (nx, ny) array
        The rigid surface's heights h (length), float64 on the host.
    total_seconds : float
        Wall time of the path so far (s).

    Returns
    -------
    xarray.Dataset
        With the attributes ``pull_off`` (per A0, >= 0: the magnitude of the most negative
        load on retraction, 0 if none is negative; NaN when the retraction's last step
        still has repulsive contact or there is none), ``separated``, ``all_converged``,
        ``total_seconds``, ``control``, ``units`` and ``attrs``.
    """
    import xarray as xr

    n = len(rows)
    data = {}
    for name in PER_STEP:
        if name == "branch":
            data[name] = (STEP, np.array(branch[:n], dtype=str))
        elif _BY_NAME[name].kind == "U":
            data[name] = (STEP, np.array([r[name] for r in rows], dtype=str))
        else:  # the dtypes of the values (an empty path: float64)
            data[name] = (STEP, np.array([r[name] for r in rows]) if n else np.zeros(0))
    ds = add_fields(xr.Dataset(data, coords={STEP: np.arange(n)}), fields)
    ds["heights"] = (_SURFACE, heights)
    retract = [r for r, b in zip(rows, branch, strict=False) if b == "retract"]
    separated = bool(retract) and retract[-1]["repulsive_area"] == 0
    # not measured unless the retraction left the repulsive contact behind
    pull_off = max(0.0, -min(r["load"] for r in retract)) if separated else math.nan
    ds.attrs.update(
        {
            "control": control,
            "pull_off": pull_off,
            "separated": int(separated),
            "all_converged": int(all(r["converged"] for r in rows)),
            "total_seconds": total_seconds,
            **attrs,
            "units": _UNITS,
        }
    )
    return ds


def add_fields(ds, fields: dict):
    """``ds`` with the maps ``{step: (pressure, gap, deflection)}`` added on ``field_step``.

    Steps whose maps ``ds`` holds already are kept (as stored); the result holds every
    step's maps sorted by step, after the other variables. Without ``fields``, ``ds``
    itself.
    """
    if not fields:
        return ds
    fields = dict(fields)
    if FIELD_STEP in ds.coords:
        stored = [name for name in FIELDS if name in ds.variables]
        if stored != list(FIELDS):
            raise ParameterError(
                f"cannot add contact maps to a path holding only {', '.join(stored) or 'none'} "
                f"of {', '.join(FIELDS)}: add them before dropping any"
            )
        for k, step in enumerate(ds[FIELD_STEP].values):
            fields[int(step)] = tuple(np.asarray(ds[name].values[k]) for name in FIELDS)
        ds = ds.drop_vars([*FIELDS, FIELD_STEP])
    steps = sorted(fields)
    ds = ds.assign_coords({FIELD_STEP: steps})
    for i, name in enumerate(FIELDS):
        ds[name] = (_MAP, np.stack([fields[s][i] for s in steps]))
    return ds


#: The yes/no attributes: 1/0 in the dataset (netCDF has no boolean attribute, and a
#: dataset from approach_retract must stay writable by ``ds.to_netcdf``), True/False once
#: read back by :func:`read_path`.
FLAGS = ("separated", "all_converged")


def read_path(path, *, check: bool = True):
    """Open a path NetCDF file (loaded into memory); a one-line ParameterError if it is not one.

    With ``check`` (default) the dataset is checked by :func:`check_path`. The yes/no
    attributes :data:`FLAGS` (``separated``, ``all_converged``; stored as 1/0) are
    returned as Python ``bool``.
    """
    from ._io import read_netcdf

    ds = read_netcdf(path, refusal=f"path file {str(path)!r} is not a readable NetCDF file")
    if check:
        check_path(ds)
    for name in FLAGS:
        value = ds.attrs.get(name)
        if isinstance(value, (np.ndarray, np.generic)) and np.size(value) == 1:
            value = value.item()
        if isinstance(value, (bool, int)) and value in (0, 1):
            ds.attrs[name] = bool(value)
    return ds


_NOT_OURS = "(the file was edited or is not a roughcontact path)"


def check_path(ds) -> None:
    """Raise a one-line ParameterError unless ``ds`` is a path the analysis can read.

    Checked: the :data:`REQUIRED` variables and required attributes are there, every
    variable of :data:`VARIABLES` present has its dims, the attributes with a range are
    in it (``thickness`` may be inf: a half-space), ``grid`` is two grid sizes and the
    required numeric variables are finite at every step.
    """
    missing = [k for k in REQUIRED if k not in ds.variables]
    missing += [f"attribute {a.name}" for a in ATTRIBUTES if a.required and a.name not in ds.attrs]
    if missing:
        raise ParameterError(
            "path dataset lacks " + ", ".join(missing) + " (not written by roughcontact "
            "approach_retract / 'roughcontact path', or by an older version)"
        )
    for name in ds.variables:
        if name in _BY_NAME and tuple(ds[name].dims) != _BY_NAME[name].dims:
            raise ParameterError(
                f"path dataset variable {name} has dims ({', '.join(ds[name].dims)}), "
                f"expected ({', '.join(_BY_NAME[name].dims)}) {_NOT_OURS}"
            )
    for a in ATTRIBUTES:
        if a.accepted is None or a.name not in ds.attrs:
            continue
        value = ds.attrs[a.name]
        if isinstance(value, (np.ndarray, np.generic)) and np.size(value) == 1:
            value = value.item()  # NumPy scalars from the file as Python numbers
        half_space = a.name == "thickness" and _is_inf(value)
        if not half_space and not a.accepted.contains(value):
            raise ParameterError(
                f"path dataset attribute {a.name} = {value!r} is out of range: accepted "
                f"{a.accepted.accepted} {_NOT_OURS}"
            )
    if "grid" in ds.attrs:
        _check_grid(ds)
    for name in REQUIRED:
        if _BY_NAME[name].kind == "U":
            continue
        values = np.asarray(ds[name].values)
        if values.dtype.kind not in "fiub" or not np.all(np.isfinite(values)):
            raise ParameterError(
                f"path dataset variable {name} must hold finite numbers at every step {_NOT_OURS}"
            )


def _is_inf(value) -> bool:
    return isinstance(value, (float, np.floating)) and value == math.inf


#: bytes per grid site that analysing a path may need (its substrate's kernel and a
#: hard-wall reference solve on the grid of the attribute ``grid``)
ANALYSIS_BYTES_PER_SITE = 160


def _check_grid(ds) -> None:
    """``grid``: two grid sizes, those of the heights and maps the file holds, and a grid
    whose analysis fits in memory, checked before anything of that size is allocated."""
    from ._validate import fits_in_memory

    raw = ds.attrs["grid"]
    grid = np.atleast_1d(raw)
    if grid.size != 2 or not all(GRID_SIZE.contains(g) for g in grid):
        raise ParameterError(
            f"path dataset attribute grid = {raw!r} is out of range: "
            f"accepted two grid sizes, each {GRID_SIZE.accepted}"
        )
    shape = (int(grid[0]), int(grid[1]))
    held = tuple(ds.sizes[d] for d in _SURFACE if d in ds.sizes)
    if len(held) == 2 and held != shape:
        raise ParameterError(
            f"path dataset attribute grid = {list(shape)} disagrees with the {held[0]} x "
            f"{held[1]} grid of the heights and maps the file holds {_NOT_OURS}"
        )
    fits_in_memory(
        "path dataset attribute grid",
        list(shape),
        ANALYSIS_BYTES_PER_SITE * shape[0] * shape[1],
        f"analysing a path on a {shape[0]} x {shape[1]} grid",
        ANALYSIS_BYTES_PER_SITE,
    )


def write_path(ds, path, *, encoding=None, attrs=None, opener=None):
    """Write a path dataset atomically: the file holds the old version or the new, never half.

    Through :func:`roughcontact._io.write_netcdf_atomic` (built in memory, written to a
    fresh temporary file, renamed over ``path``); ``encoding``, ``attrs`` (added to the
    file's attributes, not to ``ds``) and ``opener`` as there. A full disk raises
    :class:`roughcontact._io.WriteError` (one line) with ``path`` as it was. The
    :data:`FLAGS` of a dataset from :func:`read_path` (bool) are written as 1/0.
    """
    from ._io import write_netcdf_atomic

    if any(isinstance(ds.attrs.get(name), bool) for name in FLAGS):
        ds = ds.copy(deep=False)
        ds.attrs = dict(ds.attrs)
        for name in FLAGS:
            if isinstance(ds.attrs.get(name), bool):
                ds.attrs[name] = int(ds.attrs[name])
    return write_netcdf_atomic(ds, path, encoding=encoding, attrs=attrs, opener=opener)
