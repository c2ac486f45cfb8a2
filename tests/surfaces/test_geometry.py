import math

import numpy as np
import pytest

from roughcontact._validate import ParameterError
from roughcontact.surfaces.geometry import egg_box, flat, sinusoid, sphere


def test_flat():
    h = flat((4, 6))
    assert h.shape == (4, 6) and h.dtype == np.float64 and not h.any()
    assert flat(5).shape == (5, 5)


def test_sphere_paraboloid_values():
    R, a0 = 50.0, 0.5
    h = sphere((64, 32), R, pixel_size=a0)
    # summit at grid point (32, 16), i.e. (x, y) = (16, 8)
    assert h[32, 16] == 0.0
    assert h.max() == 0.0 and np.unravel_index(np.argmax(h), h.shape) == (32, 16)
    # (i, j) = (35, 12): dx = 1.5, dy = -2.0, r^2 = 6.25
    assert h[35, 12] == pytest.approx(-6.25 / (2 * R), rel=1e-14)
    assert h[0, 0] == pytest.approx(-(16.0**2 + 8.0**2) / (2 * R), rel=1e-14)


def test_sphere_odd_grid_summit_on_grid_point():
    h = sphere((31, 33), 10.0)
    assert np.unravel_index(np.argmax(h), h.shape) == (15, 16)
    assert h[15, 16] == 0.0


def test_sphere_custom_center_and_no_minimum_image():
    h = sphere(32, 100.0, center=(0.0, 0.0))
    assert h[0, 0] == 0.0
    # plain distance, not periodic: the far corner is far away, not adjacent
    assert h[31, 31] == pytest.approx(-(31.0**2 * 2) / 200.0)


def test_sphere_exact_cap_and_clip():
    R = 10.0
    h = sphere(64, R, exact=True, center=(32.0, 32.0))
    assert h[32, 32] == 0.0
    assert h[38, 32] == pytest.approx(math.sqrt(R**2 - 36) - R, rel=1e-14)
    assert h[32 + 10, 32] == pytest.approx(-R)  # rim
    assert h[0, 0] == -R  # clipped beyond the rim
    assert np.all(h >= -R)
    # close to the summit the cap and the paraboloid agree to O(r^4 / R^3)
    p = sphere(64, R, center=(32.0, 32.0))
    assert abs(h[33, 32] - p[33, 32]) < 1.0 / (8 * R**3) * 1.01


@pytest.mark.parametrize("axis", [0, 1])
def test_sinusoid_values(axis):
    lam, A = 8.0, 0.3
    h = sinusoid((32, 16), lam, A, axis=axis)
    assert h.shape == (32, 16)
    line = h[:, 0] if axis == 0 else h[0, :]
    # crest at 0, zero crossing at lam/4, trough at lam/2
    assert line[0] == pytest.approx(A)
    assert line[2] == pytest.approx(0.0, abs=1e-15)
    assert line[4] == pytest.approx(-A)
    # constant along the other axis
    assert np.ptp(h, axis=1 - axis).max() == 0.0


def test_sinusoid_pixel_size():
    h = sinusoid((40, 4), 5.0, 1.0, pixel_size=0.5)  # L = 20 = 4 wavelengths
    assert h[5, 0] == pytest.approx(math.cos(2 * math.pi * 2.5 / 5.0))
    assert h[10, 3] == pytest.approx(1.0)


def test_egg_box_values():
    h = egg_box((16, 32), 8.0, 2.0)
    assert h[0, 0] == pytest.approx(2.0)
    assert h[4, 0] == pytest.approx(-2.0)
    assert h[4, 4] == pytest.approx(2.0)
    assert h[2, 5] == pytest.approx(0.0, abs=1e-15)
    assert h[1, 1] == pytest.approx(2.0 * math.cos(math.pi / 4) ** 2)


@pytest.mark.parametrize(
    "call",
    [
        lambda: sinusoid(30, 8.0, 1.0),
        lambda: sinusoid((32, 30), 8.0, 1.0, axis=1),
        lambda: sinusoid(32, 64.0, 1.0),
        lambda: egg_box((32, 30), 8.0, 1.0),
        lambda: egg_box((30, 32), 8.0, 1.0),
    ],
)
def test_divisibility_error(call):
    with pytest.raises(ParameterError, match="wavelength"):
        call()


def test_divisibility_ok_when_other_axis_does_not_divide():
    h = sinusoid((32, 30), 8.0, 1.0, axis=0)
    assert h.shape == (32, 30)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: sphere(32, -1.0), "radius"),
        (lambda: sphere(32, 1.0, pixel_size=0), "pixel_size"),
        (lambda: sphere(32, 1.0, center=(1.0,)), "center"),
        (lambda: sinusoid(32, 8.0, math.nan), "amplitude"),
        (lambda: sinusoid(32, 0.0, 1.0), "wavelength"),
        (lambda: sinusoid(32, 8.0, 1.0, axis=2), "axis"),
        (lambda: egg_box(32, 8.0, "a"), "amplitude"),
        (lambda: flat(1), "shape"),
    ],
)
def test_bad_inputs(call, name):
    with pytest.raises(ParameterError, match=name):
        call()
