"""benchmarks/cold_load_sweep.py runs, records every case, classifies the ratios and
never replaces a file."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def _sweep(*args):
    return subprocess.run(
        [sys.executable, "cold_load_sweep.py", *args],
        capture_output=True, text=True, cwd=BENCH, timeout=300,
    )  # fmt: skip


def test_the_sweep_records_each_cold_load_solve_beside_the_offset_controlled_one(tmp_path):
    result = tmp_path / "sweep.json"
    out = _sweep("--sizes", "32", "--laws", "exp", "--loads", "0", "1e-3", "--json", str(result))
    assert out.returncode == 0, out.stderr
    rec = json.loads(result.read_text())
    cases = rec["cases"]
    assert len(cases) == 4 * 3 * 2  # surfaces x Exponential laws x loads
    for case in cases:
        if case["load_status"] == "converged":
            assert abs(case["load_reached"] - case["load"]) < 1e-8
            assert case["offset_status"] == "converged"
            ratio = case["load_iterations"] / max(case["offset_iterations"], 1)
            assert case["ratio"] == pytest.approx(ratio, rel=1e-12)
    summary = rec["summaries"]["32"]
    assert summary["cases"] == len(cases)
    assert summary["load_iterations"] == sum(c["load_iterations"] for c in cases)
    assert sum(summary["above_2x_by_state"].values()) == summary["above_2x"]
    assert "# n=32: 24 cold load solves" in out.stdout


def test_the_sweep_refuses_to_replace_a_file_in_one_line(tmp_path):
    existing = tmp_path / "kept.json"
    existing.write_text("mine")
    out = _sweep("--sizes", "32", "--json", str(existing))
    assert out.returncode == 2
    assert "exists" in out.stderr and "Traceback" not in out.stderr
    assert existing.read_text() == "mine"
    out = _sweep("--sizes", "4")
    assert out.returncode == 2 and "--sizes must be >= 8" in out.stderr
