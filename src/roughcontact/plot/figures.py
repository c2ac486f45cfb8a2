r"""The paper's figures from a collected study (Pastewka & Robbins, PNAS 111, 3298 (2014)).

Every function takes the dataset of :func:`roughcontact.studies.collect_study` (or its
NetCDF file opened with xarray) and returns a :class:`matplotlib.figure.Figure`; nothing
is drawn on screen and no global pyplot state is touched. Missing variables raise
:class:`~roughcontact.ParameterError` naming them. Areas and loads are per A0; lengths in
units of a0; loads normalised by E* (and h'rms where the paper does). Plotted curves carry
a ``gid``: ``"data:<task>"``, ``"fit:<task>"``, ``"task:<task>"``, ``"theory"``, ``"sticky"``.

* :func:`figure1` (in :mod:`.maps`): repulsive (orange) and attractive (black) sites.
* :func:`figure2`: :math:`A_{rep}/A_0` against :math:`N/(A_0 h'_{rms} E^*)` on the
  approach, one surface, several ℓa, with the fitted lines of slope κ (``kappa_fit``).
* :func:`figure3`: the collapse plots, Eq. 4 (:math:`N_{att}` against
  :math:`(w/\Delta r) A_{att}`), Eq. 2 (:math:`N_{rep}/(h'_{rms}E^*)` against
  :math:`A_{rep}`, line of slope 1/κ_rep) and :math:`P\,d_{rep}/\pi` against :math:`A_{rep}`.
* :func:`figure4`: measured :math:`A_{rep}/A_{att}` and :math:`\kappa_{att}` against
  Eqs. 6 and 7, sticky region (:math:`\kappa_{att} < \kappa_{rep}`) shaded.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .._validate import ParameterError, positive
from ..theory import pastewka_robbins as pr
from . import _data as D
from ._axes import decades, figure, log_axes, loglog
from .maps import figure1

__all__ = ["figure1", "figure2", "figure3", "figure4", "save_figures"]


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
        Upper end of the fit range in :math:`A_{rep}/A_0` (default: the study's
        ``analysis.fit_max_area``, else 0.05).

    Returns
    -------
    matplotlib.figure.Figure
        x: :math:`N/(A_0 h'_{rms} E^*)`, y: :math:`A_{rep}/A_0` on the approach branch. The
        fit of each task is the line of slope ``kappa_fit`` through the centroid of its
        points with :math:`0 < A_{rep}/A_0 \le` ``fit_max_area`` (the least-squares line of
        the path analysis), drawn over their load range.
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
    first = ds.isel(task=tasks[0])
    surface = ", ".join(f"{v} = {float(first[k]):g}" for k, v in D.LABELS.items() if k in ds.coords)
    fig = figure(6.4, 4.6)
    ax = fig.add_subplot()
    ax.axhline(0.0, color="0.85", lw=0.8, gid="axis")
    ax.axvline(0.0, color="0.85", lw=0.8, gid="axis")
    for i in sorted(tasks, key=lambda j: (np.nan_to_num(la[j], nan=-1.0), j)):
        task, colour = str(ds["task"].values[i]), style.colour(la[i])
        c = D.curves(ds, i, ("load", "repulsive_area"))
        x, y = c["load"] / scale[i], c["repulsive_area"]
        label = D.la_label(la[i]) + (f", κ = {kappa[i]:.3g}" if math.isfinite(kappa[i]) else "")
        ax.plot(x, y, "o-", ms=3, lw=0.8, color=colour, label=label, gid=f"data:{task}")
        in_fit = (y > 0) & (y <= top)
        if math.isfinite(kappa[i]) and in_fit.sum() >= 2:
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
    ax.set_xlabel("external load  N / (A0 h′rms E*)")
    ax.set_ylabel("true contact area  A_rep / A0")
    ax.set_title(
        f"Fig. 2: area–load relation on approach, lines: fits of slope κ\n{surface}", fontsize=9
    )
    ax.legend(fontsize=8, loc="upper left")
    return fig


def figure3(dataset, *, kappa_rep=pr.KAPPA_REP, d_rep="predicted"):
    r"""Fig. 3: the collapse of forces and areas over every task and contact area.

    Parameters
    ----------
    dataset : xarray.Dataset
        A collected study (per-step ``attractive_load``, ``attractive_area``,
        ``repulsive_load``, ``repulsive_area``, ``perimeter``, ``branch``; per task the
        adhesion length, ``range``, slope, ``contact_modulus``, d_rep, ``hurst``,
        ``short_cutoff``).
    kappa_rep : float
        κ_rep of the Eq. 2 line in panel (b) (the paper: 2).
    d_rep : {"predicted", "measured"}
        Panel (c) normalisation: :math:`4h'_{rms}/h''_{rms}` (the paper) or the measured
        :math:`\pi A_{rep}/P` at the target area.

    Returns
    -------
    matplotlib.figure.Figure
        (a) :math:`N_{att}/(A_0E^*)` against :math:`(\ell_a/\Delta r) A_{att}/A_0` with
        Eq. 4 (y = x); (b) :math:`N_{rep}/(A_0h'_{rms}E^*)` against :math:`A_{rep}/A_0`
        with Eq. 2 (y = x/κ_rep); (c) :math:`P d_{rep}/(\pi A_0)` against
        :math:`A_{rep}/A_0` with y = x. Converged approach states with positive values;
        symbols: :class:`~roughcontact.plot._data.TaskStyle`.
    """
    if d_rep not in D.D_REP:
        raise ParameterError(f"d_rep must be 'predicted' or 'measured', got {d_rep!r}")
    steps = ("attractive_load", "attractive_area", "repulsive_load", "repulsive_area", "perimeter")
    needs = ("branch", D.ADHESION, "range", D.SLOPE, "contact_modulus", D.D_REP[d_rep])
    D.require(dataset, (*steps, *needs, "hurst", "short_cutoff"), "Fig. 3")
    ds, kappa_rep = dataset, positive("kappa_rep", kappa_rep)
    la, dr = D.adhesion_length(ds), D.values(ds, "range")
    scale = D.values(ds, D.SLOPE) * D.values(ds, "contact_modulus")
    modulus, diameter = D.values(ds, "contact_modulus"), D.values(ds, D.D_REP[d_rep])
    style = D.TaskStyle(ds)
    fig = figure(13.0, 4.8)
    axes = fig.subplots(1, 3)
    data = [([], []), ([], []), ([], [])]
    for i in D.usable(ds):
        task, st = str(ds["task"].values[i]), style(i)
        c = D.curves(ds, i, steps, converged_only=True)
        panels = [
            (la[i] / dr[i] * c["attractive_area"], c["attractive_load"] / modulus[i]),
            (c["repulsive_area"], c["repulsive_load"] / scale[i]),
            (c["repulsive_area"], c["perimeter"] * diameter[i] / math.pi),
        ]
        for k, (x, y) in enumerate(panels):
            ok = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
            if ok.any():
                axes[k].plot(x[ok], y[ok], gid=f"task:{task}", **st)
                data[k][0].append(x[ok])
                data[k][1].append(y[ok])
    loglog(axes[0], *data[0], label="Eq. 4: N_att = (w/Δr) A_att")
    loglog(
        axes[1],
        *data[1],
        slope=1.0 / kappa_rep,
        label=f"Eq. 2: N_rep = h′rms E* A_rep / κ_rep, κ_rep = {kappa_rep:g}",
    )
    loglog(axes[2], *data[2], label="A_rep = P d_rep / π")
    which = "4h′rms/h″rms" if d_rep == "predicted" else "πA_rep/P at the target area"
    labels = [
        ("(ℓa/Δr) A_att / A0", "attractive force  N_att / (A0 E*)"),
        ("repulsive area  A_rep / A0", "repulsive force  N_rep / (A0 h′rms E*)"),
        ("repulsive area  A_rep / A0", f"P d_rep / (π A0),  d_rep = {which}"),
    ]
    for ax, (xl, yl), t in zip(
        axes, labels, ("(a) Eq. 4", "(b) Eq. 2", "(c) perimeter"), strict=True
    ):
        ax.set_xlabel(xl)
        ax.set_ylabel(yl)
        ax.set_title(t, fontsize=10)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="upper left")
    fig.legend(handles=style.legend_handles(), loc="outside right upper", fontsize=7)
    return fig


def figure4(dataset, *, kappa_rep=pr.KAPPA_REP, d_rep="measured"):
    r"""Fig. 4: measured :math:`A_{rep}/A_{att}` and :math:`\kappa_{att}` against Eqs. 6-7.

    Parameters
    ----------
    dataset : xarray.Dataset
        A collected study (per task ``area_ratio``, ``kappa_att``, d_rep, ``range``, the
        adhesion length, slope, ``hurst``, ``short_cutoff``).
    kappa_rep : float
        κ_rep bounding the shaded sticky region :math:`\kappa_{att} < \kappa_{rep}` (2).
    d_rep : {"measured", "predicted"}
        The d_rep inserted in Eqs. 6-7: measured :math:`\pi A_{rep}/P` or
        :math:`4h'_{rms}/h''_{rms}`.

    Returns
    -------
    matplotlib.figure.Figure
        (a) :math:`A_{rep}/A_{att}` against :math:`u = h'_{rms} d_{rep}/(\pi\Delta r)`, the
        line is Eq. 6, :math:`(16/9\pi)^{1/3} u^{2/3}`; (b) :math:`\kappa_{att}` against
        :math:`X = (h'_{rms}\Delta r/\ell_a)\,u^{2/3}`, the line is Eq. 7,
        :math:`(16/9\pi)^{1/3} X`; shaded: :math:`\kappa_{att} < \kappa_{rep}`. Tasks
        without adhesion or a finite measured value are left out.
    """
    if d_rep not in D.D_REP:
        raise ParameterError(f"d_rep must be 'measured' or 'predicted', got {d_rep!r}")
    needs = ("area_ratio", "kappa_att", D.D_REP[d_rep], "range", D.ADHESION, D.SLOPE)
    D.require(dataset, (*needs, "hurst", "short_cutoff"), "Fig. 4")
    ds, kr = dataset, positive("kappa_rep", kappa_rep)
    slope, dr, la = D.values(ds, D.SLOPE), D.values(ds, "range"), D.adhesion_length(ds)
    diameter = D.values(ds, D.D_REP[d_rep])
    u = slope * diameter / (math.pi * dr)
    X = slope * dr / la * u ** (2.0 / 3.0)
    measured = (D.values(ds, "area_ratio"), D.values(ds, "kappa_att"))
    style = D.TaskStyle(ds)
    fig = figure(11.5, 4.8)
    axes = fig.subplots(1, 2)
    points = [([], []), ([], [])]
    for i in D.usable(ds):
        task = str(ds["task"].values[i])
        for k, x in enumerate((u[i], X[i])):
            y = measured[k][i]
            if all(math.isfinite(v) and v > 0 for v in (x, y, la[i])):
                axes[k].plot([x], [y], gid=f"task:{task}", **style(i))
                points[k][0].append(x)
                points[k][1].append(y)
    for k, ax in enumerate(axes):
        xs, ys = (np.asarray(v, dtype=float) for v in points[k])
        if xs.size == 0:
            note = "no adhesive task with a finite value"
            ax.text(0.5, 0.5, note, transform=ax.transAxes, ha="center", color="0.5")
            xs, ys = np.array([0.1, 10.0]), np.array([kr, kr])
        xlim = decades(xs)
        grid = np.geomspace(*xlim, 100)
        if k == 0:  # Eq. 6 with h'rms = Δr = 1: u = d/π
            theory, label = pr.area_ratio(1.0, math.pi * grid, 1.0), "Eq. 6"
        else:  # Eq. 7 with h'rms = Δr = ℓa = 1: X = (d/π)^(2/3)
            theory, label = pr.kappa_att(1.0, math.pi * grid**1.5, 1.0, 1.0), "Eq. 7"
        ylim = decades(ys, theory, [kr] if k else [])
        log_axes(ax, xlim, ylim)
        ax.plot(grid, theory, "-", color="0.3", lw=1.2, gid="theory", label=label, zorder=0)
        if k == 1:
            ax.fill_between(
                grid,
                ylim[0],
                kr,
                color="tab:orange",
                alpha=0.15,
                lw=0,
                gid="sticky",
                label=f"sticky: κ_att < κ_rep = {kr:g}",
            )
        ax.legend(fontsize=8, loc="upper left")
    src = "measured πA_rep/P" if d_rep == "measured" else "4h′rms/h″rms"
    axes[0].set_xlabel(f"h′rms d_rep / (π Δr),  d_rep = {src}")
    axes[0].set_ylabel("A_rep / A_att (measured)")
    axes[0].set_title("(a) area ratio against Eq. 6", fontsize=10)
    axes[1].set_xlabel("(h′rms Δr / ℓa) · (h′rms d_rep / (π Δr))^(2/3)")
    axes[1].set_ylabel("κ_att = h′rms E* A_rep / N_att (measured)")
    axes[1].set_title("(b) κ_att against Eq. 7", fontsize=10)
    fig.legend(handles=style.legend_handles(), loc="outside right upper", fontsize=7)
    return fig


FIGURES = {"fig2_area_load": figure2, "fig3_collapse": figure3, "fig4_theory": figure4}


def save_figures(dataset, out_dir, formats=("png", "pdf"), *, maps=None, dpi=150, **fig1):
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
        Resolution of raster formats.
    **fig1
        Passed to :func:`figure1` (``target_area``, ``labels``, ``region``).

    Returns
    -------
    dict
        Figure name -> list of written paths.
    """
    if not hasattr(dataset, "variables"):
        import xarray as xr

        try:
            dataset = xr.load_dataset(dataset, engine="h5netcdf")
        except (OSError, ValueError) as err:
            raise ParameterError(f"{str(dataset)!r} is not a readable NetCDF file: {err}") from None
    formats = tuple(formats)
    if not formats or any(not isinstance(f, str) or not f.isalnum() for f in formats):
        raise ParameterError(
            f"formats must be a non-empty list like ('png', 'pdf'), got {formats!r}"
        )
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    made = {name: make(dataset) for name, make in FIGURES.items()}
    if maps:
        made = {"fig1_contact_maps": figure1(maps, **fig1), **made}
    written = {}
    for name, fig in made.items():
        written[name] = []
        for fmt in formats:
            path = out / f"{name}.{fmt}"
            fig.savefig(path, format=fmt, dpi=dpi, bbox_inches="tight")
            written[name].append(path)
    return written
