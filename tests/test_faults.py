"""Faults that must lose nothing already computed: a full disk, SIGTERM, Ctrl-C.

A full disk is simulated (no root, no tiny file system): ``os.write`` into the writers'
temporary files takes a few files' worth of bytes, then fails with ENOSPC, as a file
system does. SIGTERM and SIGINT are real signals sent to real ``roughcontact``
processes.
"""

import errno
import io
import os
import re
import select
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
import xarray as xr
from _helpers import cli_one_line_error
from click.testing import CliRunner

import roughcontact as rc
from roughcontact import _io, _signals
from roughcontact.cli.main import main
from roughcontact.studies import load_study, run_study
from roughcontact.studies.store import check_task, task_path

CLI = [sys.executable, "-c", "from roughcontact.cli.main import main; main()"]
POSIX = pytest.mark.skipif(os.name != "posix", reason="POSIX signals and ptys")


class FullDisk:
    """Temporary files whose names start with ``prefix`` (and end in .tmp) get
    ``files`` complete writes; the next one takes half its first chunk, then ENOSPC."""

    def __init__(self, monkeypatch, files, prefix="."):
        self.left, self.prefix, self.fds, self.failed = files, prefix, {}, []
        real_open, real_write, real_close = os.open, os.write, os.close

        def fake_open(path, flags, *args, **kwargs):
            fd = real_open(path, flags, *args, **kwargs)
            name = os.path.basename(os.fspath(path))
            if name.startswith(self.prefix) and name.endswith(".tmp"):
                self.fds[fd] = self.left > 0
                self.left -= 1
            return fd

        def fake_write(fd, data):
            if self.fds.get(fd, True):  # not ours, or a file that fits
                return real_write(fd, data)
            self.failed.append(fd)
            size = memoryview(data).nbytes
            if self.failed.count(fd) == 1 and size > 1:
                return real_write(fd, memoryview(data).cast("B")[: size // 2])
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

        def fake_close(fd):
            self.fds.pop(fd, None)
            return real_close(fd)

        monkeypatch.setattr(os, "open", fake_open)
        monkeypatch.setattr(os, "write", fake_write)
        monkeypatch.setattr(os, "close", fake_close)


def _temporaries(directory):
    return sorted(p.name for p in directory.rglob("*") if p.name.endswith(".tmp"))


# --- a full disk ----------------------------------------------------------------------


@pytest.fixture()
def sphere_file(tmp_path):
    out = tmp_path / "s.npy"
    np.save(out, rc.sphere((32, 32), 12.0))
    return out


def test_full_disk_during_path_exits_1_and_keeps_the_last_checkpoint(
    tmp_path, sphere_file, monkeypatch
):
    out = tmp_path / "p.nc"
    disk = FullDisk(monkeypatch, files=2)  # two checkpoints fit, the third does not
    args = ["path", str(sphere_file), "--loads", "1e-3", "5e-3", "1e-3", "-o", str(out)]
    r = CliRunner().invoke(main, [*args, "--checkpoint-seconds", "0"])
    assert r.exit_code == 1, r.output
    line = cli_one_line_error(r, code=1, start=f"no space left writing {out} ")
    assert "holds the 2 steps of the last checkpoint" in line
    assert disk.failed  # the third write did fail half-way
    with xr.open_dataset(out, engine="h5netcdf") as ds:  # the previous complete file
        assert ds.sizes["step"] == 2 and ds.attrs["surface_file"] == str(sphere_file)
        np.testing.assert_allclose(ds["load"], [1e-3, 2e-3], rtol=1e-9)
    assert _temporaries(tmp_path) == []


def test_full_disk_on_the_first_write_leaves_no_file(tmp_path, sphere_file, monkeypatch):
    out = tmp_path / "p.nc"
    FullDisk(monkeypatch, files=0)
    args = ["path", str(sphere_file), "--loads", "1e-3", "3e-3", "1e-3", "-o", str(out)]
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 1, r.output
    line = cli_one_line_error(r, code=1, start="no space left writing")
    assert "checkpoint" not in line and not out.exists() and _temporaries(tmp_path) == []


def test_full_disk_during_study_run_exits_1_and_keeps_the_finished_tasks(
    tmp_path, make_study, monkeypatch
):
    study = make_study()
    out = tmp_path / "out"
    disk = FullDisk(monkeypatch, files=3, prefix=".task-")
    cmd = ["study", "run", str(study), "-o", str(out), "--scheduler", "synchronous"]
    r = CliRunner().invoke(main, [*cmd, "--no-progress"])
    assert r.exit_code == 1, r.output
    spec = load_study(study)
    order = sorted(spec.tasks, key=lambda t: (t.params["seed"], t.id))  # seed by seed
    cli_one_line_error(r, code=1, start=f"no space left writing {task_path(out, order[3].id)} ")
    assert disk.failed and _temporaries(out) == []
    assert [check_task(out, t)[0] for t in order[:4]] == [True, True, True, False]
    monkeypatch.undo()  # space freed: resume computes the rest only
    r = CliRunner().invoke(main, [*cmd, "--no-progress", "--resume"])
    assert r.exit_code == 0, r.output
    assert "3 already finished" in r.output and "5 computed" in r.output


@POSIX
def test_a_real_write_refusal_end_to_end(tmp_path, sphere_file):
    """The kernel refuses the bytes (a file size limit: EFBIG, as ENOSPC would)."""
    import resource

    out = tmp_path / "p.nc"
    cmd = [*CLI, "path", str(sphere_file), "--loads", "1e-3", "4e-2", "1e-3", "-o", str(out)]

    def limit():  # each checkpoint is 32.8 kB + 154 B a step: about 14 of them fit
        resource.setrlimit(resource.RLIMIT_FSIZE, (35_000, 35_000))
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)

    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    r = subprocess.run(
        [*cmd, "--checkpoint-seconds", "0"],
        capture_output=True,
        text=True,
        preexec_fn=limit,
        env=env,
        timeout=300,
    )
    assert r.returncode == 1, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    assert lines[0].startswith(f"roughcontact: error: file too large writing {out} ")
    held = int(re.search(r"holds the (\d+) steps of the last checkpoint", lines[0]).group(1))
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.sizes["step"] == held and 5 <= held < 40
    assert _temporaries(tmp_path) == []


def test_atomic_writer_errors(tmp_path, monkeypatch):
    target = tmp_path / "f.bin"
    _io.write_bytes_atomic(target, b"old")
    real_fsync = os.fsync

    def failing_fsync(fd):
        raise OSError(errno.EIO, os.strerror(errno.EIO))

    monkeypatch.setattr(os, "fsync", failing_fsync)
    with pytest.raises(_io.WriteError) as info:
        _io.write_bytes_atomic(target, b"new contents")
    err = info.value
    assert isinstance(err, OSError) and err.errno == errno.EIO
    assert err.filename == str(target) and "\n" not in str(err)
    assert str(err).startswith(f"I/O error writing {target} ")
    monkeypatch.setattr(os, "fsync", real_fsync)
    assert target.read_bytes() == b"old" and _temporaries(tmp_path) == []
    # other errors (not the storage's) pass unchanged, still without a temporary file
    with pytest.raises(FileNotFoundError):
        _io.write_bytes_atomic(tmp_path / "missing" / "f.bin", b"x")
    assert _io.as_write_error(PermissionError(errno.EACCES, "denied"), target).errno == (
        errno.EACCES
    )


def test_netcdf_bytes_round_trip_without_touching_the_dataset(tmp_path):
    ds = xr.Dataset(
        {"pressure": (("x", "y"), np.zeros((8, 8))), "load": ("step", [1.0, 2.0])},
        attrs={"a": 1.5},
    )
    path = _io.write_netcdf_atomic(
        ds,
        tmp_path / "d.nc",
        encoding={"pressure": {"zlib": True, "complevel": 4}},
        attrs={"marker": "yes"},
    )
    assert ds.attrs == {"a": 1.5}
    with xr.open_dataset(path, engine="h5netcdf") as back:
        assert back.attrs == {"a": 1.5, "marker": "yes"}
        xr.testing.assert_identical(back.drop_attrs(), ds.drop_attrs())
    # the route for xarray versions that give in-memory bytes only through scipy
    data = _io._h5netcdf_in_memory(ds, {"pressure": {"zlib": True}})
    back = xr.load_dataset(io.BytesIO(bytes(data)), engine="h5netcdf")
    xr.testing.assert_identical(back, ds)


# --- signals --------------------------------------------------------------------------


@POSIX
def test_deferred_holds_a_signal_until_the_write_is_done():
    before = signal.getsignal(signal.SIGTERM)
    done = []
    with pytest.raises(_signals.Terminated) as info, _signals.interruptible():
        with _signals.deferred():
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(0.05)
            done.append(True)
    assert done == [True] and _signals.exit_code(info.value) == 143
    assert signal.getsignal(signal.SIGTERM) is before  # restored
    assert _signals.exit_code(KeyboardInterrupt()) == 130


def _read_until(fd, pattern, deadline, buffer=b""):
    """Read ``fd`` until ``pattern`` matches ``buffer`` (returns the match and buffer)."""
    while time.monotonic() < deadline:
        ready, _, _ = select.select([fd], [], [], 0.5)
        if ready:
            try:
                chunk = os.read(fd, 65536)
            except OSError:  # the other end closed
                break
            if not chunk:
                break
            buffer += chunk
        if (match := pattern(buffer)) is not None:
            return match, buffer
    return None, buffer


@POSIX
def test_sigterm_during_path_writes_the_finished_steps_and_exits_143(tmp_path):
    import fcntl
    import pty
    import struct
    import termios

    surface = tmp_path / "S.npy"
    np.save(surface, rc.self_affine((64, 64), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1))
    out = tmp_path / "p.nc"
    cmd = [*CLI, "path", str(surface), "--offsets", "0.5", "-30", "0.05"]
    cmd += ["--offset-unit", "rms_height", "--interaction", "lj93smooth"]
    cmd += ["--adhesion-length", "0.01", "-o", str(out), "--checkpoint-seconds", "1000"]
    # the progress bar (on a terminal only) says how many steps are done
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 200, 0, 0))
    proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=slave)
    os.close(slave)
    try:

        def steps(buffer):
            done = re.findall(rb"(\d+)/(\d+) \[", buffer)
            return int(done[-1][0]) if done and int(done[-1][0]) >= 3 else None

        seen, buffer = _read_until(master, steps, time.monotonic() + 120)
        assert seen is not None and proc.poll() is None, buffer[-2000:]
        proc.send_signal(signal.SIGTERM)
        _, buffer = _read_until(master, lambda b: None, time.monotonic() + 30, buffer)
        assert proc.wait(timeout=60) == 143, buffer[-2000:]
    finally:
        if proc.poll() is None:
            proc.kill()
        os.close(master)
    text = buffer.decode(errors="replace")
    message = re.search(r"roughcontact: error: terminated \(SIGTERM\): .*", text)
    assert message, text[-2000:]
    written = int(re.search(r"the (\d+) steps before it are in", message.group()).group(1))
    assert written >= seen >= 3
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.sizes["step"] == written < 611  # stopped long before the end
        assert bool(ds["converged"].all())
    assert _temporaries(tmp_path) == []


@POSIX
def test_sigterm_during_study_run_stops_the_cluster_and_exits_143(tmp_path, make_study):
    import psutil

    study = make_study(size=64, num=16)
    out = tmp_path / "out"
    cmd = [*CLI, "study", "run", str(study), "-o", str(out), "--workers", "2", "--no-progress"]
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True
    )
    try:
        deadline = time.monotonic() + 120
        while not list(out.glob("task-*.nc")) and proc.poll() is None:
            assert time.monotonic() < deadline, "no task finished within 120 s"
            time.sleep(0.02)
        children = psutil.Process(proc.pid).children(recursive=True)
        proc.send_signal(signal.SIGTERM)
        _, stderr = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
    assert proc.returncode == 143, stderr.decode()
    message = re.search(rb"roughcontact: error: terminated \(SIGTERM\): (\d+) of 8 tasks", stderr)
    assert message and b"--resume" in stderr, stderr.decode()
    finished = int(message.group(1))
    spec = load_study(study)
    assert sum(check_task(out, t)[0] for t in spec.tasks) == finished >= 1
    assert _temporaries(out) == []
    # the cluster was shut down: no worker process outlives the driver
    _, alive = psutil.wait_procs(children, timeout=20)
    assert alive == []
    summary = run_study(study, out, resume=True, scheduler="synchronous", progress=False)
    assert summary.ok and summary.skipped == finished


@POSIX
@pytest.mark.parametrize(("signum", "code"), [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_signals_during_demo(tmp_path, signum, code):
    cmd = [*CLI, "demo", "--size", "1024", "--study-size", "0", "-o", str(tmp_path / "d")]
    proc = subprocess.Popen(
        cmd,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        # a SIGINT ignored by whoever started the tests would stay ignored in the child
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    try:
        first = proc.stderr.readline()  # the first step's progress line
        assert b"step 1/" in first, first
        proc.send_signal(signum)
        _, stderr = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == code, stderr.decode()
    lines = stderr.decode().strip().splitlines()
    why = "terminated (SIGTERM)" if code == 143 else "interrupted (Ctrl-C)"
    assert lines[-1] == f"roughcontact: error: {why}" and "Traceback" not in stderr.decode()
