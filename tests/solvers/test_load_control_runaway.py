"""Load control with strong adhesion finds the equilibrium that carries the load (issue
cases: 128², ℓa/a0 = 0.05, cold), including full contact and the jump into it, never a
runaway into the 9-3 core (once: uniform p = 3.7e13 E*, "stalled")."""

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import SolveStatus
from roughcontact.solvers.adhesive_rules import physical_pressure_scale

N = 128
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=7)
SUB = rc.Substrate((N, N))
LAW = rc.SmoothLJ93.from_adhesion_length(0.05)


def _check_equilibrium(res, load):
    assert res.status is SolveStatus.CONVERGED, res.message
    assert abs(res.load - load) <= res.tol  # E* = 1: the load tolerance tol E*
    scale = physical_pressure_scale(H, SUB, LAW)
    # pressures on the physical scale (the runaway had 3.7e13 E*)
    assert float(np.abs(res.pressure).max()) < 10 * (scale + abs(load))
    # the state is an equilibrium at its offset: an offset-controlled solve from it
    # stays there (no iteration needed beyond the tolerance's)
    again = rc.solve(H, SUB, LAW, offset=res.offset, initial=res)
    assert again.converged and abs(again.load - res.load) <= 10 * res.tol


@pytest.mark.parametrize("load", [1e-3, 0.0])
def test_strong_adhesion_load_control_carries_the_load(load):
    res = rc.solve(H, SUB, LAW, load=load)
    _check_equilibrium(res, load)
    assert 0.2 < res.repulsive_area < 1.0  # jumped into a large contact, not beyond


def test_load_control_reaches_full_contact():
    # a load that only full contact carries: every site repulsive, the offset's root in
    # the wall's own stiffness
    res = rc.solve(H, SUB, LAW, load=0.3)
    _check_equilibrium(res, 0.3)
    assert res.repulsive_area == 1.0


@pytest.mark.parametrize("periodic", [True, False], ids=["periodic", "free-boundary"])
def test_cold_tensile_load_finds_the_adhered_state(periodic):
    # a tensile load below the pull-off force: from first contact the surfaces used to be
    # opened up and reported detached; now into contact at load 0 first, then pulled
    n = 64
    h = rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=7)
    sub = rc.Substrate((n, n), periodic=periodic)
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    res = rc.solve(h, sub, law, load=-1e-3)
    assert res.status is SolveStatus.CONVERGED, res.message
    assert abs(res.load + 1e-3) <= res.tol and res.repulsive_area > 0.1
    assert float(np.abs(res.pressure).max()) < 1.0
    beyond = rc.solve(h, sub, law, load=-0.05)  # far beyond the pull-off force
    assert beyond.status is SolveStatus.DETACHED and not beyond.converged
