"""Running studies: Dask local/remote, atomic task files, resume, failures, collect."""

import dataclasses
import json
import os
import socket
import time

import h5netcdf
import numpy as np
import pytest
import xarray as xr

from roughcontact import ParameterError, __version__
from roughcontact.studies import collect_study, load_study, run_study
from roughcontact.studies.store import MARKER, check_task, task_path

STEP_VARS = (
    "offset",
    "load",
    "repulsive_load",
    "attractive_load",
    "repulsive_area",
    "attractive_area",
    "perimeter",
    "converged",
    "branch",
)


def test_tiny_study_on_local_cluster_with_two_processes(tmp_path, make_study):
    study = make_study()
    summary = run_study(study, tmp_path / "out", workers=2, progress=False)
    assert summary.ok and (summary.tasks, summary.completed, summary.failed) == (8, 8, 0)
    files = sorted(p.name for p in (tmp_path / "out").glob("task-*.nc"))
    assert files == [f"task-{i:05d}.nc" for i in range(8)]
    with xr.open_dataset(tmp_path / "out" / files[3], engine="h5netcdf") as ds:
        a = ds.attrs
        params = json.loads(a["task_parameters"])
        assert params["hurst"] == 0.5 and params["adhesion_length"] == 0.05 and a["seed"] == 2
        assert a["study_sha256"] == load_study(study).sha256
        assert a["roughcontact_version"] == __version__ and a["solver_tol"] == 1e-6
        assert a["task_seconds"] > 0 and MARKER in a and "analysis" in a
        assert ds.sizes["step"] == 11 and list(ds["branch"].values[:2]) == ["approach"] * 2

    ds = collect_study(tmp_path / "out")
    assert dict(ds.sizes) == {"task": 8, "step": 11}
    for name in (
        "hurst",
        "rms_slope",
        "short_cutoff",
        "long_cutoff",
        "size",
        "pixel_size",
        "adhesion_length",
        "range",
        "seed",
        "law",
    ):
        assert ds[name].dims == ("task",) and name in ds.coords
    for name in ("kappa", "kappa_rep", "kappa_att", "area_ratio", "pull_off", "failed"):
        assert ds[name].dims == ("task",)
    for name in STEP_VARS:
        assert ds[name].dims == ("task", "step")
    assert not ds["failed"].any() and set(ds["status"].values) == {"done"}
    np.testing.assert_allclose(ds["range"], np.sqrt(24 * ds["adhesion_length"]))
    assert ds.attrs["tasks_done"] == 8


def test_collect_is_deterministic_and_pads_steps(tmp_path, cluster_address, make_study):
    study = make_study(extra="[output]\nfields_at = [0, -1]\nfields = ['gap']")
    run_study(study, tmp_path / "out", scheduler=cluster_address, progress=False)
    a = collect_study(tmp_path / "out", include_timings=False)
    b = collect_study(tmp_path / "out", include_timings=False)
    xr.testing.assert_identical(a, b)
    assert "solve_seconds" not in a and "task_seconds" not in a
    with xr.open_dataset(task_path(tmp_path / "out", "00000"), engine="h5netcdf") as ds:
        assert "gap" in ds and "pressure" not in ds and ds.sizes["field_step"] == 2
    # the combined dataset survives a NetCDF round trip unchanged
    a.to_netcdf(tmp_path / "all.nc", engine="h5netcdf")
    xr.testing.assert_identical(xr.load_dataset(tmp_path / "all.nc", engine="h5netcdf"), a)


def test_fields_at_area_keeps_the_approach_states_nearest_the_areas(tmp_path, make_study):
    extra = "[output]\nfields_at = [0]\nfields_at_area = [0.02, 0.05]\nfields = ['pressure']"
    out = tmp_path / "out"
    run_study(make_study(size=64, extra=extra), out, scheduler="synchronous", progress=False)
    for path in sorted(out.glob("task-*.nc")):
        with xr.open_dataset(path, engine="h5netcdf") as ds:
            assert "gap" not in ds and "deflection" not in ds
            approach = ds["repulsive_area"].values[ds["branch"].values == "approach"]
            nearest = {int(np.argmin(np.abs(approach - a))) for a in (0.02, 0.05)}
            steps = ds["field_step"].values.tolist()
            assert steps == sorted({0} | nearest)
            p = ds["pressure"].values
            np.testing.assert_array_equal((p > 0).mean(axis=(1, 2)), ds["repulsive_area"][steps])
        with h5netcdf.File(path, "r") as f:  # the maps are stored compressed
            assert f.variables["pressure"].compression == "gzip"
            assert f.variables["load"].compression is None


def _strip_marker(path):
    with h5netcdf.File(path, "a") as f:
        del f.attrs[MARKER]


def test_partial_and_corrupt_files_are_recomputed(tmp_path, cluster_address, make_study):
    study = make_study()
    out = tmp_path / "out"
    run_study(study, out, scheduler=cluster_address, progress=False)
    reference = collect_study(out, include_timings=False)
    spec = load_study(study)
    truncated, unmarked, garbage = (task_path(out, i) for i in ("00001", "00004", "00006"))
    truncated.write_bytes(truncated.read_bytes()[:2000])
    _strip_marker(unmarked)
    garbage.write_bytes(b"not a netcdf file")
    (out / ".task-00002.nc.abc.tmp").write_bytes(b"left by a killed run")
    assert check_task(out, spec.tasks[1])[0] is False
    assert check_task(out, spec.tasks[4]) == (False, "no completion marker (incomplete write)")
    assert check_task(out, spec.tasks[0])[0] is True
    before = {p.name: p.stat().st_mtime_ns for p in out.glob("task-*.nc")}
    with pytest.raises(ParameterError, match="already holds study results"):
        run_study(study, out, scheduler=cluster_address, progress=False)
    summary = run_study(study, out, resume=True, scheduler=cluster_address, progress=False)
    assert (summary.skipped, summary.completed, summary.failed) == (5, 3, 0)
    after = {p.name: p.stat().st_mtime_ns for p in out.glob("task-*.nc")}
    assert {k for k in after if after[k] != before.get(k)} == {
        "task-00001.nc",
        "task-00004.nc",
        "task-00006.nc",
    }
    assert not list(out.glob(".task-*"))
    xr.testing.assert_identical(collect_study(out, include_timings=False), reference)


def test_failing_task_is_recorded_and_the_rest_finish(tmp_path, make_study):
    spec = load_study(make_study())
    bad = dataclasses.replace(spec.tasks[2], params={**spec.tasks[2].params, "hurst": 1.5})
    spec = dataclasses.replace(spec, tasks=(*spec.tasks[:2], bad, *spec.tasks[3:]))
    out = tmp_path / "out"
    summary = run_study(spec, out, scheduler="synchronous", progress=False)
    assert (summary.completed, summary.failed, summary.ok) == (7, 1, False)
    assert "1 failed" in str(summary)
    record = json.loads((out / "task-00002.failed.json").read_text())
    assert "hurst" in record["reason"] and "1.5" in record["reason"]
    assert "Traceback" in record["traceback"] and record["parameters"]["hurst"] == 1.5
    ds = collect_study(out)
    assert ds["failed"].values.tolist() == [i == 2 for i in range(8)]
    assert "hurst" in str(ds["failure_reason"].values[2]) and ds["status"].values[2] == "failed"
    assert np.isnan(ds["kappa"].values[2]) and np.all(np.isnan(ds["load"].values[2]))
    assert not ds["converged"].values[2].any() and ds["n_steps"].values[2] == 0
    again = run_study(spec, out, resume=True, scheduler="synchronous", progress=False)
    assert (again.skipped, again.failed) == (7, 1)  # failed tasks are retried on resume


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_unreachable_scheduler_fails_before_any_work(tmp_path, make_study):
    study = make_study()
    t0 = time.perf_counter()
    with pytest.raises(ParameterError, match="cannot reach the Dask scheduler") as err:
        run_study(study, tmp_path / "out", scheduler=f"tcp://127.0.0.1:{_free_port()}")
    assert time.perf_counter() - t0 < 5 and "\n" not in str(err.value)
    assert not (tmp_path / "out").exists()
    with pytest.raises(ParameterError, match="workers"):
        run_study(study, tmp_path / "out", workers=0)
    with pytest.raises(ParameterError, match="local cluster only"):
        run_study(study, tmp_path / "out", scheduler="tcp://127.0.0.1:1", workers=2)


def test_resume_of_a_finished_study_starts_no_cluster(tmp_path, monkeypatch, make_study):
    study = make_study()
    run_study(study, tmp_path / "out", scheduler="synchronous", progress=False)
    import roughcontact.studies.cluster as cluster

    monkeypatch.setattr(cluster, "connect", lambda *a: pytest.fail("connected"))
    s = run_study(study, tmp_path / "out", resume=True, progress=False)
    assert (s.skipped, s.completed) == (8, 0) and os.path.exists(tmp_path / "out" / "study.json")


def test_device_is_checked_before_work_and_float32_is_recorded(tmp_path, make_study):
    study = make_study(extra='dtype = "float32"')
    with pytest.raises(ParameterError, match="device must be 'cpu', 'cuda' or 'cuda:N'"):
        run_study(study, tmp_path / "bad", scheduler="synchronous", device="gpu")
    assert not (tmp_path / "bad").exists()
    out = tmp_path / "out"
    summary = run_study(study, out, scheduler="synchronous", progress=False, device="cpu")
    assert summary.ok
    with xr.open_dataset(sorted(out.glob("task-*.nc"))[0], engine="h5netcdf") as ds:
        assert ds.attrs["solver_dtype"] == "float32" and ds.attrs["dtype"] == "float32"
        assert ds.attrs["device"] == "cpu"


def test_own_cluster_keeps_glibc_malloc_defaults(monkeypatch):
    # Dask's workers get MALLOC_TRIM_THRESHOLD_=65536, which turns off glibc's adaptive
    # mmap threshold (every large array mmapped and unmapped: most of the demo's time went
    # to the kernel); the cluster we start leaves it unset, an explicit setting still wins
    from roughcontact.studies import cluster

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    client, own = cluster.connect(None, 1)
    try:
        env = client.run(lambda: os.environ.get("MALLOC_TRIM_THRESHOLD_"))
        assert list(env.values()) == [None]
        threads = client.run(lambda: os.environ.get("OPENBLAS_NUM_THREADS"))
        assert list(threads.values()) == ["1"]  # Dask's other settings are kept
    finally:
        client.close()
        own.close()


def test_unconverged_steps_give_an_analysis_error_per_task_counted_in_the_summary(
    tmp_path, make_study
):
    # max_iter = 2: the adhesive steps around 1 % do not converge; the analysis refuses
    # to interpolate across them, each task records why, the summary counts them
    spec = load_study(make_study(extra="max_iter = 2"))
    out = tmp_path / "out"
    summary = run_study(spec, out, scheduler="synchronous", progress=False)
    assert summary.failed == 0 and summary.unconverged_steps > 0
    ds = collect_study(out)
    errors = [str(e) for e in ds["analysis_error"].values]
    assert summary.analysis_errors == sum(1 for e in errors if e) > 0
    assert f"{summary.analysis_errors} without analysis" in str(summary)
    for i, e in enumerate(errors):
        if e:  # unconverged around the target, or short of it because of them
            assert "did not converge" in e and ("residual" in e or "not reached" in e)
            assert np.isnan(ds["kappa"].values[i]) and ds["verdict"].values[i] == ""
    again = run_study(spec, out, resume=True, scheduler="synchronous", progress=False)
    assert again.analysis_errors == summary.analysis_errors  # counted from the files too
    # the explicit opt-in analyses them, marked unreliable; the key changes the task keys
    opt_in = load_study(make_study(extra="max_iter = 2\n[analysis]\nallow_unconverged = true",
                                   name="opt_in.toml"))  # fmt: skip
    assert opt_in.tasks[0].key != spec.tasks[0].key
    summary = run_study(opt_in, tmp_path / "in", scheduler="synchronous", progress=False)
    ds = collect_study(tmp_path / "in")
    assert summary.analysis_errors < len(errors)
    analysed = np.isfinite(ds["kappa"].values) | np.isinf(ds["kappa"].values)
    assert (ds["reliable"].values[analysed] == 0).any()


def test_default_analysis_keys_keep_the_task_keys(make_study):
    plain = load_study(make_study())
    spelled = load_study(make_study(
        extra="[analysis]\nallow_unconverged = false\nhard_wall_reference = true",
        name="spelled.toml",
    ))  # fmt: skip
    assert [t.key for t in plain.tasks] == [t.key for t in spelled.tasks]
