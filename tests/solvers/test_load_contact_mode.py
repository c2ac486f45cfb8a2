"""The bounded solver's uniform mode under load control follows the contact's response
(adhesive_rules.contact_mode, _free_mean.FreeMean.add_on, _bounded_jax): its rules against
the elastic operator, and cold hard-core load control as cheap as offset control."""

import importlib

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.solvers.fourier import compliance_operator, stiffness_operator

rules = importlib.import_module("roughcontact.solvers.adhesive_rules")
free_mean = importlib.import_module("roughcontact.solvers._free_mean")


def _surface(n, seed=7):
    return rc.self_affine((n, n), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=seed)


def test_contact_mode_is_the_lifted_body_and_its_rayleigh_quotient():
    n = 64
    sub = rc.Substrate((n, n))
    h = _surface(n).ravel()
    active = h > np.quantile(h, 0.93)  # 7 % of the sites on the wall
    a = active.mean()
    v = compliance_operator(sub)(np.where(active, 1.0 - a, -a))
    floor = np.pi / n
    u, k = rules.contact_mode(v, active, floor)
    # 1 on average, 0 on average over the wall (sum_A u = 0), larger off the contacts
    assert u.mean() == pytest.approx(1.0, abs=1e-12)
    assert u[active].sum() == pytest.approx(0.0, abs=1e-9 * n * n)
    assert u[~active].mean() > 1.0 > np.abs(u[active]).max()
    # the stiffness per site: CONTACT_FRACTION of u K u / n, the elastic energy of u (float64)
    quotient = float(u @ stiffness_operator(sub)(u)) / (n * n)
    assert k == pytest.approx(rules.CONTACT_FRACTION * quotient, rel=1e-9)
    assert k < floor  # a few contacts: softer than the longest wavelength (the floor before)
    # no site on the wall: a uniform shift over the floor
    u0, k0 = rules.contact_mode(v, np.zeros(n * n, bool), floor)
    assert np.all(u0 == 1.0) and k0 == floor
    # recomputed only when more than CONTACT_REFRESH of the wall's sites changed
    assert not rules.contact_stale(10, 100) and rules.contact_stale(11, 100)
    assert rules.contact_stale(1, 0)


@pytest.mark.parametrize(("law", "load"), [
    (rc.Exponential(work_of_adhesion=0.005, range=1.0), 0.0),
    (rc.Exponential(work_of_adhesion=0.05, range=1.0), 0.0),
    (rc.Exponential(work_of_adhesion=0.005, range=1.0), -1e-3),
])  # fmt: skip
def test_hard_core_cold_load_control_along_the_contact_response(monkeypatch, law, load):
    # measured at 128² (fine-grid iterations, load control / offset control): 19 / 17,
    # 28 / 28, 16 / 15; with the uniform shift before 29, 38, 26 (benchmarks/README.md)
    n = 128
    h, sub = _surface(n), rc.Substrate((n, n))
    res = rc.solve(h, sub, law, load=load)
    assert res.converged and abs(res.load - load) <= res.tol, res.message
    same = rc.solve(h, sub, law, offset=res.offset)
    assert same.converged and np.abs(same.gap - res.gap).max() < 1e-6
    assert res.iterations <= 1.3 * same.iterations, (res.iterations, same.iterations)
    # the rule before (a uniform shift of the free sites): the same state, more iterations
    add_on = free_mean.FreeMean.add_on
    monkeypatch.setattr(free_mean.FreeMean, "add_on",
                        lambda self, z, rr, gap, free, it, green=None:
                        add_on(self, z, rr, gap, free, it))  # fmt: skip
    before = rc.solve(h, sub, law, load=load)
    assert before.converged and np.abs(before.gap - res.gap).max() < 1e-6
    assert before.iterations >= 1.3 * res.iterations, (before.iterations, res.iterations)
