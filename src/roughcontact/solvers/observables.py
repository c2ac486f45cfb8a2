"""Assemble a :class:`ContactResult` from solved fields."""

from __future__ import annotations

import numpy as np

from .._backend import to_numpy
from ..analysis.contact_geometry import perimeter_edges
from .result import ContactResult, SolveStatus


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

    Fields of any backend are copied to host NumPy here, once per solve (the record is
    an edge: files, analysis, plots).
    """
    heights, pressure, deflection = (to_numpy(a) for a in (heights, pressure, deflection))
    if repulsive is not None:
        repulsive = to_numpy(repulsive)
    if attractive is not None:
        attractive = to_numpy(attractive)
    n = pressure.size
    gap = offset - heights + deflection
    if repulsive is None:
        repulsive = pressure > 0
    if attractive is None:
        attractive = np.zeros_like(repulsive)
    # accumulated in float64 also for float32 fields (the single-precision option)
    rep_load = float(pressure[repulsive].sum(dtype=np.float64)) / n
    att_load = -float(pressure[attractive].sum(dtype=np.float64)) / n
    edges = perimeter_edges(repulsive)
    a0 = substrate.pixel_size
    return ContactResult(
        offset=float(offset),
        load=float(pressure.sum(dtype=np.float64)) / n,
        repulsive_load=rep_load,
        attractive_load=att_load,
        repulsive_area=float(np.count_nonzero(repulsive)) / n,
        attractive_area=float(np.count_nonzero(attractive)) / n,
        perimeter=edges * np.pi / 4 * a0 / substrate.nominal_area,
        perimeter_edges=edges,
        mean_gap=float(gap.mean(dtype=np.float64)),
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
