"""Pieces of the index-array hard-wall loop against numpy.fft."""

from __future__ import annotations

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.solvers._pk_sparse import _PointKernel


@pytest.mark.parametrize("thickness", [None, 6.0])
@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_point_responses_are_the_convolution_of_the_point_forces(thickness, dtype):
    # s += sum_j c_j G(x - x_j), periodic, for sites anywhere (wrapping at both edges)
    shape = (12, 10)
    sub = rc.Substrate(shape, contact_modulus=2.0, pixel_size=0.5, thickness=thickness)
    sites = np.array([0, 7, 10 * 11 + 9, 5 * 10 + 3])
    coeffs = np.array([1.0, -0.5, 2.0, 0.25])
    forces = np.zeros(shape[0] * shape[1])
    forces[sites] = coeffs
    compliance = sub.multipliers(np.zeros(1)).compliance
    want = np.fft.irfft2(np.fft.rfft2(forces.reshape(shape)) * compliance, s=shape)
    s = np.full(forces.size, 0.125, dtype=dtype)
    kernel = _PointKernel(sub, dtype)
    kernel.add(s, sites, coeffs)
    eps = np.finfo(dtype).eps
    np.testing.assert_allclose(s.reshape(shape), 0.125 + want, atol=50 * eps * np.abs(want).max())
