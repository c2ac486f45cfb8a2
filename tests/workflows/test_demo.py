"""The demo workflow: its load path is the warm-started load loop, its report the rows.

Oracles: the definition of the demo's path (one load-controlled :func:`roughcontact.solve`
per load, each warm-started from the last, as the demo computed it before it used
:func:`roughcontact.approach_retract`) and κ_rep = h'rms E* A_rep / N_rep at A_rep = 1 %
of A0 (Pastewka & Robbins, PNAS 111, 3298 (2014), Eq. 2) on the linear interpolation
between the bracketing loads.
"""

import numpy as np
import pytest

import roughcontact as rc
from roughcontact._signals import Terminated
from roughcontact.workflows.demo import demo_path
from roughcontact.workflows.report import figure1_note, report_lines, table_lines

SIZE, SEED = 64, 5
LOADS = np.geomspace(1.5e-4, 3e-3, 6)


@pytest.fixture(scope="module")
def demo():
    return demo_path(size=SIZE, seed=SEED, loads=LOADS)


def test_the_path_is_the_warm_started_load_loop(demo):
    h = rc.self_affine(
        (SIZE, SIZE), hurst=0.8, rms_slope=0.1, short_cutoff=8.0, long_cutoff=SIZE / 2, seed=SEED
    )
    sub, previous, states = rc.Substrate((SIZE, SIZE)), None, []
    for load in LOADS:
        previous = rc.solve(h, sub, load=float(load), initial=previous, tol=1e-8)
        states.append(previous)
    assert len(demo["path"]) == len(states)
    for row, s in zip(demo["path"], states, strict=True):
        for key in ("load", "repulsive_area", "corrected_repulsive_area", "offset", "perimeter",
                    "mean_gap", "iterations", "converged"):  # fmt: skip
            assert row[key] == getattr(s, key), key
        # JSON-ready: the command's --json writes what json cannot take as null
        assert type(row["iterations"]) is int and type(row["converged"]) is bool
    assert demo["all_converged"] == all(s.converged for s in states)
    assert demo["surface"]["rms_slope"] == pytest.approx(rc.statistics(h).rms_slope)


def test_kappa_rep_at_one_percent(demo):
    area = np.array([r["repulsive_area"] for r in demo["path"]])
    load = np.array([r["load"] for r in demo["path"]])
    k = int(np.searchsorted(area, 0.01))
    assert 0 < k < area.size  # 1 % is bracketed
    t = (0.01 - area[k - 1]) / (area[k] - area[k - 1])
    n = load[k - 1] + t * (load[k] - load[k - 1])
    assert demo["load_at_1_percent"] == pytest.approx(n, rel=1e-12)
    slope = demo["surface"]["rms_slope"]
    assert demo["kappa_rep"] == pytest.approx(slope * 0.01 / n, rel=1e-12)
    assert 1 < demo["kappa_rep_corrected"] < demo["kappa_rep"]  # the lattice's bias removed


@pytest.mark.parametrize("signal", [KeyboardInterrupt(), Terminated("terminated (SIGTERM)")])
def test_a_signal_stops_the_demo_as_itself(signal):
    def progress(i, n, res):
        raise signal

    with pytest.raises(type(signal)) as err:
        demo_path(size=32, seed=1, loads=[1e-3, 2e-3], progress=progress)
    assert err.value is signal  # not the path's PathInterrupted: the exit code follows it


def test_the_report_holds_a_line_per_row_and_the_notes():
    row = {
        "adhesion_length": 0.005,
        "analysed": 2,
        "kappa": -1.23456,
        "inverse_kappa": -0.81,
        "inverse_kappa_low": -1.5,
        "inverse_kappa_high": -0.1,
        "verdict": "sticky",
        "predicted_verdict": "sticky",
        "predicted_verdict_continuum": "not sticky",
    }
    table = table_lines([row, dict(row, adhesion_length=0.02)])
    assert len(table) == 4 and table[0].count("|") == table[2].count("|")
    assert "| 0.005 | 2 | −1.23 | −0.81 [−1.5, −0.1] |" in table[2]
    assert "not drawn" in figure1_note([], 0.02)[0]
    lines = report_lines(
        size=64, seeds=[1, 2], short_cutoff=4.0, rows=[row], summary=["S."], map_rows=[],
        map_area=0.02, run="R", figures={"fig2": ["x/fig2.png"], "fig1": []},
    )  # fmt: skip
    assert lines[0] == "# roughcontact demo" and "S." in lines and "Run: R" in lines
    assert lines[-1] == "![fig2](figures/fig2.png)" and table_lines([row])[2] in lines


def _row(la, verdict, continuum, measured_kappa_rep, kappas):
    inv = [1 / k for k in kappas]
    return {
        "adhesion_length": la,
        "analysed": len(kappas),
        "kappa_values": kappas,
        "kappa": 1 / np.mean(inv),
        "inverse_kappa": float(np.mean(inv)),
        "inverse_kappa_low": min(inv),
        "inverse_kappa_high": max(inv),
        "inverse_predicted_kappa_continuum": 0.23,
        "inverse_predicted_kappa": -0.01,
        "verdict": verdict,
        "predicted_verdict": measured_kappa_rep,
        "predicted_verdict_continuum": continuum,
        "kappa_rep": 3.8,
        "kappa_rep_values": [3.5, 4.1],
        "kappa_rep_hard_wall": 2.37,
        "kappa_rep_hard_wall_corrected": 2.13,
    }


def test_the_summary_never_counts_a_miss_as_agreement():
    """Measured undecided with every seed κ < 0, Eq. 10 (κ_rep = 2) "not sticky": a miss,
    named, not counted; both undecided: no verdict, not counted either."""
    from roughcontact.workflows.report import summary_lines

    rows = [
        _row(0.001, "not sticky", "not sticky", "not sticky", [5.0, 6.0]),
        _row(0.005, "undecided", "not sticky", "undecided", [-2.4, -8.5, -70.0]),
        _row(0.02, "sticky", "sticky", "sticky", [-0.5, -0.8]),
    ]
    lines = summary_lines(rows)
    paper = next(x for x in lines if x.startswith("Eq. 10 with the paper's κ_rep = 2"))
    assert "at ℓa/a0 = 0.001, 0.02 (2 of 3 adhesion lengths)" in paper
    (miss,) = [x for x in lines if x.startswith("NOT reproduced at ℓa/a0 = 0.005")]
    assert '"not sticky"' in miss and "all 3 seeds have κ < 0" in miss
    assert "Not counted as agreement" in miss
    ours = next(x for x in lines if x.startswith("Eq. 10 with the measured κ_rep"))
    assert "(2 of 3 adhesion lengths)" in ours and "0.005 both are undecided" in ours
    # κ_rep: the paper's value not reproduced, the measured ones given, the reason ours
    assert any(x.startswith("κ_rep is NOT reproduced") and "3.8" in x for x in lines)
    assert any(x.startswith("Our explanation (not the paper's)") for x in lines)


def test_the_report_holds_the_hard_wall_path_as_printed(demo):
    from roughcontact.workflows.report import hard_wall_lines

    lines = hard_wall_lines(demo)
    assert len(lines) == 3 + len(demo["path"]) + 2
    assert f"{demo['kappa_rep']:.3f} (site count)" in lines[-2] and "our reading" in lines[-2]
    report = report_lines(
        size=64, seeds=[1], short_cutoff=4.0, rows=[], summary=[], map_rows=[],
        map_area=0.02, run="R", figures={}, hard_wall=demo,
    )  # fmt: skip
    assert report[2] == "## Hard-wall load path" and lines[0] in report and lines[-2] in report
