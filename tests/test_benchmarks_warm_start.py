"""benchmarks/warm_start.py, spectrum.py --coarse-block, fas.py and adhesive.py --offset-step
run and say what they measured."""

import json
import re
import subprocess
import sys
from pathlib import Path

BENCH = Path(__file__).resolve().parents[1] / "benchmarks"


def run(*args) -> str:
    out = subprocess.run(
        [sys.executable, *args], capture_output=True, text=True, cwd=BENCH, timeout=300
    )
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_warm_start_compares_three_starts_on_the_same_offsets():
    text = run("warm_start.py", "--size", "32", "--adhesion-length", "0.05")
    rows = {}
    for line in text.splitlines()[1:]:
        name, iterations = line.split()[0], re.search(r"iterations \[([\d, ]+)\]", line)[1]
        rows[name] = [int(i) for i in iterations.split(",")]
        assert len(line.split("A_rep/A0")[1].split()) == 10  # one area per step
    assert set(rows) == {"previous", "secant", "coarse"}
    # step 1 starts cold in all three: the same solve
    assert len({r[0] for r in rows.values()}) == 1 and all(len(r) == 10 for r in rows.values())
    assert "coarse " in text.splitlines()[-1]  # the coarse grid's own iterations said


def test_spectrum_coarse_block_raises_the_smallest_eigenvalue():
    text = run("spectrum.py", "--sizes", "32", "--adhesion-lengths", "0.05", "--coarse-block", "8")
    rows = {line.split()[2]: [float(v) for v in line.split()[3:6]] for line in text.splitlines()
            if line.split()[:1] == ["32"]}  # fmt: skip
    assert set(rows) == {"green", "block", "block+coarse8"}
    # a Galerkin coarse correction adds an exact solve on its span: lambda_min goes up
    assert rows["block+coarse8"][1] > rows["block"][1]


def test_spectrum_refuses_a_coarse_block_that_does_not_divide_the_grid():
    out = subprocess.run(
        [sys.executable, "spectrum.py", "--sizes", "32", "--coarse-block", "5"],
        capture_output=True, text=True, cwd=BENCH, timeout=60,
    )  # fmt: skip
    assert out.returncode == 2 and "--coarse-block must be" in out.stderr


def test_adhesive_offset_step_takes_equal_steps_over_the_same_range(tmp_path):
    out = tmp_path / "offset_step.json"
    run("adhesive.py", "--sizes", "32", "--adhesion-lengths", "0.05", "--peers",
        "--repeats", "1", "--offset-step", "0.1", "--json", str(out))  # fmt: skip
    (detail,) = json.loads(out.read_text())["details"]
    offsets = [s["offset"] for s in detail["steps"]]
    start, end = detail["schedule"]["d_start"], detail["schedule"]["d_end"]
    assert offsets[-1] == end and len(offsets) == int(-(-(start - end) // 0.1))
    # every step but the last (which ends on the range's end) moves the offset by 0.1 a0
    steps = [a - b for a, b in zip([start, *offsets[:-2]], offsets[:-1], strict=True)]
    assert max(abs(d - 0.1) for d in steps) < 1e-9 and 0 < offsets[-2] - end <= 0.1 + 1e-12


def test_fas_cycles_reach_the_plain_solvers_states():
    text = run("fas.py", "--size", "32", "--nu", "5", "--prolongation", "linear")
    rows = [json.loads(line) for line in text.splitlines() if line.startswith("{")]
    assert len(rows) == 10 and "fine" not in rows[0]  # step 1 starts cold: not compared
    for row in rows[1:]:  # every FAS step converges to the plain solver's state
        assert row["converged"] and row["area_diff_pixels"] == 0 and row["cycles"] >= 0
        assert len(row["steps"]) == row["cycles"] and set(row["steps"]) <= {0.0, 0.25, 0.5, 1.0}
    total = sum(r["fine"] for r in rows[1:])
    assert f"FAS {total} fine" in text.splitlines()[-1]
