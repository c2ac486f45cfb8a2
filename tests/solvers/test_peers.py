"""Cross-checks of the hard-wall solver against the peer libraries tamaas and
ContactMechanics (test-only dependencies; each test skips when its peer is missing).

All three codes discretise the periodic half-space the same way: the continuum
stiffness k(q) = E*|q|/2 evaluated on the FFT wavevectors (|q| from the wrapped
indices, Nyquist included), applied to nodal pressures. tamaas' displacement from its
pressure reproduces ``Substrate.deflection`` to 1e-15; ContactMechanics differs only at
q = 0 (it gives the uniform mode the stiffness of the lowest mode instead of a rigid
one), which shifts its mean displacement and is absorbed in its offset — the pressure
and the gap are unaffected. So there is no systematic difference: the solutions agree
to the solvers' tolerance and the contact sets are identical (measured at tol = 1e-10
on these surfaces: pressure relative L2 differences 1e-10 (rough) and 1e-9 (sphere),
offsets 1e-11, 0 differing contact pixels).

Sign conventions, checked on the paraboloid (summit at the centre of the cell):
* tamaas: heights point at the elastic body like ours (no sign flip);
  ``model.traction`` is p (> 0 compressive), ``model.displacement`` is d + w, so the
  offset is its mean; ``solve(p_mean)`` imposes the mean pressure; E* = E/(1 - nu^2).
* ContactMechanics: heights point at the substrate like ours; the gap is
  u - h - offset_CM with u positive into the substrate, so d = mean(u) - offset_CM;
  ``result.jac`` holds pixel forces (> 0 compressive), equal to pressures for a0 = 1;
  the load is the total force ``external_force = p_mean * n^2 * a0^2``.
"""

from __future__ import annotations

import numpy as np
import pytest

import roughcontact as rc

pytestmark = pytest.mark.peers

N = 128
TOL = 1e-10  # each code's own tolerance; all three reach ~1e-10 relative L2 here
# Agreement asserted: measured 1e-10 (rough) / 1e-9 (sphere) pressure rel. L2 at TOL,
# limited by the solvers' convergence, not by the discretisation; 10-100x margin.
PRESSURE_RTOL = 2e-8
OFFSET_ATOL = 1e-8  # lengths in units of a0; measured <= 2e-10
MAX_PIXEL_MISMATCH = 2  # contact sets agree exactly in practice


def _rough():
    h = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=8, long_cutoff=N / 2, seed=1)
    return h, 1e-3  # ~2 % contact


def _sphere():
    radius = 200.0
    h = rc.sphere((N, N), radius)
    # Hertz: a = (3 F R / (4 E*))^(1/3); aim at a contact area of 3 % of the cell
    a = np.sqrt(0.03 * N * N / np.pi)
    return h, 4 * a**3 / (3 * radius) / N**2


SURFACES = {"rough": _rough, "sphere": _sphere}


def _solve_rc(h, load):
    sub = rc.Substrate(h.shape, contact_modulus=1.0, pixel_size=1.0)
    res = rc.solve(h, sub, rc.HardWall(), load=load, tol=TOL)
    assert res.converged, res.message
    return res.pressure, res.offset


def _solve_tamaas(h, load):
    tm = pytest.importorskip("tamaas")
    n0, n1 = h.shape
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [float(n0), float(n1)], [n0, n1])
    model.E, model.nu = 1.0, 0.0  # E* = E / (1 - nu^2) = 1
    heights = np.ascontiguousarray(h, dtype=np.float64)
    solver = tm.PolonskyKeerRey(model, heights, TOL)
    solver.dump_freq = 10**9
    solver.max_iter = 10_000
    err = solver.solve(load)  # mean pressure
    assert err <= TOL
    disp = np.array(model.displacement)
    return np.array(model.traction), float(disp.mean())


def _solve_cm(h, load):
    pytest.importorskip("ContactMechanics")
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from ContactMechanics.Optimization.ConstrainedConjugateGradients import (
        constrained_conjugate_gradients,
    )

    n0, n1 = h.shape
    size = (float(n0), float(n1))
    # stiffness_q0=None (default): the uniform mode gets the lowest mode's stiffness.
    # stiffness_q0=0 would match our rigid uniform mode but breaks CM's load control.
    sub = PeriodicFFTElasticHalfSpace((n0, n1), 1.0, physical_sizes=size)
    res = constrained_conjugate_gradients(
        sub,
        np.asarray(h, dtype=np.float64),
        external_force=load * n0 * n1,  # total force, a0 = 1
        pentol=TOL * float(np.std(h)),
        forcetol=TOL * load,
        thermotol=TOL,
        maxiter=10_000,
    )
    assert res.success, res.message
    u = np.asarray(res.x)
    return np.asarray(res.jac), float(u.mean() - res.offset)


PEERS = {"tamaas": _solve_tamaas, "contactmechanics": _solve_cm}


def _compare(p, d, p_ref, d_ref, load):
    assert p.shape == p_ref.shape
    assert p.mean() == pytest.approx(load, rel=1e-12)
    assert p_ref.mean() == pytest.approx(load, rel=1e-12)
    assert p.min() >= 0.0
    c, c_ref = p > 0, p_ref > 0
    assert 0.01 < c_ref.mean() < 0.06
    assert np.count_nonzero(c != c_ref) <= MAX_PIXEL_MISMATCH
    assert abs(c.mean() - c_ref.mean()) < 1e-2 * c_ref.mean() + 2.0 / p.size
    rel = np.linalg.norm(p - p_ref) / np.linalg.norm(p_ref)
    assert rel < PRESSURE_RTOL
    assert d == pytest.approx(d_ref, abs=OFFSET_ATOL)


@pytest.mark.parametrize("surface", sorted(SURFACES))
@pytest.mark.parametrize("peer", sorted(PEERS))
def test_hardwall_matches_peer(peer, surface):
    """Same heights, same mean pressure: same pressure field, contact set and offset."""
    h, load = SURFACES[surface]()
    p_peer, d_peer = PEERS[peer](h, load)
    p, d = _solve_rc(h, load)
    _compare(p, d, p_peer, d_peer, load)


@pytest.mark.parametrize("surface", sorted(SURFACES))
def test_peers_agree_with_each_other(surface):
    """tamaas and ContactMechanics agree (a check of the conventions used above)."""
    h, load = SURFACES[surface]()
    p_tm, d_tm = _solve_tamaas(h, load)
    p_cm, d_cm = _solve_cm(h, load)
    _compare(p_cm, d_cm, p_tm, d_tm, load)


@pytest.mark.parametrize("peer", sorted(PEERS))
def test_sign_convention_paraboloid(peer):
    """The summit (maximum of h) is where the peer puts the contact, as we do."""
    h, load = _sphere()
    centre = np.unravel_index(np.argmax(h), h.shape)
    p_peer, _ = PEERS[peer](h, load)
    assert np.unravel_index(np.argmax(p_peer), p_peer.shape) == centre
    p, _ = _solve_rc(h, load)
    assert np.unravel_index(np.argmax(p), p.shape) == centre
