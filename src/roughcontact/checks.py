r"""Property checks shipped with the library (run them on your own surfaces and laws).

* :func:`total_energy` -- elastic plus interaction energy of a solved state,
  :math:`E = E_{el}(w) + a_0^2 \sum_i V(g_i)` (pressure × length³).
* :func:`load_work_balance` -- along a reversible displacement-controlled branch the work
  of the load equals the change of the minimised energy, because
  :math:`dE_{min}/dd = -N` (envelope theorem); a solver, substrate or law whose forces
  are not the gradient of its energy fails this check.
"""

from __future__ import annotations

import numpy as np

from ._backend import array_namespace

__all__ = ["load_work_balance", "total_energy"]


def total_energy(result, substrate, interaction) -> float:
    """Elastic plus interaction energy of ``result`` (pressure × length³)."""
    xp = array_namespace(result.gap)  # summed where the result's fields are
    site_energy = float(xp.sum(interaction.energy(result.gap)))
    return substrate.energy(result.deflection) + substrate.pixel_size**2 * site_energy


def load_work_balance(heights, substrate, interaction, offsets, *, tol=1e-11):
    r"""Energy change and load work along warm-started displacement-controlled states.

    Parameters
    ----------
    heights, substrate, interaction
        As for :func:`roughcontact.solve`.
    offsets : sequence of float
        Offsets d (length) of one reversible branch, in order.
    tol : float
        Solver tolerance (tight: the balance is only as good as the states).

    Returns
    -------
    (energy_change, work) : (float, float)
        :math:`E(d_{last}) - E(d_0)` and :math:`-\int N\,dd` (trapezoidal rule), both in
        pressure × length³; equal to the rule's accuracy for a correct solver.

    Raises
    ------
    RuntimeError
        If a state does not converge (the balance would be meaningless).
    """
    from .solvers import solve

    previous, loads, energies = None, [], []
    for d in offsets:
        previous = solve(heights, substrate, interaction, offset=d, initial=previous, tol=tol)
        if not previous.converged:
            raise RuntimeError(f"state at offset {d:g} did not converge: {previous.message}")
        loads.append(previous.load * substrate.nominal_area)
        energies.append(total_energy(previous, substrate, interaction))
    return energies[-1] - energies[0], float(-np.trapezoid(loads, offsets))
