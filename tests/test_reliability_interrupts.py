"""Reliability round four: Ctrl-C and SIGTERM during ``study run`` are one line and prompt.

Ctrl-C reaches every process of the terminal's foreground group: the command's own and
the local cluster's worker processes. Pressed while the cluster starts, while it runs or
while it stops, the command prints one line (``interrupted`` once) and exits 130; the
workers print nothing, Dask's exit hook finds no half-started cluster to close again
(``AssertionError: Status.init``) and the private scratch directory is gone. SIGTERM
(a scheduler) during the work: exit 143, one line, the workers killed instead of
waited for.
"""

import os
import signal
import subprocess
import sys
import time

import pytest
from _helpers import POSIX

pytestmark = [
    pytest.mark.skipif(not POSIX, reason="process groups and signals"),
    pytest.mark.filterwarnings("ignore::DeprecationWarning"),
]


def _start(tmp_path, make_study, name):
    pytest.importorskip("distributed")
    script = tmp_path / "roughcontact"  # argv[0] names the console script, as installed
    script.write_text(
        "import sys\nfrom roughcontact.cli.main import main\n"
        'if __name__ == "__main__":\n    sys.exit(main())\n'
    )
    tmp = tmp_path / "tmp"
    tmp.mkdir(exist_ok=True)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path), TMPDIR=str(tmp))
    # 8 paths of 128² and 96 steps: ~14 s on a quiet 2-core machine, so that a signal
    # sent while the tasks run finds work left on a faster one (64² and 24 steps took 4 s,
    # and a Ctrl-C 5 s after the start found the command finished)
    study = make_study(size=128, num=96)
    out = tmp_path / name
    cmd = [sys.executable, str(script), "study", "run", str(study), "-o", str(out),
           "--workers", "2", "--no-progress"]  # fmt: skip
    proc = subprocess.Popen(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True,
        start_new_session=True,  # its own group: a Ctrl-C to it reaches nothing else
        # a SIGINT ignored by whoever started the tests (nohup, a CI runner, `cmd &` in a
        # script) would stay ignored in the child: a terminal's Ctrl-C reaches it as usual
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )  # fmt: skip
    return proc, tmp


def _finish(proc, code, tmp):
    try:
        _, err = proc.communicate(timeout=90)
    except subprocess.TimeoutExpired:  # pragma: no cover - the failure being tested
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
        raise AssertionError("the command did not exit within 90 s") from None
    time.sleep(0.5)  # anything the workers would still print
    lines = err.strip().splitlines()
    assert proc.returncode == code, err
    assert len(lines) == 1 and lines[0].startswith("roughcontact: error: "), err
    assert "Traceback" not in err and "CRITICAL" not in err
    assert not [p.name for p in tmp.iterdir() if p.name.startswith("roughcontact-dask-")]
    return lines[0]


def _wait_for_the_tasks(proc, out):
    """Until the study's record exists (the cluster is up and the tasks run)."""
    deadline = time.monotonic() + 60
    while not (out / "study.json").exists() and proc.poll() is None:
        assert time.monotonic() < deadline
        time.sleep(0.05)


# (phase, seconds): 1.5 s after the start (the cluster starts), or that long after the
# tasks began to run; signals timed from the start alone missed the run on a fast machine
@pytest.mark.parametrize("phase, delay", [("start", 1.5), ("run", 0.5), ("run", 3.0)])
def test_ctrl_c_to_the_process_group_while_the_cluster_starts_or_runs(
    tmp_path, make_study, phase, delay
):
    proc, tmp = _start(tmp_path, make_study, "out")
    if phase == "run":
        _wait_for_the_tasks(proc, tmp_path / "out")
    time.sleep(delay)
    assert proc.poll() is None, "the study ended before the Ctrl-C: make it larger"
    os.killpg(proc.pid, signal.SIGINT)  # as the terminal does: every process of the group
    line = _finish(proc, 130, tmp)
    assert line.count("interrupted") == 1


def test_sigterm_during_the_work_exits_143_at_once(tmp_path, make_study):
    proc, tmp = _start(tmp_path, make_study, "out")
    _wait_for_the_tasks(proc, tmp_path / "out")
    time.sleep(1.0)
    assert proc.poll() is None, "the study ended before the SIGTERM: make it larger"
    proc.send_signal(signal.SIGTERM)  # to the command only, as a scheduler or kill does
    line = _finish(proc, 143, tmp)
    assert "terminated (SIGTERM)" in line and "--resume" in line
