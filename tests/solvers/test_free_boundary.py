"""Every solver on the free-boundary half-space (``Substrate(..., periodic=False)``).

Oracles: Hertz's sphere (no periodic images: the indentation is measured from the
undeformed surface far away), the exact free-space deflection of the solved pressure
(which holds only if the padding of the work grid carries no pressure), the
interaction law on every site of the patch, and the array-API loops against the NumPy
ones.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.theory.hertz import hertz

N = 32


@pytest.fixture(scope="module")
def free():
    return rc.Substrate((N, N), periodic=False)


def _hertz_errors(res, radius, load, n):
    hz = hertz(load=load * n * n, radius=radius, contact_modulus=1.0)
    a = math.sqrt(res.corrected_repulsive_area * n * n / math.pi)
    delta = -res.offset  # the summit is at h = 0
    return (
        abs(a / hz.contact_radius - 1),
        abs(res.pressure.max() / hz.central_pressure - 1),
        abs(delta / hz.indentation - 1),
    )


def test_hertz_without_periodic_images(free):
    # a sphere whose contact radius is a third of the box (a = 9.9 a0 on 32 a0): on the
    # free half-space contact radius, peak pressure and indentation are Hertz's to the
    # grid's resolution; the periodic substrate is squeezed by its images (and measures
    # the indentation from its mean surface)
    radius, load = 64.0, 0.02
    h = rc.sphere((N, N), radius)
    res = rc.polonsky_keer(h, free, load=load, tol=1e-10)
    assert res.converged and res.load == pytest.approx(load, rel=1e-12)
    da, dp, dd = _hertz_errors(res, radius, load, N)
    assert da < 0.015 and dp < 0.005 and dd < 1e-3
    periodic = rc.polonsky_keer(h, rc.Substrate((N, N)), load=load, tol=1e-10)
    pa, pp, pd = _hertz_errors(periodic, radius, load, N)
    assert pp > 5 * dp and pd > 0.3 and pa > da
    # the solved pressure deflects the free surface by the solver's deflection
    np.testing.assert_allclose(free.deflection(res.pressure), res.deflection, atol=1e-11)


@pytest.mark.parametrize("precondition", [True, False])
def test_hard_wall_offset_control_meets_signorini(free, precondition):
    h = rc.self_affine((N, N), hurst=0.8, rms_slope=0.2, short_cutoff=4, seed=5)
    offset = float(h.max() - 1.0 * h.std())
    res = rc.polonsky_keer(h, free, offset=offset, precondition=precondition, tol=1e-10)
    assert res.converged
    gap = offset - h + free.deflection(res.pressure)  # an independent deflection
    scale = h.std()
    assert np.abs(gap[res.pressure > 0]).max() <= 2e-10 * scale
    assert gap.min() >= -2e-10 * scale and res.pressure.min() >= 0
    # load control at the load found gives the same state and offset
    again = rc.polonsky_keer(h, free, load=res.load, tol=1e-10)
    assert again.offset == pytest.approx(offset, abs=1e-8 * scale)
    np.testing.assert_allclose(again.pressure, res.pressure, atol=1e-7 * res.pressure.max())


def test_nested_iteration_keeps_the_free_boundary():
    # 256^2: the coarse guesses are solved on the coarsened free substrate; the answer
    # is that of the cold solve
    n = 256
    sub = rc.Substrate((n, n), periodic=False)
    assert sub.coarsened().periodic is False
    h = rc.sphere((n, n), 512.0)
    nested = rc.polonsky_keer(h, sub, load=2e-3, tol=1e-9)
    cold = rc.polonsky_keer(h, sub, load=2e-3, tol=1e-9, nested=False)
    assert nested.converged and cold.converged
    np.testing.assert_allclose(nested.pressure, cold.pressure, atol=1e-6 * cold.pressure.max())
    hz = hertz(load=2e-3 * n * n, radius=512.0, contact_modulus=1.0)
    assert -nested.offset == pytest.approx(hz.indentation, rel=2e-3)


def test_point_responses_on_the_padded_grid():
    # the hard wall's few-site corrections add point responses stored on the work grid:
    # they must give the free-space deflection of those point forces (no wrap-around)
    from roughcontact.solvers._pk_sparse import _PointKernel

    shape = (12, 10)
    sub = rc.Substrate(shape, contact_modulus=2.0, pixel_size=0.5, periodic=False)
    sites = np.array([0, 7, 11 * 10 + 9, 5 * 10 + 3])
    coeffs = np.array([1.0, -0.5, 2.0, 0.25])
    forces = np.zeros(shape[0] * shape[1])
    forces[sites] = coeffs
    want = sub.deflection(forces.reshape(shape))
    s = np.full(forces.size, 0.125)
    _PointKernel(sub, np.float64).add(s, sites, coeffs)
    np.testing.assert_allclose(s.reshape(shape), 0.125 + want, atol=1e-14)


@pytest.mark.parametrize(
    "law",
    [
        rc.SmoothLJ93.from_adhesion_length(0.05),
        rc.LennardJones93(work_of_adhesion=0.01),
        rc.Exponential(work_of_adhesion=0.01, range=0.5),
        rc.MaugisDugdale(work_of_adhesion=0.01, range=0.5),
    ],
    ids=lambda law: law.name,
)
def test_adhesive_solve_leaves_no_pressure_on_the_padding(free, law):
    # the deflection variable lives on the padded work grid with the interaction on the
    # patch only: at equilibrium the padding carries no pressure, so the patch's
    # deflection is the free-space deflection of the patch's pressure (an exact
    # convolution, independent of the solver), and the pressure is the law's
    h = rc.sphere((N, N), 30.0)
    offset = 0.3 if not law.hard_core else -0.2
    res = rc.solve(h, free, law, offset=offset, tol=1e-10)
    assert res.converged, res.message
    assert res.repulsive_area > 0.01 and res.attractive_area > 0
    np.testing.assert_allclose(free.deflection(res.pressure), res.deflection, atol=1e-8)
    if not law.hard_core:
        np.testing.assert_allclose(res.pressure, law.pressure(res.gap), atol=1e-15)
        if math.isfinite(law.cutoff):  # beyond the cutoff no site carries pressure
            beyond = res.gap >= law.cutoff
            assert beyond.any() and not res.pressure[beyond].any()
    else:  # off the wall the traction is the law's, on it g = 0
        off = res.gap > 1e-9
        np.testing.assert_allclose(res.pressure[off], law.pressure(res.gap[off]), atol=1e-15)
        assert res.gap.min() >= -1e-12


def test_load_work_balance(free):
    # envelope theorem along a reversible branch: the change of the minimised energy
    # (the free substrate's elastic energy 1/2 a0^2 sum p w, with no pressure outside the
    # patch, plus the interaction's) equals the work of the load, -int N dd
    from roughcontact.checks import load_work_balance

    h = rc.sphere((N, N), 30.0)
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    energy, work = load_work_balance(h, free, law, np.linspace(-0.1, -0.5, 21))
    assert energy == pytest.approx(work, rel=2e-4)  # the trapezoidal rule's accuracy
    assert work > 0.5


def test_adhesive_load_control_and_warm_start(free):
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    h = rc.sphere((N, N), 30.0)
    res = rc.solve(h, free, law, load=5e-3)
    assert res.converged and res.load == pytest.approx(5e-3, abs=1e-8)
    # a warm start from the result (its pressure gives the padding's deflection) is
    # converged at once (up to the rounding of that reconstruction); one from its patch
    # deflection alone (zero on the padding) is not, but converges
    again = rc.solve(h, free, law, offset=res.offset, initial=res)
    assert again.converged and again.iterations <= 3
    from_array = rc.solve(h, free, law, offset=res.offset, initial=res.deflection)
    assert from_array.converged
    np.testing.assert_allclose(from_array.pressure, res.pressure, atol=1e-6)


def test_path_and_hard_wall_reference(free):
    pytest.importorskip("xarray")
    from roughcontact.analysis.hard_wall_reference import hard_wall_reference

    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    h = rc.sphere((N, N), 30.0)
    ds = rc.approach_retract(h, free, law, offsets=np.linspace(3.0, -0.6, 10), fields_at=[-1])
    assert bool(ds.attrs["all_converged"])
    # on approach the repulsive load grows as the sphere presses in; the retraction pulls
    # off with a tensile (negative) load and separates
    approach = ds["branch"].values == "approach"
    assert np.all(np.diff(ds["repulsive_load"].values[approach]) >= 0)
    assert ds.attrs["pull_off"] > 0
    rough = rc.self_affine((N, N), hurst=0.8, rms_slope=0.2, short_cutoff=4, seed=6)
    ref = hard_wall_reference(rough, free, target_area=0.05)
    assert ref.converged and 0.5 < ref.kappa_rep < 5


@pytest.mark.parametrize("dtype", ["float32"])
def test_single_precision(free, dtype):
    h = rc.sphere((N, N), 64.0)
    res = rc.solve(h, free, load=0.02, dtype=dtype)
    exact = rc.solve(h, free, load=0.02)
    assert res.converged and res.pressure.dtype == np.float32
    np.testing.assert_allclose(res.pressure, exact.pressure, atol=1e-5 * exact.pressure.max())
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    single = rc.solve(h, free, law, offset=0.3, dtype=dtype)
    assert single.converged
    np.testing.assert_allclose(
        single.pressure, rc.solve(h, free, law, offset=0.3).pressure, atol=1e-5
    )


CASES = [
    (None, {"load": 0.02}),
    (None, {"offset": -1.0}),
    (rc.SmoothLJ93.from_adhesion_length(0.05), {"offset": 0.3}),
    (rc.Exponential(work_of_adhesion=0.01, range=0.5), {"offset": -0.2}),
]


@pytest.mark.parametrize(("law", "control"), CASES, ids=["hw-load", "hw-offset", "lj", "exp"])
def test_array_api_loops_take_the_numpy_steps(free, law, control):
    # the full-grid (mask) loops of any array-API backend against the NumPy ones
    xp = pytest.importorskip("array_api_strict")
    h = rc.sphere((N, N), 64.0)
    want = rc.solve(h, free, law, **control)
    got = rc.solve(xp.asarray(h), free, law, **control)
    assert got.converged and got.iterations == want.iterations
    np.testing.assert_allclose(got.pressure, want.pressure, atol=1e-7 * want.pressure.max())


def test_cli_non_periodic(tmp_path):
    # --non-periodic reaches the solver (Hertz's indentation, measured from far away),
    # the JSON says periodic; the path file records it; a layer is refused in one line
    import json

    from click.testing import CliRunner

    from roughcontact.cli.main import main

    surface = tmp_path / "sphere.npy"
    np.save(surface, rc.sphere((N, N), 64.0))
    run = CliRunner().invoke
    free = run(main, ["contact", str(surface), "--load", "0.02", "--non-periodic", "--json"])
    assert free.exit_code == 0, free.output
    got = json.loads(free.output)
    assert got["periodic"] is False and got["converged"]
    hz = hertz(load=0.02 * N * N, radius=64.0, contact_modulus=1.0)
    assert -got["offset"] == pytest.approx(hz.indentation, rel=1e-3)
    periodic = json.loads(run(main, ["contact", str(surface), "--load", "0.02", "--json"]).output)
    assert periodic["periodic"] is True and -periodic["offset"] < 0.7 * hz.indentation
    out = tmp_path / "p.nc"
    args = ["path", str(surface), "--offsets", "0.5", "-0.5", "0.5", "-o", str(out)]
    path = run(main, [*args, "--non-periodic", "--json"])
    assert path.exit_code == 0, path.output
    assert json.loads(path.output)["periodic"] is False
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(out) as ds:
        assert ds.attrs["periodic"] == 0 and "periodic=False" in ds.attrs["substrate"]
    layer = ["--non-periodic", "--thickness", "8"]
    bad = run(main, ["contact", str(surface), "--load", "0.02", *layer])
    assert bad.exit_code == 2 and "periodic=False needs thickness=None" in bad.output
    assert "Traceback" not in bad.output


def test_study_key_periodic():
    # [substrate] periodic: left at its default true, the task keys are those of before
    # the key existed; false gives other keys and a free-boundary task
    from roughcontact.studies import study_from_dict
    from roughcontact.studies.task import compute_task

    def study(**substrate):
        return study_from_dict(
            {
                "surface": {
                    "size": 16, "hurst": 0.8, "rms_slope": 0.1, "short_cutoff": 4.0, "seeds": [1]
                },
                "interaction": {"adhesion_length": 0.005},
                "path": {"start": 0.5, "stop": -1.0, "step": 0.5},
                "substrate": substrate,
            }
        )  # fmt: skip

    default = study()  # (its key pinned from before: tests/studies/test_spec.py)
    assert study(periodic=True).tasks[0].key == default.tasks[0].key
    assert default.tasks[0].params["periodic"] is True
    free = study(periodic=False)
    assert free.tasks[0].key != default.tasks[0].key and free.tasks[0].params["periodic"] is False
    both = study(periodic=[True, False])
    assert [t.params["periodic"] for t in both.tasks] == [True, False]
    with pytest.raises(rc.ParameterError, match="periodic = false needs a half-space"):
        study(periodic=False, thickness=8.0)
    pytest.importorskip("xarray")
    ds = compute_task(free.tasks[0])
    assert ds.attrs["periodic"] == 0 and "periodic=False" in ds.attrs["substrate"]


def test_contact_cut_by_the_window_has_no_perimeter_along_it(free):
    # a sphere centred on the window's corner: the free-boundary result counts only the
    # bonds inside the window (the periodic count would add the cut edges)
    h = rc.sphere((N, N), 64.0, center=(0.0, 0.0))
    res = rc.polonsky_keer(h, free, load=0.02, tol=1e-8)
    mask = res.pressure > 0
    assert res.converged and mask[0, 0] and mask[0].sum() > 1
    assert res.perimeter_edges == rc.perimeter_edges(mask, periodic=False)
    assert res.perimeter_edges < rc.perimeter_edges(mask)
    assert res.corrected_repulsive_area * N * N == pytest.approx(
        rc.corrected_area(mask, periodic=False)
    )


def test_path_statistics_of_a_window_have_no_wrap_around(free):
    # the path's provenance (h'rms behind κ = h'rms E* A/N) takes a free-boundary
    # surface as a window: a tilted plane keeps its slope, where one period would add
    # the wrap-around jump
    from roughcontact.solvers.path import provenance

    plane = 0.1 * np.arange(N)[:, None] + np.zeros((1, N))
    assert provenance(plane, free, None)["rms_slope"] == pytest.approx(0.1, rel=1e-12)
    assert provenance(plane, rc.Substrate((N, N)), None)["rms_slope"] > 0.5
