"""Input checks that name the parameter and the accepted range.

The accepted range of a parameter is written once, here (a :class:`Range` constant such
as :data:`TOL`), and checked from there by the Python API, the command line (option
callbacks, :func:`click_check`) and the study schema (:mod:`roughcontact.studies.schema`
takes its ``accepted`` text and test from the same constant).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._backend import array_namespace, is_numpy_array, to_numpy
from ._memory import available_memory as available_memory
from .errors import ParameterError


def _num(v) -> str:
    return f"{v:g}".replace("e+", "e")


def _is_number(value, integer: bool) -> bool:
    if isinstance(value, (bool, np.bool_)):
        return False
    if integer:
        return isinstance(value, (int, np.integer))
    return isinstance(value, (int, float, np.integer, np.floating))


@dataclass(frozen=True)
class Range:
    """The accepted values of one parameter: bounds (open or closed), integer or real.

    ``accepted`` is the range in words (as the messages and the study schema print it),
    ``contains`` the test and ``check`` the validation (a :class:`ParameterError` naming
    the parameter, the value and the range). Booleans and strings are never numbers
    here; real ranges reject NaN and infinities.
    """

    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    integer: bool = False

    @property
    def accepted(self) -> str:
        kind = "an integer " if self.integer else ""
        if self.lo is not None and self.hi is not None:
            left, right = "(" if self.lo_open else "[", ")" if self.hi_open else "]"
            return f"{kind}in {left}{_num(self.lo)}, {_num(self.hi)}{right}"
        finite = "" if self.integer else " and finite"
        if self.lo is not None:
            return f"{kind}{'>' if self.lo_open else '>='} {_num(self.lo)}{finite}"
        if self.hi is not None:
            return f"{kind}{'<' if self.hi_open else '<='} {_num(self.hi)}{finite}"
        return "an integer" if self.integer else "finite"

    def contains(self, value) -> bool:
        """Is ``value`` a number of the right kind inside the range?"""
        if not _is_number(value, self.integer):
            return False
        v = int(value) if self.integer else float(value)
        if not self.integer and not math.isfinite(v):
            return False
        if self.lo is not None and not (v > self.lo if self.lo_open else v >= self.lo):
            return False
        return self.hi is None or (v < self.hi if self.hi_open else v <= self.hi)

    def check(self, name: str, value):
        """``value`` (an int or a float) if :meth:`contains` it, else a ParameterError."""
        if not self.contains(value):
            kind = "an integer" if self.integer else "a number"
            what = "" if _is_number(value, self.integer) else f" ({kind})"
            raise ParameterError(f"{name} must be {self.accepted}{what}, got {value!r}")
        return int(value) if self.integer else float(value)


#: Solver tolerance (the solvers' residual measure); float32 has a floor of its own.
TOL = Range(0, 1, lo_open=True, hi_open=True)
#: Iteration cap of one solve.
MAX_ITER = Range(1, integer=True)
#: A_rep/A0 at which a path is analysed (and Fig. 1's maps are drawn).
TARGET_AREA = Range(0, 1, lo_open=True, hi_open=True)
#: Largest A_rep/A0 in the fit of A_rep against N.
FIT_MAX_AREA = Range(0, 1, lo_open=True)
#: Hurst exponent of a self-affine surface.
HURST = Range(0, 1, lo_open=True)
#: Random seed of a surface (NumPy's SeedSequence takes integers >= 0).
SEED = Range(0, integer=True)
#: Grid spacing a0 (length): a0**11 (the 9-3 wall's curvature), a0**3 (energies) and n² a0²
#: (areas) stay normal floats; any unit system fits (a0 = 1e-10 m in SI).
PIXEL_SIZE = Range(1e-25, 1e25)
#: Contact modulus E* (pressure): loads, stiffnesses and energies (E* a0**3) stay normal.
CONTACT_MODULUS = Range(1e-100, 1e100)
#: Thickness of a layer in units of the pixel size (thinner layers are too stiff for the
#: solvers' float64 residuals; thicker ones overflow the layer stiffness).
THICKNESS_RATIO = Range(1e-6, 1e100)
#: Poisson ratio of a layer.
POISSON = Range(0, 0.5)
#: Grid size along one axis (sites).
GRID_SIZE = Range(2, integer=True)
#: Resolution of raster figures (dots per inch).
DPI = Range(10, 2400, integer=True)
#: The most steps of the approach of a path (the retraction doubles it).
MAX_PATH_STEPS = 100_000


def click_check(rng: Range):
    """A click option callback that checks the option's value against ``rng``.

    The error names the option as typed (``--tol``); None (option not given) passes.
    Multiple options are checked value by value.
    """

    def callback(ctx, param, value):
        if value is None:
            return value
        name = max(param.opts, key=len) if param.opts else param.name
        if isinstance(value, tuple):
            return tuple(rng.check(name, v) for v in value)
        return rng.check(name, value)

    return callback


def layer_thickness(name: str, thickness, pixel_size: float) -> float:
    """A layer thickness (length) in :data:`THICKNESS_RATIO` times the pixel size."""
    t = Range(0, lo_open=True).check(name, thickness)
    if not THICKNESS_RATIO.contains(t / pixel_size):
        lo, hi = (b * pixel_size for b in (THICKNESS_RATIO.lo, THICKNESS_RATIO.hi))
        raise ParameterError(
            f"{name} must be in [{_num(THICKNESS_RATIO.lo)}, {_num(THICKNESS_RATIO.hi)}] x "
            f"pixel_size = [{_num(lo)}, {_num(hi)}] (length), got {thickness!r}"
        )
    return t


def surface_seed(name: str, value):
    """Check a surface seed: None, a Generator/SeedSequence, or integer(s) >= 0."""
    if value is None or isinstance(value, (np.random.Generator, np.random.SeedSequence)):
        return value
    if isinstance(value, (list, tuple)):
        for v in value:
            SEED.check(name, v)
        return value
    if isinstance(value, np.random.BitGenerator):
        return value
    return SEED.check(name, value)


#: the loosest tolerance in float32: beyond it a single-precision solve stops before its
#: answer means anything (A_rep 0.110 at tol 0.999 against 0.026 converged)
MAX_TOL_FLOAT32 = 0.1


def tolerance(name: str, value, precision: str = "float64", floor: float = 1e-6) -> float:
    """Check a solver tolerance: :data:`TOL`, and in float32 ``[floor, MAX_TOL_FLOAT32]``
    (below the floor its rounding hides the residual, above 0.1 the answer is noise)."""
    tol = TOL.check(name, value)
    if precision == "float32" and tol < floor:
        raise ParameterError(
            f"{name} must be >= {floor:g} with dtype='float32' (single precision cannot "
            f"resolve smaller residuals), got {value!r}; use dtype='float64'"
        )
    if precision == "float32" and tol > MAX_TOL_FLOAT32:
        raise ParameterError(
            f"{name} must be in [{floor:g}, {MAX_TOL_FLOAT32:g}] with dtype='float32' (a "
            f"looser single-precision solve stops before its answer means anything), got "
            f"{value!r}"
        )
    return tol


def step_list(name: str, steps) -> list[int]:
    """``steps`` (an int or a sequence of ints; no bools, no floats) as a list of ints."""
    if _is_number(steps, True):
        steps = [steps]
    try:
        steps = list(steps)
    except TypeError:
        raise ParameterError(
            f"{name} must be a list of integer step indices, got {steps!r}"
        ) from None
    for step in steps:
        if not _is_number(step, True):
            raise ParameterError(f"{name} must be integer step indices, got {step!r}")
    return [int(step) for step in steps]


def step_indices(name: str, steps, size: int) -> list[int]:
    """Step indices of a path of ``size`` steps, negative ones counted from the end.

    Returns them as indices in ``[0, size)``; an index outside ``[-size, size)`` is a
    ParameterError naming the accepted range.
    """
    out = []
    for i in step_list(name, steps):
        if not -size <= i < size:
            raise ParameterError(
                f"{name} step {i} is out of range for a path of {size} steps: accepted "
                f"{-size} to {size - 1} (negative: counted from the end)"
            )
        out.append(i % size)
    return out


def _gib(nbytes: float) -> str:
    if nbytes >= 2**40:
        return f"{nbytes / 2**40:.3g} TiB"
    return f"{nbytes / 2**30:.3g} GiB"


def fits_in_memory(name: str, value, needed: float, what: str, per_item: float = 0.0):
    """Raise a ParameterError if ``needed`` bytes exceed the memory available here.

    ``per_item`` (bytes per grid site) lets the message give the largest square grid
    that would fit.
    """
    free = available_memory()
    if free is None or needed <= free:
        return
    n = math.isqrt(int(free / per_item)) if per_item else 0
    largest = f"; accepted here: up to about {n} x {n} sites" if per_item else ""
    raise ParameterError(
        f"{name} = {value!r} is too large: {what} needs about {_gib(needed)} of memory, "
        f"more than the {_gib(free)} available{largest}"
    )


#: The magnitudes :func:`positive` accepts: their squares and inverse squares are normal
#: floats, so no quantity derived from them silently becomes 0 or inf (any unit system
#: fits well inside).
MAGNITUDE = (1e-150, 1e150)


def positive(name: str, value, *, allow_inf: bool = False) -> float:
    """Return ``float(value)`` if it is > 0 and finite, else raise :class:`ParameterError`.

    Magnitudes outside :data:`MAGNITUDE` are rejected too (``inf`` passes with
    ``allow_inf``).
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a positive number, got {value!r}") from None
    if not (v > 0) or (math.isinf(v) and not allow_inf) or math.isnan(v):
        raise ParameterError(f"{name} must be > 0 and finite, got {value!r}")
    lo, hi = MAGNITUDE
    if not (lo <= v <= hi or math.isinf(v)):
        raise ParameterError(
            f"{name} must be > 0 and finite, in [{_num(lo)}, {_num(hi)}], got {value!r}"
        )
    return v


def _checked(name: str, value, convert, ok, not_a_number: str, bad: str):
    """``convert(value)`` if ``ok`` of it, else a :class:`ParameterError`: ``not_a_number``
    when ``convert`` refuses the value, ``bad`` when it fails ``ok`` (message templates with
    ``{name}`` and ``{value!r}``, formatted only on failure: a large array's repr is slow)."""
    try:
        v = convert(value)
    except (TypeError, ValueError):
        raise ParameterError(not_a_number.format(name=name, value=value)) from None
    if not ok(v):
        raise ParameterError(bad.format(name=name, value=value))
    return v


def in_range(name: str, value, lo: float, hi: float) -> float:
    """Return ``float(value)`` if ``lo <= value <= hi``, else raise :class:`ParameterError`."""
    return _checked(
        name, value, float, lambda v: lo <= v <= hi,
        f"{{name}} must be a number in [{lo}, {hi}], got {{value!r}}",
        f"{{name}} must be in [{lo}, {hi}], got {{value!r}}",
    )  # fmt: skip


def shape2d(name: str, shape) -> tuple[int, int]:
    """Normalise an int or a pair of ints to a 2D grid shape (each >= 2)."""
    if isinstance(shape, (int, np.integer)):
        shape = (int(shape), int(shape))
    try:
        nx, ny = (int(s) for s in shape)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be an int or a pair of ints, got {shape!r}") from None
    if nx < 2 or ny < 2:
        raise ParameterError(f"{name} must have both sizes >= 2, got {(nx, ny)}")
    return nx, ny


_KIND_WORDS = {"b": "boolean", "c": "complex", "O": "object", "U": "text", "S": "text",
               "V": "structured", "M": "datetime", "m": "timedelta"}  # fmt: skip


def _dtype_kind(x) -> str:
    """NumPy's one-letter kind of an array's dtype, for any array-API backend."""
    try:
        return np.dtype(x.dtype).kind
    except TypeError:
        xp = array_namespace(x)
        for kind, words in (("f", "real floating"), ("i", "integral"), ("c", "complex floating")):
            if xp.isdtype(x.dtype, words):
                return kind
        return "b"


def real_array(name: str, heights):
    """``heights`` as an array if it holds real numbers (no bool/complex/object/text/mask).

    Array-likes (lists) become NumPy arrays; arrays are returned as given. Nothing is
    converted silently: a complex array would lose its imaginary part, a masked one its
    mask, a boolean one would read as heights 0 and 1.
    """
    if isinstance(heights, np.ma.MaskedArray):
        raise ParameterError(
            f"{name} must be a plain array of real numbers, got a masked array (its mask "
            "would be ignored); fill the masked sites first (e.g. heights.filled(value))"
        )
    if not hasattr(heights, "shape") or not hasattr(heights, "dtype"):
        try:
            heights = np.asarray(heights)
        except (TypeError, ValueError) as err:
            raise ParameterError(
                f"{name} must be a 2D array of real numbers, got {type(heights).__name__} ({err})"
            ) from None
    kind = _dtype_kind(heights)
    if kind not in "fiu":
        raise ParameterError(
            f"{name} must hold real numbers (float or integer), got dtype {heights.dtype} "
            f"({_KIND_WORDS.get(kind, kind)}); accepted: a 2D array of finite real heights"
        )
    return heights


def heights2d(name: str, heights):
    """Check that a height map is a 2D array of finite reals (NumPy input: as float64).

    Rejected: boolean, complex, object or text arrays, masked arrays, NaN or inf, and
    heights so large that their rms (a sum of squares) overflows.
    """
    heights = real_array(name, heights)
    if heights.ndim != 2:
        raise ParameterError(f"{name} must be a 2D array, got {heights.ndim} dimension(s)")
    if heights.shape[0] < 2 or heights.shape[1] < 2:
        raise ParameterError(f"{name} must be at least 2x2, got shape {tuple(heights.shape)}")
    xp = array_namespace(heights)
    if is_numpy_array(heights) and heights.dtype not in (np.float64, np.float32):
        heights = np.asarray(heights, dtype=float)
    if is_numpy_array(heights):
        finite, top = bool(np.isfinite(heights).all()), None
    elif xp.isdtype(heights.dtype, "real floating"):  # both scalars in one transfer
        wide = [xp.astype(xp.all(xp.isfinite(heights)), xp.float64), xp.max(xp.abs(heights))]
        finite, top = (float(v) for v in to_numpy(xp.stack(
            [v if v.dtype == xp.float64 else xp.astype(v, xp.float64) for v in wide])))  # fmt: skip
        finite = finite > 0
    else:
        finite, top = bool(xp.all(xp.isfinite(heights))), None
    if not finite:
        raise ParameterError(f"{name} must be finite everywhere (found NaN or inf)")
    _rms_is_finite(name, heights, xp, top)
    return heights


def _rms_is_finite(name, heights, xp, top=None) -> None:
    """Reject heights whose rms overflows (checked exactly only when |h| is that large);
    ``top``: max |h| when the caller has it."""
    if not xp.isdtype(heights.dtype, "real floating"):
        return
    top = float(xp.max(xp.abs(heights))) if top is None else top
    limit = math.sqrt(float(xp.finfo(heights.dtype).max)) * 1e-3
    if top <= limit:
        return
    with np.errstate(over="ignore", invalid="ignore"):
        centred = heights - xp.mean(heights)
        rms = float(xp.sqrt(xp.mean(centred * centred)))
    if not math.isfinite(rms):
        raise ParameterError(
            f"{name} have an rms that overflows in {heights.dtype} (|h| up to "
            f"{_num(top)}): accepted heights with a finite rms (|h| below about "
            f"{_num(float(f'{limit:.0e}'))}); rescale the length unit"
        )


def finite(name: str, value) -> float:
    """Return ``float(value)`` if it is a finite real number, else raise ParameterError."""
    message = "{name} must be a finite real number, got {value!r}"
    return _checked(name, value, float, math.isfinite, message, message)


def nonnegative(name: str, value) -> float:
    """Return ``float(value)`` if it is finite and >= 0, else raise ParameterError."""
    return _checked(
        name, value, float, lambda v: v >= 0 and not math.isinf(v),
        "{name} must be a number >= 0, got {value!r}",
        "{name} must be finite and >= 0, got {value!r}",
    )  # fmt: skip


def _float_array(value):
    return np.asarray(value, dtype=float)


def nonnegative_array(name: str, value):
    """``value`` as a float array (or 0-d array) that is finite and >= 0."""
    return _checked(
        name, value, _float_array, lambda v: np.all(np.isfinite(v)) and not np.any(v < 0),
        "{name} must be a number or array >= 0, got {value!r}",
        "{name} must be finite and >= 0, got {value!r}",
    )  # fmt: skip


def positive_array(name: str, value):
    """``value`` as a float array (or 0-d array) that is finite and > 0."""
    return _checked(
        name, value, _float_array,
        lambda v: v.size > 0 and np.all(np.isfinite(v)) and not np.any(v <= 0),
        "{name} must be a positive number or array, got {value!r}",
        "{name} must be > 0 and finite, got {value!r}",
    )  # fmt: skip


def json_ready(record) -> dict:
    """A dataclass record as a JSON-ready dict: non-finite floats become ``None``."""
    from dataclasses import asdict

    return {
        k: (None if isinstance(v, float) and not math.isfinite(v) else v)
        for k, v in asdict(record).items()
    }


class JsonRecord:
    """Base of a dataclass result whose :meth:`to_dict` is :func:`json_ready`."""

    __slots__ = ()

    def to_dict(self) -> dict:
        """JSON-ready dict; non-finite numbers become ``None``."""
        return json_ready(self)


def json_safe(obj):
    """``obj`` with every non-finite float (NaN, inf) replaced by None, recursively.

    For ``json.dumps(..., allow_nan=False)``: JSON has no NaN or Infinity. NumPy scalars
    become Python numbers; dicts, lists and tuples are walked.
    """
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_safe(v) for v in obj]
    if isinstance(obj, (np.bool_,)):
        return bool(obj)
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        v = float(obj)
        return v if math.isfinite(v) else None
    return obj
