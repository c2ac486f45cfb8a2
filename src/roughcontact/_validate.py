"""Input checks that name the parameter and the accepted range."""

from __future__ import annotations

import math

import numpy as np


class ParameterError(ValueError):
    """A parameter is outside its accepted range; the message names both."""


def positive(name: str, value, *, allow_inf: bool = False) -> float:
    """Return ``float(value)`` if it is finite and > 0, else raise :class:`ParameterError`."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a positive number, got {value!r}") from None
    if not (v > 0) or (math.isinf(v) and not allow_inf) or math.isnan(v):
        raise ParameterError(f"{name} must be > 0 and finite, got {value!r}")
    return v


def in_range(name: str, value, lo: float, hi: float) -> float:
    """Return ``float(value)`` if ``lo <= value <= hi``, else raise :class:`ParameterError`."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number in [{lo}, {hi}], got {value!r}") from None
    if not (lo <= v <= hi):
        raise ParameterError(f"{name} must be in [{lo}, {hi}], got {value!r}")
    return v


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


def heights2d(name: str, heights):
    """Check that a height map is a 2D array of finite reals (NumPy input: as float64)."""
    from ._backend import array_namespace, is_numpy_array

    if not hasattr(heights, "shape"):
        heights = np.asarray(heights, dtype=float)
    if heights.ndim != 2:
        raise ParameterError(f"{name} must be a 2D array, got {heights.ndim} dimension(s)")
    if heights.shape[0] < 2 or heights.shape[1] < 2:
        raise ParameterError(f"{name} must be at least 2x2, got shape {tuple(heights.shape)}")
    xp = array_namespace(heights)
    if is_numpy_array(heights) and heights.dtype not in (np.float64, np.float32):
        heights = np.asarray(heights, dtype=float)
    if not bool(xp.all(xp.isfinite(heights))):
        raise ParameterError(f"{name} must be finite everywhere (found NaN or inf)")
    return heights


def finite(name: str, value) -> float:
    """Return ``float(value)`` if it is a finite real number, else raise ParameterError."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a finite real number, got {value!r}") from None
    if not math.isfinite(v):
        raise ParameterError(f"{name} must be a finite real number, got {value!r}")
    return v


def nonnegative_array(name: str, value):
    """``value`` as a float array (or 0-d array) that is finite and >= 0."""
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number or array >= 0, got {value!r}") from None
    if not np.all(np.isfinite(v)) or np.any(v < 0):
        raise ParameterError(f"{name} must be finite and >= 0, got {value!r}")
    return v


def positive_array(name: str, value):
    """``value`` as a float array (or 0-d array) that is finite and > 0."""
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a positive number or array, got {value!r}") from None
    if v.size == 0 or not np.all(np.isfinite(v)) or np.any(v <= 0):
        raise ParameterError(f"{name} must be > 0 and finite, got {value!r}")
    return v


def json_ready(record) -> dict:
    """A dataclass record as a JSON-ready dict: non-finite floats become ``None``."""
    from dataclasses import asdict

    return {
        k: (None if isinstance(v, float) and not math.isfinite(v) else v)
        for k, v in asdict(record).items()
    }
