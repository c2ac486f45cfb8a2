import math

import numpy as np
import pytest
from scipy.integrate import quad

from roughcontact._validate import ParameterError
from roughcontact.theory import HertzContact, hertz, hertz_load


@pytest.mark.parametrize("N, R, E", [(1.0, 1.0, 1.0), (0.37, 120.0, 0.5), (5e3, 3.0, 2e2)])
def test_closed_forms(N, R, E):
    c = hertz(load=N, radius=R, contact_modulus=E)
    assert isinstance(c, HertzContact)
    # independent closed forms (Johnson 1985, Eqs. 4.23): p0 = (6 N E*^2 / (pi^3 R^2))^(1/3),
    # delta = (9 N^2 / (16 R E*^2))^(1/3)
    np.testing.assert_allclose(
        c.central_pressure, (6 * N * E**2 / (math.pi**3 * R**2)) ** (1 / 3), rtol=1e-13
    )
    np.testing.assert_allclose(c.indentation, (9 * N**2 / (16 * R * E**2)) ** (1 / 3), rtol=1e-13)
    np.testing.assert_allclose(c.contact_radius, (3 * N * R / (4 * E)) ** (1 / 3), rtol=1e-13)
    # p0 = 2 a E* / (pi R) is another textbook form
    np.testing.assert_allclose(
        c.central_pressure, 2 * c.contact_radius * E / (math.pi * R), rtol=1e-13
    )
    np.testing.assert_allclose(c.mean_pressure, 2 / 3 * c.central_pressure, rtol=1e-13)
    np.testing.assert_allclose(c.contact_area, math.pi * c.contact_radius**2, rtol=1e-13)


@pytest.mark.parametrize("N, R, E", [(1.0, 1.0, 1.0), (0.37, 120.0, 0.5)])
def test_pressure_integrates_to_load(N, R, E):
    c = hertz(load=N, radius=R, contact_modulus=E)
    total, _ = quad(lambda r: 2 * math.pi * r * c.pressure(r), 0, c.contact_radius)
    np.testing.assert_allclose(total, N, rtol=1e-9)


def test_pressure_shape():
    c = hertz(load=2.0, radius=10.0, contact_modulus=1.0)
    a = c.contact_radius
    assert c.pressure(0.0) == pytest.approx(c.central_pressure)
    assert c.pressure(a) == 0.0
    assert c.pressure(2 * a) == 0.0
    r = np.array([0.0, 0.5 * a, 1.5 * a])
    p = c.pressure(r)
    assert p.shape == (3,)
    np.testing.assert_allclose(p, [c.central_pressure, c.central_pressure * math.sqrt(0.75), 0])
    assert isinstance(c.pressure(0.1), float)


@pytest.mark.parametrize("N", [1e-3, 0.5, 7.0, 1e4])
def test_load_indentation_inverse(N):
    R, E = 25.0, 0.8
    c = hertz(load=N, radius=R, contact_modulus=E)
    np.testing.assert_allclose(hertz_load(c.indentation, R, E), N, rtol=1e-12)


def test_hertz_load_array_and_no_contact():
    d = np.array([-1.0, 0.0, 1.0, 4.0])
    N = hertz_load(d, 1.0, 3.0)
    np.testing.assert_allclose(N, [0.0, 0.0, 4.0, 32.0])
    assert hertz_load(-0.5, 1.0, 1.0) == 0.0


def test_stiffness_is_two_a_estar():
    # dN/d delta = 2 a E* (Johnson 1985, ch. 4): check by finite difference
    R, E, N = 4.0, 1.5, 2.0
    c = hertz(load=N, radius=R, contact_modulus=E)
    eps = 1e-6 * c.indentation
    k = (hertz_load(c.indentation + eps, R, E) - hertz_load(c.indentation - eps, R, E)) / (2 * eps)
    np.testing.assert_allclose(k, 2 * c.contact_radius * E, rtol=1e-7)


@pytest.mark.parametrize(
    "kw, name",
    [
        (dict(load=-1.0, radius=1.0, contact_modulus=1.0), "load"),
        (dict(load=1.0, radius=0.0, contact_modulus=1.0), "radius"),
        (dict(load=1.0, radius=1.0, contact_modulus=math.inf), "contact_modulus"),
    ],
)
def test_bad_inputs(kw, name):
    with pytest.raises(ParameterError, match=name):
        hertz(**kw)
    if name != "load":
        with pytest.raises(ParameterError, match=name):
            hertz_load(1.0, kw["radius"], kw["contact_modulus"])
