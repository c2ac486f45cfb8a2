"""The paper's analysis on grids larger than the tests use (issue 4's checks at scale).

For one self-affine surface per seed (H = 0.8, h'rms = 0.1, lambda_L = n/2, E* = a0 = 1)
it follows approach paths and prints, at A_rep = 1 % of A0 (``analyze_path``):

* non-adhesive kappa_rep with the hard wall: literature 1.8-2.6 (the paper: ~2); with the
  paper's soft wall at vanishing adhesion (``SmoothLJ93`` with l_a = 1e-7) it is larger by
  its repulsive band: kappa_rep / kappa_rep_hard_wall = A_rep / A_rep,hw at the same N_rep
  (within 5 %), band width delta 0.3-1.2 a0;
* Eq. 4: N_att / A_att over w / Delta_r (weak adhesion: within 10 % of 1);
* N_rep / A_rep with weak adhesion against l_a = 1e-7 (Fig. 3 upper inset: unchanged);
* d_rep = pi A_rep / P against 4 h'rms / h''rms (within a factor 2);
* measured stickiness (kappa < 0, the one rule) against Eq. 10's verdict (with the
  measured kappa_rep), for a clearly non-sticky (l_a = 0.0005) and a clearly sticky
  (l_a = 0.02) case.

    python benchmarks/analysis.py                      # 512², lambda_s = 8, seeds 1 2
    python benchmarks/analysis.py --size 1024 --short-cutoff 16 --seeds 1 --json a.json

Each check prints PASS or FAIL with its figures; nothing here is timed. On the 2-core
development machine the default run takes a few minutes.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

import roughcontact as rc
from roughcontact.analysis.path_analysis import analyze_path

NON_ADHESIVE = 1e-7
WEAK, STICKY = 0.0005, 0.02


def paths(n: int, short_cutoff: float, seed: int, steps: int) -> dict:
    """Hard-wall and soft-wall paths of one surface, reaching beyond 1 % contact."""
    h = rc.self_affine(
        (n, n), hurst=0.8, rms_slope=0.1, short_cutoff=short_cutoff, long_cutoff=n / 2,
        seed=seed,
    )  # fmt: skip
    sub = rc.Substrate((n, n))
    loads = np.geomspace(1e-4, 2e-3, steps)  # hard wall: about 0.3 % to 4 % contact
    out = {"hardwall": rc.approach_retract(h, sub, loads=loads, retract=False)}
    deepest = float(out["hardwall"]["offset"][-1])
    for la in (NON_ADHESIVE, WEAK, STICKY):
        law = rc.SmoothLJ93.from_adhesion_length(la)
        top = float(h.max()) + law.cutoff  # first attraction
        offsets = np.linspace(top, deepest + 1.0, 2 * steps)  # + a0: the soft wall's zero
        out[la] = rc.approach_retract(h, sub, law, offsets=offsets, tol=1e-7)
    return out


def check(name: str, ok: bool, detail: str, rows: list) -> None:
    rows.append({"check": name, "pass": bool(ok), "detail": detail})
    print(f"{'PASS' if ok else 'FAIL'}  {name}: {detail}", flush=True)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--short-cutoff", type=float, default=8.0, help="λs / a0")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--steps", type=int, default=12, help="approach steps (soft wall: 2x)")
    ap.add_argument("--json", metavar="OUT")
    args = ap.parse_args(argv)
    rows: list = []
    for seed in args.seeds:
        t0 = time.perf_counter()
        p = paths(args.size, args.short_cutoff, seed, args.steps)
        a = {k: analyze_path(v) for k, v in p.items()}
        tag = f"{args.size}² λs={args.short_cutoff:g} seed {seed}"
        k = a["hardwall"].kappa_rep
        check(f"{tag} κ_rep hard wall", 1.8 <= k <= 2.6, f"{k:.3f} (1.8-2.6)", rows)
        soft = a[NON_ADHESIVE]
        band = soft.kappa_rep / soft.kappa_rep_hard_wall / (0.01 / soft.hard_wall_repulsive_area)
        check(
            f"{tag} κ_rep soft wall = hard wall × A_rep/A_rep,hw",
            abs(band - 1) <= 0.05 and 0.3 <= soft.band_width <= 1.2,
            f"{soft.kappa_rep:.3f} vs {soft.kappa_rep_hard_wall:.3f} (ratio/area ratio "
            f"{band:.3f}, δ = {soft.band_width:.2f} a0)",
            rows,
        )
        eq4 = a[WEAK].attractive_pressure_over_w_per_dr
        check(f"{tag} Eq. 4 at ℓa={WEAK}", abs(eq4 - 1) <= 0.1, f"{eq4:.3f} (1 ± 0.1)", rows)
        pr = {la: a[la].repulsive_pressure for la in (NON_ADHESIVE, WEAK)}
        change = pr[WEAK] / pr[NON_ADHESIVE] - 1
        check(
            f"{tag} N_rep/A_rep weak vs no adhesion",
            abs(change) <= 0.1,
            f"{100 * change:+.1f} % (|Δ| <= 10 %)",
            rows,
        )
        ratio = a[NON_ADHESIVE].d_rep / a[NON_ADHESIVE].d_rep_predicted
        check(f"{tag} d_rep / (4h'/h'')", 0.5 <= ratio <= 2, f"{ratio:.2f} (0.5-2)", rows)
        for la in (WEAK, STICKY):
            r = a[la]
            same = bool(r.sticky) == bool(r.predicted_sticky)
            check(
                f"{tag} stickiness at ℓa={la}",
                same,
                f"measured {r.verdict} (κ={r.kappa:.3g}; pull-off {r.pull_off:.3g} E*), "
                f"Eq. 10 {r.predicted_sticky} (margin {r.predicted_margin:.3g})",
                rows,
            )
        print(f"      ({time.perf_counter() - t0:.0f} s)", flush=True)
    failed = [r for r in rows if not r["pass"]]
    print(f"{len(rows) - len(failed)} of {len(rows)} checks pass")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"options": vars(args), "checks": rows}, f, indent=1, default=str)
    return 0 if not failed else 1


if __name__ == "__main__":
    raise SystemExit(main())
