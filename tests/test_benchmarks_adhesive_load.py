"""benchmarks/adhesive_load.py (and adhesive.py --load-control) runs and records its rows."""

import json
import subprocess
import sys
from pathlib import Path

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def test_adhesive_load_records_cold_cases_and_paths(tmp_path):
    result = tmp_path / "load.json"
    out = subprocess.run(
        [sys.executable, "adhesive_load.py", "--sizes", "32", "--adhesion-lengths", "0.05",
         "--loads", "1e-3", "--path-loads", "0", "1e-3", "2e-3", "--nested",
         "--json", str(result)],
        capture_output=True, text=True, cwd=BENCH, timeout=300,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    rec = json.loads(result.read_text())
    (cold,) = rec["cold"]
    assert cold["load_status"] == "converged" and abs(cold["load_reached"] - 1e-3) < 1e-8
    assert cold["same_state_max_gap_difference"] < 1e-6
    # the one minimisation against the nested search it replaced, on the same run
    assert cold["load_iterations"] < cold["nested_iterations"]
    (path,) = rec["paths"]
    assert path["converged"] and len(path["load_iterations"]) == 3
    assert "ratio load/offset iterations" in out.stdout and "# path n=32" in out.stdout


def test_adhesive_load_takes_the_rough_surface_and_maugis_dugdale(tmp_path):
    result = tmp_path / "load.json"
    out = subprocess.run(
        [sys.executable, "adhesive_load.py", "--sizes", "128", "--adhesion-lengths", "0.01",
         "--law", "dugdale", "--surface", "rough", "--loads", "0", "--path-loads", "1e-3", "0",
         "--json", str(result)],
        capture_output=True, text=True, cwd=BENCH, timeout=300,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr
    (cold,) = json.loads(result.read_text())["cold"]
    assert cold["surface"] == "rough" and cold["law"] == "dugdale"
    assert cold["load_status"] == "converged" and abs(cold["load_reached"]) < 1e-8
    # the case that crawled through the jump into contact (1210 iterations, then 212 and
    # 146 with a restart from the hard wall): searched from the first wall contact, 27
    # against 25 for the offset-controlled solve at the offset reached
    assert not cold["restarted_from_hard_wall"] and "restarted from a hard wall" not in out.stdout
    assert cold["load_iterations"] <= 2 * cold["offset_iterations"]
