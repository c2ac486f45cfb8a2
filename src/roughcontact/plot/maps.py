"""Fig. 1: maps of the repulsive (orange) and attractive (black) sites at a fixed A_rep.

A site is repulsive where its force pushes the surfaces apart (p > 0) and attractive
where it pulls them together (p < 0), the classification of every roughcontact law
(``classify``). Without a pressure field the gap is used: repulsive g < a0, attractive
a0 < g < a0 + Δr (the smoothed 9-3 Lennard-Jones wall; a0 the equilibrium distance).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .._backend import to_numpy
from .._validate import ParameterError
from ._data import SURFACE_KEYS, la_label

__all__ = ["ORANGE", "contact_masks", "figure1", "study_maps"]

ORANGE = "#f28e1c"  # repulsive sites
COLOURS = ("white", "black", ORANGE)  # category 0 none, 1 attractive, 2 repulsive


def contact_masks(item, target_area=0.02):
    """``(repulsive, attractive, label, pixel_size)`` of one map.

    ``item`` is a path dataset (with ``pressure`` or ``gap`` on ``field_step, x, y``), its
    NetCDF file, or a 2D pressure array. Of a path's stored field steps the one whose
    repulsive area is closest to ``target_area`` (per A0) is used. ``label`` is the
    mathtext ``$\\ell_a/a_0 = ...$`` of the path's attributes (``"non-adhesive"`` without
    adhesion, ``""`` for an array); ``pixel_size`` is a0 in the path's length unit.
    """
    if isinstance(item, (str, Path)):
        from ..pathdata import read_path

        item = read_path(item)
    if not hasattr(item, "variables"):
        p = np.asarray(to_numpy(item), dtype=float)  # e.g. a result's pressure on a GPU
        if p.ndim != 2:
            raise ParameterError(
                f"Fig. 1: a contact map must be a 2D pressure array, got shape {p.shape}"
            )
        return p > 0, p < 0, "", 1.0
    ds, attrs = item, item.attrs
    if "pressure" in ds.variables:
        field = np.asarray(ds["pressure"].values, dtype=float)
        rep, att = field > 0, field < 0
    elif "gap" in ds.variables:
        missing = [k for k in ("equilibrium_distance", "range") if k not in attrs]
        if missing:
            raise ParameterError(
                "Fig. 1: classifying sites by the gap needs the path "
                f"attributes {', '.join(missing)} (or a pressure field)"
            )
        g, a0, dr = (
            np.asarray(ds["gap"].values, dtype=float),
            attrs["equilibrium_distance"],
            attrs["range"],
        )
        rep, att = g < a0, (g > a0) & (g < a0 + dr)
    else:
        raise ParameterError(
            "Fig. 1: the path dataset lacks pressure and gap fields; run the path with "
            "fields_at=[...] (a study: [output] fields_at = [...])"
        )
    if rep.ndim == 2:
        rep, att = rep[None], att[None]
    k = int(np.argmin(np.abs(rep.mean(axis=(1, 2)) - target_area)))
    w, modulus = attrs.get("work_of_adhesion", math.nan), attrs.get("contact_modulus", 1.0)
    a0 = float(attrs.get("pixel_size", 1.0))
    return rep[k], att[k], la_label(float(w) / float(modulus) / a0), a0


def figure1(maps, *, labels=None, target_area=0.02, region=None):
    """Fig. 1: repulsive (orange) and attractive (black) sites, one panel per map.

    Parameters
    ----------
    maps : sequence
        Path datasets with contact fields (``fields_at=``), their files, or 2D pressure
        arrays (e.g. one per ℓa on the same surface, as in the paper's Fig. 1 C-E).
    labels : sequence of str, optional
        Panel titles (default: ``$\\ell_a/a_0 = ...$`` (mathtext) from the path's
        attributes).
    target_area : float
        A_rep/A0 (dimensionless) at which the maps are compared (the paper: about 0.02);
        of each path's stored steps the closest is shown and its A_rep/A0 printed in the
        title.
    region : tuple of int, optional
        ``(x0, y0, width)`` in pixels: an expanded view (periodic wrap-around).

    Notes
    -----
    Symbols are typeset with matplotlib mathtext; the legend of the site colours sits
    below the panels, outside them.

    Returns
    -------
    matplotlib.figure.Figure
        One image per map; pixel category 0 (white): neither, 1 (black): attractive,
        2 (orange): repulsive; x horizontal, y vertical, in units of a0 (axes
        :math:`x/a_0`, :math:`y/a_0`).
    """
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch

    items = list(maps) if maps is not None else []
    if not items:
        raise ParameterError("Fig. 1 needs at least one contact map (path dataset or array)")
    if labels is not None and len(labels) != len(items):
        raise ParameterError(f"Fig. 1: {len(labels)} labels for {len(items)} maps")
    fig = Figure(figsize=(3.3 * len(items) + 0.4, 3.9), layout="constrained")
    axes = fig.subplots(1, len(items), squeeze=False)[0]
    cmap, norm = ListedColormap(COLOURS), BoundaryNorm([-0.5, 0.5, 1.5, 2.5], 3)
    for n, (ax, item) in enumerate(zip(axes, items, strict=True)):
        rep, att, label, a0 = contact_masks(item, target_area)
        cat = np.where(rep, 2, np.where(att, 1, 0)).astype(np.int8)
        area = float(rep.mean())
        x0 = y0 = 0
        if region is not None:
            x0, y0, width = (int(v) for v in region)
            if width < 1:
                raise ParameterError(f"Fig. 1: region width must be >= 1, got {width}")
            cat = np.take(
                np.take(cat, np.arange(x0, x0 + width), 0, mode="wrap"),
                np.arange(y0, y0 + width),
                1,
                mode="wrap",
            )
        nx, ny = cat.shape
        extent = ((x0 - 0.5) * a0, (x0 + nx - 0.5) * a0, (y0 - 0.5) * a0, (y0 + ny - 0.5) * a0)
        ax.imshow(
            cat.T,
            origin="lower",
            cmap=cmap,
            norm=norm,
            interpolation="nearest",
            extent=extent,
            gid=f"map:{n}",
        )
        title = labels[n] if labels is not None else (label or f"map {n + 1}")
        areas = rf"$A_\mathrm{{rep}}/A_0 = {area:.4f}$, $A_\mathrm{{att}}/A_0 = {att.mean():.4f}$"
        ax.set_title(f"{title}\n{areas}", fontsize=9)
        ax.set_xlabel(r"$x/a_0$")
        ax.set_ylabel(r"$y/a_0$" if n == 0 else "")
    fig.legend(
        handles=[Patch(color=ORANGE, label="repulsive"), Patch(color="black", label="attractive")],
        loc="outside lower center",
        ncols=2,
        fontsize=8,
        # the figure's title goes here: a suptitle collides with the two-line panel titles
        title=rf"Fig. 1: contact maps at $A_\mathrm{{rep}}/A_0 \approx {target_area:g}$",
        title_fontsize=9,
    )
    return fig


def study_maps(study_dir):
    """Path datasets for Fig. 1 from a study directory: one surface, every ℓa.

    Of the task files (:func:`roughcontact.studies.store.task_files`) that hold contact
    fields, those of the same surface, substrate and seed (:data:`~._data.SURFACE_KEYS`)
    are grouped; the largest group (the first on a tie) is returned, sorted by ℓa. An
    empty list when no task file holds fields. A task file whose task key is not the
    manifest's (copied in from another study) is left out.
    """
    import xarray as xr

    from ..pathdata import read_path
    from ..studies.store import task_files, task_keys, task_parameters

    groups, keys = {}, task_keys(study_dir)
    for path in task_files(study_dir):
        try:
            with xr.open_dataset(path, engine="h5netcdf") as ds:
                if "pressure" not in ds.variables and "gap" not in ds.variables:
                    continue
                if keys is not None and ds.attrs.get("task_key") != keys.get(path.name):
                    continue  # another study's file (or other parameters): not this study
                params = task_parameters(ds.attrs)
        except Exception:  # noqa: BLE001 - unreadable or damaged (h5py's RuntimeError)
            continue
        key = json.dumps({k: params.get(k) for k in SURFACE_KEYS}, sort_keys=True)
        la = params.get("adhesion_length")
        groups.setdefault(key, []).append((-1.0 if la is None else float(la), path))
    if not groups:
        return []
    best = max(groups.values(), key=len)
    return [read_path(p, check=False) for _, p in sorted(best)]
