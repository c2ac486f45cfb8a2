"""The hard-wall reference: κ_rep of the same surface with a hard wall, and the band δ."""

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.analysis.hard_wall_reference import band_width, hard_wall_reference
from roughcontact.analysis.path_analysis import analyze_path
from roughcontact.theory.hertz import hertz


@pytest.fixture(scope="module")
def rough():
    h = rc.self_affine((128, 128), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
    return h, rc.Substrate(h.shape)


def test_reference_against_the_hard_wall_solver_itself(rough):
    h, sub = rough
    ref = hard_wall_reference(h, sub, target_area=0.01)
    assert ref.converged and ref.solves <= 12
    # the hard-wall solve at the reported load has the target area (linear between
    # lattice states 2 % apart in load: within a few sites)
    at = rc.solve(h, sub, rc.HardWall(), load=ref.load)
    assert at.repulsive_area == pytest.approx(0.01, abs=4 / h.size)
    at = rc.solve(h, sub, rc.HardWall(), load=ref.corrected_load)
    assert at.corrected_repulsive_area == pytest.approx(0.01, abs=4 / h.size)
    slope = rc.statistics(h).rms_slope
    assert ref.kappa_rep == pytest.approx(slope * 0.01 / ref.load)
    # the corrected area is smaller than the site count, so its κ is smaller
    assert 1.5 < ref.kappa_rep_corrected < ref.kappa_rep < 3.5


def test_reference_on_a_sphere_follows_hertz():
    # corrected area = the continuum area: the load at which it is π a² is Hertz's
    n, radius = 128, 200.0
    h = rc.sphere((n, n), radius)
    sub = rc.Substrate((n, n))
    target = math.pi * 12.0**2 / n**2  # a = 12 a0
    ref = hard_wall_reference(h, sub, target_area=target, rms_slope=1.0)
    a = math.sqrt(target * n**2 / math.pi)
    hertz_load = 4 * a**3 / (3 * radius) / n**2  # N/A0 for a = 12 (E* = 1)
    assert ref.corrected_load == pytest.approx(hertz_load, rel=0.04)
    assert hertz(load=ref.corrected_load * n**2, radius=radius, contact_modulus=1.0
                 ).contact_radius == pytest.approx(a, rel=0.015)  # fmt: skip


def test_band_of_a_soft_wall_on_a_sphere():
    # Hertz gives the hard-wall area at the soft wall's repulsive load; the soft wall
    # adds a band δ ≈ (A_rep − π a_H²)/P. The lattice count of the hard wall exceeds
    # π a_H² by Yastrebov's bias, ~0.118 n_e a0² ≈ 0.15 a0 × P: the tolerance.
    n, radius = 128, 200.0
    h = rc.sphere((n, n), radius)
    sub = rc.Substrate((n, n))
    law = rc.SmoothLJ93.from_adhesion_length(1e-7)  # the paper's wall, no adhesion to speak of
    ds = rc.approach_retract(h, sub, law, offsets=1.0 - np.linspace(0.0, 1.2, 25), retract=False)
    target = math.pi * 12.0**2 / n**2
    r = analyze_path(ds, target_area=target, heights=h)
    a_h = hertz(load=r.repulsive_load * n**2, radius=radius, contact_modulus=1.0).contact_radius
    oracle = (target - math.pi * a_h**2 / n**2) / r.perimeter
    assert r.band_width == pytest.approx(oracle, abs=0.2)
    assert 0.3 < r.band_width < 1.5  # a fraction of a0 to one a0, as on rough surfaces
    assert r.band_fraction == pytest.approx(math.pi * r.band_width / r.d_rep)
    assert r.kappa_rep_hard_wall < r.kappa_rep


def test_band_width_definition_and_bad_input():
    assert band_width(0.012, 0.010, 0.004) == pytest.approx(0.5)
    with pytest.raises(rc.ParameterError, match="perimeter"):
        band_width(0.01, 0.01, 0.0)
    with pytest.raises(rc.ParameterError, match="target_area"):
        hard_wall_reference(np.zeros((8, 8)), rc.Substrate((8, 8)), target_area=2.0)
