"""Reading a collected study dataset for the figures, and the paper's symbol code.

The dataset is the one of :func:`roughcontact.studies.collect_study`: dimension ``task``
(parameters as coordinates), per-task analysis scalars, per-step curves along ``step``
(padded with NaN / ""). Nothing here imports matplotlib at module level.
"""

from __future__ import annotations

import json
import math

import numpy as np

from .._validate import ParameterError
from ..interactions.registry import PARAMETERS

#: Parameters that describe one surface realisation and its substrate (Fig. 2 picks one).
SURFACE_KEYS = (
    "size",
    "pixel_size",
    "hurst",
    "rms_slope",
    "rms_height",
    "short_cutoff",
    "long_cutoff",
    "rolloff",
    "contact_modulus",
    "thickness",
    "poisson",
    "base",
    "seed",
)
#: Parameters of the interaction (what varies between the curves of Fig. 2 and maps of Fig. 1).
ADHESION_KEYS = ("law", *PARAMETERS)  # the law and the registry's parameters
#: Mathtext symbols (without the ``$``) of the parameters in titles, captions and keys.
SYMBOLS = {
    "hurst": "H",
    "adhesion_length": r"\ell_a/a_0",
    "rms_slope": r"h'_\mathrm{rms}",
    "short_cutoff": r"\lambda_s/a_0",
    "size": "n",
    "seed": r"\mathrm{seed}",
}
#: Typeset names of the parameters in titles (matplotlib mathtext).
LABELS = {k: f"${SYMBOLS[k]}$" for k in ("hurst", "rms_slope", "short_cutoff", "size", "seed")}
# alternatives, first found wins: the measured slope is what the analysis normalised with
SLOPE = ("measured_rms_slope", "rms_slope")
ADHESION = ("adhesion_length", "work_of_adhesion")
D_REP = {"measured": ("d_rep",), "predicted": ("predicted_d_rep", "d_rep_predicted")}
PAPER_MARKERS = {0.3: "^", 0.5: "s", 0.8: "o"}  # triangles, squares, circles (Figs. 3-4)
OTHER_MARKERS = ("D", "v", "p", "h", "<", ">", "*")
# ℓa/a0 = 0.0005, 0.005, 0.05 are black, blue, red in the paper (Figs. 3-4): those values
# keep the paper's colours, any other ℓa takes the next of COLOURS by rank
PAPER_COLOURS = {0.0005: "black", 0.005: "tab:blue", 0.05: "tab:red"}
COLOURS = (
    "tab:green",
    "tab:purple",
    "tab:orange",
    "tab:brown",
    "tab:olive",
    "tab:cyan",
    "tab:pink",
)
NON_ADHESIVE = "0.55"


def _has(ds, name) -> bool:
    return name in ds.variables


def require(ds, needs, figure: str) -> None:
    """Raise :class:`ParameterError` naming every variable of ``needs`` the dataset lacks.

    ``needs`` holds names or tuples of alternative names.
    """
    if not hasattr(ds, "variables") or "task" not in getattr(ds, "dims", {}):
        raise ParameterError(
            f"{figure} needs a collected study dataset (an xarray.Dataset with a 'task' "
            f"dimension, from roughcontact.studies.collect_study), got {type(ds).__name__}"
        )
    missing = []
    for need in needs:
        names = (need,) if isinstance(need, str) else tuple(need)
        if not any(_has(ds, n) for n in names):
            missing.append(" or ".join(names))
    if missing:
        raise ParameterError(
            f"{figure}: the dataset lacks " + ", ".join(missing) + " (collect the study "
            "with 'roughcontact study collect DIR -o OUT.nc')"
        )


def values(ds, names) -> np.ndarray:
    """Float values on ``task`` of the first of ``names`` present, NaNs filled from the next."""
    names = (names,) if isinstance(names, str) else names
    found = [np.asarray(ds[n].values, dtype=float).reshape(-1) for n in names if _has(ds, n)]
    if not found:
        raise ParameterError("the dataset lacks " + " or ".join(names))
    out = found[0].copy()
    for more in found[1:]:
        out = np.where(np.isnan(out), more, out)
    return out


def adhesion_length(ds) -> np.ndarray:
    """ℓa = w/E* per task (NaN for non-adhesive tasks)."""
    if _has(ds, "adhesion_length"):
        return values(ds, "adhesion_length")
    return values(ds, "work_of_adhesion") / values(ds, "contact_modulus")


def usable(ds) -> np.ndarray:
    """Indices of the tasks that finished (``failed`` False, when the variable exists)."""
    n = ds.sizes["task"]
    if _has(ds, "failed"):
        return np.flatnonzero(~np.asarray(ds["failed"].values, dtype=bool))
    return np.arange(n)


def fit_max_area(ds, given=None) -> float:
    """The ``fit_max_area`` of the study's analysis (default 0.05) unless ``given``."""
    if given is not None:
        return float(given)
    try:
        return float(json.loads(ds.attrs.get("study_settings", "{}"))["analysis"]["fit_max_area"])
    except (KeyError, TypeError, ValueError):
        return 0.05


def curves(ds, i, names, *, branch="approach", converged_only=False) -> dict:
    """Per-step arrays of task ``i`` on ``branch``, steps with any non-finite value dropped."""
    keep = np.asarray(ds["branch"].values[i]) == branch
    if converged_only and _has(ds, "converged"):
        keep &= np.asarray(ds["converged"].values[i], dtype=bool)
    out = {n: np.asarray(ds[n].values[i], dtype=float)[keep] for n in names}
    finite = np.all([np.isfinite(v) for v in out.values()], axis=0) if out else keep
    return {n: v[finite] for n, v in out.items()}


def same(a, b) -> bool:
    """Equality of two coordinate values, NaN equal to NaN."""
    try:
        fa, fb = float(a), float(b)
    except (TypeError, ValueError):
        return a == b
    return fa == fb or (math.isnan(fa) and math.isnan(fb))


def param_text(key: str, value) -> str:
    """``"$<symbol> = <value>$"`` of a parameter (mathtext), e.g. ``$H = 0.8$``."""
    try:
        value = f"{float(value):g}"
    except (TypeError, ValueError):
        value = str(value)
    return f"${SYMBOLS.get(key, key)} = {value}$"


def la_label(la: float) -> str:
    """``$\\ell_a/a_0 = ...$`` (mathtext), or ``non-adhesive`` for NaN / non-positive ℓa/a0."""
    if not math.isfinite(la) or la <= 0:
        return "non-adhesive"
    return param_text("adhesion_length", la)


def harmonic_mean(ds, name) -> tuple[float, int]:
    """``(1/mean(1/x), count)`` of the per-task variable ``name`` over the usable tasks.

    Only finite positive values count (1/κ is the quantity that adds up over seeds and
    surfaces, never κ itself). ``(nan, 0)`` when the variable is missing or no usable
    task has a finite positive value.
    """
    if not _has(ds, name):
        return math.nan, 0
    x = np.asarray(ds[name].values, dtype=float).reshape(-1)[usable(ds)]
    x = x[np.isfinite(x) & (x > 0)]
    if x.size == 0:
        return math.nan, 0
    return float(1.0 / np.mean(1.0 / x)), int(x.size)


def kappa_rep_choice(ds, given=None) -> tuple[float, str]:
    """The κ_rep of the Eq. 2 line and the sticky region, and how it was obtained.

    ``given`` (a positive float) wins (``"given"``); else the measured
    :func:`harmonic_mean` of ``kappa_rep`` (``"measured"``); else, when the dataset has
    no finite positive ``kappa_rep``, the continuum hard-wall value
    :data:`~roughcontact.theory.pastewka_robbins.KAPPA_REP` (``"continuum"``).
    """
    from .._validate import positive
    from ..theory.pastewka_robbins import KAPPA_REP

    if given is not None:
        return positive("kappa_rep", given), "given"
    value, _ = harmonic_mean(ds, "kappa_rep")
    if math.isfinite(value):
        return value, "measured"
    return KAPPA_REP, "continuum"


class TaskStyle:
    """The paper's symbols: marker by H, colour by ℓa/a0, filled/open by h'rms, size by λs.

    Values the paper used get its symbols (H = 0.3, 0.5, 0.8: triangle, square, circle;
    ℓa/a0 = 0.0005, 0.005, 0.05 black, blue, red; the smallest h'rms filled); other
    values get the next symbols in order. Sizes grow with the rank of λs. The symbols are
    assigned over every usable task of the dataset, so a task looks the same in every
    figure; :meth:`legend_handles` and :meth:`caption` describe the tasks actually drawn.
    """

    def __init__(self, ds):
        n = ds.sizes["task"]
        self.hurst = values(ds, "hurst") if _has(ds, "hurst") else np.full(n, 0.8)
        a0 = values(ds, "pixel_size") if _has(ds, "pixel_size") else 1.0
        self.la = adhesion_length(ds) / a0  # ℓa/a0, the paper's parameter
        self.slope = values(ds, "rms_slope")
        self.cutoff = values(ds, "short_cutoff") if _has(ds, "short_cutoff") else self.slope * 0
        self.size = values(ds, "size") if _has(ds, "size") else np.full(n, np.nan)
        self._use = use = usable(ds)
        self._h = _unique(self.hurst[use])
        self._la = _unique(self.la[use][np.isfinite(self.la[use]) & (self.la[use] > 0)])
        self._s = _unique(self.slope[use])
        self._c = _unique(self.cutoff[use])
        extra = iter(OTHER_MARKERS * 4)
        self._markers = {h: PAPER_MARKERS.get(round(h, 6)) or next(extra) for h in self._h}

    def colour(self, la) -> str:
        if not math.isfinite(la) or la <= 0:
            return NON_ADHESIVE
        paper = PAPER_COLOURS.get(round(la, 9))
        if paper:
            return paper
        others = [v for v in self._la if round(v, 9) not in PAPER_COLOURS]
        return COLOURS[_rank(others, la) % len(COLOURS)]

    def __call__(self, i) -> dict:
        """``Axes.plot`` keywords of task ``i`` (markers only)."""
        colour = self.colour(self.la[i])
        filled = _rank(self._s, self.slope[i]) == 0
        return {
            "marker": self._markers.get(self.hurst[i], "o"),
            "color": colour,
            "markeredgecolor": colour,
            "markerfacecolor": colour if filled else "none",
            "markersize": 4.0 + 1.5 * _rank(self._c, self.cutoff[i]),
            "linestyle": "none",
        }

    def levels(self, tasks=None) -> dict:
        """Distinct values of H, ℓa/a0 (NaN: non-adhesive), h'rms, λs/a0, n over ``tasks``.

        ``tasks``: indices of the drawn tasks (default: every usable task).
        """
        idx = self._use if tasks is None else np.asarray(sorted(set(tasks)), dtype=int)
        la = self.la[idx]
        adhesive = _unique(la[np.isfinite(la) & (la > 0)])
        return {
            "hurst": _unique(self.hurst[idx]),
            "adhesion_length": adhesive + ([math.nan] if np.any(~(la > 0)) else []),
            "rms_slope": _unique(self.slope[idx]),
            "short_cutoff": _unique(self.cutoff[idx]),
            "size": _unique(self.size[idx]),
        }

    def legend_handles(self, tasks=None):
        """Proxy artists explaining the symbol code of the drawn ``tasks``.

        A parameter gets keys only where it takes more than one value among ``tasks``
        (default: every usable task); the constant ones are in :meth:`caption`.
        """
        from matplotlib.lines import Line2D

        def proxy(label, **kw):
            kw = {"marker": "o", "color": "0.3", "markersize": 6, "linestyle": "none", **kw}
            return Line2D([], [], label=label, **kw)

        lv = self.levels(tasks)
        handles = []
        if len(lv["hurst"]) > 1:
            handles += [
                proxy(param_text("hurst", h), marker=self._markers.get(h, "o")) for h in lv["hurst"]
            ]
        if len(lv["adhesion_length"]) > 1:
            handles += [proxy(la_label(la), color=self.colour(la)) for la in lv["adhesion_length"]]
        if len(lv["rms_slope"]) > 1:
            handles += [
                proxy(
                    param_text("rms_slope", s),
                    markerfacecolor="0.3" if _rank(self._s, s) == 0 else "none",
                )
                for s in lv["rms_slope"]
            ]
        if len(lv["short_cutoff"]) > 1:
            handles += [
                proxy(param_text("short_cutoff", c), markersize=4.0 + 1.5 * _rank(self._c, c))
                for c in lv["short_cutoff"]
            ]
        return handles

    def caption(self, tasks=None) -> str:
        """One line (mathtext) of the parameters constant over ``tasks``.

        E.g. ``$H = 0.8$, $h'_\\mathrm{rms} = 0.1$, $\\lambda_s/a_0 = 4$, $n = 256$``; ``""``
        when none is constant.
        """
        parts = []
        for key, vals in self.levels(tasks).items():
            if len(vals) != 1:
                continue
            if key == "adhesion_length":
                parts.append(la_label(vals[0]))
            elif math.isfinite(vals[0]):
                parts.append(param_text(key, vals[0]))
        return ", ".join(parts)


def _unique(a) -> list:
    a = np.asarray(a, dtype=float)
    return sorted(set(a[np.isfinite(a)].tolist()))


def _rank(levels, v) -> int:
    return levels.index(v) if v in levels else 0


def select_tasks(ds, select):
    """Indices of the usable tasks matching ``select`` (default: the first task's surface)."""
    use = usable(ds)
    if use.size == 0:
        raise ParameterError("Fig. 2: no finished task in the dataset (all failed)")
    if select is None:
        select = {k: ds[k].values[use[0]] for k in SURFACE_KEYS if k in ds.coords}
    for key in select:
        if key not in ds.variables:
            raise ParameterError(f"Fig. 2: select key {key!r} is not a parameter of the dataset")
    chosen = [i for i in use if all(same(ds[k].values[i], v) for k, v in select.items())]
    if not chosen:
        raise ParameterError(f"Fig. 2: no finished task matches select = {dict(select)!r}")
    return chosen


#: The paper shows only states with A_rep/λs² ≳ 10, "so that there is a statistical number
#: of contacting asperities" (Methods); Figs. 3 and the demo's report use the same rule.
STATISTICAL_CONTACTS = 10.0


def area_per_cutoff(ds) -> np.ndarray:
    """Per task A0/λs² (dimensionless; A0 = (n a0)², λs in length): A_rep/λs² is
    (A_rep/A0) times this. NaN where the dataset lacks ``size`` or ``short_cutoff``."""
    n = ds.sizes["task"]
    if not (_has(ds, "size") and _has(ds, "short_cutoff")):
        return np.full(n, np.nan)
    a0 = values(ds, "pixel_size") if _has(ds, "pixel_size") else np.ones(n)
    return (values(ds, "size") * a0 / values(ds, "short_cutoff")) ** 2


def eq4_outliers(ds, threshold=STATISTICAL_CONTACTS, far=0.5) -> dict:
    """How the converged approach states with attraction compare with Eq. 4, and which of
    them Fig. 3 leaves out (A_rep/λs² < ``threshold``).

    ``r`` = N_att/((w/Δr) A_att) (dimensionless; Eq. 4: r = 1). Returns a dict:
    ``threshold``; ``hidden`` (states below the threshold); ``shown_range`` ((min, max)
    of r over the states shown, or None); ``far`` (states with r < ``far``),
    ``far_no_contact`` (of them, with A_rep = 0), ``far_max_sites`` (their largest number
    of attractive sites, A_att n²), ``far_hidden`` (of them, below the threshold) and
    ``lowest`` (the smallest r; None without any state).
    """
    factor, la, dr = area_per_cutoff(ds), adhesion_length(ds), values(ds, "range")
    modulus = values(ds, "contact_modulus")
    sites = values(ds, "size") ** 2 if _has(ds, "size") else np.full(ds.sizes["task"], np.nan)
    r_all, shown, hidden, no_contact, counts = [], [], [], [], []
    for i in usable(ds):
        if not (math.isfinite(la[i]) and la[i] > 0):
            continue
        names = ("attractive_area", "attractive_load", "repulsive_area")
        c = curves(ds, i, names, converged_only=True)
        ok = c["attractive_area"] > 0
        area, rep = c["attractive_area"][ok], c["repulsive_area"][ok]
        r = c["attractive_load"][ok] / modulus[i] / (la[i] / dr[i]) / area
        below = rep * factor[i] < threshold if math.isfinite(factor[i]) else np.zeros_like(ok[ok])
        r_all += list(r)
        shown += list(r[~below])
        hidden += list(below)
        no_contact += list(rep == 0)
        counts += list(np.rint(area * sites[i]))
    r_all, hidden = np.asarray(r_all), np.asarray(hidden, dtype=bool)
    no_contact, counts = np.asarray(no_contact, dtype=bool), np.asarray(counts)
    out = r_all < far
    return {
        "threshold": float(threshold),
        "hidden": int(hidden.sum()),
        "shown_range": (float(min(shown)), float(max(shown))) if shown else None,
        "far": int(out.sum()),
        "far_below": float(far),
        "far_no_contact": int((out & no_contact).sum()),
        "far_hidden": int((out & hidden).sum()),
        "far_max_sites": int(counts[out].max())
        if out.any() and np.isfinite(counts[out]).all()
        else None,
        "lowest": float(r_all.min()) if r_all.size else None,
    }


def kappa_rep_levels(ds, given=None, name="kappa_rep") -> tuple[list[float], str]:
    """The κ_rep values of the Eq. 2 line and the sticky region, and how they were obtained.

    ``given`` (a positive float) wins: ``([given], "given")``. Else the measured κ_rep of
    each row of the study's table (:func:`roughcontact.studies.aggregate.aggregate_seeds`:
    tasks with equal parameters but the seed, :math:`1/\\langle 1/\\kappa_{rep}\\rangle`
    over their usable tasks with a finite positive ``kappa_rep``), sorted, with
    ``"measured"``; never one value pooled over different parameters, which no row of the
    table shows. Without any, ``([2.0], "continuum")`` (the paper's value). ``name``: the
    variable (``kappa_rep_hard_wall`` for the hard-wall reference).
    """
    from .._validate import positive
    from ..studies.aggregate import _parameter_sets
    from ..theory.pastewka_robbins import KAPPA_REP

    if given is not None:
        return [positive("kappa_rep", given)], "given"
    if not _has(ds, name):
        return [KAPPA_REP], "continuum"
    kappa = np.asarray(ds[name].values, dtype=float).reshape(-1)
    use = set(usable(ds).tolist())
    levels = []
    for tasks in _parameter_sets(ds)[1].values():
        x = np.array([kappa[i] for i in tasks if i in use])
        x = x[np.isfinite(x) & (x > 0)]
        if x.size:
            levels.append(float(1.0 / np.mean(1.0 / x)))
    if not levels:
        return [KAPPA_REP], "continuum"
    return sorted(levels), "measured"


def levels_text(levels) -> str:
    """``3.55`` or ``3.55–4.1`` (3 significant digits) of the sorted ``levels``."""
    lo, hi = f"{levels[0]:.3g}", f"{levels[-1]:.3g}"
    return lo if lo == hi else f"{lo}–{hi}"
