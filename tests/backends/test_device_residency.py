"""Results come back on the heights' backend and device; contact maps count on theirs.

array_api_strict stands for another library's arrays (a GPU's): its extra devices refuse
arrays of another device. Its heights go to the compiled program (through DLPack, see
``roughcontact._accelerator``) and the fields come back as array_api_strict arrays on the
heights' device; the states must equal the NumPy ones. The device-side counts of the
contact maps are checked against scipy's graph components and a plain enumeration of the
lattice's bonds.
"""

import importlib
import itertools

import numpy as np
import pytest

import roughcontact as rc
from roughcontact._backend import to_numpy
from roughcontact.analysis.contact_geometry import count_patches

xp = pytest.importorskip("array_api_strict")

N = 32
H = rc.self_affine((N, N), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=3)
SUB = rc.Substrate((N, N))
TOP = float(H.max())
FIELDS = ("pressure", "gap", "deflection")
EXPONENTIAL = rc.Exponential(work_of_adhesion=0.01, range=0.4)
# adhesive load control on a sphere: a few dozen iterations per state (the rough surface
# takes hundreds, slow on array_api_strict)
SPHERE = rc.sphere((N, N), 20.0)

# (law, control, value; offsets relative to max(h))
CASES = [
    (None, "load", 2e-3),
    (None, "offset", -0.1),
    (rc.SmoothLJ93.from_adhesion_length(0.005), "offset", 0.6),
    (EXPONENTIAL, "offset", -0.1),
    (EXPONENTIAL, "load", 2e-4),
]
IDS = ["hardwall-load", "hardwall-offset", "lj93smooth", "exponential", "exponential-load"]


@pytest.fixture(autouse=True)
def _nested_load_control_on_numpy(monkeypatch):
    """NumPy's references by the method the off-NumPy arrays take: load control's nested
    search (NumPy itself puts the load inside the one minimisation, solvers/_free_mean.py,
    whose state agrees to the solvers' tolerance, not to these tests' 1e-8)."""
    load_control = importlib.import_module("roughcontact.solvers.load_control")
    monkeypatch.setattr(load_control, "_one_minimisation", lambda *args: False)


def _heights(law, control):
    return SPHERE if law is EXPONENTIAL and control.startswith("load") else H


def _control(control, value):
    return {control: value + TOP if control == "offset" else value}


@pytest.mark.parametrize(("law", "control", "value"), CASES, ids=IDS)
def test_result_fields_are_arrays_of_the_heights_backend(law, control, value):
    heights = _heights(law, control)
    ref = rc.solve(heights, SUB, law, tol=1e-10, **_control(control, value))
    got = rc.solve(xp.asarray(heights), SUB, law, tol=1e-10, **_control(control, value))
    assert ref.converged and got.converged
    for name in FIELDS:
        assert isinstance(getattr(got, name), type(xp.asarray(H))), name
    host = got.to_numpy()
    assert all(type(getattr(host, k)) is np.ndarray for k in FIELDS)
    # the same state as NumPy's (to the solvers' tolerance; the float32 convolutions of
    # numpy.fft (strict) and scipy.fft (NumPy) round differently)
    scale = max(abs(ref.load), 1e-12)
    np.testing.assert_allclose(host.pressure, ref.pressure, rtol=1e-8, atol=1e-8 * scale)
    np.testing.assert_allclose(host.deflection, ref.deflection, rtol=1e-8, atol=1e-10)
    np.testing.assert_allclose(host.gap, ref.gap, rtol=1e-8, atol=1e-10)
    # the scalars, reduced on the device: Python numbers, and the definitions on the host
    assert type(got.load) is float and type(got.perimeter_edges) is int
    assert got.load == pytest.approx(np.mean(host.pressure), rel=1e-12, abs=1e-15)
    assert got.mean_gap == pytest.approx(np.mean(host.gap), rel=1e-12, abs=1e-15)
    np.testing.assert_allclose(host.gap, got.offset - heights + host.deflection, atol=1e-12)
    for k in ("repulsive_area", "attractive_area", "perimeter_edges"):
        assert getattr(got, k) == getattr(ref, k), k
    assert got.load == pytest.approx(ref.load, rel=1e-8, abs=1e-12)


def test_to_numpy_is_a_host_copy_and_idle_on_numpy():
    ref = rc.solve(H, SUB, load=2e-3)
    assert ref.to_numpy() is ref
    got = rc.solve(xp.asarray(H), SUB, load=2e-3)
    host = got.to_numpy()
    assert host.summary() == got.summary()
    for name in FIELDS:
        np.testing.assert_array_equal(getattr(host, name), to_numpy(getattr(got, name)))


def test_path_on_another_device_keeps_its_fields_there():
    # array_api_strict's other devices refuse host copies without to_device, and mixing
    # devices: a path runs there and returns host data only through its dataset
    if not hasattr(xp, "Device"):
        pytest.skip("array_api_strict without multiple devices")
    other = xp.Device("device1")
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    seen = []
    offsets = TOP + np.array([0.6, 0.3, 0.0])
    ds = rc.approach_retract(
        xp.asarray(H, device=other), SUB, law, offsets=offsets, fields_at=[-1],
        progress=lambda step, n, res: seen.append(res.deflection.device),
    )  # fmt: skip
    assert seen == [other] * ds.sizes["step"]
    ref = rc.approach_retract(H, SUB, law, offsets=offsets, fields_at=[-1])
    np.testing.assert_allclose(ds["pressure"], ref["pressure"], rtol=1e-8, atol=1e-12)


def _torus_components(mask, periodic):
    """Connected components of the mask's sites on the (periodic) 4-neighbour lattice."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    nx, ny = mask.shape
    index = np.arange(nx * ny).reshape(nx, ny)
    rows, cols = [], []
    for axis in (0, 1):
        nb = np.roll(index, -1, axis=axis)
        bond = mask & np.roll(mask, -1, axis=axis)
        if not periodic:  # no bond from the last row (column) to the first
            last = np.zeros(mask.shape, bool)
            last[(-1, slice(None)) if axis == 0 else (slice(None), -1)] = True
            bond &= ~last
        rows.append(index[bond])
        cols.append(nb[bond])
    r, c = np.concatenate(rows), np.concatenate(cols)
    graph = coo_matrix((np.ones(r.size), (r, c)), shape=(nx * ny, nx * ny))
    _, labels = connected_components(graph, directed=False)
    return np.unique(labels[mask.ravel()]).size


def _boundary_bonds(mask):
    nx, ny = mask.shape
    return sum(
        mask[i, j] != mask[(i + di) % nx, (j + dj) % ny]
        for i, j in itertools.product(range(nx), range(ny))
        for di, dj in ((1, 0), (0, 1))
    )


@pytest.mark.parametrize("seed", range(6))
def test_device_side_counts_of_contact_maps(seed):
    rng = np.random.default_rng(seed)
    for _ in range(15):
        shape = tuple(int(s) for s in rng.integers(1, 14, size=2))
        mask = rng.random(shape) < rng.choice([0.0, 0.2, 0.5, 0.6, 0.8, 1.0])
        on_device = xp.asarray(mask)
        for periodic in (True, False):
            want = _torus_components(mask, periodic)
            assert count_patches(on_device, periodic=periodic) == want
            assert count_patches(mask, periodic=periodic) == want
            assert rc.contact_patches(mask, periodic=periodic)[1].size == want
        assert rc.perimeter_edges(on_device) == _boundary_bonds(mask)
        assert rc.area_fraction(on_device) == np.count_nonzero(mask) / mask.size


def test_patches_winding_around_the_torus():
    # stripes that close on themselves across the boundary, and a spiral-like comb
    stripes = np.zeros((12, 10), bool)
    stripes[::3] = True
    comb = np.zeros((16, 16), bool)
    comb[:, ::4] = True
    comb[0, :] = True
    for mask in (stripes, comb, ~comb, np.eye(9, dtype=bool)):
        for periodic in (True, False):
            want = _torus_components(mask, periodic)
            assert count_patches(xp.asarray(mask), periodic=periodic) == want
    assert count_patches(xp.asarray(stripes)) == 4
    assert count_patches(xp.asarray(np.eye(9, dtype=bool))) == 9


def test_consumers_convert_at_the_edge():
    from roughcontact.checks import total_energy
    from roughcontact.plot.maps import contact_masks
    from roughcontact.studies.task import AreaFields

    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    ref = rc.solve(H, SUB, law, offset=TOP + 0.3)
    got = rc.solve(xp.asarray(H), SUB, law, offset=TOP + 0.3)
    assert total_energy(got, SUB, law) == pytest.approx(total_energy(ref, SUB, law), rel=1e-8)
    rep, att, _, _ = contact_masks(got.pressure)
    np.testing.assert_array_equal(rep, ref.pressure > 0)
    keep = AreaFields([ref.repulsive_area], approach_steps=1)
    keep(1, 1, got)
    (fields,) = keep.fields().values()
    assert all(type(f) is np.ndarray for f in fields)
    np.testing.assert_allclose(fields[0], ref.pressure, rtol=1e-8, atol=1e-12)
