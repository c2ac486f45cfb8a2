"""The benchmarks' thread limit (benchmarks/_threads.py) is enforced, verified and recorded.

Each case runs in a fresh interpreter: what matters is the order in which the thread
variables are set and NumPy's OpenBLAS is loaded, and whether threadpoolctl can be
imported (hidden by ``sys.modules["threadpoolctl"] = None``).
"""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def _load_threads():
    spec = importlib.util.spec_from_file_location("_bench_threads", BENCH / "_threads.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


_threads = _load_threads()
HIDE = 'import sys; sys.modules["threadpoolctl"] = None\n'


def _env() -> dict:
    """This environment without any thread variable (the libraries' defaults)."""
    return {k: v for k, v in os.environ.items() if k not in _threads.ENV_VARS}


def _python(code: str, *args: str, hide=False, timeout=120) -> subprocess.CompletedProcess:
    """Run ``code`` in a fresh interpreter in benchmarks/ (``hide``: no threadpoolctl)."""
    return subprocess.run(
        [sys.executable, "-c", (HIDE if hide else "") + textwrap.dedent(code), *args],
        capture_output=True,
        text=True,
        cwd=BENCH,
        env=_env(),
        timeout=timeout,
    )


def test_threads_from_argv():
    f = _threads.threads_from_argv
    assert f([], default=1) == 1
    assert f(["--sizes", "64"], default=None) is None
    assert f(["--blas-threads", "3"], default=1) == 3
    assert f(["--blas-threads=4", "--sizes", "64"], default=1) == 4
    assert f(["--blas-threads", "2", "--blas-threads", "5"], default=1) == 5  # argparse: last
    assert f(["--blas-threads", "x"], default=1) == 1  # argparse reports it
    assert f(["--", "--blas-threads", "3"], default=1) == 1


def test_environment_before_numpy_enforces_without_threadpoolctl():
    """Variables set before NumPy: 1 thread, verified without threadpoolctl, then checked
    with it (the ground truth) once it is importable again."""
    out = _python(
        """
        import json
        import _threads
        _threads.preset(1)
        import numpy, scipy.linalg
        with _threads.enforced(1, preload=("scipy.optimize",)) as rec:
            numpy.dot(numpy.ones(10), numpy.ones(10))
        del sys.modules["threadpoolctl"]
        from threadpoolctl import threadpool_info
        rec["truth"] = sorted({p["num_threads"] for p in threadpool_info()})
        print(json.dumps(rec))
        """,
        hide=True,
    )
    assert out.returncode == 0, out.stderr
    rec = json.loads(out.stdout)
    assert rec["requested"] == 1
    assert rec["threadpoolctl"] is None
    assert rec["enforced_by"] == ["environment (set before NumPy was loaded)"]
    assert "threadpoolctl not installed" in rec["verified_by"]
    assert all(rec["env"][v] == "1" for v in _threads.ENV_VARS)
    if rec["threadpools"] is not None:  # OpenBLAS asked through ctypes (Linux wheels)
        assert rec["threadpools"] and {p["num_threads"] for p in rec["threadpools"]} == {1}
    assert rec["truth"] == [1]
    assert rec["cpu_count"] >= 1 and rec["versions"]["numpy"]


def test_refuses_when_numpy_was_loaded_first_and_no_threadpoolctl():
    out = _python(
        """
        import numpy
        import _threads
        with _threads.enforced(1):
            print("ran")
        """,
        hide=True,
    )
    assert out.returncode != 0
    assert "ran" not in out.stdout
    assert "refusing to run: cannot enforce 1 BLAS/OpenMP thread(s)" in out.stderr
    assert "threadpoolctl" in out.stderr


def test_threadpoolctl_limits_loaded_pools_and_restores_them():
    pytest.importorskip("threadpoolctl")
    out = _python(
        """
        import json
        import numpy
        from threadpoolctl import threadpool_info
        import _threads
        before = {p["filepath"]: p["num_threads"] for p in threadpool_info()}
        with _threads.enforced(1, preload=("scipy.optimize",)) as rec:
            inside = sorted({p["num_threads"] for p in threadpool_info()})
        # the pools loaded before (NumPy's) are back at their counts
        after = {p["filepath"]: p["num_threads"] for p in threadpool_info()}
        after = {k: v for k, v in after.items() if k in before}
        print(json.dumps(dict(rec=rec, before=before, inside=inside, after=after)))
        """
    )
    assert out.returncode == 0, out.stderr
    res = json.loads(out.stdout)
    assert res["inside"] == [1]
    assert "threadpoolctl.threadpool_limits" in res["rec"]["enforced_by"]
    assert res["rec"]["verified_by"] == "threadpoolctl.threadpool_info"
    assert res["rec"]["verified_after"] is True
    assert res["after"] == res["before"]


def test_unlimited_records_the_defaults():
    out = _python(
        """
        import json
        import _threads
        with _threads.enforced(None, preload=("numpy",)) as rec:
            pass
        print(json.dumps(rec))
        print(_threads.describe(rec))
        """
    )
    assert out.returncode == 0, out.stderr
    rec = json.loads(out.stdout.splitlines()[0])
    assert rec["requested"] is None and rec["enforced_by"] == []
    assert all(rec["env"][v] is None for v in _threads.ENV_VARS)
    assert "# threads: BLAS/OpenMP not limited (library defaults)" in out.stdout


def test_adhesive_help():
    out = subprocess.run(
        [sys.executable, str(BENCH / "adhesive.py"), "--help"],
        capture_output=True,
        text=True,
        env=_env(),
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    assert "--blas-threads" in out.stdout


@pytest.mark.parametrize("hide", [True, False], ids=["no-threadpoolctl", "threadpoolctl"])
def test_adhesive_prints_and_records_the_enforced_limit(tmp_path, hide):
    if not hide:
        pytest.importorskip("threadpoolctl")
    result = tmp_path / "adhesive.json"
    argv = ["--sizes", "32", "--adhesion-lengths", "0.05", "--steps", "2", "--repeats", "1"]
    out = _python(
        """
        import runpy
        import sys
        sys.path.insert(0, ".")
        sys.argv = ["adhesive.py", *sys.argv[1:]]
        runpy.run_path("adhesive.py", run_name="__main__")
        """,
        *argv,
        "--peers",
        "--json",
        str(result),
        hide=hide,
    )
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    assert lines[0].startswith("# adhesive approach") and "BLAS threads 1" in lines[0]
    assert lines[1].startswith("# threads: BLAS/OpenMP 1 per library, enforced by environment")
    rec = json.loads(result.read_text())["meta"]["threads"]
    assert rec["requested"] == 1
    assert rec["verified_after"] is not False
    if rec["threadpools"] is not None:
        assert {p["num_threads"] for p in rec["threadpools"]} == {1}
    if hide:
        assert "threadpoolctl not installed" in rec["verified_by"]
    else:
        assert rec["verified_by"] == "threadpoolctl.threadpool_info"
