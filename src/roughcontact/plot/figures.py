r"""The paper's figures from a collected study (Pastewka & Robbins, PNAS 111, 3298 (2014)).

Every function takes the dataset of :func:`roughcontact.studies.collect_study` (or its
NetCDF file opened with xarray) and returns a :class:`matplotlib.figure.Figure`; nothing
is drawn on screen and no global pyplot state is touched. Missing variables raise
:class:`~roughcontact.ParameterError` naming them. Areas and loads are per A0; lengths in
units of a0; loads normalised by E* (and h'rms where the paper does). Plotted curves carry
a ``gid``: ``"data:<task>"``, ``"fit:<task>"``, ``"task:<task>"``, ``"theory"``, ``"sticky"``,
and the κ_rep reference lines ``"kappa_rep_continuum"`` (κ_rep = 2, dashed) and
``"kappa_rep_hard_wall"`` (dotted). Symbols are typeset with matplotlib mathtext; legends
sit outside the axes; the symbol key lists only the parameters that vary among the drawn
tasks, the constant ones are in the title.

* :func:`figure1` (in :mod:`.maps`): repulsive (orange) and attractive (black) sites.
* :func:`figure2`: :math:`A_{rep}/A_0` against :math:`N/(A_0 h'_{rms} E^*)` on the
  approach, one surface, several ℓa, with the fitted lines of slope
  :math:`\kappa_{fit}` (``kappa_fit``; not ``kappa``, the ratio
  :math:`h'_{rms}E^*A_{rep}/N` at the target area).
* :func:`figure3`: the collapse plots, Eq. 4 (:math:`N_{att}` against
  :math:`(w/\Delta r) A_{att}`), Eq. 2 (:math:`N_{rep}/(h'_{rms}E^*)` against
  :math:`A_{rep}`, line of slope 1/κ_rep, κ_rep measured) and :math:`P\,d_{rep}/\pi`
  against :math:`A_{rep}`.
* :func:`figure4`: measured :math:`A_{rep}/A_{att}` and :math:`\kappa_{att}` against
  Eqs. 6 and 7, sticky region (:math:`\kappa_{att} < \kappa_{rep}`, κ_rep measured)
  shaded.

The measured κ_rep is that of each row of the study's table (tasks equal but for the seed,
:math:`1/\langle 1/\kappa_{rep}\rangle` over their seeds: 1/κ adds up over seeds; κ itself
is never averaged), never one value pooled over different parameters.
"""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np

from .._io import write_bytes_atomic
from .._validate import DPI, ParameterError
from ..theory import pastewka_robbins as pr
from . import _codes as C
from . import _data as D
from .axes import decades, figure, log_axes, loglog
from .maps import figure1

__all__ = ["figure1", "figure2", "figure3", "figure4", "save_figures"]

#: Typeset symbols of the axis labels and legends (matplotlib mathtext).
AREA = r"$A_\mathrm{rep}/A_0$"
LOAD = r"$N/(A_0 h'_\mathrm{rms} E^*)$"
KAPPA_FIT = r"\kappa_\mathrm{fit}"
KAPPA_REP = r"\kappa_\mathrm{rep}"
D_REP_TEXT = {
    "measured": r"$d_\mathrm{rep} = \pi A_\mathrm{rep}/P$ (measured)",
    "predicted": r"$d_\mathrm{rep} = 4h'_\mathrm{rms}/h''_\mathrm{rms}$",
}
HOW = {"measured": "measured", "given": "given", "continuum": "continuum, none measured"}
LEGEND = {"fontsize": 8, "frameon": False}


def _kappa_rep_text(value, how) -> str:
    return rf"${KAPPA_REP} = {value:.3g}$ ({HOW[how]})"


def _key(fig, style, tasks):
    """The symbol key (varied parameters only) outside the axes, right; the caption."""
    handles = style.legend_handles(tasks)
    if handles:
        fig.legend(handles=handles, loc="outside right upper", title="symbols", **LEGEND)
    return style.caption(tasks)


def figure2(dataset, *, select=None, fit_max_area=None):
    r"""Fig. 2: true contact area against load for several ℓa, with the linear fits.

    Parameters
    ----------
    dataset : xarray.Dataset
        A collected study (needs ``load``, ``repulsive_area``, ``branch``, ``kappa_fit``,
        ``rms_slope`` (the measured ``measured_rms_slope`` is preferred), ``contact_modulus``).
    select : dict, optional
        Parameter values (coordinates on ``task``) of the tasks to show. Default: the
        surface, substrate and seed of the first finished task, every interaction.
    fit_max_area : float, optional
        Upper end of the fit range in :math:`A_{rep}/A_0` (dimensionless; default: the
        study's ``analysis.fit_max_area``, else 0.05).

    Returns
    -------
    matplotlib.figure.Figure
        x: :math:`N/(A_0 h'_{rms} E^*)`, y: :math:`A_{rep}/A_0` (both dimensionless) on
        the approach branch. The fit of each task is the line of slope ``kappa_fit``
        through the centroid of its points with :math:`0 < A_{rep}/A_0 \le`
        ``fit_max_area`` (the least-squares line of the path analysis), drawn over their
        load range. The legend (outside the axes, right) gives ℓa/a0 and the fitted slope
        as :math:`\kappa_{fit}`, never as κ (which is the ratio at the target area); the
        title names the surface (the values shared by the shown tasks). Colours as in
        the paper: red sticky (κ < 0 at the target area), blue adhesive with κ > 0,
        black non-adhesive (shades darker with growing ℓa).
    """
    D.require(
        dataset,
        ("load", "repulsive_area", "branch", "kappa_fit", D.SLOPE, "contact_modulus", D.ADHESION),
        "Fig. 2",
    )
    ds, tasks = dataset, D.select_tasks(dataset, select)
    scale = D.values(ds, D.SLOPE) * D.values(ds, "contact_modulus")
    kappa, top = D.values(ds, "kappa_fit"), D.fit_max_area(ds, fit_max_area)
    style = D.TaskStyle(ds)
    la = style.la
    colours = C.sticky_colours(ds, tasks, la)
    surface = []
    for key in D.LABELS:
        if key in ds.coords:
            vals = list(dict.fromkeys(f"{float(ds[key].values[i]):g}" for i in tasks))
            surface.append(f"${D.SYMBOLS[key]} = {', '.join(vals)}$")
    fig = figure(8.0, 4.6)
    ax = fig.add_subplot()
    ax.axhline(0.0, color="0.85", lw=0.8, gid="axis")
    ax.axvline(0.0, color="0.85", lw=0.8, gid="axis")
    fitted = False
    for i in sorted(tasks, key=lambda j: (np.nan_to_num(la[j], nan=-1.0), j)):
        task, (colour, verdict) = str(ds["task"].values[i]), colours[i]
        c = D.curves(ds, i, ("load", "repulsive_area"))
        x, y = c["load"] / scale[i], c["repulsive_area"]
        label = D.la_label(la[i]) + (f" ({verdict})" if verdict else "")
        if math.isfinite(kappa[i]):
            label += rf", ${KAPPA_FIT} = {kappa[i]:.3g}$"
        ax.plot(x, y, "o-", ms=3, lw=0.8, color=colour, label=label, gid=f"data:{task}")
        in_fit = (y > 0) & (y <= top)
        if math.isfinite(kappa[i]) and in_fit.sum() >= 2:
            fitted = True
            xf = np.array([x[in_fit].min(), x[in_fit].max()])
            intercept = float(np.mean(y[in_fit] - kappa[i] * x[in_fit]))
            ax.plot(
                xf,
                kappa[i] * xf + intercept,
                "-",
                lw=2.5,
                alpha=0.5,
                color=colour,
                gid=f"fit:{task}",
            )
    ax.set_xlabel(f"external load  {LOAD}")
    ax.set_ylabel(f"true contact area  {AREA}")
    ax.set_title(
        f"Fig. 2: area–load relation on approach, lines: fits of slope ${KAPPA_FIT}$\n"
        + ", ".join(surface),
        fontsize=9,
    )
    handles, labels = ax.get_legend_handles_labels()
    if fitted:
        from matplotlib.lines import Line2D

        handles.append(Line2D([], [], lw=2.5, alpha=0.5, color="0.4"))
        labels.append(rf"fit, slope ${KAPPA_FIT}$, over $0 < A_\mathrm{{rep}}/A_0 \leq {top:g}$")
    fig.legend(handles, labels, loc="outside right upper", **LEGEND)
    return fig


def _legend_below(fig, axes):
    """One legend of every panel's lines and shadings, below the panels (covers no data)."""
    handles, texts = [], []
    for ax in axes:
        h, t = ax.get_legend_handles_labels()
        handles += h
        texts += t
    fig.legend(handles, texts, loc="outside lower center", ncols=2, **LEGEND)


def figure3(dataset, *, kappa_rep=None, d_rep="predicted", min_area_per_cutoff=None):
    r"""Fig. 3: the collapse of forces and areas over every task and contact area.

    Parameters
    ----------
    dataset : xarray.Dataset
        A collected study (per-step ``attractive_load``, ``attractive_area``,
        ``repulsive_load``, ``repulsive_area``, ``perimeter``, ``branch``; per task the
        adhesion length, ``range``, slope, ``contact_modulus``, d_rep, ``hurst``,
        ``short_cutoff``; ``kappa_rep`` and ``kappa_rep_hard_wall`` when present).
    kappa_rep : float, optional
        κ_rep (dimensionless) of the Eq. 2 line in panel (b). Default ``None``: the
        measured κ_rep of each row of the study's table
        (:func:`~roughcontact.plot._data.kappa_rep_levels`): one line when there is one
        row, else the band between the smallest and the largest (``gid="theory_band"``);
        the continuum 2 when none is measured.
    d_rep : {"predicted", "measured"}
        Panel (c) normalisation: :math:`4h'_{rms}/h''_{rms}` (the paper) or the measured
        :math:`\pi A_{rep}/P` at the target area (lengths in a0).
    min_area_per_cutoff : float, optional
        The paper's rule (Methods): only states with :math:`A_{rep}/\lambda_s^2 \ge` this
        (e.g. 10, "a statistical number of contacting asperities") are drawn with their
        symbols; the earlier ones as small grey points (``gid="few:<task>"``). Default
        ``None``: every state with its symbol.

    Returns
    -------
    matplotlib.figure.Figure
        (a) :math:`N_{att}/(A_0E^*)` against :math:`(\ell_a/\Delta r) A_{att}/A_0` with
        Eq. 4 (y = x); (b) :math:`N_{rep}/(A_0h'_{rms}E^*)` against :math:`A_{rep}/A_0`
        with Eq. 2 (y = x/κ_rep, ``gid="theory"``), the continuum y = x/2 dashed
        (``"kappa_rep_continuum"``) and, when the dataset has it, the hard-wall reference
        ``kappa_rep_hard_wall`` dotted (``"kappa_rep_hard_wall"``); (c)
        :math:`P d_{rep}/(\pi A_0)` against :math:`A_{rep}/A_0` with y = x. Converged
        approach states with positive values; symbols:
        :class:`~roughcontact.plot._data.TaskStyle`. Legends below (lines) and right
        (symbols, varied parameters only) of the axes; constant parameters in the title.
    """
    if d_rep not in D.D_REP:
        raise ParameterError(f"d_rep must be 'predicted' or 'measured', got {d_rep!r}")
    steps = ("attractive_load", "attractive_area", "repulsive_load", "repulsive_area", "perimeter")
    needs = ("branch", D.ADHESION, "range", D.SLOPE, "contact_modulus", D.D_REP[d_rep])
    D.require(dataset, (*steps, *needs, "hurst", "short_cutoff"), "Fig. 3")
    ds = dataset
    levels, how = D.kappa_rep_levels(ds, kappa_rep)
    la, dr = D.adhesion_length(ds), D.values(ds, "range")
    scale = D.values(ds, D.SLOPE) * D.values(ds, "contact_modulus")
    modulus, diameter = D.values(ds, "contact_modulus"), D.values(ds, D.D_REP[d_rep])
    factor = D.area_per_cutoff(ds)
    style = D.TaskStyle(ds)
    fig = figure(13.0, 5.4)
    axes = fig.subplots(1, 3)
    data = [([], []), ([], []), ([], [])]
    drawn, greyed = [], False
    for i in D.usable(ds):
        task, st = str(ds["task"].values[i]), style(i)
        c = D.curves(ds, i, steps, converged_only=True)
        few = np.zeros(c["repulsive_area"].shape, dtype=bool)
        if min_area_per_cutoff is not None and math.isfinite(factor[i]):
            few = c["repulsive_area"] * factor[i] < min_area_per_cutoff
        panels = [
            (la[i] / dr[i] * c["attractive_area"], c["attractive_load"] / modulus[i]),
            (c["repulsive_area"], c["repulsive_load"] / scale[i]),
            (c["repulsive_area"], c["perimeter"] * diameter[i] / math.pi),
        ]
        for k, (x, y) in enumerate(panels):
            ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
            if (ok & ~few).any():
                axes[k].plot(x[ok & ~few], y[ok & ~few], gid=f"task:{task}", **st)
                drawn.append(i)
            if (ok & few).any():
                label = None
                if not greyed:
                    label = (
                        rf"$A_\mathrm{{rep}}/\lambda_s^2 < {min_area_per_cutoff:g}$ (first "
                        "contacts; left out by the paper)"
                    )
                    greyed = True
                axes[k].plot(x[ok & few], y[ok & few], ".", ms=2.5, color="0.7",
                             gid=f"few:{task}", label=label, zorder=0.8)  # fmt: skip
            data[k][0].append(x[ok])
            data[k][1].append(y[ok])
    loglog(axes[0], *data[0], label=r"(a) Eq. 4: $N_\mathrm{att} = (w/\Delta r)\,A_\mathrm{att}$")
    refs = C.reference_lines(ds)
    eq2 = r"(b) Eq. 2: $N_\mathrm{rep} = h'_\mathrm{rms} E^* A_\mathrm{rep}/\kappa_\mathrm{rep}$"
    one = len(levels) == 1
    xlim = loglog(
        axes[1],
        *data[1],
        slope=1.0 / levels[0] if one else None,
        label=f"{eq2}, {_kappa_rep_text(levels[0], how)}" if one else None,
        also=[1.0 / v for v in levels] + [1.0 / r[1] for r in refs],
    )
    if xlim is not None:
        line = np.geomspace(*xlim, 50)
        if not one:
            axes[1].fill_between(
                line,
                line / levels[-1],
                line / levels[0],
                color="0.55",
                alpha=0.35,
                lw=0,
                zorder=0,
                gid="theory_band",
                label=f"{eq2}, ${KAPPA_REP} = {D.levels_text(levels)}$ (measured, the "
                "table's rows)",
            )
        for gid, value, label, kw in refs:
            text = f"(b) {label}" if label else None
            axes[1].plot(line, line / value, gid=gid, label=text, zorder=0.5, **kw)
    loglog(axes[2], *data[2], label=r"(c) $A_\mathrm{rep} = P\,d_\mathrm{rep}/\pi$")
    labels = [
        (
            r"$(\ell_a/\Delta r)\,A_\mathrm{att}/A_0$",
            r"attractive force  $N_\mathrm{att}/(A_0 E^*)$",
        ),
        (f"repulsive area  {AREA}", r"repulsive force  $N_\mathrm{rep}/(A_0 h'_\mathrm{rms} E^*)$"),
        (f"repulsive area  {AREA}", r"$P\,d_\mathrm{rep}/(\pi A_0)$"),
    ]
    titles = ("(a) Eq. 4", "(b) Eq. 2", f"(c) perimeter, {D_REP_TEXT[d_rep]}")
    for ax, (xl, yl), t in zip(axes, labels, titles, strict=True):
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_title(t, fontsize=10)
    _legend_below(fig, axes)
    caption = _key(fig, style, drawn)
    title = "Fig. 3: collapse of forces and areas, converged approach states"
    fig.suptitle(title + (f"\n{caption}" if caption else ""), fontsize=10)
    return fig


def figure4(dataset, *, kappa_rep=None, d_rep="measured"):
    r"""Fig. 4: measured :math:`A_{rep}/A_{att}` and :math:`\kappa_{att}` against Eqs. 6-7.

    Parameters
    ----------
    dataset : xarray.Dataset
        A collected study (per task ``area_ratio``, ``kappa_att``, d_rep, ``range``, the
        adhesion length, slope, ``hurst``, ``short_cutoff``; ``kappa_rep`` and
        ``kappa_rep_hard_wall`` when present).
    kappa_rep : float, optional
        κ_rep (dimensionless) bounding the shaded sticky region
        :math:`\kappa_{att} < \kappa_{rep}`. Default ``None``: the measured κ_rep of the
        rows of the study's table (:func:`~roughcontact.plot._data.kappa_rep_levels`):
        shaded below the smallest (``gid="sticky"``), lighter up to the largest
        (``gid="sticky_band"``, when the rows differ); the continuum 2 when none is
        measured; a float overrides it.
    d_rep : {"measured", "predicted"}
        The d_rep inserted in Eqs. 6-7: measured :math:`\pi A_{rep}/P` or
        :math:`4h'_{rms}/h''_{rms}` (lengths in a0).

    Returns
    -------
    matplotlib.figure.Figure
        (a) :math:`A_{rep}/A_{att}` against :math:`u = h'_{rms} d_{rep}/(\pi\Delta r)`, the
        line is Eq. 6, :math:`(16/9\pi)^{1/3} u^{2/3}`; (b) :math:`\kappa_{att}` against
        :math:`X = (h'_{rms}\Delta r/\ell_a)\,u^{2/3}`, the line is Eq. 7,
        :math:`(16/9\pi)^{1/3} X`; shaded (``gid="sticky"``):
        :math:`\kappa_{att} < \kappa_{rep}`; dashed (``"kappa_rep_continuum"``): the
        continuum hard-wall κ_rep = 2; dotted (``"kappa_rep_hard_wall"``, only when the
        dataset has finite ``kappa_rep_hard_wall``): its :math:`1/\langle 1/x\rangle`.
        All quantities dimensionless. Tasks without adhesion or a finite measured value
        are left out. Legends below (lines) and right (symbols, varied parameters only)
        of the axes; constant parameters in the title.
    """
    if d_rep not in D.D_REP:
        raise ParameterError(f"d_rep must be 'measured' or 'predicted', got {d_rep!r}")
    needs = ("area_ratio", "kappa_att", D.D_REP[d_rep], "range", D.ADHESION, D.SLOPE)
    D.require(dataset, (*needs, "hurst", "short_cutoff"), "Fig. 4")
    ds = dataset
    levels, how = D.kappa_rep_levels(ds, kappa_rep)
    kr = levels[0]
    refs = C.reference_lines(ds)
    slope, dr, la = D.values(ds, D.SLOPE), D.values(ds, "range"), D.adhesion_length(ds)
    diameter = D.values(ds, D.D_REP[d_rep])
    u = slope * diameter / (math.pi * dr)
    X = slope * dr / la * u ** (2.0 / 3.0)
    measured = (D.values(ds, "area_ratio"), D.values(ds, "kappa_att"))
    style = D.TaskStyle(ds)
    fig = figure(11.5, 5.6)
    axes = fig.subplots(1, 2)
    points = [([], []), ([], [])]
    drawn = []
    for i in D.usable(ds):
        task = str(ds["task"].values[i])
        for k, x in enumerate((u[i], X[i])):
            y = measured[k][i]
            if all(math.isfinite(v) and v > 0 for v in (x, y, la[i])):
                axes[k].plot([x], [y], gid=f"task:{task}", **style(i))
                points[k][0].append(x)
                points[k][1].append(y)
                drawn.append(i)
    lines_at = [*levels, *(r[1] for r in refs)]
    for k, ax in enumerate(axes):
        xs, ys = (np.asarray(v, dtype=float) for v in points[k])
        if xs.size == 0:
            note = "no adhesive task with a finite value"
            ax.text(0.5, 0.5, note, transform=ax.transAxes, ha="center", color="0.5")
            xs, ys = np.array([0.1, 10.0]), np.array([kr, kr])
        xlim = decades(xs)
        grid = np.geomspace(*xlim, 100)
        if k == 0:  # Eq. 6 with h'rms = Δr = 1: u = d/π
            theory = pr.area_ratio(1.0, math.pi * grid, 1.0)
            label = r"(a) Eq. 6: $A_\mathrm{rep}/A_\mathrm{att} = (16/9\pi)^{1/3}\,u^{2/3}$"
        else:  # Eq. 7 with h'rms = Δr = ℓa = 1: X = (d/π)^(2/3)
            theory = pr.kappa_att(1.0, math.pi * grid**1.5, 1.0, 1.0)
            label = r"(b) Eq. 7: $\kappa_\mathrm{att} = (16/9\pi)^{1/3}\,X$"
        ylim = decades(ys, theory, lines_at if k else [])
        log_axes(ax, xlim, ylim)
        ax.plot(grid, theory, "-", color="0.3", lw=1.2, gid="theory", label=label, zorder=0)
        if k == 1:
            # sticky below the smallest κ_rep of the table's rows; between the smallest
            # and the largest the boundary depends on the row (lighter band)
            ax.fill_between(
                grid,
                ylim[0],
                kr,
                color="tab:orange",
                alpha=0.15,
                lw=0,
                gid="sticky",
                label=r"(b) sticky: $\kappa_\mathrm{att} < \kappa_\mathrm{rep} = "
                + f"{kr:.3g}$ ({HOW[how]}"
                + (", the smallest of the table's rows)" if len(levels) > 1 else ")"),
            )
            if len(levels) > 1:
                ax.fill_between(
                    grid,
                    kr,
                    levels[-1],
                    color="tab:orange",
                    alpha=0.07,
                    lw=0,
                    gid="sticky_band",
                    label=r"(b) sticky only below its own row's $\kappa_\mathrm{rep}$ "
                    + f"(${KAPPA_REP} = {D.levels_text(levels)}$, measured per row)",
                )
            for gid, value, text, kw in refs:
                ax.axhline(value, gid=gid, label=f"(b) {text}" if text else None, zorder=0.5, **kw)
    axes[0].set_xlabel(
        rf"$u = h'_\mathrm{{rms}} d_\mathrm{{rep}}/(\pi\,\Delta r)$,  {D_REP_TEXT[d_rep]}"
    )
    axes[0].set_ylabel(r"$A_\mathrm{rep}/A_\mathrm{att}$ (measured)")
    axes[0].set_title("(a) area ratio against Eq. 6", fontsize=10)
    axes[1].set_xlabel(r"$X = (h'_\mathrm{rms}\,\Delta r/\ell_a)\,u^{2/3}$")
    axes[1].set_ylabel(
        r"$\kappa_\mathrm{att} = h'_\mathrm{rms} E^* A_\mathrm{rep}/N_\mathrm{att}$ (measured)"
    )
    axes[1].set_title(r"(b) $\kappa_\mathrm{att}$ against Eq. 7", fontsize=10)
    _legend_below(fig, axes)
    caption = _key(fig, style, drawn)
    title = (
        r"Fig. 4: measured $A_\mathrm{rep}/A_\mathrm{att}$ and $\kappa_\mathrm{att}$"
        " against Eqs. 6 and 7"
    )
    fig.suptitle(title + (f"\n{caption}" if caption else ""), fontsize=10)
    return fig


FIGURES = {"fig2_area_load": figure2, "fig3_collapse": figure3, "fig4_theory": figure4}


def save_figures(
    dataset,
    out_dir,
    formats=("png", "pdf"),
    *,
    maps=None,
    dpi=150,
    min_area_per_cutoff=None,
    **fig1,
):
    """Write Figs. 2-4 (and Fig. 1 when ``maps`` are given) in every format.

    Parameters
    ----------
    dataset : xarray.Dataset or path-like
        A collected study or its NetCDF file.
    out_dir : path-like
        Directory for the files (created): ``fig1_contact_maps.<fmt>``,
        ``fig2_area_load.<fmt>``, ``fig3_collapse.<fmt>``, ``fig4_theory.<fmt>``.
    formats : sequence of str
        File formats matplotlib can write (``png``, ``pdf``, ``svg``, ...).
    maps : sequence, optional
        Path datasets (or files, or pressure arrays) for :func:`figure1`; without them
        Fig. 1 is not made (a collected dataset holds no contact maps).
    dpi : int
        Resolution of raster formats (dots per inch, an integer in [10, 2400]).
    min_area_per_cutoff : float, optional
        Passed to :func:`figure3` (the paper's rule: 10).
    **fig1
        Passed to :func:`figure1` (``target_area``, ``labels``, ``region``).

    Returns
    -------
    dict
        Figure name -> list of written paths.
    """
    if not hasattr(dataset, "variables"):
        from .._io import read_netcdf

        refusal = f"{str(dataset)!r} is not a readable NetCDF file"
        dataset = read_netcdf(dataset, refusal=refusal)
    dpi = DPI.check("dpi", dpi)  # before any work: matplotlib fails late on a huge canvas
    formats = tuple(formats)
    if not formats or any(not isinstance(f, str) or not f.isalnum() for f in formats):
        raise ParameterError(
            f"formats must be a non-empty list like ('png', 'pdf'), got {formats!r}"
        )
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    options = {"fig3_collapse": {"min_area_per_cutoff": min_area_per_cutoff}}
    made = {name: make(dataset, **options.get(name, {})) for name, make in FIGURES.items()}
    if maps:
        made = {"fig1_contact_maps": figure1(maps, **fig1), **made}
    written = {}
    for name, fig in made.items():
        written[name] = []
        for fmt in formats:  # rendered in memory, renamed into place: no half-written file
            buf = io.BytesIO()
            fig.savefig(buf, format=fmt, dpi=dpi, bbox_inches="tight")
            written[name].append(write_bytes_atomic(out / f"{name}.{fmt}", buf.getvalue()))
    return written
