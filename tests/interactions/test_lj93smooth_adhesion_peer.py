r"""Cross-check of :class:`SmoothLJ93` against the peer library Adhesion (test-only).

Adhesion 0.93 builds the paper's smoothed 9-3 wall by decorating its plain ``LJ93``
with a quartic spline tail::

    LJ93(epsilon, sigma).spline_cutoff(gamma=w)      # Adhesion.Interactions

(``spline_cutoff`` is ``SmoothPotential`` registered on ``Potential``; there is no
separate ``LJ93smooth`` class in this version). Its conventions, read from its source:

* ``LJ93.evaluate(g, potential, gradient, curvature)`` returns ``(V, dV/dg, d2V/dg2)``:
  the *gradient*, not a force. Our ``pressure`` is ``-dV/dg`` (> 0 repulsive); its
  ``SmoothContactSystem`` makes the same pixel force ``-dV/dg * a0^2``.
* ``V_LJ = eps [(2/15)(sigma/g)^9 - (sigma/g)^3]``: the same function as ours, with the
  minimum at ``r_min = sigma (2/5)^(1/6)``. So ``sigma = a0 (5/2)^(1/6)``, and
  ``eps = k a0^2 / (12 [(sigma/a0)^9 - (sigma/a0)^3])`` from its ``V''``.
* The potential is per unit area (the system multiplies by the pixel area), like ours.
* ``SmoothPotential`` with the default transition ``r_t = r_min`` keeps the LJ core
  below ``r_t`` shifted by ``offset = V_LJ(r_t) + gamma`` (so ``V(r_min) = -gamma``) and
  continues it by the quartic with a triple zero at the cutoff ``r_c`` that matches
  ``V'`` (= 0) and ``V''`` (= k) at ``r_t``. That quartic is unique, and it is ours,
  ``-w (1 - x)^3 (1 + 3x)``; its depth condition gives ``r_c - r_t = sqrt(12 gamma / k)``,
  i.e. our ``w = k dr^2 / 12``. With ``gamma = w`` the two potentials are the same
  function; without ``gamma`` Adhesion uses the LJ depth ``-V_LJ(a0)`` as ``w`` (which
  then fixes the range). Adhesion solves for ``r_c`` numerically (``xtol = 1e-10 gamma``),
  but lands on ``a0 + dr`` to ~1e-15.

Measured agreement (E* = 1, a0 = 1, k = 1/2 and the other pairs below): V, -dV/dg and
V'' agree to <= 1e-14 relative to the local value plus the natural scale (w, w/dr, k),
``r_min`` and the cutoff are a0 and a0 + dr to 1e-15. Asserted: 1e-10.

The one difference is by design: below ``g_min = 0.05 a0`` our core is continued as the
quadratic with the same V, V', V'' at ``g_min`` (finite, repulsive, defined for g <= 0),
while Adhesion keeps the bare LJ core (divergent at g = 0, sign-flipped for g < 0).
Since V_LJ''' < 0 our continuation lies below the bare core there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import roughcontact as rc

pytest.importorskip("Adhesion")
from Adhesion.Interactions import LJ93  # noqa: E402

pytestmark = pytest.mark.peers

RTOL = 1e-10  # measured <= 1e-14
G_MIN = 0.05  # start of our quadratic core continuation, in units of a0

# (E*, a0, k, dr): the paper's k = E*/(2 a0) with la = 0.005 and 0.05 (dr = sqrt(24 la)),
# a weaker law, and stiffer/softer, shorter/longer-ranged, non-unit a0 and E* cases.
CASES = [
    (1.0, 1.0, 0.5, math.sqrt(24 * 0.005)),
    (1.0, 1.0, 0.5, math.sqrt(24 * 0.05)),
    (1.0, 1.0, 0.5, math.sqrt(24 * 0.0005)),
    (1.0, 1.0, 2.0, 0.3),
    (1.0, 1.0, 0.1, 1.5),
    (3.0, 0.5, 7.0, 0.2),
]
IDS = [f"Es{c[0]:g}-a{c[1]:g}-k{c[2]:g}-dr{c[3]:.4g}" for c in CASES]


def _peer_parameters(a0, k):
    """Adhesion's LJ93 (eps, sigma) with its minimum at a0 and V''(a0) = k."""
    sigma = a0 * 2.5 ** (1 / 6)
    s = sigma / a0
    eps = k * a0**2 / (12 * (s**9 - s**3))
    return eps, sigma


def _gaps(a0, dr):
    """Dense gaps through the core, the minimum, the spline band and beyond the cutoff."""
    rc_ = a0 + dr
    tiny = 1e-9 * a0
    return np.unique(
        np.concatenate(
            [
                np.linspace(G_MIN * a0, a0, 4001),  # core (V crosses zero in here)
                np.linspace(a0, rc_, 4001),  # spline band
                np.linspace(rc_, rc_ + 2 * dr + a0, 401),  # beyond the cutoff: zero
                [a0 - tiny, a0 + tiny, rc_ - tiny, rc_ + tiny],
                [a0 + dr / 3, rc_ - 1e-3 * dr],  # inflection point of the quartic, near r_c
            ]
        )
    )


def _close(ours, peer, scale):
    err = np.abs(ours - peer)
    bound = RTOL * (np.abs(peer) + scale)
    worst = int(np.argmax(err / bound))
    assert np.all(err <= bound), (worst, ours[worst], peer[worst])


@pytest.mark.parametrize(("es", "a0", "k", "dr"), CASES, ids=IDS)
def test_same_function_as_adhesion_spline_cutoff(es, a0, k, dr):
    """V, p = -dV/dg and V'' are Adhesion's LJ93(...).spline_cutoff(gamma=w)."""
    law = rc.SmoothLJ93(contact_modulus=es, pixel_size=a0, stiffness=k, range=dr)
    w = law.work_of_adhesion
    assert w == pytest.approx(k * dr**2 / 12, rel=1e-14)
    eps, sigma = _peer_parameters(a0, k)
    assert law.epsilon == pytest.approx(eps, rel=1e-13)
    assert law.sigma == pytest.approx(sigma, rel=1e-14)

    pot = LJ93(eps, sigma).spline_cutoff(gamma=w)
    # the peer's derived geometry: minimum at a0, cutoff at a0 + dr, core shift V_LJ(a0) + w
    assert pot.r_min == pytest.approx(a0, rel=1e-14)
    assert pot.r_t == pytest.approx(a0, rel=1e-14)
    assert pot.cutoff_radius == pytest.approx(law.cutoff, rel=1e-12)
    v_lj_a0 = LJ93(eps, sigma).evaluate(a0)[0]
    assert pot.offset == pytest.approx(v_lj_a0 + w, rel=1e-12)

    g = _gaps(a0, dr)
    v, dv, d2v = (np.asarray(x) for x in pot.evaluate(g, True, True, True))
    _close(law.energy(g), v, w)
    _close(law.pressure(g), -dv, w / dr)  # Adhesion returns the gradient: p = -dV/dg
    _close(law.curvature(g), d2v, k)

    # the landmarks, on both sides
    beyond = g >= law.cutoff + 1e-9 * a0
    assert not np.any(v[beyond]) and not np.any(law.energy(g[beyond]))
    assert np.all(dv[g < a0 * (1 - 1e-9)] < 0)  # repulsive core: gradient < 0, p > 0
    assert np.all(law.pressure(g[g < a0 * (1 - 1e-9)]) > 0)
    band = (g > a0 * (1 + 1e-9)) & (g < law.cutoff - 1e-9 * a0)
    assert np.all(dv[band] > 0) and np.all(law.pressure(g[band]) < 0)


@pytest.mark.parametrize(("es", "a0", "k", "dr"), CASES, ids=IDS)
def test_same_lj93_core(es, a0, k, dr):
    """The bare 9-3 wall is Adhesion's LJ93 with the mapped (eps, sigma); our smoothed
    core has its V' and V'' unchanged (only V is shifted, by V_LJ(a0) + w)."""
    law = rc.SmoothLJ93(contact_modulus=es, pixel_size=a0, stiffness=k, range=dr)
    eps, sigma = _peer_parameters(a0, k)
    peer = LJ93(eps, sigma)
    g = np.linspace(G_MIN * a0, 4 * a0, 2001)
    v, dv, d2v = (np.asarray(x) for x in peer.evaluate(g, True, True, True))

    bare = rc.LennardJones93.from_epsilon_sigma(eps, sigma)
    assert bare.equilibrium_distance == pytest.approx(a0, rel=1e-14)
    assert bare.stiffness == pytest.approx(k, rel=1e-13)
    assert bare.work_of_adhesion == pytest.approx(-peer.v_min, rel=1e-13)
    _close(bare.energy(g), v, eps)
    _close(bare.pressure(g), -dv, eps / a0)
    _close(bare.curvature(g), d2v, k)

    core = g < a0
    shift = float(np.asarray(peer.evaluate(a0)[0])) + law.work_of_adhesion
    _close(law.energy(g[core]), v[core] - shift, law.work_of_adhesion)
    _close(law.pressure(g[core]), -dv[core], law.work_of_adhesion / dr)
    _close(law.curvature(g[core]), d2v[core], k)
    # V_LJ'(a0) = 0 and V_LJ''(a0) = k on the peer's side too
    _, dv0, d2v0 = peer.evaluate(a0, True, True, True)
    assert abs(dv0) <= 1e-13 * k * a0
    assert d2v0 == pytest.approx(k, rel=1e-13)


def test_default_gamma_is_the_lj_depth():
    """Without gamma Adhesion uses w = -V_LJ(a0); ours with that w and k is the same law."""
    a0, k = 1.0, 0.5
    eps, sigma = _peer_parameters(a0, k)
    pot = LJ93(eps, sigma).spline_cutoff()
    w = -LJ93(eps, sigma).evaluate(a0)[0]
    assert pot.gamma == pytest.approx(w, rel=1e-14)
    law = rc.SmoothLJ93(stiffness=k, work_of_adhesion=w)
    assert pot.cutoff_radius == pytest.approx(law.cutoff, rel=1e-12)
    g = _gaps(a0, law.range)
    v, dv, d2v = pot.evaluate(g, True, True, True)
    _close(law.energy(g), v, w)
    _close(law.pressure(g), -dv, w / law.range)
    _close(law.curvature(g), d2v, k)


def test_from_adhesion_length_is_the_papers_parametrisation():
    """l_a = w/E*, k = E*/(2 a0): gamma = l_a E*, the peer's range is sqrt(24 a0 l_a)."""
    es, a0, la = 2.0, 1.0, 0.005
    law = rc.SmoothLJ93.from_adhesion_length(la, contact_modulus=es, pixel_size=a0)
    eps, sigma = _peer_parameters(a0, es / (2 * a0))
    pot = LJ93(eps, sigma).spline_cutoff(gamma=la * es)
    assert pot.cutoff_radius - pot.r_min == pytest.approx(math.sqrt(24 * a0 * la), rel=1e-12)
    g = _gaps(a0, law.range)
    _, dv, _ = pot.evaluate(g, True, True)  # (Adhesion needs potential=True here)
    _close(law.pressure(g), -np.asarray(dv), law.work_of_adhesion / law.range)


def test_core_continuation_below_g_min_is_the_only_difference():
    """Below 0.05 a0 ours is the C2 quadratic continuation, softer than the bare core."""
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    eps, sigma = _peer_parameters(1.0, law.stiffness)
    pot = LJ93(eps, sigma).spline_cutoff(gamma=law.work_of_adhesion)
    g = np.linspace(0.01, G_MIN, 41)[:-1]
    v, dv, _ = pot.evaluate(g, True, True, True)
    assert np.all(law.energy(g) < v)
    assert np.all(0 < law.pressure(g)) and np.all(law.pressure(g) < -dv)
    # continuous at g_min with the peer's value
    at = np.array([G_MIN])
    _close(law.energy(at), np.asarray(pot.evaluate(at)[0]), law.work_of_adhesion)
