"""benchmarks/float32_floor.py and gpu_path_phases.py run on the CPU and record their rows."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def run(tmp_path, *args):
    result = tmp_path / "out.json"
    out = subprocess.run(
        [sys.executable, *args, "--json", str(result)],
        capture_output=True, text=True, cwd=BENCH, timeout=300,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    return json.loads(result.read_text())


def test_float32_floor_reports_the_float64_residual_of_the_float32_state(tmp_path):
    rows = run(tmp_path, "float32_floor.py", "--size", "64", "--loop", "numpy")
    assert [r["tol"] for r in rows] == [1e-6, 1e-6]  # the default is 1e-6 up to 1024²
    for r in rows:
        assert r["status"] == "converged" and r["iterations"] > 0
        # the state's force balance in float64: below the tolerance, above float64's rounding
        assert 1e-12 < r["residual_float64"] <= 2 * r["tol"]


def test_path_phases_time_the_solves_and_the_patch_counts(tmp_path):
    pytest.importorskip("jax")
    rec = run(tmp_path, "gpu_path_phases.py", "--size", "32", "--states", "5")
    assert rec["states"] == 5 and rec["iterations"] > 0
    assert set(rec["phases"]) == {"solve", "patch_count"}
    assert 0 < rec["phases"]["solve"] <= rec["synchronised_seconds"]
    assert rec["count_seconds"] > 0
