"""Substrate operators against Johnson's half-space solution and exact identities."""

import numpy as np
import pytest

from roughcontact import ParameterError, Substrate
from roughcontact.elastic import (
    bonded_layer_stiffness,
    frictionless_layer_stiffness,
    half_space_stiffness,
    uniaxial_layer_stiffness,
)


@pytest.mark.parametrize("shape,axis,mode", [((64, 64), 0, 3), ((48, 80), 1, 5), ((31, 20), 0, 2)])
def test_half_space_cosine_pressure(shape, axis, mode):
    # Johnson (1985) §13.2: p0 cos(qx) on a half-space deflects by 2 p0 /(E* q) cos(qx)
    a0, es, p0 = 0.5, 3.0, 0.2
    sub = Substrate(shape, contact_modulus=es, pixel_size=a0)
    n = shape[axis]
    q = 2 * np.pi * mode / (n * a0)
    x = np.arange(n) * a0
    prof = p0 * np.cos(q * x)
    p = np.broadcast_to(prof[:, None] if axis == 0 else prof[None, :], shape).copy()
    w = sub.deflection(p)
    expected = 2 * p / (es * q)
    np.testing.assert_allclose(w, expected, atol=1e-12 * abs(expected).max())
    np.testing.assert_allclose(sub.pressure(w), p, atol=1e-12)


def test_rigid_mean_mode_of_half_space():
    sub = Substrate((16, 16))
    w = sub.deflection(np.full((16, 16), 0.3))
    assert sub.rigid_mean
    np.testing.assert_allclose(w, 0.0, atol=1e-15)


def test_energy_gradient_is_pressure_by_finite_differences():
    rng = np.random.default_rng(0)
    sub = Substrate((16, 12), contact_modulus=2.0, pixel_size=0.7, thickness=5.0, poisson=0.3)
    w = rng.normal(size=(16, 12))
    grad = sub.pressure(w) * sub.pixel_size**2  # dE/dw_i = a0^2 p_i
    eps = 1e-6
    for i, j in [(0, 0), (3, 7), (15, 11), (8, 6)]:
        dw = np.zeros_like(w)
        dw[i, j] = eps
        fd = (sub.energy(w + dw) - sub.energy(w - dw)) / (2 * eps)
        assert fd == pytest.approx(grad[i, j], rel=1e-6, abs=1e-10)


@pytest.mark.parametrize("ny", [12, 13])
def test_energy_equals_half_work_of_pressure(ny):
    rng = np.random.default_rng(1)
    sub = Substrate((10, ny), pixel_size=1.3)
    w = rng.normal(size=(10, ny))
    w -= w.mean()
    e_real = 0.5 * sub.pixel_size**2 * float(np.sum(sub.pressure(w) * w))
    assert sub.energy(w) == pytest.approx(e_real, rel=1e-12)


def test_layer_tends_to_half_space_without_overflow():
    q = np.array([1e-1, 1.0, 10.0, 1e3])
    t = 1e3
    for nu in (0.0, 0.3, 0.5):
        k = bonded_layer_stiffness(q, t, 1.0, nu)
        assert np.all(np.isfinite(k))
        np.testing.assert_allclose(k[1:], half_space_stiffness(q[1:], 1.0), rtol=1e-12)
    np.testing.assert_allclose(
        frictionless_layer_stiffness(q[1:], t, 1.0), half_space_stiffness(q[1:], 1.0), rtol=1e-12
    )


def test_thin_film_limits():
    es, t = 1.0, 1.0
    q = np.array([1e-3])
    # compressible film bonded to its base: uniaxial strain, k -> M/t
    for nu in (0.0, 0.25, 0.4):
        m = es * (1 - nu) ** 2 / (1 - 2 * nu)
        assert bonded_layer_stiffness(q, t, es, nu)[0] == pytest.approx(m / t, rel=1e-5)
        assert uniaxial_layer_stiffness(t, es, nu) == pytest.approx(m / t)
    # incompressible bonded film (lubrication limit): k = 3 E* / (4 q^2 t^3)
    assert bonded_layer_stiffness(q, t, es, 0.5)[0] == pytest.approx(
        3 * es / (4 * q[0] ** 2), rel=1e-4
    )
    # frictionless base: plate of thickness 2t in plane strain, k -> E*/t
    assert frictionless_layer_stiffness(q, t, es)[0] == pytest.approx(es / t, rel=1e-5)


def test_finite_layer_uniform_mode():
    sub = Substrate((8, 8), thickness=4.0, poisson=0.25)
    p = np.full((8, 8), 0.01)
    w = sub.deflection(p)
    np.testing.assert_allclose(w, 0.01 / uniaxial_layer_stiffness(4.0, 1.0, 0.25))
    assert Substrate((8, 8), thickness=4.0, poisson=0.5).rigid_mean


@pytest.mark.parametrize(
    "kwargs,name",
    [
        ({"contact_modulus": 0.0}, "contact_modulus"),
        ({"contact_modulus": -1.0}, "contact_modulus"),
        ({"pixel_size": float("nan")}, "pixel_size"),
        ({"poisson": 0.6, "thickness": 3.0}, "poisson"),
        ({"poisson": -0.1}, "poisson"),
        ({"thickness": 0.0}, "thickness"),
        ({"base": "glued"}, "base"),
    ],
)
def test_bad_parameters_name_the_parameter(kwargs, name):
    with pytest.raises(ParameterError, match=name):
        Substrate((8, 8), **kwargs)


def test_shape_mismatch_is_an_error():
    with pytest.raises(ParameterError, match="shape"):
        Substrate((8, 8)).deflection(np.zeros((8, 9)))


def test_self_stiffness():
    # K_ii: the pressure at a site per unit deflection of that site alone ...
    sub = Substrate((64, 48), thickness=12.0, poisson=0.3)
    unit = np.zeros(sub.shape)
    unit[5, 7] = 1.0
    assert sub.self_stiffness == pytest.approx(sub.pressure(unit)[5, 7], rel=1e-12)
    # ... and for a half-space the mean of E*|q|/2 over the Brillouin zone [-pi, pi]^2,
    # E* pi (sqrt(2) + asinh(1)) / (6 a0), approached as the grid is refined
    continuum = np.pi * (np.sqrt(2.0) + np.arcsinh(1.0)) / 6.0
    assert Substrate((256, 256)).self_stiffness == pytest.approx(continuum, rel=1e-3)
    assert Substrate((64, 64), contact_modulus=3.0, pixel_size=0.5).self_stiffness == (
        pytest.approx(3.0 / 0.5 * continuum, rel=1e-2)
    )
