"""Assemble a :class:`ContactResult` from solved fields."""

from __future__ import annotations

import numpy as np
from array_api_compat import is_jax_array  # (looks at sys.modules: imports no jax)

from .._backend import array_namespace
from ..analysis.contact_geometry import boundary_bonds
from .reductions import fetch
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
    outcome=None,
):
    """Build the result record; ``repulsive``/``attractive`` masks default to p > 0 / none.

    ``status`` (a :class:`SolveStatus`) gives ``converged``. ``outcome``: ``(scalars,
    resolve)``, a loop's device scalars read in the record's one transfer and
    ``resolve(values) -> (iterations, residual, status, message[, offset])`` of their
    values, which replace the positional ones (a compiled loop whose outcome is read with
    its record; ``offset`` a device scalar before, e.g. moved by load control).

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
    # a free-boundary solve is a window: its edge is not a contact boundary
    # the record's scalars in one transfer (a GPU waits once)
    f64 = xp.float64
    if is_jax_array(pressure):  # fixed shapes: a boolean gather compiles anew per count
        p_rep, p_att = xp.where(repulsive, pressure, 0.0), xp.where(attractive, pressure, 0.0)
    else:
        p_rep, p_att = pressure[repulsive], pressure[attractive]
    sums = fetch(xp, [
        xp.sum(p_rep, dtype=f64), xp.sum(p_att, dtype=f64),
        xp.sum(pressure, dtype=f64), xp.sum(gap, dtype=f64), xp.count_nonzero(repulsive),
        xp.count_nonzero(attractive), boundary_bonds(repulsive, periodic=substrate.periodic),
        *(() if outcome is None else outcome[0]),
    ])  # fmt: skip
    if outcome is not None:
        iterations, residual, status, message, *moved = outcome[1](sums[7:])
        offset = moved[0] if moved else offset
    p_rep, p_att, p_all, gap_sum, n_rep, n_att, edges = sums[:7]
    edges = int(edges)
    a0 = substrate.pixel_size
    return ContactResult(
        offset=float(offset),
        load=p_all / n,
        repulsive_load=p_rep / n,
        attractive_load=-p_att / n,
        repulsive_area=n_rep / n,
        attractive_area=n_att / n,
        perimeter=edges * np.pi / 4 * a0 / substrate.nominal_area,
        perimeter_edges=edges,
        mean_gap=gap_sum / n,
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
