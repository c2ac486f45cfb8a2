"""``roughcontact study report``: data, claims, figures and the report of a study."""

import html
import json
import re

import pandas as pd
import pytest
import xarray as xr
from _browser import external_references
from _helpers import assert_numbers_close
from click.testing import CliRunner

from roughcontact.cli.main import main
from roughcontact.studies import load_study, run_study
from roughcontact.studies.runner import _pending


def test_report_from_a_study_and_from_its_collected_data(tmp_path, make_study):
    study = make_study()
    out = tmp_path / "out"
    run_study(load_study(study), out, scheduler="synchronous", progress=False)
    report = tmp_path / "report"
    r = CliRunner().invoke(main, ["study", "report", str(out), "-o", str(report)])
    assert r.exit_code == 0, r.output
    assert "analysed tasks" in r.output
    text = (report / "README.md").read_text()
    for n in range(1, 9):
        assert f"## {n}." in text
    claims = json.loads((report / "claims.json").read_text())
    ds = xr.load_dataset(report / "data" / "collected.nc", engine="h5netcdf")
    assert "task_seconds" not in ds  # reproducible files: no wall-clock times
    tasks = pd.read_csv(report / "data" / "tasks.csv", dtype={"task": str})
    steps = pd.read_csv(report / "data" / "steps.csv", dtype={"task": str})
    assert len(tasks) == 8 and set(steps.task) == set(tasks.task)
    assert len(steps) == int(ds["n_steps"].sum())
    # per-task numbers in the CSV are the collected ones
    assert tasks["kappa"].to_numpy() == pytest.approx(ds["kappa"].values, nan_ok=True)
    for name in ("fig2_area_load", "fig3_collapse", "fig4_theory"):
        assert (report / "figures" / f"{name}.png").stat().st_size > 1000
    # report.html beside README.md: the same sections, the claims' numbers, Figs. 2-4 inline
    page = (report / "report.html").read_text()
    words = " ".join(html.unescape(re.sub(r"<[^>]+>", " ", page)).split())
    for heading in re.findall(r"^## (.+)$", text, flags=re.M):
        assert " ".join(heading.replace("`", "").split()) in words, heading
    crit = claims["eq10_criterion"]["measured_kappa_rep"]
    assert f"With the measured κ_rep: {crit['agree']} of {crit['decided']} decided" in words
    assert len(re.findall(r'<img src="data:image/png;base64,', page)) == 3
    assert external_references(page) == [] and "report.html" in r.output
    # the committed data alone regenerate the same numbers
    again = tmp_path / "again"
    r = CliRunner().invoke(
        main, ["study", "report", str(report / "data" / "collected.nc"), "-o", str(again)]
    )
    assert r.exit_code == 0, r.output
    # (the same machine: its numbers to 1e-12, keys, verdicts and texts exactly)
    assert_numbers_close(json.loads((again / "claims.json").read_text()), claims, rel=1e-12)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["again", "out", "report", "tiny.toml"]


def test_bad_input_is_one_line(tmp_path):
    bad = tmp_path / "x.nc"
    xr.Dataset({"a": ("x", [1.0])}).to_netcdf(bad, engine="h5netcdf")
    for args in (
        [str(bad), "-o", str(tmp_path / "r")],
        [str(tmp_path / "missing"), "-o", str(tmp_path / "r")],
        [str(bad), "-o", str(tmp_path / "r"), "--confidence", "1.5"],
    ):
        r = CliRunner().invoke(main, ["study", "report", *args])
        assert r.exit_code == 2, r.output
        assert len(r.output.strip().splitlines()) == 1 and "Traceback" not in r.output


def test_tasks_run_seed_by_seed(tmp_path, make_study):
    """A study stopped part-way holds whole realisations: seeds are submitted in order."""
    spec = load_study(make_study())
    _, todo = _pending(spec, tmp_path / "none", resume=False)
    seeds = [t.params["seed"] for t in todo]
    assert seeds == sorted(seeds) and len(set(seeds)) == 2
    assert [t.id for t in todo if t.params["seed"] == 1] == sorted(
        t.id for t in spec.tasks if t.params["seed"] == 1
    )


def test_report_of_a_non_adhesive_study(tmp_path):
    """A hard-wall study has no adhesion length: the report still runs (no Eq. 10 claims)."""
    study = tmp_path / "hw.toml"
    study.write_text(
        '[study]\nname = "hw"\n[surface]\nsize = 32\nhurst = 0.8\nrms_slope = 0.1\n'
        'short_cutoff = 4.0\nseeds = [1, 2]\n[interaction]\nlaw = "hardwall"\n'
        '[path]\nunit = "rms_height"\nstart = 0.5\nstop = -2.0\nnum = 6\n[solver]\ntol = 1e-6\n'
    )
    out = tmp_path / "out"
    run_study(load_study(study), out, scheduler="synchronous", progress=False)
    r = CliRunner().invoke(main, ["study", "report", str(out), "-o", str(tmp_path / "report")])
    assert r.exit_code == 0, r.output
    assert "Traceback" not in r.output
    assert (tmp_path / "report" / "README.md").read_text().startswith("#")
