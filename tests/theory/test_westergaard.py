import math

import numpy as np
import pytest
from scipy.integrate import quad

from roughcontact._validate import ParameterError
from roughcontact.theory import (
    westergaard_contact_fraction,
    westergaard_contact_half_width,
    westergaard_full_contact_pressure,
    westergaard_pressure,
)

D, LAM, E = 0.2, 16.0, 2.0  # amplitude, wavelength, contact modulus
PSTAR = math.pi * E * D / LAM


def test_full_contact_pressure():
    assert westergaard_full_contact_pressure(D, LAM, E) == pytest.approx(PSTAR, rel=1e-15)
    # scaling: linear in E* and amplitude, inverse in wavelength
    assert westergaard_full_contact_pressure(2 * D, 2 * LAM, 3 * E) == pytest.approx(3 * PSTAR)


@pytest.mark.parametrize("frac", [0.01, 0.2, 0.5, 0.9, 0.999, 1.0, 1.5, 3.0])
def test_mean_pressure_from_quadrature(frac):
    pbar = frac * PSTAR
    a = westergaard_contact_half_width(pbar, D, LAM, E)
    pts = [-a, a] if a < LAM / 2 else None
    total, _ = quad(
        lambda x: westergaard_pressure(x, pbar, D, LAM, E),
        -LAM / 2,
        LAM / 2,
        points=pts,
        limit=200,
    )
    np.testing.assert_allclose(total / LAM, pbar, rtol=1e-8)


def test_pressure_periodic_and_symmetric():
    pbar = 0.3 * PSTAR
    x = np.linspace(-LAM, LAM, 101)
    p = westergaard_pressure(x, pbar, D, LAM, E)
    np.testing.assert_allclose(westergaard_pressure(x + 3 * LAM, pbar, D, LAM, E), p, atol=1e-14)
    np.testing.assert_allclose(westergaard_pressure(-x, pbar, D, LAM, E), p, atol=1e-14)
    assert np.all(p >= 0)


def test_contact_region():
    pbar = 0.25 * PSTAR
    a = westergaard_contact_half_width(pbar, D, LAM, E)
    # sin^2(pi a / lam) = 1/4 -> a = lam / 6
    np.testing.assert_allclose(a, LAM / 6, rtol=1e-14)
    np.testing.assert_allclose(westergaard_contact_fraction(pbar, D, LAM, E), 1 / 3, rtol=1e-14)
    assert westergaard_pressure(0.99 * a, pbar, D, LAM, E) > 0
    assert westergaard_pressure(1.01 * a, pbar, D, LAM, E) == 0.0
    assert westergaard_pressure(LAM / 2, pbar, D, LAM, E) == 0.0
    # peak at the crest: p(0) = 2 sqrt(pbar p*)
    np.testing.assert_allclose(
        westergaard_pressure(0.0, pbar, D, LAM, E), 2 * math.sqrt(pbar * PSTAR), rtol=1e-14
    )


def test_contact_fraction_tends_to_one():
    fr = [
        westergaard_contact_fraction(f * PSTAR, D, LAM, E) for f in (0.9, 0.99, 0.9999, 1 - 1e-10)
    ]
    assert all(np.diff(fr) > 0) and all(f < 1 for f in fr)
    assert 1 - fr[-1] < 1e-4
    assert westergaard_contact_fraction(PSTAR, D, LAM, E) == 1.0
    assert westergaard_contact_fraction(2 * PSTAR, D, LAM, E) == 1.0
    assert westergaard_contact_fraction(0.0, D, LAM, E) == 0.0


def test_continuity_at_full_contact():
    x = np.linspace(-LAM / 2, LAM / 2, 201)
    below = westergaard_pressure(x, PSTAR * (1 - 1e-9), D, LAM, E)
    at = westergaard_pressure(x, PSTAR, D, LAM, E)
    np.testing.assert_allclose(below, at, atol=1e-4 * PSTAR)
    np.testing.assert_allclose(at, PSTAR * (1 + np.cos(2 * np.pi * x / LAM)), atol=1e-14)
    # at full contact the pressure vanishes exactly at the trough
    assert westergaard_pressure(LAM / 2, PSTAR, D, LAM, E) == pytest.approx(0.0, abs=1e-14)


def test_small_load_limit_is_line_hertz():
    # each crest is a cylinder of radius R = lam^2 / (4 pi^2 D); line-contact Hertz
    # (Johnson 1985, Eq. 4.43): a^2 = 4 P R / (pi E*), with P = pbar * lam per period
    pbar = 1e-6 * PSTAR
    R = LAM**2 / (4 * math.pi**2 * D)
    a_hertz = math.sqrt(4 * pbar * LAM * R / (math.pi * E))
    a = westergaard_contact_half_width(pbar, D, LAM, E)
    np.testing.assert_allclose(a, a_hertz, rtol=1e-5)
    # and the peak pressure p0 = 2P / (pi a)
    np.testing.assert_allclose(
        westergaard_pressure(0.0, pbar, D, LAM, E), 2 * pbar * LAM / (math.pi * a_hertz), rtol=1e-5
    )


def test_zero_load():
    assert westergaard_pressure(0.0, 0.0, D, LAM, E) == 0.0
    assert isinstance(westergaard_pressure(0.0, 0.1, D, LAM, E), float)


@pytest.mark.parametrize(
    "args, name",
    [
        ((-0.1, D, LAM, E), "mean_pressure"),
        ((0.1, -D, LAM, E), "amplitude"),
        ((0.1, D, 0.0, E), "wavelength"),
        ((0.1, D, LAM, math.nan), "contact_modulus"),
    ],
)
def test_bad_inputs(args, name):
    with pytest.raises(ParameterError, match=name):
        westergaard_contact_fraction(*args)
    with pytest.raises(ParameterError, match=name):
        westergaard_pressure(0.0, *args)
