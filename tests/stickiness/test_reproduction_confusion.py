"""The committed confusion tables of the criteria, recomputed independently.

From ``reproduction/data/parameter_sets.csv`` alone: the spectral moments by numerical
quadrature of the self-affine spectrum (not roughcontact's closed form), each criterion's
formula written out here, and the measured verdicts of the file; the counts must equal
those of ``reproduction/claims.json`` (which ``roughcontact study report`` writes).
"""

from __future__ import annotations

import functools
import json
import math
from pathlib import Path

import pytest
from scipy.integrate import quad

pd = pytest.importorskip("pandas")
ROOT = Path(__file__).resolve().parents[2]
SETS = ROOT / "reproduction" / "data" / "parameter_sets.csv"
CLAIMS = ROOT / "reproduction" / "claims.json"


@functools.cache
def _moments(H, lam_s, lam_L, size, slope):
    qs, qL, q0 = 2 * math.pi / lam_s, 2 * math.pi / lam_L, 2 * math.pi / size

    def C(q):
        return 1.0 if q < qL else (q / qL) ** (-2 - 2 * H)

    def M(k):
        parts = [(q0, qL), (qL, qs)]
        return sum(2 * math.pi * quad(lambda q: q ** (k + 1) * C(q), a, b)[0] for a, b in parts)

    raw = {k: M(k) for k in (0, 1, 2, 4)}
    return {k: slope**2 / raw[2] * v for k, v in raw.items()}


def moments(row):
    return _moments(row.hurst, row.short_cutoff, row.long_cutoff, row["size"], row.rms_slope)


def verdicts(row):
    m = moments(row)
    E, w, dr, s = row.contact_modulus, row.work_of_adhesion, row["range"], row.rms_slope
    curv = math.sqrt(m[4])
    # Pastewka & Robbins Eq. 10, d_rep = 4 h'/h'', kappa_rep = 2
    d_rep = 4 * s / curv
    S = s * dr / (2 * w / E) * (s * d_rep / (4 * dr)) ** (2 / 3)
    # Persson & Tosatti: (E*/4) M1 / (w (1 + h'^2/2))
    P = E / 4 * m[1] / (w * (1 + s**2 / 2))
    # Fuller & Tabor with McCool's summits: m0, m2 = h'^2/2, m4 = 3 h''^2/8
    m0, m2, m4 = m[0], s**2 / 2, 3 * curv**2 / 8
    sig = math.sqrt(m0 * (1 - 0.8968 / (m0 * m4 / m2**2)))
    R = 0.375 * math.sqrt(math.pi / m4)
    theta = E * sig**1.5 / (w * math.sqrt(R))
    say = {True: "sticky", False: "not sticky"}
    return {
        "pastewka_robbins": say[S < math.pi * (3 / 16) ** (2 / 3)],
        "persson_tosatti": say[P < 1],
        "fuller_tabor": say[theta < 10],
    }


def test_committed_confusion_tables_follow_from_the_parameter_sets():
    sets = pd.read_csv(SETS)
    committed = json.loads(CLAIMS.read_text())["stickiness_criteria"]
    assert committed["parameter_sets"] == len(sets) == 72
    predicted = [verdicts(r) for _, r in sets.iterrows()]
    for key in ("pastewka_robbins", "persson_tosatti", "fuller_tabor"):
        table = committed["criteria"][key]["table"]
        for measured in ("sticky", "not sticky", "undecided"):
            for p in ("sticky", "not sticky"):
                n = sum(
                    1
                    for v, pr in zip(sets.verdict, predicted, strict=True)
                    if v == measured and pr[key] == p
                )
                assert table[measured][p] == n, (key, measured, p)
    # Dahlquist (no scale in lattice units) and Muser (a regime) give no verdict
    for key in ("dahlquist", "muser"):
        assert committed["criteria"][key]["no_verdict"] == 72
