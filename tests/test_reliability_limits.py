"""Reliability round four: crafted path files, memory limits, options checked when given.

A path file whose ``grid`` attribute disagrees with its data or would not fit in memory
is refused before anything of that size is allocated; a corrupted file is "not a
readable NetCDF file"; the memory estimate includes RLIMIT_AS and the cgroup's limit;
the path file stores its length unit; --pressure-scale, --length-scale and
--checkpoint-seconds are checked whenever they are given; the local cluster never
touches the shared $TMPDIR/dask-scratch-space and removes its own stale scratch.
"""

import json
import os
import random
import subprocess
import sys
import time

import numpy as np
import pytest
from _helpers import DATA, POSIX
from _helpers import cli_one_line_error as _one_line
from _helpers import random_surface as _surface
from click.testing import CliRunner

from roughcontact import _memory, _validate
from roughcontact.cli.main import main


@pytest.fixture(scope="module")
def path_file(tmp_path_factory):
    """A small hard-wall path with a retraction, written by ``roughcontact path``."""
    d = tmp_path_factory.mktemp("path")
    np.save(d / "s.npy", _surface(1, 32))
    out = d / "p.nc"
    args = ["path", str(d / "s.npy"), "--offsets", "0.5", "-2.5", "0.125", "--offset-unit",
            "rms_height", "--retract", "-o", str(out)]  # fmt: skip
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 0, r.output
    return out


def _crafted(path_file, tmp_path, name, **attrs):
    import xarray as xr

    ds = xr.load_dataset(path_file, engine="h5netcdf")
    drop = attrs.pop("drop", ())
    ds = ds.drop_vars(list(drop))
    ds.attrs.update(attrs)
    out = tmp_path / name
    ds.to_netcdf(out, engine="h5netcdf")
    return out


def test_a_grid_attribute_that_disagrees_or_does_not_fit_is_refused_before_allocating(
    path_file, tmp_path, monkeypatch
):
    import roughcontact.elastic as elastic

    def no_substrate(*a, **k):
        raise AssertionError("a substrate of the claimed grid was made")

    monkeypatch.setattr(elastic.Substrate, "from_attrs", no_substrate, raising=False)
    lying = _crafted(path_file, tmp_path, "lying.nc", grid=[100000, 100000])
    _one_line(CliRunner().invoke(main, ["analyze", str(lying)]), "grid", "disagrees", "32 x 32")
    huge = _crafted(path_file, tmp_path, "huge.nc", grid=[100000, 100000], drop=["heights"])
    monkeypatch.setattr(_validate, "available_memory", lambda: 4 * 2**30)  # 4 GiB here
    _one_line(CliRunner().invoke(main, ["analyze", str(huge)]), "grid", "memory", "4 GiB")


def test_a_corrupted_path_file_is_not_a_readable_netcdf_file(path_file, tmp_path):
    data = bytearray(path_file.read_bytes())
    rng = random.Random(1)
    for i in rng.sample(range(2000, len(data)), 200):
        data[i] ^= 0xFF
    bad = tmp_path / "flipped.nc"
    bad.write_bytes(bytes(data))
    _one_line(CliRunner().invoke(main, ["analyze", str(bad)]), "not a readable NetCDF file")


def test_the_path_file_stores_its_length_unit_and_analyze_never_guesses(path_file, tmp_path):
    import xarray as xr

    assert xr.load_dataset(path_file, engine="h5netcdf").attrs["length_unit"] == "a0"
    args = ["analyze", "--no-hard-wall-reference", "--target-area", "0.02", "--json",
            "--pressure-scale", "1 MPa"]  # fmt: skip
    out = json.loads(CliRunner().invoke(main, [*args, str(path_file)]).stdout)
    assert out["nominal_area_si"] is None and "a0" in out["si_scales"]
    # an old file without the attribute: unknown, even with its surface file around
    old = _crafted(path_file, tmp_path, "old.nc", surface_file="scan.spm")
    with xr.load_dataset(old, engine="h5netcdf") as ds:
        del ds.attrs["length_unit"]
        ds.to_netcdf(tmp_path / "older.nc", engine="h5netcdf")
    (tmp_path / "scan.spm").write_bytes(b"instrument file")
    out = json.loads(CliRunner().invoke(main, [*args, str(tmp_path / "older.nc")]).stdout)
    assert out["nominal_area_si"] is None and "unknown" in out["si_scales"]
    metres = _crafted(path_file, tmp_path, "m.nc", length_unit="m")
    out = json.loads(CliRunner().invoke(main, [*args, str(metres)]).stdout)
    assert out["nominal_area_si"] == pytest.approx(32 * 32, rel=1e-12)  # A0 in m^2 as is


@pytest.mark.parametrize("value", ["0", "-1", "nan", "inf", "1e308", "abc", ""])
def test_pressure_and_length_scales_are_checked_when_given(value, path_file):
    for option in ("--pressure-scale", "--length-scale"):
        r = CliRunner().invoke(main, ["analyze", str(path_file), option, value])
        _one_line(r, option)


@pytest.mark.parametrize("value", ["nan", "inf", "-1"])
def test_checkpoint_seconds_must_be_finite(value, tmp_path):
    np.save(tmp_path / "s.npy", _surface())
    args = ["path", str(tmp_path / "s.npy"), "--loads", "1e-3", "2e-3", "1e-3", "-o",
            str(tmp_path / "p.nc"), "--checkpoint-seconds", value]  # fmt: skip
    _one_line(CliRunner().invoke(main, args), "--checkpoint-seconds")
    assert not (tmp_path / "p.nc").exists()


def test_stick_dpi_is_checked_without_a_report_directory(monkeypatch):
    import roughcontact.topography.verdict as verdict

    def no_work(*a, **k):
        raise AssertionError("analysed before --dpi was checked")

    monkeypatch.setattr(verdict, "stick", no_work)
    args = ["stick", str(DATA / "di-1.di"), "--modulus", "1GPa", "--work-of-adhesion",
            "50mJ/m^2", "--dpi", "0"]  # fmt: skip
    _one_line(CliRunner().invoke(main, args), "dpi")


def test_load_help_names_the_units_of_modulus():
    text = " ".join(CliRunner().invoke(main, ["contact", "--help"]).output.split())
    assert "units of --modulus" in text


# --- the memory estimate: RAM, RLIMIT_AS, the cgroup --------------------------------------


def test_the_memory_estimate_includes_the_cgroup_limits(tmp_path):
    v2 = tmp_path / "v2"
    (v2 / "job" / "step").mkdir(parents=True)
    (v2 / "job" / "memory.max").write_text(f"{3 * 2**30}\n")
    (v2 / "job" / "memory.current").write_text(f"{2 * 2**30}\n")
    (v2 / "job" / "memory.stat").write_text(f"anon 1\ninactive_file {2**29}\n")
    (v2 / "job" / "step" / "memory.max").write_text("max\n")
    proc = tmp_path / "cgroup"
    proc.write_text("0::/job/step\n")
    left = _memory.cgroup_memory_left(str(proc), str(v2))
    assert left == pytest.approx(1.5 * 2**30, rel=1e-12)  # 3 GiB - (2 GiB - 0.5 GiB cache)
    v1 = tmp_path / "v1"
    (v1 / "memory").mkdir(parents=True)
    (v1 / "memory" / "memory.limit_in_bytes").write_text(f"{2**30}\n")
    (v1 / "memory" / "memory.usage_in_bytes").write_text(f"{2**28}\n")
    proc.write_text("4:memory:/elsewhere\n0::/\n")  # a namespace: the mount is its own
    assert _memory.cgroup_memory_left(str(proc), str(v1)) == pytest.approx(0.75 * 2**30)
    (v1 / "memory" / "memory.limit_in_bytes").write_text("9223372036854771712\n")
    assert _memory.cgroup_memory_left(str(proc), str(v1)) is None  # no limit


@pytest.mark.skipif(not POSIX, reason="ulimit -v")
def test_an_address_space_limit_refuses_a_large_surface_in_one_line(tmp_path):
    code = (
        "import resource, sys; from roughcontact.cli.main import main; "
        "resource.setrlimit(resource.RLIMIT_AS, (3_000_000 * 1024, resource.RLIM_INFINITY)); "
        "sys.argv = ['roughcontact', 'surface', sys.argv[1], '--size', '12000', '--hurst', "
        "'0.8', '--rms-slope', '0.1', '--short-cutoff', '4']; main()"
    )
    r = subprocess.run([sys.executable, "-c", code, str(tmp_path / "m.npy")],
                       capture_output=True, text=True, timeout=120)  # fmt: skip
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "too large" in lines[0] and "Traceback" not in r.stderr
    assert not (tmp_path / "m.npy").exists()


# --- the local cluster's scratch: never the shared path; stale ones removed ---------------


def test_a_local_study_creates_nothing_under_a_planted_dask_scratch_space(
    tmp_path, make_study, monkeypatch
):
    pytest.importorskip("distributed")
    import tempfile

    from roughcontact.studies import run_study

    tmp = tmp_path / "tmp"
    planted = tmp / "dask-scratch-space"
    planted.mkdir(parents=True)
    planted.chmod(0o777)
    (planted / "worker-planted").mkdir()
    monkeypatch.setenv("TMPDIR", str(tmp))
    monkeypatch.setattr(tempfile, "tempdir", str(tmp))
    summary = run_study(make_study(num=2), tmp_path / "out", workers=1, progress=False)
    assert summary.ok
    assert sorted(p.name for p in planted.iterdir()) == ["worker-planted"]
    assert not any(p.name.startswith("roughcontact-dask-") for p in tmp.iterdir())


@pytest.mark.skipif(not POSIX, reason="owners and flock")
def test_stale_scratch_directories_of_ours_are_removed_live_or_young_ones_kept(tmp_path):
    from roughcontact.studies import _scratch

    old = time.time() - 2 * _scratch.STALE_SCRATCH_SECONDS
    stale = tmp_path / "roughcontact-dask-stale"
    (stale / "dask-scratch-space").mkdir(parents=True)
    young = tmp_path / "roughcontact-dask-young"
    young.mkdir()
    live = tmp_path / "roughcontact-dask-live"
    live.mkdir()
    held = _scratch.lock_scratch(str(live))
    other = tmp_path / "something-else"
    other.mkdir()
    target = tmp_path / "target"
    target.mkdir()
    link = tmp_path / "roughcontact-dask-link"
    link.symlink_to(target)
    for p in (stale, live, other, target):
        os.utime(p, (old, old))
    os.utime(link, (old, old), follow_symlinks=False)
    try:
        removed = _scratch.remove_stale_scratch(tmp_path)
    finally:
        _scratch.remove_scratch(str(live), held)
    assert removed == [str(stale)] and not stale.exists()
    assert young.is_dir() and other.is_dir() and target.is_dir() and link.is_symlink()


def test_a_damaged_task_file_is_counted_missing_not_a_traceback(tmp_path, make_study):
    from roughcontact.studies import collect_study, run_study

    out = tmp_path / "study"
    run_study(make_study(num=2), out, scheduler="synchronous", progress=False)
    task = out / "task-00001.nc"
    data = bytearray(task.read_bytes())
    for i in random.Random(2).sample(range(2000, len(data)), 200):
        data[i] ^= 0xFF
    task.write_bytes(bytes(data))
    ds = collect_study(out)
    assert ds.attrs["tasks_missing"] == 1 and ds.attrs["tasks_done"] == 7
    assert "damaged" in str(ds["failure_reason"].sel(task="00001").values)
    r = CliRunner().invoke(main, ["figures", str(out), "-o", str(tmp_path / "fig"),
                                  "--format", "png"])  # fmt: skip
    assert r.exit_code == 0, r.output
