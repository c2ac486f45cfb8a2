"""``roughcontact analyze``: the one rule, both κ_rep, unconverged brackets refused."""

import json

import numpy as np
from click.testing import CliRunner

import roughcontact as rc
from roughcontact.cli.main import main


def _path(tmp_path, max_iter):
    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=2)
    law = rc.SmoothLJ93.from_adhesion_length(0.005)
    offsets = rc.relative_offsets(h, np.arange(0.5, -2.51, -0.125), unit="rms_height",
                                  interaction=law)  # fmt: skip
    ds = rc.approach_retract(h, rc.Substrate(h.shape), law, offsets=offsets, retract=False,
                             max_iter=max_iter, tol=1e-7)  # fmt: skip
    f = tmp_path / f"path{max_iter}.nc"
    ds.to_netcdf(f, engine="h5netcdf")
    return f


def test_analyze_reports_both_kappa_rep_and_the_verdict(tmp_path):
    r = CliRunner().invoke(main, ["analyze", str(_path(tmp_path, 5000)), "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert out["verdict"] in ("sticky", "not sticky") and out["reliable"] is True
    assert out["sticky"] is (out["inverse_kappa"] < 0)
    assert out["kappa_rep_hard_wall"] < out["kappa_rep"] and out["band_width"] > 0
    assert out["necessary_condition"].startswith("not applicable")
    assert out["necessary_condition_met"] is None


def test_analyze_refuses_an_unconverged_bracket_with_exit_3(tmp_path):
    f = _path(tmp_path, 3)
    r = CliRunner().invoke(main, ["analyze", str(f), "--json"])
    assert r.exit_code == 3
    assert "did not converge" in r.stderr and "residual" in r.stderr and r.stdout == ""
    r = CliRunner().invoke(main, ["analyze", str(f), "--json", "--allow-unconverged"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["reliable"] is False
