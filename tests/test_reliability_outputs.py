"""Reliability round three, writing and bounds: one atomic writer, limits up front.

Links at output names are replaced, never written through; a full disk while a file is
overwritten keeps the old file; outputs are checked before the work; study sizes and
strings are refused before anything starts; foreign task files are not counted; Ctrl-C
while the command line starts is one line; the local cluster's scratch is private.
"""

import errno
import json
import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from _helpers import DATA, POSIX, SMOKE
from _helpers import cli_one_line_error as _one_line
from _helpers import random_surface as _surface
from click.testing import CliRunner

from roughcontact import ParameterError, _io, _startup
from roughcontact.cli.main import main
from roughcontact.studies import study_from_dict
from roughcontact.surfaces import load_heights, save_heights

# --- bounds before anything starts -----------------------------------------------------


def _smoke(**changes):
    import tomllib

    data = tomllib.loads(SMOKE.read_text())
    for dotted, value in changes.items():
        section, key = dotted.split("__")
        data.setdefault(section, {})[key] = value
    return data


@pytest.mark.parametrize(
    "changes, words",
    [
        ({"study__name": "a\0b"}, ["name", "control character"]),
        ({"study__description": "x\x00"}, ["description", "control character"]),
        ({"surface__size": 100_000}, ["size", "16384"]),
        ({"surface__size": 2_000_000_000}, ["size"]),
        ({"surface__size": 2**63}, ["size"]),
        ({"surface__rms_slope": 1e300}, ["rms_slope", "1e4"]),
        ({"surface__rms_slope": 1e-300}, ["rms_slope", "1e-8"]),
        ({"surface__rms_height": 1e300, "surface__rms_slope": None}, ["rms_height"]),
        ({"substrate__contact_modulus": 1e50}, ["contact_modulus", "1e20"]),
        ({"substrate__contact_modulus": 1e-40}, ["contact_modulus", "1e-20"]),
        ({"surface__seeds": list(range(1000)), "surface__hurst": [i / 400 for i in range(1, 201)]},
         ["tasks", "100000"]),
        ({"path__values": [0.1] * 150_000, "path__start": None}, ["150000", "100000"]),
        ({"path__lead_in": [1.0] * 100_000}, ["lead_in", "100000"]),
        ({"solver__dtype": "float32", "solver__tol": 0.999}, ["tol", "float32"]),
    ],
)  # fmt: skip
def test_study_bounds_are_refused_up_front(changes, words):
    data = _smoke(**changes)
    data["surface"] = {k: v for k, v in data["surface"].items() if v is not None}
    if data["path"].get("start") is None:
        for key in ("start", "stop", "step"):
            data["path"].pop(key, None)
    t0 = time.monotonic()
    with pytest.raises(ParameterError) as err:
        study_from_dict(data)
    message = str(err.value)
    assert "\n" not in message
    assert message.count("study:") == 1, message  # no "study: [output] study: ..."
    for word in words:
        assert word in message, (word, message)
    assert time.monotonic() - t0 < 5  # refused before 10^5+ tasks are built


def test_path_step_error_is_not_prefixed_twice():
    data = _smoke(path__step=1e-9)
    data["output"]["fields_at"] = [1]
    with pytest.raises(ParameterError) as err:
        study_from_dict(data)
    assert str(err.value).count("study:") == 1, str(err.value)


def test_workers_are_capped_by_the_cores():
    from roughcontact.studies.cluster import check_options, max_workers

    check_options(None, max_workers(), None, False)
    for bad in (max_workers() + 1, 1000, 0, True):
        with pytest.raises(ParameterError, match="workers"):
            check_options(None, bad, None, False)
    r = CliRunner().invoke(main, ["study", "run", str(SMOKE), "-o", "x", "--workers", "1000"])
    _one_line(r, "workers", "per CPU core")


def test_float32_tolerance_is_bounded_on_the_command_line(tmp_path):
    np.save(tmp_path / "s.npy", _surface())
    args = ["contact", str(tmp_path / "s.npy"), "--load", "1e-2", "--dtype", "float32"]
    _one_line(CliRunner().invoke(main, [*args, "--tol", "0.999"]), "tol", "float32")


def test_float32_accepts_the_offsets_float64_accepts():
    from roughcontact import Substrate, solve

    h = _surface(3, 32)
    h -= h.mean()
    sub = Substrate(h.shape)
    for dtype in ("float64", "float32"):
        res = solve(h, sub, offset=0.0, dtype=dtype, tol=1e-4)
        assert res.load > 0


def test_contact_refuses_a_tiny_free_boundary_surface_like_path(tmp_path):
    np.save(tmp_path / "s.npy", np.array([[0.0, 1.0], [0.5, 0.2]]))
    for args in (
        ["contact", str(tmp_path / "s.npy"), "--non-periodic", "--offset", "0.5"],
        ["path", str(tmp_path / "s.npy"), "--non-periodic", "--offsets", "1", "0", "0.5",
         "-o", str(tmp_path / "p.nc")],
    ):  # fmt: skip
        _one_line(CliRunner().invoke(main, args), "3 x 3")


# --- one writer: atomic, never through a link, checked before the work -----------------


def test_save_heights_replaces_a_link_instead_of_writing_through_it(tmp_path):
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    for name in ("out.npy", "out.txt"):
        link = tmp_path / name
        link.symlink_to(target)
        save_heights(link, _surface())
        assert not link.is_symlink()
        assert target.read_text() == "keep me"
        np.testing.assert_array_equal(load_heights(link), _surface())


def _enospc(monkeypatch):
    real_write = os.write

    def full(fd, data):
        if os.readlink(f"/proc/self/fd/{fd}").endswith(".tmp"):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        return real_write(fd, data)

    monkeypatch.setattr(os, "write", full)


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc")
def test_full_disk_overwriting_a_surface_keeps_the_old_file(tmp_path, monkeypatch):
    out = tmp_path / "s.npy"
    save_heights(out, _surface(1))
    before = out.read_bytes()
    _enospc(monkeypatch)
    with pytest.raises(_io.WriteError, match="no space left"):
        save_heights(out, _surface(2))
    assert out.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["s.npy"]  # no temporary file left


@pytest.mark.skipif(not os.path.isdir("/proc/self/fd"), reason="needs /proc")
def test_full_disk_on_the_command_line_is_one_line_and_keeps_the_old_files(tmp_path, monkeypatch):
    s, f = tmp_path / "s.npy", tmp_path / "f.npz"
    np.save(s, _surface())
    f.write_bytes(b"old fields")
    _enospc(monkeypatch)
    args = ["surface", str(s), "--size", "16", "--hurst", "0.8", "--rms-slope", "0.1",
            "--short-cutoff", "4", "--seed", "1"]  # fmt: skip
    _one_line(CliRunner().invoke(main, args), "no space left", code=1)
    np.testing.assert_array_equal(np.load(s), _surface())
    r = CliRunner().invoke(main, ["contact", str(s), "--load", "1e-2", "--save-fields", str(f)])
    _one_line(r, "no space left", code=1)
    assert f.read_bytes() == b"old fields"


def test_save_fields_writes_exactly_the_name_given(tmp_path):
    np.save(tmp_path / "s.npy", _surface())
    base = ["contact", str(tmp_path / "s.npy"), "--load", "1e-2", "--save-fields"]
    _one_line(CliRunner().invoke(main, [*base, str(tmp_path / "sf.dat")]), ".npz", "sf.dat")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.npy"]  # nothing computed
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    link = tmp_path / "f.npz"
    link.symlink_to(target)
    # a link at the name the user gave is refused (-o /dev/stdout), never written through
    _one_line(CliRunner().invoke(main, [*base, str(link)]), "symbolic link", "f.npz")
    assert target.read_text() == "keep me" and link.is_symlink()
    r = CliRunner().invoke(main, [*base, str(tmp_path / "g.npz")])
    assert r.exit_code == 0, r.output
    with np.load(tmp_path / "g.npz") as z:
        assert set(z.files) == {"pressure", "gap", "deflection"}


@pytest.mark.parametrize("command", ["path", "surface", "contact"])
def test_unwritable_output_is_refused_before_any_work(tmp_path, command, monkeypatch):
    np.save(tmp_path / "s.npy", _surface())
    missing = tmp_path / "missing" / "out"
    args = {
        "path": ["path", str(tmp_path / "s.npy"), "--loads", "1e-3", "2e-3", "1e-3", "-o",
                 f"{missing}.nc"],
        "surface": ["surface", f"{missing}.npy", "--size", "16", "--hurst", "0.8",
                    "--rms-slope", "0.1", "--short-cutoff", "4"],
        "contact": ["contact", str(tmp_path / "s.npy"), "--load", "1e-2", "--save-fields",
                    f"{missing}.npz"],
    }[command]  # fmt: skip
    import roughcontact.solvers as solvers
    import roughcontact.surfaces as surfaces

    def no_work(*a, **k):
        raise AssertionError("computed before the output was checked")

    monkeypatch.setattr(solvers, "approach_retract", no_work)
    monkeypatch.setattr(solvers, "solve", no_work)
    monkeypatch.setattr(surfaces, "self_affine", no_work)
    _one_line(CliRunner().invoke(main, args), "does not exist")


def test_output_directories_are_checked_before_any_work(tmp_path):
    (tmp_path / "file").write_text("")
    bad = str(tmp_path / "file" / "out")
    with pytest.raises(ParameterError, match="not a directory"):
        _io.check_directory_writable(bad)
    with pytest.raises(ParameterError, match="exists and is not a directory"):
        _io.check_directory_writable(tmp_path / "file")
    assert _io.check_directory_writable(tmp_path / "new" / "deeper") == tmp_path / "new" / "deeper"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file"]  # nothing created
    scan = str(DATA / "di-1.di")
    for args in (
        ["figures", str(tmp_path), "-o", bad],
        ["stick", scan, "--modulus", "1 GPa", "--work-of-adhesion", "50 mJ/m^2", "-o", bad],
        ["demo", "--size", "16", "-o", bad],
    ):
        _one_line(CliRunner().invoke(main, args), "not a directory")


def test_output_directory_replaces_a_planted_link(tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    report = tmp_path / "report"
    report.mkdir()
    (report / "data").symlink_to(elsewhere)
    made = _io.output_directory(report / "data")
    assert made.is_dir() and not made.is_symlink()
    _io.write_bytes_atomic(made / "x.csv", b"1\n")
    assert list(elsewhere.iterdir()) == []
    assert _io.output_directory(made) == made  # a real directory is kept


def test_check_writable_names_the_problem(tmp_path):
    assert _io.check_writable(tmp_path / "ok.nc") == tmp_path / "ok.nc"
    assert list(tmp_path.iterdir()) == []  # the probe is gone
    with pytest.raises(ParameterError, match="is a directory"):
        _io.check_writable(tmp_path)
    (tmp_path / "file").write_text("")
    with pytest.raises(ParameterError, match="not a directory"):
        _io.check_writable(tmp_path / "file" / "out.nc")


# --- foreign task files --------------------------------------------------------------


def test_a_task_file_of_another_study_is_not_counted(tmp_path, make_study):
    from roughcontact.studies import collect_study, run_study
    from roughcontact.studies.collect import FOREIGN

    data = _smoke()
    data["surface"].update(size=16, hurst=0.8, seeds=[1, 2])
    data["interaction"] = {"law": "hardwall"}
    data["path"] = {"control": "offset", "unit": "rms_height", "values": [0.5, 0.0, -0.5],
                    "retract": False}  # fmt: skip
    data["analysis"] = {"hard_wall_reference": False}
    out = tmp_path / "s"
    run_study(study_from_dict(data), out, scheduler="synchronous", progress=False)
    manifest = json.loads((out / "study.json").read_text())
    manifest["tasks"][1]["key"] = "0" * 64  # task-00001.nc now belongs to other parameters
    (out / "study.json").write_text(json.dumps(manifest))
    with pytest.warns(RuntimeWarning, match="another study"):
        ds = collect_study(out)
    assert list(ds["status"].values) == ["done", "missing"]
    assert ds["failure_reason"].values[1] == FOREIGN
    assert ds.attrs["tasks_foreign"] == 1 and ds.attrs["tasks_done"] == 1
    from roughcontact.studies.store import task_keys

    assert task_keys(out)["task-00001.nc"] == "0" * 64  # Fig. 1's maps skip that file
    assert task_keys(out / "absent") is None


# --- Ctrl-C while the command line starts --------------------------------------------


def test_startup_handler_only_for_the_console_script():
    previous = signal.getsignal(signal.SIGINT)
    try:
        assert not _startup.install("/usr/bin/python")
        assert not _startup.install("-c")
        assert signal.getsignal(signal.SIGINT) is previous
        signal.signal(signal.SIGINT, signal.default_int_handler)
        assert _startup.install("/venv/bin/roughcontact")
        assert signal.getsignal(signal.SIGINT) is _startup.exit_interrupted
    finally:
        signal.signal(signal.SIGINT, previous)


@POSIX
def test_ctrl_c_while_starting_is_one_line_and_130(tmp_path):
    script = tmp_path / "roughcontact"  # argv[0] names the console script
    script.write_text(
        "import sys\nfrom roughcontact.cli.main import main\n"
        'if __name__ == "__main__":\n    sys.exit(main())\n'
    )
    np.save(tmp_path / "s.npy", _surface())
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    interrupted = []
    # (the command takes ~1.4 s here; on a busy machine this process can wake from its
    # sleep only after the command has finished, when a Ctrl-C is ignored by design and
    # the exit status is 0: such a late signal is no test, so shorter delays follow)
    for k, delay in enumerate((0.3, 0.6, 0.15, 0.05, 0.02)):
        out = tmp_path / f"p{k}.nc"
        p = subprocess.Popen(
            [sys.executable, str(script), "path", str(tmp_path / "s.npy"), "--loads", "1e-3",
             "1e-1", "1e-3", "-o", str(out)],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
        )  # fmt: skip
        start = time.monotonic()
        time.sleep(delay)
        p.send_signal(signal.SIGINT)
        late = time.monotonic() - start > delay + 0.5
        _out, err = p.communicate(timeout=60)
        text = err.decode()
        if p.returncode == 0 and late and out.is_file():
            continue  # the command had finished: the signal came too late to test anything
        assert p.returncode == 130, (text, _out.decode()[-300:], delay, late, out.is_file())
        assert "Traceback" not in text and len(text.strip().splitlines()) == 1, text
        # at start-up "interrupted (Ctrl-C)"; once the path runs, the step it stopped in
        assert "interrupted" in text
        interrupted.append(delay)
        if len(interrupted) == 2:
            break
    assert interrupted, "every Ctrl-C came after the command had finished"


def test_a_path_imports_its_dataset_and_writer_libraries_before_its_first_step(tmp_path):
    # a Ctrl-C inside a first import (dask's, 0.8 s into `roughcontact path`) left the
    # module half-made, and saving the partial path then failed with an AttributeError
    # traceback: after load_libraries(write=True) neither making nor writing a path
    # dataset imports anything of xarray, dask, distributed or the netCDF engine
    code = (
        "import sys, numpy as np, roughcontact as rc\n"
        "from roughcontact.pathdata import load_libraries, write_path\n"
        "load_libraries(write=True)\n"
        "before = set(sys.modules)\n"
        "h = rc.self_affine((16, 16), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1)\n"
        "ds = rc.approach_retract(h, rc.Substrate(h.shape), loads=[1e-3, 1e-2])\n"
        f"write_path(ds, {str(tmp_path / 'p.nc')!r})\n"
        "late = sorted(m for m in set(sys.modules) - before if m.split('.')[0] in\n"
        "              ('xarray', 'dask', 'distributed', 'h5netcdf', 'h5py', 'netCDF4'))\n"
        "print(late)\n"
    )
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, env=env)  # fmt: skip
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


# --- the local cluster's private scratch directory -----------------------------------


def test_local_cluster_scratch_is_private_and_removed(monkeypatch):
    pytest.importorskip("distributed")
    import distributed

    from roughcontact.studies import cluster

    seen = {}

    class FakeCluster:
        def __init__(self, **kwargs):
            seen.update(kwargs)

        def close(self):
            seen["closed"] = True

    monkeypatch.setattr(distributed, "SpecCluster", FakeCluster)
    local = cluster._local_cluster(1, False)
    scratch = Path(seen["worker"]["options"]["local_directory"])
    assert scratch.is_dir()
    assert stat.S_IMODE(scratch.stat().st_mode) == 0o700
    assert scratch.stat().st_uid == os.getuid()
    other = cluster._local_cluster(1, False)
    assert Path(seen["worker"]["options"]["local_directory"]) != scratch  # fresh each run
    cluster.close(None, local)
    cluster.close(None, other)
    assert seen["closed"] and not scratch.exists()
