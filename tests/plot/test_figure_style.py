"""Publication style of the figures on small synthetic datasets (no study run).

Typeset symbols, κ_fit against κ(1 %), the measured κ_rep of the sticky region, the
κ_rep reference lines, legends outside the data, keys only for varied parameters.
"""

import itertools
import json
import math
import re

import numpy as np
import pytest

pytest.importorskip("matplotlib")
xr = pytest.importorskip("xarray")

from matplotlib.figure import Figure  # noqa: E402

from roughcontact.plot import _data as D  # noqa: E402
from roughcontact.plot import figure2, figure3, figure4, save_figures  # noqa: E402
from roughcontact.theory import pastewka_robbins as pr  # noqa: E402

NAN = math.nan


def synthetic(
    *,
    hurst=(0.5, 0.8),
    la=(NAN, 0.005, 0.05),
    rms_slope=(0.1,),
    seeds=(1,),
    kappa_rep=None,
    failed=None,
    extra=None,
    steps=10,
):
    """A collected-study-like dataset: one task per (H, h'rms, seed, ℓa), Eqs. 2 and 4 exact.

    ``kappa_rep`` / ``failed``: per-task values (default 2.5 + task / 10, all finished);
    ``extra``: more per-task variables (name -> values).
    """
    combos = list(itertools.product(hurst, rms_slope, seeds, la))
    n = len(combos)
    kr = np.array([2.5 + k / 10 for k in range(n)] if kappa_rep is None else kappa_rep, float)
    h, s, seed, adh = (np.array(v, dtype=float) for v in zip(*combos, strict=True))
    adhesive = np.isfinite(adh)
    dr = np.where(adhesive, np.sqrt(24 * np.where(adhesive, adh, 1.0)), NAN)
    d_pred = 4 * s / (s * 0.5)  # 4 h'rms / h''rms with h''rms = h'rms/2
    area = np.geomspace(1e-3, 0.08, steps)
    a_rep = np.tile(area, (n, 1)) * (1 + 0.05 * np.arange(n))[:, None]
    n_rep = s[:, None] * a_rep / kr[:, None]
    a_att = np.where(adhesive[:, None], 0.5 * a_rep, 0.0)
    n_att = np.where(adhesive[:, None], np.nan_to_num(adh / dr)[:, None] * a_att, 0.0)
    load = n_rep - n_att
    branch = np.array([["approach"] * (steps - 2) + ["retract"] * 2] * n)
    area_ratio = np.where(adhesive, 0.05 + 0.01 * np.arange(n), NAN)
    kappa_att = np.where(adhesive, 0.2 + 0.1 * np.arange(n), NAN)
    task = [f"{k:05d}" for k in range(n)]
    coords = {
        "task": task,
        "size": ("task", np.full(n, 64)),
        "pixel_size": ("task", np.ones(n)),
        "hurst": ("task", h),
        "rms_slope": ("task", s),
        "short_cutoff": ("task", np.full(n, 4.0)),
        "contact_modulus": ("task", np.ones(n)),
        "law": ("task", np.where(adhesive, "lj93smooth", "hardwall")),
        "adhesion_length": ("task", adh),
        "work_of_adhesion": ("task", adh),
        "range": ("task", dr),
        "seed": ("task", seed.astype(int)),
    }
    per_task = {
        "kappa": 1 / (1 / kr - np.where(adhesive, 1 / kappa_att, 0.0)),
        "kappa_rep": kr,
        "kappa_att": kappa_att,
        "kappa_fit": 0.8 * kr,
        "area_ratio": area_ratio,
        "d_rep": np.full(n, 7.5),
        "predicted_d_rep": d_pred,
        "measured_rms_slope": s,
        "failed": np.zeros(n, bool) if failed is None else np.asarray(failed, bool),
        **(extra or {}),
    }
    per_step = {
        "load": load,
        "repulsive_area": a_rep,
        "repulsive_load": n_rep,
        "attractive_area": a_att,
        "attractive_load": n_att,
        "perimeter": math.pi * a_rep / d_pred[:, None],
        "branch": branch,
        "converged": np.ones((n, steps), bool),
    }
    data = {k: ("task", np.asarray(v)) for k, v in per_task.items()}
    data |= {k: (("task", "step"), v) for k, v in per_step.items()}
    settings = {"analysis": {"fit_max_area": 0.05, "target_area": 0.01}}
    return xr.Dataset(data, coords=coords, attrs={"study_settings": json.dumps(settings)})


def _gid(ax, gid):
    return [a for a in [*ax.lines, *ax.collections] if a.get_gid() == gid]


def _texts(fig):
    """Every label, title, suptitle and legend text of ``fig``."""
    out = [t.get_text() for t in fig.texts]
    if fig._suptitle is not None:
        out.append(fig._suptitle.get_text())
    for ax in fig.axes:
        out += [ax.get_xlabel(), ax.get_ylabel(), ax.get_title()]
    legends = [*fig.legends, *(ax.get_legend() for ax in fig.axes if ax.get_legend())]
    for leg in legends:
        out += [t.get_text() for t in leg.get_texts()] + [leg.get_title().get_text()]
    return [t for t in out if t]


def _symbol_key(fig):
    """Labels of the symbol-code legend (titled "symbols"), [] when there is none."""
    for leg in fig.legends:
        if leg.get_title().get_text() == "symbols":
            return [t.get_text() for t in leg.get_texts()]
    return []


# --- 1. symbols typeset with mathtext ---------------------------------------------------


def test_symbols_are_typeset_with_mathtext():
    ds = synthetic(extra={"kappa_rep_hard_wall": np.full(6, 3.0)})
    figs = {"2": figure2(ds), "3": figure3(ds), "4": figure4(ds)}
    for name, fig in figs.items():
        for text in _texts(fig):
            assert text.count("$") % 2 == 0, (name, text)
            plain = re.sub(r"\$[^$]*\$", "", text)  # what is outside the math
            # no unicode stand-ins, no ASCII subscripts like A_rep or h'rms outside math
            assert not re.search(r"[κ′″ℓλΔπ≈_*]|h'|A0|a0", plain), (name, text)
    ax2 = figs["2"].axes[0]
    assert r"$N/(A_0 h'_\mathrm{rms} E^*)$" in ax2.get_xlabel()
    assert r"$A_\mathrm{rep}/A_0$" in ax2.get_ylabel()
    assert r"$A_\mathrm{rep}/A_0$" in figs["3"].axes[1].get_xlabel()
    assert r"$\kappa_\mathrm{att}" in figs["4"].axes[1].get_ylabel()
    assert r"\ell_a" in figs["4"].axes[1].get_xlabel()
    assert r"\Delta r" in figs["4"].axes[1].get_xlabel()
    assert r"$\ell_a/a_0 = 0.005$" in _symbol_key(figs["3"])
    assert D.la_label(0.05) == r"$\ell_a/a_0 = 0.05$" and D.la_label(NAN) == "non-adhesive"
    # every label parses: drawing raises on invalid mathtext
    for fig in figs.values():
        fig.draw_without_rendering()


# --- 2. Fig. 2: the fitted slope is κ_fit, never κ --------------------------------------


def test_figure2_legend_names_the_fitted_slope_kappa_fit():
    ds = synthetic(hurst=(0.8,))
    fig = figure2(ds)
    (legend,) = fig.legends
    texts = [t.get_text() for t in legend.get_texts()]
    data = {ln.get_gid()[5:]: ln for ln in fig.axes[0].lines if ln.get_gid().startswith("data:")}
    assert len(data) == 3
    for tid, line in data.items():
        fit = float(ds["kappa_fit"].sel(task=tid))
        assert rf"$\kappa_\mathrm{{fit}} = {fit:.3g}$" in line.get_label()
        assert line.get_label() in texts
    for text in texts:  # κ (the ratio at 1 %) and κ_fit never share a symbol
        assert r"\kappa =" not in text and r"\kappa$" not in text and "κ" not in text
    assert any(r"slope $\kappa_\mathrm{fit}$" in t for t in texts)  # the fit lines' key
    title = fig.axes[0].get_title()
    assert r"$\kappa_\mathrm{fit}$" in title
    assert "$H = 0.8$" in title and r"$h'_\mathrm{rms} = 0.1$" in title
    assert r"$\lambda_s/a_0 = 4$" in title and "$n = 64$" in title


# --- 3. Figs. 3-4: the measured κ_rep of the table's rows, 1/mean(1/κ_rep) over seeds ---


def _sticky_top(fig):
    (shade,) = _gid(fig.axes[1], "sticky")
    return shade.get_paths()[0].vertices[:, 1].max(), shade.get_label()


def test_sticky_region_is_drawn_at_the_measured_kappa_rep():
    # one row of the table (H, ℓa fixed; six seeds), usable finite positive κ_rep: 2, 4,
    # 8 -> 1/mean(1/κ) = 3/(7/8) = 24/7 (κ mean: 4.67); NaN, negative and the failed
    # task's 100 are left out
    per_task = [2.0, 4.0, NAN, -1.0, 8.0, 100.0]
    ds = synthetic(hurst=(0.8,), la=(0.005,), seeds=range(1, 7), kappa_rep=per_task,
                   failed=[0, 0, 0, 0, 0, 1])  # fmt: skip
    expect = 24.0 / 7.0
    assert D.kappa_rep_levels(ds) == ([pytest.approx(expect, rel=1e-12)], "measured")
    top, label = _sticky_top(figure4(ds))
    assert top == pytest.approx(expect, rel=1e-12)
    assert r"$\kappa_\mathrm{att} < \kappa_\mathrm{rep} = 3.43$ (measured)" in label
    assert not _gid(figure4(ds).axes[1], "sticky_band")  # one row: one boundary
    # Fig. 3 (b): Eq. 2 with the same measured κ_rep
    (eq2,) = _gid(figure3(ds).axes[1], "theory")
    xy = eq2.get_xydata()
    np.testing.assert_allclose(xy[:, 1], xy[:, 0] / expect, rtol=1e-12)
    assert "3.43" in eq2.get_label() and "(measured)" in eq2.get_label()
    # a float overrides
    top, label = _sticky_top(figure4(ds, kappa_rep=2.5))
    assert top == pytest.approx(2.5) and "(given)" in label
    (eq2,) = _gid(figure3(ds, kappa_rep=2.5).axes[1], "theory")
    np.testing.assert_allclose(eq2.get_xydata()[:, 1], eq2.get_xydata()[:, 0] / 2.5)
    # nothing measured: the paper's value, said so
    none = synthetic(kappa_rep=[NAN] * 6)
    top, label = _sticky_top(figure4(none))
    assert top == pytest.approx(pr.KAPPA_REP) and "continuum" in label
    top, _ = _sticky_top(figure4(none.drop_vars("kappa_rep")))
    assert top == pytest.approx(pr.KAPPA_REP)


def test_several_rows_give_the_rows_values_never_a_pooled_one():
    # 6 rows (H x ℓa) of two seeds; per row 1/mean(1/κ) of (a, b); the pooled harmonic
    # mean over all 12 tasks is in no row, and is drawn nowhere
    first = [2.0, 3.0, 4.0, 2.5, 3.5, 4.5]
    second = [4.0, 6.0, 8.0, 5.0, 7.0, 9.0]
    order = [(h, seed, la) for h in range(2) for seed in range(2) for la in range(3)]
    per_task = [(first if seed == 0 else second)[3 * h + la] for h, seed, la in order]
    ds = synthetic(seeds=(1, 2), kappa_rep=per_task)
    rows = sorted(2.0 / (1.0 / a + 1.0 / b) for a, b in zip(first, second, strict=True))
    levels, how = D.kappa_rep_levels(ds)
    np.testing.assert_allclose(levels, rows, rtol=1e-12)
    assert how == "measured"
    fig4 = figure4(ds)
    top, label = _sticky_top(fig4)
    assert top == pytest.approx(rows[0], rel=1e-12) and "smallest of the table's rows" in label
    (band,) = _gid(fig4.axes[1], "sticky_band")
    assert band.get_paths()[0].vertices[:, 1].max() == pytest.approx(rows[-1], rel=1e-12)
    fig3 = figure3(ds)
    assert not _gid(fig3.axes[1], "theory")
    (band,) = _gid(fig3.axes[1], "theory_band")
    xy = band.get_paths()[0].vertices
    np.testing.assert_allclose(
        [(xy[:, 1] / xy[:, 0]).min(), (xy[:, 1] / xy[:, 0]).max()], [1 / rows[-1], 1 / rows[0]]
    )
    assert f"{rows[0]:.3g}–{rows[-1]:.3g}" in band.get_label()
    pooled = f"{1.0 / np.mean(1.0 / np.array(per_task)):.3g}"
    assert all(pooled not in t for t in _texts(fig3) + _texts(fig4))


def test_continuum_kappa_rep_line_is_dashed_at_2():
    ds = synthetic(kappa_rep=[4.0] * 6)
    (line,) = _gid(figure4(ds).axes[1], "kappa_rep_continuum")
    assert line.get_linestyle() == "--" and set(line.get_ydata()) == {pr.KAPPA_REP}
    assert "the paper's" in line.get_label()
    assert r"$\kappa_\mathrm{rep} \approx 2$" in line.get_label()
    (line,) = _gid(figure3(ds).axes[1], "kappa_rep_continuum")
    xy = line.get_xydata()
    assert line.get_linestyle() == "--"
    np.testing.assert_allclose(xy[:, 1], xy[:, 0] / pr.KAPPA_REP, rtol=1e-12)
    # the y-range holds both the measured and the continuum value
    lo, hi = figure4(ds).axes[1].get_ylim()
    assert lo < pr.KAPPA_REP < 4.0 < hi


def test_hard_wall_reference_only_when_the_dataset_has_it():
    ds = synthetic()
    for fig in (figure3(ds), figure4(ds)):
        assert not _gid(fig.axes[1], "kappa_rep_hard_wall")
    nan = ds.assign(kappa_rep_hard_wall=("task", np.full(6, NAN)))
    for fig in (figure3(nan), figure4(nan)):
        assert not _gid(fig.axes[1], "kappa_rep_hard_wall")
    # each row of the table (two seeds) has 3 and 6: 1/mean(1/x) = 4, not the mean 4.5
    ds = synthetic(seeds=(1, 2))
    hw = ds.assign(kappa_rep_hard_wall=("task", [3.0] * 3 + [6.0] * 3 + [3.0] * 3 + [6.0] * 3))
    expect = 4.0
    (line,) = _gid(figure4(hw).axes[1], "kappa_rep_hard_wall")
    assert line.get_linestyle() == ":"
    np.testing.assert_allclose(line.get_ydata(), expect, rtol=1e-12)
    assert r"$\kappa_\mathrm{rep} = 4$" in line.get_label()
    (line,) = _gid(figure3(hw).axes[1], "kappa_rep_hard_wall")
    xy = line.get_xydata()
    np.testing.assert_allclose(xy[:, 1], xy[:, 0] / expect, rtol=1e-12)


# --- 4. legends never cover data ---------------------------------------------------------


def _within(xy, box):
    return (xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1) & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1)


def _overlaps(fig):
    """``[(legend, what)]`` for every legend over a drawn data point or a data axes."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    legends = [*fig.legends, *(ax.get_legend() for ax in fig.axes if ax.get_legend())]
    assert legends, "every figure has a legend"
    bad = []
    for leg in legends:
        box = leg.get_window_extent(renderer)
        for ax in fig.axes:
            points = [
                ln.get_transform().transform(ln.get_xydata())
                for ln in ax.lines
                if ln.get_marker() not in (None, "None", "none", "", " ") and len(ln.get_xydata())
            ]
            if not points and not ax.images:
                continue
            if box.overlaps(ax.bbox):  # at minimum: not inside an axes that holds data
                bad.append((leg, f"axes {ax.get_title()!r}"))
            for xy in points:
                xy = xy[_within(xy, ax.bbox)]  # the points drawn (not clipped)
                inside = _within(xy, box)
                if inside.any():
                    bad.append((leg, f"{int(inside.sum())} points of {ax.get_title()!r}"))
    return bad


@pytest.mark.parametrize(
    "kwargs",
    [
        {},  # H and ℓa varied: symbol keys
        {"hurst": (0.8,), "rms_slope": (0.1, 0.2), "seeds": (1, 2)},
        {"extra": {"kappa_rep_hard_wall": np.full(6, 3.0)}},
    ],
)
def test_no_legend_covers_data_in_the_saved_figures(kwargs, tmp_path, monkeypatch):
    ds = synthetic(**kwargs)
    saved, real = {}, Figure.savefig

    def spy(fig, *args, **kw):
        saved[id(fig)] = fig
        return real(fig, *args, **kw)

    monkeypatch.setattr(Figure, "savefig", spy)
    rng = np.random.default_rng(0)
    maps = [rng.normal(size=(32, 32)) for _ in range(2)]
    written = save_figures(ds, tmp_path, formats=("png",), maps=maps)
    assert len(written) == 4 and len(saved) == 4
    for fig in saved.values():
        assert _overlaps(fig) == []


# --- 5. keys only for varied parameters --------------------------------------------------


def test_constant_parameters_get_no_key_but_a_caption():
    ds = synthetic(hurst=(0.8,), la=(NAN, 0.005, 0.05))  # H, h'rms, λs, n constant
    for make in (figure3, figure4):
        fig = make(ds)
        key = _symbol_key(fig)
        assert not any("H =" in t or r"h'_\mathrm{rms}" in t or r"\lambda_s" in t for t in key)
        caption = fig._suptitle.get_text()
        for const in ("$H = 0.8$", r"$h'_\mathrm{rms} = 0.1$", r"$\lambda_s/a_0 = 4$", "$n = 64$"):
            assert const in caption
    # ℓa varies: keyed (Fig. 3 draws the non-adhesive tasks too, Fig. 4 only adhesive ones)
    assert _symbol_key(figure3(ds)) == [
        r"$\ell_a/a_0 = 0.005$",
        r"$\ell_a/a_0 = 0.05$",
        "non-adhesive",
    ]
    assert _symbol_key(figure4(ds)) == [r"$\ell_a/a_0 = 0.005$", r"$\ell_a/a_0 = 0.05$"]
    # varied H and h'rms are keyed and not in the caption
    varied = synthetic(hurst=(0.5, 0.8), rms_slope=(0.1, 0.2), la=(0.01,))
    fig = figure4(varied)
    key = _symbol_key(fig)
    assert key == ["$H = 0.5$", "$H = 0.8$", r"$h'_\mathrm{rms} = 0.1$", r"$h'_\mathrm{rms} = 0.2$"]
    caption = fig._suptitle.get_text()
    assert "$H =" not in caption and r"$h'_\mathrm{rms} =" not in caption
    assert r"$\ell_a/a_0 = 0.01$" in caption and r"$\lambda_s/a_0 = 4$" in caption
    # a single task: no symbol key at all
    single = synthetic(hurst=(0.8,), la=(0.01,))
    assert _symbol_key(figure4(single)) == []


def test_task_style_keys_follow_the_drawn_tasks():
    ds = synthetic(hurst=(0.5, 0.8), la=(NAN, 0.005))
    style = D.TaskStyle(ds)
    labels = [h.get_label() for h in style.legend_handles()]
    assert labels == ["$H = 0.5$", "$H = 0.8$", r"$\ell_a/a_0 = 0.005$", "non-adhesive"]
    # only the H = 0.8 tasks drawn: H is constant there, in the caption
    tasks = np.flatnonzero(ds["hurst"].values == 0.8)
    labels = [h.get_label() for h in style.legend_handles(tasks)]
    assert labels == [r"$\ell_a/a_0 = 0.005$", "non-adhesive"]
    assert style.caption(tasks).startswith("$H = 0.8$")
    # the symbols themselves do not depend on which tasks are keyed
    assert style(int(tasks[0]))["marker"] == "o"
