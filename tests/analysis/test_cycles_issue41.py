"""Cycles a user can trust (issue 41, items 6 and 7).

Oracles: a jump-free cycle dissipates nothing (on one stable branch the energy is a
potential of the offset), so W = 0 within the solver's tolerance, never negative; a
path that does not return unloaded to its first offset is no closed cycle; a hard-core
law has no soft repulsion to widen the contacts.
"""

import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
from click.testing import CliRunner

import roughcontact as rc
from roughcontact.analysis.hard_wall_reference import _band_warning
from roughcontact.analysis.hysteresis import hysteresis_from_steps
from roughcontact.cli.main import main


def _jump_free(noise):
    """A smooth N(d) approached and retracted through the same offsets; the retraction's
    loads off by ``noise`` (a solver's tolerance)."""
    d = np.linspace(2.0, -1.0, 31)
    n = np.where(d < 0, d**2, 0.0) - 0.05 * np.exp(-np.abs(d))
    off = np.concatenate([d, d[::-1]])
    load = np.concatenate([n, n[::-1] + noise])
    branch = ["approach"] * d.size + ["retract"] * d.size
    return off, load, branch


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_a_cycle_without_jumps_is_zero_within_the_solver_tolerance(sign):
    off, load, branch = _jump_free(sign * 1e-8)
    jump = np.zeros(len(off), bool)
    raw = hysteresis_from_steps(off, load, branch).raw_dissipated_energy  # the trapezoid's
    # higher loads on the way back: -∮N dd < 0, a cycle "producing" energy
    assert raw == pytest.approx(-sign * 1e-8 * 3.0, rel=1e-6)
    hy = hysteresis_from_steps(off, load, branch, jump, solver_tolerance=1e-7)
    assert hy.dissipated_energy == 0.0 and hy.zero_within_tolerance
    assert hy.raw_dissipated_energy == pytest.approx(raw, rel=1e-12)
    # the bound: the solver's tolerance on N/A0 times the path's length in offset (6)
    assert hy.tolerance == pytest.approx(1e-7 * 6.0, rel=1e-12)
    assert hy.energy_uncertainty >= abs(hy.raw_dissipated_energy)
    assert hy.to_dict()["zero_within_tolerance"] is True
    # without the solver's tolerance: 1e-6 of the path's work scale, still far above 3e-8
    assert hysteresis_from_steps(off, load, branch, jump).dissipated_energy == 0.0
    # dissipation far beyond the bound with no flagged jump is kept, with a warning
    off2, load2, branch2 = _jump_free(sign * 1e-3)
    big = hysteresis_from_steps(off2, load2, branch2, jump, solver_tolerance=1e-7)
    assert not big.zero_within_tolerance and any("without flagged jumps" in w for w in big.warnings)
    if sign < 0:  # dissipation: kept
        assert big.dissipated_energy == big.raw_dissipated_energy and big.dissipated_energy > 0
    else:  # "production": never negative, 0 within the deficit, said
        assert big.dissipated_energy == 0.0 and big.energy_uncertainty >= -big.raw_dissipated_energy
        assert any("negative beyond its bound" in w for w in big.warnings)


def test_stick_simulate_on_a_stiff_material_never_reports_negative_hysteresis(tmp_path):
    h = rc.self_affine(128, hurst=0.8, rms_slope=0.1, short_cutoff=1.2, pixel_size=0.6, seed=5)
    path = tmp_path / "fine.npy"
    np.save(path, h)
    r = rc.stick(path, pixel_size="0.6 nm", height_unit="nm", periodic=True, detrend="height",
                 modulus="160 GPa", work_of_adhesion="0.1 J/m^2", simulate=True,
                 simulate_size=64, simulate_seeds=2)  # fmt: skip
    seeds = r.hysteresis["seeds"]
    for s in seeds:
        assert s["dissipated_energy_si"] >= 0
        if s["jumps"] == 0:
            assert s["zero_within_tolerance"] and s["dissipated_energy_si"] == 0.0
            assert s["energy_uncertainty_si"] >= abs(s["raw_dissipated_energy_si"])
            assert s["tolerance_si"] > 0
    from roughcontact.topography.report import summary

    text = "\n".join(summary(r))
    if all(s["jumps"] == 0 for s in seeds):
        assert "hysteresis: none: no seed's cycle has a jump" in text


def _open_path(tmp_path):
    """A Maugis-Dugdale (hard core) path that starts in contact and stops at 8 % repulsive
    area: its retraction ends in contact, under load."""
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=2)
    sub = rc.Substrate((32, 32), contact_modulus=1.0)
    law = rc.MaugisDugdale(work_of_adhesion=0.02, range=0.5)
    offsets = np.linspace(h.max() - 0.01, h.max() - 2.0, 24)
    ds = rc.approach_retract(h, sub, law, offsets=offsets, retract=True, until_area=0.08,
                             tol=1e-6)  # fmt: skip
    f = tmp_path / "open.nc"
    ds.to_netcdf(f, engine="h5netcdf")
    return f


def test_analyze_says_a_cycle_is_not_closed(tmp_path):
    f = _open_path(tmp_path)
    args = ["analyze", str(f), "--no-hard-wall-reference", "--target-area", "0.04",
            "--allow-unconverged"]  # fmt: skip
    r = CliRunner().invoke(main, [*args, "--json"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["cycle_closed"] is False
    assert any(w.startswith("the cycle is not closed") for w in d["warnings"])
    text = CliRunner().invoke(main, args).stdout
    assert "NOT a closed cycle" in text and "note: the cycle is not closed" in text
    assert "over the whole cycle" not in text


def test_the_kappa_rep_band_warning_names_the_cause_of_the_law():
    ref = SimpleNamespace(kappa_rep=2.1, kappa_rep_corrected=2.0)
    base = {"pixel_size": 1.0, "contact_modulus": 1.0}
    dugdale = SimpleNamespace(attrs={**base, "interaction_name": "dugdale"})
    soft = SimpleNamespace(attrs={**base, "interaction_name": "lj93smooth", "stiffness": 0.5})
    hard = _band_warning(dugdale, 3.0, 0.4, 0.3, ref)
    assert "hard core" in hard and "adhesion" in hard and "finite stiffness" not in hard
    assert "site stiffness" not in hard and "stiffer wall" not in hard
    wall = _band_warning(soft, 3.0, 0.4, 0.3, ref)
    assert "site stiffness k = 0.5 E*/a0" in wall and "hard core" not in wall
    assert math.isclose(0.3, 0.3)
