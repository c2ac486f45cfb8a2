"""The paper's figures from a real tiny study: the plotted data, not just the files."""

import math
import subprocess
import sys

import numpy as np
import pytest
from click.testing import CliRunner

pytest.importorskip("matplotlib")

from roughcontact import ParameterError  # noqa: E402
from roughcontact.cli.main import main  # noqa: E402
from roughcontact.plot import (  # noqa: E402
    contact_masks,
    figure1,
    figure2,
    figure3,
    figure4,
    save_figures,
    study_maps,
)
from roughcontact.plot._codes import STICKY_COLOURS  # noqa: E402
from roughcontact.plot.maps import ORANGE  # noqa: E402
from roughcontact.studies import collect_study, run_study, study_from_dict  # noqa: E402
from roughcontact.theory import pastewka_robbins as pr  # noqa: E402

STUDY = {
    "study": {"name": "figures"},
    "surface": {
        "size": 64,
        "hurst": [0.5, 0.8],
        "rms_slope": 0.1,
        "short_cutoff": 4.0,
        "seeds": [1, 2],
    },  # fmt: skip
    "cases": [
        {"law": "hardwall"},
        {"law": "lj93smooth", "adhesion_length": 0.005},
        {"law": "lj93smooth", "adhesion_length": 0.05},
    ],
    "path": {"unit": "rms_height", "start": 0.5, "stop": -1.5, "step": 0.25},
    "solver": {"tol": 1e-6},
    "output": {"fields_at": [3, 4, 5, 6], "fields": ["pressure", "gap"]},
}


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    out = tmp_path_factory.mktemp("study") / "run"
    summary = run_study(study_from_dict(STUDY), out, scheduler="synchronous", progress=False)
    assert summary.ok
    return out, collect_study(out)


def _lines(ax, prefix):
    return {ln.get_gid().split(":", 1)[1]: ln for ln in ax.lines
            if (ln.get_gid() or "").startswith(prefix)}  # fmt: skip


def _approach(task, *names):
    keep = task["branch"].values == "approach"
    return [np.asarray(task[n].values, dtype=float)[keep] for n in names]


def test_figure2_plots_the_approach_and_the_fitted_kappa(study):
    _, ds = study
    fig = figure2(ds, select={"hurst": 0.8, "seed": 1})
    ax = fig.axes[0]
    data, fits = _lines(ax, "data:"), _lines(ax, "fit:")
    chosen = ds.where((ds.hurst == 0.8) & (ds.seed == 1), drop=True)["task"].values
    assert sorted(data) == sorted(chosen) and len(data) == 3  # hardwall, two ℓa
    colours = {}
    for tid, line in data.items():
        t = ds.sel(task=tid)
        scale = float(t["measured_rms_slope"]) * float(t["contact_modulus"])
        load, area = _approach(t, "load", "repulsive_area")
        np.testing.assert_allclose(line.get_xydata(), np.column_stack([load / scale, area]))
        colours[float(t["adhesion_length"])] = line.get_color()
        kappa = float(t["kappa_fit"])
        if not math.isfinite(kappa):
            assert tid not in fits
            continue
        (x0, y0), (x1, y1) = fits[tid].get_xydata()
        assert (y1 - y0) / (x1 - x0) == pytest.approx(kappa, rel=1e-9)
        # the path analysis' least-squares line of A_rep(N) over 0 < A_rep <= 0.05
        use = (area > 0) & (area <= 0.05)
        slope, intercept = np.polyfit(load[use], area[use], 1)
        assert slope == pytest.approx(kappa / scale, rel=1e-9)
        assert y0 == pytest.approx(slope * load[use].min() + intercept, abs=1e-12)
        assert x0 == pytest.approx(load[use].min() / scale) and x1 == pytest.approx(
            load[use].max() / scale
        )
    # the paper's colours: black non-adhesive, red sticky (κ < 0 at the target area),
    # blue κ > 0, green where κ and the fitted slope differ in sign (the onset)
    for tid, line in data.items():
        t = ds.sel(task=tid)
        la, k, fit = (float(t[n]) for n in ("adhesion_length", "kappa", "kappa_fit"))
        if math.isnan(la):
            kind = "non-adhesive"
        elif k * fit < 0:
            kind = "onset"
        else:
            kind = "sticky" if k < 0 else "not sticky"
        assert line.get_color() in STICKY_COLOURS[kind], (tid, kind)
    assert colours[[k for k in colours if math.isnan(k)][0]] == "black"
    assert r"$N/(A_0 h'_\mathrm{rms} E^*)$" in ax.get_xlabel()
    assert r"$A_\mathrm{rep}/A_0$" in ax.get_ylabel()
    # the legend names the fitted slope κ_fit, the title the surface (typeset)
    texts = [t.get_text() for t in fig.legends[0].get_texts()]
    assert any(r"$\kappa_\mathrm{fit} = " in t for t in texts)
    assert not any(r"$\kappa = " in t or "κ" in t for t in texts)
    assert "$H = 0.8$" in ax.get_title() and r"$h'_\mathrm{rms} = 0.1$" in ax.get_title()
    # default: the surface (and seed) of the first task, every interaction
    assert sorted(_lines(figure2(ds).axes[0], "data:")) == ["00000", "00004", "00008"]


def test_figure3_collapse_data_and_symbols(study):
    _, ds = study
    fig = figure3(ds)
    att, rep, per = (_lines(ax, "task:") for ax in fig.axes[:3])
    adhesive = ds["task"].values[np.isfinite(ds["adhesion_length"].values)]
    assert sorted(att) == sorted(adhesive)  # no attraction without adhesion
    for tid in ds["task"].values:
        t = ds.sel(task=tid)
        keep = (t["branch"].values == "approach") & t["converged"].values
        get = {n: t[n].values[keep] for n in ("attractive_area", "attractive_load",
               "repulsive_area", "repulsive_load", "perimeter")}  # fmt: skip
        scale = float(t["measured_rms_slope"]) * float(t["contact_modulus"])
        x, y = get["repulsive_area"], get["repulsive_load"] / scale
        ok = (x > 0) & (y > 0)
        np.testing.assert_allclose(rep[tid].get_xydata(), np.column_stack([x[ok], y[ok]]))
        y = get["perimeter"] * float(t["predicted_d_rep"]) / math.pi
        ok = (x > 0) & (y > 0)
        np.testing.assert_allclose(per[tid].get_xydata(), np.column_stack([x[ok], y[ok]]))
        if tid in att:
            x = float(t["adhesion_length"]) / float(t["range"]) * get["attractive_area"]
            y = get["attractive_load"] / float(t["contact_modulus"])
            ok = (x > 0) & (y > 0)
            np.testing.assert_allclose(att[tid].get_xydata(), np.column_stack([x[ok], y[ok]]))
        line = rep[tid]  # symbols: H -> marker, h'rms (one value) filled, ℓa -> colour
        assert line.get_marker() == {0.5: "s", 0.8: "o"}[float(t["hurst"])]
        assert line.get_markerfacecolor() == line.get_markeredgecolor()
    theory = [next(ln for ln in fig.axes[k].lines if ln.get_gid() == "theory") for k in (0, 2)]
    for line in theory:  # Eq. 4 and P d/π: y = x
        xy = line.get_xydata()
        np.testing.assert_allclose(xy[:, 1], xy[:, 0], rtol=1e-12)
    # Eq. 2: the band between the smallest and the largest κ_rep of the table's rows (the
    # tasks equal but for the seed, 1/<1/κ_rep> over the seeds), never a pooled value
    lo, hi = min(_row_kappa_rep(ds)), max(_row_kappa_rep(ds))
    assert hi > lo
    assert not any(ln.get_gid() == "theory" for ln in fig.axes[1].lines)
    band = next(c for c in fig.axes[1].collections if c.get_gid() == "theory_band")
    xy = band.get_paths()[0].vertices
    ratio = xy[:, 1] / xy[:, 0]
    assert ratio.min() == pytest.approx(1 / hi, rel=1e-9)
    assert ratio.max() == pytest.approx(1 / lo, rel=1e-9)
    assert f"{lo:.3g}–{hi:.3g}" in band.get_label()
    continuum = next(ln for ln in fig.axes[1].lines if ln.get_gid() == "kappa_rep_continuum")
    xy = continuum.get_xydata()  # κ_rep = 2 for reference, dashed
    np.testing.assert_allclose(xy[:, 1], xy[:, 0] / pr.KAPPA_REP, rtol=1e-12)
    assert continuum.get_linestyle() == "--"
    given = next(ln for ln in figure3(ds, kappa_rep=2.0).axes[1].lines if ln.get_gid() == "theory")
    np.testing.assert_allclose(given.get_xydata()[:, 1], given.get_xydata()[:, 0] / 2.0)


def _row_kappa_rep(ds):
    """κ_rep of each row of the study's table, by hand: tasks equal but for the seed."""
    rows = {}
    for i in range(ds.sizes["task"]):
        t = ds.isel(task=i)
        k = float(t["kappa_rep"])
        if bool(t["failed"]) or not (math.isfinite(k) and k > 0):
            continue
        key = (float(t["hurst"]), repr(float(t["adhesion_length"])), str(t["law"].values))
        rows.setdefault(key, []).append(1.0 / k)
    return [1.0 / np.mean(v) for v in rows.values()]


def test_figure3_leaves_out_what_the_paper_does(study):
    """min_area_per_cutoff: states with A_rep/λs² below it in grey, the others as symbols."""
    _, ds = study
    fig = figure3(ds, min_area_per_cutoff=10.0)
    rep, few = _lines(fig.axes[1], "task:"), _lines(fig.axes[1], "few:")
    assert few  # a 64² surface with λs = 4 has A_rep/λs² < 10 below A_rep/A0 = 0.039
    for tid in ds["task"].values:
        t = ds.sel(task=tid)
        keep = (t["branch"].values == "approach") & t["converged"].values
        x = t["repulsive_area"].values[keep]
        y = t["repulsive_load"].values[keep]
        ok = (x > 0) & (y > 0)
        small = x * (64 / 4.0) ** 2 < 10.0
        if (ok & small).any():
            np.testing.assert_allclose(few[tid].get_xdata(), x[ok & small])
        if (ok & ~small).any():
            np.testing.assert_allclose(rep[tid].get_xdata(), x[ok & ~small])


def test_figure4_theory_lines_are_eqs_6_and_7(study):
    _, ds = study
    fig = figure4(ds)
    ax_ratio, ax_kappa = fig.axes[:2]
    a = pr.AREA_RATIO_PREFACTOR
    eq6 = next(ln for ln in ax_ratio.lines if ln.get_gid() == "theory").get_xydata()
    np.testing.assert_allclose(eq6[:, 1], a * eq6[:, 0] ** (2 / 3), rtol=1e-12)
    eq7 = next(ln for ln in ax_kappa.lines if ln.get_gid() == "theory").get_xydata()
    np.testing.assert_allclose(eq7[:, 1], a * eq7[:, 0], rtol=1e-12)
    points = _lines(ax_kappa, "task:")
    ok = np.isfinite(ds["kappa_att"].values) & np.isfinite(ds["d_rep"].values)
    assert sorted(points) == sorted(ds["task"].values[ok]) and len(points) >= 4
    for tid, line in points.items():
        t = ds.sel(task=tid)
        args = (float(t["measured_rms_slope"]), float(t["d_rep"]), float(t["range"]),
                float(t["adhesion_length"]))  # fmt: skip
        (x, y), = line.get_xydata()  # fmt: skip
        assert y == pytest.approx(float(t["kappa_att"]))
        # the line at the point's abscissa is Eq. 7 for the task's own parameters
        assert np.interp(np.log(x), np.log(eq7[:, 0]), np.log(eq7[:, 1])) == pytest.approx(
            math.log(pr.kappa_att(*args)), abs=1e-3
        )
        (u, ratio), = _lines(ax_ratio, "task:")[tid].get_xydata()  # fmt: skip
        assert ratio == pytest.approx(float(t["area_ratio"]))
        assert a * u ** (2 / 3) == pytest.approx(pr.area_ratio(*args[:3]))
    # sticky below the smallest κ_rep of the table's rows, the lighter band up to the largest
    rows = _row_kappa_rep(ds)
    shade = next(c for c in ax_kappa.collections if c.get_gid() == "sticky")
    assert shade.get_paths()[0].vertices[:, 1].max() == pytest.approx(min(rows), rel=1e-12)
    assert f"{min(rows):.3g}" in shade.get_label() and "(measured" in shade.get_label()
    band = next(c for c in ax_kappa.collections if c.get_gid() == "sticky_band")
    assert band.get_paths()[0].vertices[:, 1].max() == pytest.approx(max(rows), rel=1e-12)
    continuum = next(ln for ln in ax_kappa.lines if ln.get_gid() == "kappa_rep_continuum")
    assert continuum.get_linestyle() == "--" and set(continuum.get_ydata()) == {pr.KAPPA_REP}
    ax_given = figure4(ds, kappa_rep=pr.KAPPA_REP).axes[1]
    shade = next(c for c in ax_given.collections if c.get_gid() == "sticky")
    assert shade.get_paths()[0].vertices[:, 1].max() == pytest.approx(pr.KAPPA_REP)


def test_figure1_pixels_are_the_masks(study):
    out, _ = study
    maps = study_maps(out)
    assert [m.attrs.get("work_of_adhesion") for m in maps] == [None, 0.005, 0.05]
    fig = figure1(maps, target_area=0.02)
    images = [ax.images[0] for ax in fig.axes[: len(maps)]]
    orange = np.array([int(ORANGE[i : i + 2], 16) / 255 for i in (1, 3, 5)])
    for ds, im in zip(maps, images, strict=True):
        p = ds["pressure"].values
        k = np.argmin(np.abs((p > 0).mean(axis=(1, 2)) - 0.02))
        rep, att = p[k] > 0, p[k] < 0
        rgb = im.to_rgba(im.get_array())[..., :3].transpose(1, 0, 2)  # back to (x, y)
        np.testing.assert_allclose(rgb[rep], np.broadcast_to(orange, rgb[rep].shape))
        np.testing.assert_array_equal(rgb[att], 0.0)
        np.testing.assert_array_equal(rgb[~rep & ~att], 1.0)
        assert att.any() == ("work_of_adhesion" in ds.attrs) and rep.any()
        # the gap classification of the smoothed LJ wall gives the same sites
        if "range" in ds.attrs:
            r, a, _, _ = contact_masks(ds.drop_vars("pressure"), 0.02)
            np.testing.assert_array_equal(r, rep)
            np.testing.assert_array_equal(a, att)
    sub = figure1([maps[2]["pressure"].values[1]], labels=["x"], region=(60, 5, 8))
    cat = sub.axes[0].images[0].get_array().T
    expect = np.where(maps[2]["pressure"].values[1] > 0, 2, 0)
    expect[maps[2]["pressure"].values[1] < 0] = 1
    np.testing.assert_array_equal(cat, np.roll(expect, (-60, -5), (0, 1))[:8, :8])


def test_missing_input_is_named(study):
    _, ds = study
    with pytest.raises(ParameterError, match="kappa_fit"):
        figure2(ds.drop_vars("kappa_fit"))
    with pytest.raises(ParameterError, match="perimeter"):
        figure3(ds.drop_vars("perimeter"))
    with pytest.raises(ParameterError, match="kappa_att.*d_rep|d_rep.*kappa_att"):
        figure4(ds.drop_vars(["kappa_att", "d_rep"]))
    with pytest.raises(ParameterError, match="measured_rms_slope or rms_slope"):
        figure4(ds.drop_vars(["measured_rms_slope", "rms_slope"]))
    with pytest.raises(ParameterError, match="'task' dimension"):
        figure3({"load": [1.0]})
    with pytest.raises(ParameterError, match="no finished task matches"):
        figure2(ds, select={"hurst": 0.3})
    with pytest.raises(ParameterError, match="pressure and gap"):
        figure1([ds.isel(task=0)])
    with pytest.raises(ParameterError, match="at least one"):
        figure1([])


def test_save_figures_and_cli(study, tmp_path):
    out, ds = study
    written = save_figures(ds, tmp_path / "api", formats=("png",))
    assert sorted(written) == ["fig2_area_load", "fig3_collapse", "fig4_theory"]
    collected = tmp_path / "collected.nc"
    ds.to_netcdf(collected, engine="h5netcdf")
    r = CliRunner().invoke(main, ["figures", str(collected), "-o", str(tmp_path / "nc")])
    assert r.exit_code == 0, r.output
    for name in ("fig2_area_load", "fig3_collapse", "fig4_theory"):
        assert (tmp_path / "nc" / f"{name}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert (tmp_path / "nc" / f"{name}.pdf").read_bytes()[:5] == b"%PDF-"
    r = CliRunner().invoke(main, ["figures", str(out), "-o", str(tmp_path / "dir"),
                                  "--format", "png"])  # fmt: skip
    assert r.exit_code == 0, r.output
    assert (tmp_path / "dir" / "fig1_contact_maps.png").stat().st_size > 1000
    bad = tmp_path / "bad.nc"
    bad.write_text("not netcdf")
    r = CliRunner().invoke(main, ["figures", str(bad), "-o", str(tmp_path / "x")])
    assert r.exit_code == 2 and "nor a readable NetCDF" in r.output


def test_core_does_not_import_matplotlib():
    code = "import sys, roughcontact, roughcontact.plot; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
