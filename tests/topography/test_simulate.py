"""``stick(..., simulate=True)``: the paper's simulation on surfaces continuing a scan.

Oracles: the closed-form h'_rms of the scan's fitted power law continued to lambda_s
(as in test_verdict) against :func:`roughcontact.statistics` of the synthetic surface;
the Hurst exponent refitted on it; the same path run and analysed directly
(:func:`roughcontact.approach_retract`, ``analyze_path``) for the per-seed kappa; Eq. 7's
identity 1/kappa = 1/kappa_rep - 1/kappa_att; ``inverse_mean`` for the combination; the
paper's statement that l_a/a0 = 0.05 with h'rms = 0.1 adheres (Fig. 4) and that a
thousand times weaker adhesion on a steeper surface does not (l_a/a0 << 0.49 h'rms).
"""

import dataclasses
import json
import math

import numpy as np
import pytest

import roughcontact as rc
from roughcontact import ParameterError
from roughcontact.analysis.path_analysis import analyze_path
from roughcontact.analysis.stickiness import inverse_mean
from roughcontact.solvers.offsets import relative_offsets
from roughcontact.topography import Topography, scale_statistics, stick
from roughcontact.topography import simulate as sim_module
from roughcontact.topography.simulate import simulate_stickiness, synthetic_surface
from roughcontact.topography.verdict import UNITS

NM = 1e-9
A0 = 0.3 * NM
E_STAR = 1e11  # Pa: l_a/a0 = w/(E* a0) of order 0.01 for w of order J/m^2


def _scan(slope=0.1, hurst=0.8, seed=5):
    """A periodic scan whose Nyquist wavelength is 4 a0: its h'rms is the one at lambda_s."""
    a = 2 * A0
    h = rc.self_affine(128, hurst=hurst, rms_slope=slope, short_cutoff=2 * a, pixel_size=a,
                       seed=seed)  # fmt: skip
    return Topography(h, (a, a), periodic=True, height_unit="m", info={"length_unit": "m"})


def _work(la_over_a0):
    return la_over_a0 * A0 * E_STAR


def _stick(topo, la, **kwargs):
    return stick(topo, modulus=E_STAR, work_of_adhesion=_work(la), detrend="height",
                 simulate=True, simulate_size=64, **kwargs)  # fmt: skip


@pytest.fixture(scope="module")
def strong():
    return _stick(_scan(slope=0.1), 0.05, simulate_seeds=2)


@pytest.fixture(scope="module")
def weak():
    return _stick(_scan(slope=0.3), 0.0005, simulate_seeds=1)


def test_synthetic_surface_has_the_extrapolated_slope_and_the_fitted_hurst():
    a = 5 * NM
    h = rc.self_affine(128, hurst=0.6, rms_slope=0.05, short_cutoff=2 * a, pixel_size=a, seed=3)
    stats = scale_statistics(h, a, periodic=True)
    fit = stats.fit
    # closed form: the fitted C_p (q/q_p)^-(2+2H) integrated from q_c to 2 pi/(4 a0)
    H, q_c, q_s = fit.hurst, 2 * np.pi / stats.measured_scale, 2 * np.pi / (4 * A0)
    amp = 2 * np.pi * fit.psd_pivot * fit.q_pivot ** (2 + 2 * H)
    target = math.sqrt(
        stats.rms_slope**2 + amp * (q_s ** (2 - 2 * H) - q_c ** (2 - 2 * H)) / (2 - 2 * H)
    )
    heights, params = synthetic_surface(stats, atomic_spacing=A0, size=256, seed=1)
    assert heights.shape == (256, 256)
    assert params["rms_slope"] == pytest.approx(target, rel=1e-9)
    assert rc.statistics(heights).rms_slope == pytest.approx(target, rel=1e-9)
    assert params["hurst"] == H and not params["hurst_clipped"]
    assert params["short_cutoff"] == 4 and params["long_cutoff"] == 128
    refit = scale_statistics(heights, 1.0, periodic=True, fit_range=(8, 64)).fit
    assert abs(refit.hurst - H) < 3 * refit.hurst_stderr


@pytest.mark.parametrize(("fitted", "used"), [(1.4, 1.0), (-0.2, sim_module.HURST_MIN)])
def test_hurst_outside_the_generator_range_is_clipped_and_said(fitted, used):
    stats = scale_statistics(_scan().heights, 2 * A0, periodic=True)
    stats = dataclasses.replace(stats, fit=dataclasses.replace(stats.fit, hurst=fitted))
    heights, params = synthetic_surface(stats, atomic_spacing=A0, size=64, seed=1)
    assert params["hurst"] == used and params["hurst_clipped"]
    assert params["hurst_fitted"] == fitted
    s = simulate_stickiness(stats, contact_modulus=E_STAR, work_of_adhesion=_work(0.005),
                            atomic_spacing=A0, size=64, seeds=1)  # fmt: skip
    assert any(f"fitted H = {fitted:.3f} is outside" in n for n in s.notes)
    assert s.surface["hurst"] == used


def test_strong_adhesion_is_sticky_weak_is_not(strong, weak):
    s, w = strong.simulation, weak.simulation
    assert s.interaction["adhesion_length_over_a0"] == pytest.approx(0.05)
    assert s.surface["rms_slope"] == pytest.approx(0.1, rel=1e-9)
    assert s.verdict == "sticky" and s.sticky is True
    assert all(r.verdict == "sticky" and r.kappa < 0 for r in s.runs)
    assert w.surface["rms_slope"] == pytest.approx(0.3, rel=1e-9)
    assert w.verdict == "not sticky" and w.sticky is False
    assert all(r.verdict == "not sticky" and r.kappa > 0 for r in w.runs)
    # pulling the surfaces apart needs more force the stronger the adhesion
    assert s.pull_off_pressure > 100 * w.pull_off_pressure > 0


def test_per_seed_kappa_is_the_direct_analysis_of_the_same_path(strong):
    sim = strong.simulation
    run = sim.runs[0]
    assert not run.error and run.seed == 1
    surface = sim.surface
    heights = rc.self_affine((64, 64), hurst=surface["hurst"], rms_slope=surface["rms_slope"],
                             short_cutoff=4.0, long_cutoff=32.0, seed=1)  # fmt: skip
    np.testing.assert_array_equal(heights, run.heights)
    # the range asked for (stick's default 0.5 nm), on a hard wall (Maugis-Dugdale)
    law = rc.MaugisDugdale(work_of_adhesion=0.05, range=0.5 * NM / A0)
    assert sim.interaction["range"] == pytest.approx(0.5 * NM, rel=1e-12)
    assert sim.interaction["range_over_a0"] == pytest.approx(law.range)
    lead = relative_offsets(heights, sim.path["lead_in"], "length", law)
    body = relative_offsets(heights, sim.path["bearing_area"], "bearing_area", law)
    substrate = rc.Substrate((64, 64), contact_modulus=1.0, thickness=64.0, poisson=0.5,
                             base="bonded")  # fmt: skip
    ds = rc.approach_retract(heights, substrate, law, offsets=np.concatenate((lead, body)),
                             tol=1e-7, max_iter=20000, until_area=0.015)  # fmt: skip
    direct = analyze_path(ds, target_area=0.01, heights=heights, substrate=substrate)
    assert run.kappa == pytest.approx(direct.kappa, rel=1e-9)
    assert run.kappa_rep == pytest.approx(direct.kappa_rep, rel=1e-9)
    assert run.kappa_att == pytest.approx(direct.kappa_att, rel=1e-9)
    assert run.predicted_verdict == direct.predicted_verdict
    assert run.pull_off_pressure == pytest.approx(ds.attrs["pull_off"] * E_STAR, rel=1e-9)
    # Eq. 7: 1/kappa = 1/kappa_rep - 1/kappa_att
    for r in sim.runs:
        assert 1 / r.kappa == pytest.approx(1 / r.kappa_rep - 1 / r.kappa_att, rel=1e-9)


def test_combined_verdict_is_inverse_mean_of_the_seeds(strong, weak):
    for result in (strong, weak):
        sim = result.simulation
        ref = inverse_mean([r.kappa for r in sim.runs])
        assert sim.verdict == ref.verdict
        assert sim.inverse_kappa.mean == pytest.approx(ref.mean, rel=1e-12)
        pred = inverse_mean([r.predicted_kappa for r in sim.runs])
        assert sim.predicted_verdict == pred.verdict
        d = result.to_dict()["simulation"]
        assert d["verdict"] == ref.verdict and d["predicted_verdict"] == pred.verdict
        assert [x["kappa"] for x in d["seeds"]] == [r.kappa for r in sim.runs]


def test_json_has_the_simulation_and_a_unit_for_each_of_its_numbers(strong):
    d = strong.to_dict()
    assert json.loads(json.dumps(d, allow_nan=False)) == d
    sim = d["simulation"]
    for key in ("verdict", "predicted_verdict", "kappa", "inverse_kappa_interval", "surface",
                "interaction", "seeds", "pull_off_pressure", "notes"):  # fmt: skip
        assert key in sim
    for key in ("kappa", "kappa_rep", "kappa_att", "verdict", "pull_off_pressure"):
        assert key in sim["seeds"][0]
    assert d["units"] == UNITS

    def leaves(obj, path):
        if isinstance(obj, dict):
            for k, v in obj.items():
                yield from leaves(v, f"{path}.{k}")
        elif isinstance(obj, list):
            for v in obj:
                yield from leaves(v, path)
        elif isinstance(obj, (int, float)) and not isinstance(obj, bool):
            yield path

    paths = set(leaves(sim, "simulation"))
    assert "simulation.seeds.kappa" in paths and "simulation.interaction.range" in paths
    assert not paths - set(UNITS), paths - set(UNITS)  # every number its own unit
    assert "range 0.5 nm" in " ".join(sim["notes"])
    assert stick(_scan(), modulus=E_STAR, work_of_adhesion=_work(0.05)).to_dict()[
        "simulation"
    ] is None  # fmt: skip


def test_unconverged_steps_are_recorded_per_seed(monkeypatch):
    monkeypatch.setattr(sim_module, "MAX_ITER", 3)
    stats = scale_statistics(_scan().heights, 2 * A0, periodic=True)
    s = simulate_stickiness(stats, contact_modulus=E_STAR, work_of_adhesion=_work(0.05),
                            atomic_spacing=A0, size=64, seeds=1)  # fmt: skip
    run = s.runs[0]
    assert run.error.startswith("not converged") and run.steps_not_converged > 0
    assert math.isnan(run.kappa) and s.verdict == "undecided" and s.inverse_kappa.n == 0
    assert any("seed 1: no result" in n for n in s.notes)
    assert json.dumps(s.to_dict(), allow_nan=False)


def test_progress_is_called_once_per_seed():
    calls = []
    _stick(_scan(), 0.005, simulate_seeds=2, simulate_progress=lambda k, n: calls.append((k, n)))
    assert calls == [(1, 2), (2, 2)]


def test_bad_options_are_one_line_parameter_errors():
    topo = _scan()
    cases = [
        ({"simulate_size": 32}, "simulate_size"),
        ({"simulate_size": 2048}, "simulate_size"),
        ({"simulate_size": 64.5}, "simulate_size"),
        ({"simulate_seeds": 0}, "simulate_seeds"),
        ({"simulate_seeds": 33}, "simulate_seeds"),
        ({"work_of_adhesion": _work(200)}, "l_a/a0"),
        ({"work_of_adhesion": _work(1e-6)}, "l_a/a0"),
        ({"work_of_adhesion": "50 mJ/m^2", "modulus": "1 MPa"}, "l_a/a0"),  # 167 > 100
    ]
    for kwargs, word in cases:
        args = {"modulus": E_STAR, "work_of_adhesion": _work(0.01), "simulate_size": 64}
        args.update(kwargs)
        with pytest.raises(ParameterError, match=word) as info:
            stick(topo, simulate=True, **args)
        assert "\n" not in str(info.value)
