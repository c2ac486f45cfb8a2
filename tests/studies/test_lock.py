"""One run per study directory: the flock, its message, stale locks and the fallback."""

import errno
import os
import signal
import subprocess
import sys
import textwrap

import pytest

from roughcontact.studies import DirectoryLocked, collect_study, run_study
from roughcontact.studies import lock as lock_module
from roughcontact.studies.lock import LOCK_NAME, directory_lock
from roughcontact.studies.store import MANIFEST

HOLD = textwrap.dedent(
    """
    import sys, time
    from roughcontact.studies.lock import directory_lock
    with directory_lock(sys.argv[1]):
        print("held", flush=True)
        time.sleep(120)
    """
)


@pytest.fixture()
def holder(tmp_path):
    """``holder(directory)``: a separate process holding the directory's lock (a Popen)."""
    procs = []

    def start(directory):
        proc = subprocess.Popen(
            [sys.executable, "-c", HOLD, str(directory)], stdout=subprocess.PIPE, text=True
        )
        procs.append(proc)
        assert proc.stdout.readline().strip() == "held"
        return proc

    yield start
    for proc in procs:
        if proc.poll() is None:
            proc.kill()
        proc.wait()


def _assert_names_holder(err, out, pid):
    message = str(err)
    assert repr(str(out)) in message and str(out / LOCK_NAME) in message
    assert f"PID {pid} on " in message and "--resume" in message and "\n" not in message


def test_second_run_fails_at_once_and_touches_nothing(tmp_path, make_study):
    study, out = make_study(), tmp_path / "out"
    with directory_lock(out) as path:  # as a run in this process holds it
        assert path == out / LOCK_NAME
        with pytest.raises(DirectoryLocked) as err:
            run_study(study, out, resume=True, scheduler="synchronous", progress=False)
        _assert_names_holder(err.value, out, os.getpid())
        assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME]
    summary = run_study(study, out, scheduler="synchronous", progress=False)
    assert summary.ok and summary.completed == 8


def test_lock_of_a_killed_process_does_not_block_resume(tmp_path, make_study, holder):
    study, out = make_study(), tmp_path / "out"
    proc = holder(out)
    with pytest.raises(DirectoryLocked) as err:
        run_study(study, out, scheduler="synchronous", progress=False)
    _assert_names_holder(err.value, out, proc.pid)
    assert not (out / MANIFEST).exists()  # the holder's directory is left alone
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    # the lock file is still there, naming the dead process: only the kernel's lock counts
    assert f"PID {proc.pid} " in (out / LOCK_NAME).read_text()
    summary = run_study(study, out, resume=True, scheduler="synchronous", progress=False)
    assert summary.ok and summary.completed == 8
    assert collect_study(out).attrs["tasks_done"] == 8


def test_a_failed_run_leaves_no_directory_behind(tmp_path, make_study):
    out = tmp_path / "new"
    with pytest.raises(RuntimeError), directory_lock(out):
        raise RuntimeError("before anything was written")
    assert not out.exists()


@pytest.mark.parametrize("broken", ["no fcntl", "no locks on this file system"])
def test_without_locks_the_run_warns_and_goes_on(tmp_path, make_study, monkeypatch, broken):
    class NoLocks:
        LOCK_EX = LOCK_NB = 0

        @staticmethod
        def flock(fd, how):
            raise OSError(errno.ENOLCK, "No locks available")

    monkeypatch.setattr(lock_module, "fcntl", None if broken == "no fcntl" else NoLocks)
    out = tmp_path / "out"
    with pytest.warns(RuntimeWarning, match="cannot lock .*no other roughcontact run"):
        summary = run_study(make_study(), out, scheduler="synchronous", progress=False)
    assert summary.ok and summary.completed == 8
