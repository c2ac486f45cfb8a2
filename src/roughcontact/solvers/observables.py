"""Assemble a :class:`ContactResult` from solved fields."""

from __future__ import annotations

import numpy as np

from .._backend import array_namespace
from ..analysis.contact_geometry import perimeter_edges
from .result import ContactResult, SolveStatus


def _sum64(x) -> float:
    """Sum of ``x`` accumulated in float64, also for float32 fields (single precision)."""
    xp = array_namespace(x)
    return float(xp.sum(x, dtype=xp.float64))


def make_result(
    heights,
    substrate,
    pressure,
    deflection,
    offset,
    iterations,
    residual,
    status,
    message,
    tol,
    solver,
    seconds,
    repulsive=None,
    attractive=None,
):
    """Build the result record; ``repulsive``/``attractive`` masks default to p > 0 / none.

    ``status`` (a :class:`SolveStatus`) gives ``converged``.

    The fields stay on the heights' backend and device (no copy to the host: a path on a
    GPU warm-starts each step from the last one there); the scalars are reduced there
    and only they reach the host. :meth:`ContactResult.to_numpy` is the edge.
    """
    xp = array_namespace(pressure)
    n = pressure.size
    gap = offset - heights + deflection
    if repulsive is None:
        repulsive = pressure > 0
    if attractive is None:
        attractive = xp.zeros_like(repulsive)
    rep_load = _sum64(pressure[repulsive]) / n
    att_load = -_sum64(pressure[attractive]) / n
    # a free-boundary solve is a window: its edge is not a contact boundary
    edges = perimeter_edges(repulsive, periodic=substrate.periodic)
    a0 = substrate.pixel_size
    return ContactResult(
        offset=float(offset),
        load=_sum64(pressure) / n,
        repulsive_load=rep_load,
        attractive_load=att_load,
        repulsive_area=float(xp.count_nonzero(repulsive)) / n,
        attractive_area=float(xp.count_nonzero(attractive)) / n,
        perimeter=edges * np.pi / 4 * a0 / substrate.nominal_area,
        perimeter_edges=edges,
        mean_gap=_sum64(gap) / n,
        iterations=int(iterations),
        residual=float(residual),
        converged=status is SolveStatus.CONVERGED,
        status=status,
        message=message,
        solve_seconds=float(seconds),
        nominal_area=substrate.nominal_area,
        pixel_size=a0,
        tol=float(tol),
        solver=solver,
        pressure=pressure,
        gap=gap,
        deflection=deflection,
    )
