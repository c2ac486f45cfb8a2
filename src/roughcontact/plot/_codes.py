"""The paper's codes in the figures: Fig. 2's colours by stickiness, the κ_rep reference
lines of Figs. 3-4 (the paper's κ_rep ≈ 2 and the hard wall on the same surfaces)."""

from __future__ import annotations

import math

from . import _data as D

#: Fig. 2's colours as the paper's: black non-adhesive, blue adhesive but not sticky
#: (κ > 0), green at the onset (κ diverges), red sticky (κ < 0); shades from light to
#: dark with growing ℓa.
STICKY_COLOURS = {
    "non-adhesive": ("black",),
    "not sticky": ("#9ecae1", "#6baed6", "#3182bd", "#08519c", "#08306b"),
    "onset": ("#74c476", "#31a354", "#006d2c"),
    "sticky": ("#fc9272", "#ef3b2c", "#cb181d", "#a50f15", "#67000d"),
}
_KAPPA_1 = r"\kappa_{1\%}"  # κ at the target area (1 %), mathtext
VERDICT_TEXT = {
    "not sticky": rf"${_KAPPA_1} > 0$",
    "onset": rf"onset: ${_KAPPA_1}$ and $\kappa_\mathrm{{fit}}$ differ in sign",
    "sticky": rf"sticky, ${_KAPPA_1} < 0$",
}


def sticky_colours(ds, tasks, la) -> dict:
    """Task index -> (colour, verdict text) of Fig. 2, the paper's code.

    The sign of the task's κ at the target area (``kappa``) picks red (κ < 0: sticky) or
    blue (κ > 0); green where κ and the fitted slope ``kappa_fit`` differ in sign (κ
    diverges near the target area: the onset of stickiness); grey when κ is not finite;
    non-adhesive tasks black. Shades darken with growing ℓa within each kind.
    """
    kappa = D.values(ds, ("kappa", "kappa_fit"))
    fit = D.values(ds, ("kappa_fit", "kappa")) if D._has(ds, "kappa_fit") else kappa
    kinds = {}
    for i in tasks:
        if not (math.isfinite(la[i]) and la[i] > 0):
            kinds[i] = "non-adhesive"
        elif not (math.isfinite(kappa[i]) and kappa[i] != 0):
            kinds[i] = None
        elif math.isfinite(fit[i]) and fit[i] * kappa[i] < 0:
            kinds[i] = "onset"
        else:
            kinds[i] = "sticky" if kappa[i] < 0 else "not sticky"
    out = {}
    for kind, shades in STICKY_COLOURS.items():
        members = sorted((la[i], i) for i in tasks if kinds[i] == kind)
        for rank, (_, i) in enumerate(members):
            # the darkest shades for the largest ℓa
            k = len(shades) - len(members) + rank if len(members) <= len(shades) else rank
            out[i] = (shades[max(0, k) % len(shades)], VERDICT_TEXT.get(kind, ""))
    for i in tasks:
        out.setdefault(i, ("0.55", r"$\kappa$ not measured"))
    return out


_KAPPA_REP_TEX = r"\kappa_\mathrm{rep}"


def reference_lines(ds):
    """``[(gid, κ_rep, label, line style)]``: the paper's κ_rep = 2 and, when the dataset
    has finite values, the hard wall on the same surfaces (``kappa_rep_hard_wall``), one
    line per distinct value of the table's rows (:func:`kappa_rep_levels`)."""
    from ..theory.pastewka_robbins import KAPPA_REP

    refs = [
        (
            "kappa_rep_continuum",
            KAPPA_REP,
            rf"the paper's ${_KAPPA_REP_TEX} \approx {KAPPA_REP:g}$",
            {"linestyle": "--", "color": "0.25", "lw": 1.0},
        )
    ]
    hard, how = D.kappa_rep_levels(ds, name="kappa_rep_hard_wall")
    if how == "measured":
        distinct = sorted({float(f"{v:.3g}") for v in hard})
        label = rf"hard wall on these surfaces, ${_KAPPA_REP_TEX} = {D.levels_text(hard)}$"
        for k, value in enumerate(distinct):
            refs.append(
                (
                    "kappa_rep_hard_wall",
                    value,
                    label if k == 0 else None,
                    {"linestyle": ":", "color": "#8c510a", "lw": 1.5},
                )
            )
    return refs
