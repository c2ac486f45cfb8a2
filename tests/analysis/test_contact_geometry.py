"""Perimeter and patches on exact lattice shapes."""

import numpy as np
import pytest

import roughcontact as rc


def disc(n, radius, center):
    """A disc on the periodic n x n lattice (minimum-image distances)."""
    x, y = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    dx = (x - center[0] + n / 2) % n - n / 2
    dy = (y - center[1] + n / 2) % n - n / 2
    return dx**2 + dy**2 <= radius**2


def test_square_has_four_m_edges():
    m = np.zeros((20, 20), bool)
    m[3:10, 5:12] = True
    assert rc.perimeter_edges(m) == 4 * 7
    assert rc.perimeter(m, pixel_size=2.0) == pytest.approx(4 * 7 * np.pi / 4 * 2.0)


def test_disc_perimeter_is_circumference():
    # 8R Manhattan edges times pi/4 = 2 pi R
    m = disc(200, 60.0, (100, 100))
    assert rc.perimeter(m) == pytest.approx(2 * np.pi * 60.0, rel=0.02)


def test_periodic_wrap_around():
    m = disc(64, 6.0, (0, 0))  # a disc centred on the corner, cut in four pieces
    labels, sizes = rc.contact_patches(m)
    assert sizes.tolist() == [int(m.sum())]
    assert labels.max() == 1
    _, sizes_open = rc.contact_patches(m, periodic=False)
    assert len(sizes_open) == 4
    # the wrapped disc has the same perimeter as a centred one
    assert rc.perimeter_edges(m) == rc.perimeter_edges(disc(64, 6.0, (32, 32)))


def test_patches_sorted_by_size_and_four_connected():
    m = np.zeros((16, 16), bool)
    m[1:3, 1:3] = True  # 4 sites
    m[8:12, 8:11] = True  # 12 sites
    m[5, 5] = m[6, 6] = True  # diagonal neighbours are separate patches
    labels, sizes = rc.contact_patches(m)
    assert sizes.tolist() == [12, 4, 1, 1]
    assert (labels[8:12, 8:11] == 1).all()
    assert labels[5, 5] != labels[6, 6]


def test_empty_and_full():
    assert rc.contact_patches(np.zeros((4, 4), bool))[1].size == 0
    assert rc.contact_patches(np.ones((4, 4), bool))[1].tolist() == [16]
    assert rc.perimeter_edges(np.ones((4, 4), bool)) == 0
    assert rc.area_fraction(np.eye(4, dtype=bool)) == 0.25


def test_interpolate_at_area_and_kappa():
    areas, loads = [0.005, 0.02], [0.001, 0.004]
    assert rc.analysis.interpolate_at_area(areas, loads, 0.01) == pytest.approx(0.002)
    assert rc.analysis.kappa(0.01, 0.002, 0.1) == pytest.approx(0.5)
    with pytest.raises(rc.ParameterError, match="not reached"):
        rc.analysis.interpolate_at_area(areas, loads, 0.5)
