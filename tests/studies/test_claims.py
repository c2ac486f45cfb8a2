"""The claim statistics on a synthetic study that obeys the paper's relations exactly.

Oracle: a collected dataset built from the relations themselves (A_rep = κ_rep N_rep/
(h'E*), N_att = (w/Δr) A_att, A_rep = P d/π, κ_att ∝ ℓa^-1, 1/κ = 1/κ_rep - 1/κ_att), so
every claim has a known answer: linear everywhere, ratios exactly 1, β = -1, the
criterion's confusion table diagonal.
"""

import math

import numpy as np
import pytest
import xarray as xr

from roughcontact.studies import claims
from roughcontact.studies.report import render_report

SLOPE, MODULUS, D = 0.1, 1.0, 6.0
KAPPA_REP = {4.0: 3.0, 8.0: 2.5}  # by λs
AREAS = np.geomspace(1e-4, 5e-2, 30)


def synthetic(seeds=(1, 2, 3), la_levels=(1e-3, 1e-2, 1e-1), cutoffs=(4.0, 8.0)):
    rows = []
    for lam in cutoffs:
        for la in la_levels:
            for s in seeds:
                rows.append((lam, la, s))
    n, m = len(rows), AREAS.size
    lam = np.array([r[0] for r in rows])
    la = np.array([r[1] for r in rows])
    seed = np.array([r[2] for r in rows])
    kr = np.array([KAPPA_REP[x] for x in lam]) * (1 + 0.01 * (seed - 2))  # seeds differ a bit
    dr = np.sqrt(24 * la)
    w = la * MODULUS
    katt = 0.2 / la  # κ_att ∝ 1/ℓa
    area_ratio = 0.05 / la
    a_rep = np.tile(AREAS, (n, 1))
    n_rep = SLOPE * MODULUS * a_rep / kr[:, None]
    a_att = a_rep / area_ratio[:, None]
    n_att = (w / dr)[:, None] * a_att
    kappa = 1 / (1 / kr - 1 / katt)
    ds = xr.Dataset(
        {
            "status": ("task", np.array(["done"] * n)),
            "kappa": ("task", kappa),
            "kappa_rep": ("task", kr),
            "kappa_rep_hard_wall": ("task", kr / 1.5),
            "kappa_rep_hard_wall_corrected": ("task", kr / 1.7),
            "kappa_att": ("task", katt),
            "predicted_kappa_att": ("task", 0.3 / la ** (5 / 6)),
            "predicted_kappa": ("task", kappa),
            "predicted_kappa_continuum": ("task", kappa),
            "area_ratio": ("task", area_ratio),
            "predicted_area_ratio": ("task", area_ratio / 1.2),
            "attractive_pressure_over_w_per_dr": ("task", np.ones(n)),
            "d_rep": ("task", np.full(n, D)),
            "predicted_d_rep": ("task", np.full(n, D / 1.5)),
            "measured_rms_slope": ("task", np.full(n, SLOPE)),
            "sticky": ("task", (kappa < 0).astype(float)),
            "predicted_sticky": ("task", (kappa < 0).astype(float)),
            "predicted_sticky_continuum": ("task", (kappa < 0).astype(float)),
            "necessary_condition": ("task", np.array(["not applicable: test"] * n)),
            "analysis_error": ("task", np.array([""] * n)),
            "steps_not_converged": ("task", np.zeros(n)),
            "branch": (("task", "step"), np.full((n, m), "approach")),
            "converged": (("task", "step"), np.ones((n, m), dtype=bool)),
            "repulsive_area": (("task", "step"), a_rep),
            "repulsive_load": (("task", "step"), n_rep),
            "attractive_area": (("task", "step"), a_att),
            "attractive_load": (("task", "step"), n_att),
            "perimeter": (("task", "step"), math.pi * a_rep / D),
        },
        coords={
            "task": [f"{i:03d}" for i in range(n)],
            "size": ("task", np.full(n, 256)),
            "pixel_size": ("task", np.ones(n)),
            "hurst": ("task", np.full(n, 0.8)),
            "rms_slope": ("task", np.full(n, SLOPE)),
            "short_cutoff": ("task", lam),
            "adhesion_length": ("task", la),
            "work_of_adhesion": ("task", w),
            "range": ("task", dr),
            "contact_modulus": ("task", np.full(n, MODULUS)),
            "seed": ("task", seed),
        },
    )
    return ds


def test_linear_area_load_everywhere():
    c = claims.area_load_linearity(synthetic())
    assert c["linear_from"] == claims.AREA_EDGES[0]
    assert c["linear_to"] == claims.AREA_EDGES[-1]
    for b in c["bins"]:
        assert b["median"] == pytest.approx(1.0, rel=1e-12)
    # the paper's statistical bound 10 λs²/A0
    assert c["statistical_from"]["8.0"] == pytest.approx(640 / 256**2)


def test_linearity_breaks_where_the_load_bends():
    ds = synthetic()
    a = ds["repulsive_area"].values
    ds["repulsive_load"] = ds["repulsive_load"] * np.where(a > 3e-2, 1.5, 1.0)
    c = claims.area_load_linearity(ds)
    assert c["linear_to"] == 3e-2


def test_kappa_rep_per_cutoff_through_inverses():
    c = claims.kappa_rep_by_cutoff(synthetic())
    rows = {r["short_cutoff"]: r for r in c["rows"]}
    for lam, kr in KAPPA_REP.items():
        # per seed 1/mean(1/κ) over its tasks, then the mean over seeds 0.99, 1, 1.01 × κ
        assert rows[lam]["kappa_rep"]["mean"] == pytest.approx(kr, rel=1e-12)
        assert rows[lam]["kappa_rep"]["low"] < kr < rows[lam]["kappa_rep"]["high"]
        assert rows[lam]["kappa_rep_hard_wall"]["mean"] == pytest.approx(kr / 1.5)


def test_attractive_pressure_is_exactly_w_over_dr():
    c = claims.attractive_pressure(synthetic())
    assert c["all"]["steps"]["median"] == pytest.approx(1.0, rel=1e-12)
    assert c["all"]["fraction_within_band"] == 1.0
    # A_att spans AREAS (3.7 decades) times the spread of A_rep/A_att over ℓa (2 decades)
    assert c["all"]["decades"] == pytest.approx(math.log10(5e-2 / 1e-4) + 2, rel=1e-12)


def test_contact_diameter_ratio_and_constancy():
    c = claims.contact_diameter(synthetic())
    assert c["ratio"]["median"] == pytest.approx(1.5)
    assert c["fraction_within_factor"] == 1.0
    assert c["variation_with_area"]["max"] == pytest.approx(0.0, abs=1e-12)


def test_thin_rim_split_and_ratios():
    c = claims.thin_rim_theory(synthetic())
    # A_rep/A_att = 0.05/ℓa: > 1 for ℓa = 1e-3, 1e-2; < 1 for 0.1
    assert c["thin_rim"]["tasks"] == 2 * 2 * 3
    assert c["wide_rim"]["tasks"] == 2 * 3
    assert c["thin_rim"]["area_ratio"]["median"] == pytest.approx(1.2)


def test_kappa_att_exponents():
    c = claims.kappa_att_scaling(synthetic())
    assert c["measured"]["median"] == pytest.approx(-1.0, abs=1e-12)
    assert c["predicted"]["median"] == pytest.approx(-5 / 6, abs=1e-12)


def test_criterion_confusion_is_diagonal_when_predictions_match():
    c = claims.criterion(synthetic())
    block = c["measured_kappa_rep"]
    assert block["agree"] == block["decided"] > 0
    assert c["disagreements"] == []
    sticky = block["table"]["sticky"]["sticky"]
    # κ_att = 0.2/ℓa < κ_rep only for ℓa = 0.1 (κ_att = 2): sticky at both λs
    assert sticky == 2


def test_necessary_condition_table():
    c = claims.necessary_condition(synthetic())
    # bound 0.486 h' = 0.0486: met by ℓa = 0.1 only
    assert sum(c["table"]["met"].values()) == 2
    assert c["sticky_without_condition"] == 0


def test_one_seed_has_no_interval_and_the_report_says_so():
    ds = synthetic(seeds=(1,))
    c = claims.all_claims(ds)
    assert math.isnan(c["kappa_rep"]["rows"][0]["kappa_rep"]["low"])
    meta = {
        "title": "t", "study_name": "s", "study_sha256": "0" * 64, "tasks_done": 6,
        "tasks_failed": 0, "tasks_missing": 0, "analysed": 6, "seeds": [1], "grid": "g",
        "unconverged_steps": 0, "study_file": "S.toml", "study_dir": "D", "report_dir": "R",
        "versions": {"roughcontact": "x", "python": "x", "numpy": "x", "scipy": "x"},
    }  # fmt: skip
    text = render_report(c, meta)
    assert "1 seed: no interval" in text
    assert "## 8." in text


def test_bad_confidence():
    from roughcontact import ParameterError

    with pytest.raises(ParameterError, match="confidence"):
        claims.all_claims(synthetic(), confidence=1.5)
