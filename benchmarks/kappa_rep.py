"""κ_rep of the paper's wall against the hard wall on the same surfaces (the README table).

For self-affine surfaces (H, h'rms, λL = L/2, E* = a0 = 1) and several λs it follows the
approach of the paper's smoothed 9-3 wall at vanishing adhesion (``SmoothLJ93`` with
ℓa = 1e-7, k = E*/(2 a0)) and analyses it at A_rep = 1 % of A0 with the hard-wall
reference (``analyze_path``): κ_rep of the paper's wall, of the hard wall at the same
area (site count and perimeter-corrected area), their ratio and the band width
δ = (A_rep − A_rep,hw)/P at the same repulsive load. Mean over the seeds (κ through 1/κ),
printed as a Markdown table; nothing is timed.

    python benchmarks/kappa_rep.py                                # 512², λs = 4 8 16 32
    python benchmarks/kappa_rep.py --size 256 --short-cutoffs 4 8 --seeds 1 2 3
    python benchmarks/kappa_rep.py --stiffness 8                  # a stiffer wall (E*/a0)
"""

from __future__ import annotations

import argparse
import json

import numpy as np

import roughcontact as rc
from roughcontact.analysis.path_analysis import analyze_path
from roughcontact.analysis.stickiness import inverse_mean

NON_ADHESIVE = 1e-7


def one(n, hurst, slope, cutoff, seed, stiffness, steps):
    h = rc.self_affine((n, n), hurst=hurst, rms_slope=slope, short_cutoff=cutoff,
                       long_cutoff=n / 2, seed=seed)  # fmt: skip
    sub = rc.Substrate((n, n))
    if stiffness is None:
        law = rc.SmoothLJ93.from_adhesion_length(NON_ADHESIVE)
    else:  # the same (vanishing) w with another site stiffness
        law = rc.SmoothLJ93(stiffness=stiffness, work_of_adhesion=NON_ADHESIVE)
    # from the first attraction to the bearing area of 3 %: beyond 1 % repulsive contact
    deep = float(np.quantile(h, 1 - 0.03)) + law.equilibrium_distance
    offsets = np.linspace(float(h.max()) + law.cutoff, deep, steps)
    ds = rc.approach_retract(h, sub, law, offsets=offsets, retract=False, tol=1e-7)
    return analyze_path(ds)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--hurst", type=float, default=0.8)
    ap.add_argument("--rms-slope", type=float, default=0.1)
    ap.add_argument("--short-cutoffs", type=float, nargs="+", default=[4, 8, 16, 32])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--stiffness", type=float, default=None, help="site stiffness k (E*/a0)")
    ap.add_argument("--steps", type=int, default=24)
    ap.add_argument("--json", metavar="OUT")
    args = ap.parse_args(argv)
    print(f"{args.size}², H = {args.hurst}, h'rms = {args.rms_slope}, seeds {args.seeds}, "
          f"k = {args.stiffness or 0.5} E*/a0")  # fmt: skip
    head = ("| λs/a0 | κ_rep hard wall | hard wall, corrected area | κ_rep smoothed LJ wall "
            "| ratio | δ/a0 | πδ/d_rep | A_rep/λs² |")  # fmt: skip
    print(head + "\n|" + "---|" * 8, flush=True)
    out = []
    for cutoff in args.short_cutoffs:
        r = [one(args.size, args.hurst, args.rms_slope, cutoff, s, args.stiffness, args.steps)
             for s in args.seeds]  # fmt: skip
        hw = inverse_mean([x.kappa_rep_hard_wall for x in r]).value
        corr = inverse_mean([x.kappa_rep_hard_wall_corrected for x in r]).value
        soft = inverse_mean([x.kappa_rep for x in r]).value
        delta = float(np.mean([x.band_width for x in r]))
        frac = float(np.mean([x.band_fraction for x in r]))
        spots = 0.01 * args.size**2 / cutoff**2
        print(f"| {cutoff:g} | {hw:.2f} | {corr:.2f} | {soft:.2f} | {soft / hw:.2f} | "
              f"{delta:.2f} | {frac:.2f} | {spots:.3g} |", flush=True)  # fmt: skip
        out.append({"short_cutoff": cutoff, "kappa_rep_hard_wall": hw,
                    "kappa_rep_hard_wall_corrected": corr, "kappa_rep": soft,
                    "band_width": delta, "band_fraction": frac,
                    "per_seed": [x.to_dict() for x in r]})  # fmt: skip
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"options": vars(args), "rows": out}, f, indent=1, default=str)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
