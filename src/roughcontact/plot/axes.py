"""Axes helpers of the figures: a pyplot-free Figure, log axes over whole decades.

Shared by the paper's figures (:mod:`roughcontact.plot.figures`) and the report of a
measured scan (:mod:`roughcontact.topography.report`), so both look alike.
"""

from __future__ import annotations

__all__ = ["decades", "figure", "log_axes", "loglog"]

import math

import numpy as np


def figure(width, height):
    """A matplotlib ``Figure`` of ``width`` x ``height`` inches, constrained layout.

    Made without pyplot, so no global state and no GUI backend is touched.
    """
    from matplotlib.figure import Figure

    return Figure(figsize=(width, height), layout="constrained")


def decades(*arrays):
    """Whole decades around the positive finite values of ``arrays`` (log-axis limits)."""
    v = np.concatenate([np.ravel(np.asarray(a, dtype=float)) for a in arrays])
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        return 0.1, 10.0
    lo, hi = math.floor(math.log10(v.min())), math.ceil(math.log10(v.max()))
    return 10.0**lo, 10.0 ** max(hi, lo + 1)


def log_axes(ax, xlim, ylim):
    """Log-scaled x and y axes with the given limits and no minor tick labels."""
    from matplotlib.ticker import NullFormatter

    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_minor_formatter(NullFormatter())


def loglog(ax, xs, ys, slope=1.0, label=None, *, also=()):
    """Log axes over the data and the line y = slope·x across them (``gid="theory"``;
    ``slope=None``: no line).

    ``also``: further slopes whose lines y = s·x must fit in the y-range (reference lines
    drawn by the caller). Returns the x-limits (the decades of the data), or ``None``
    when there is no data (then the axes say so).
    """
    x = np.concatenate([np.ravel(v) for v in xs]) if xs else np.zeros(0)
    y = np.concatenate([np.ravel(v) for v in ys]) if ys else np.zeros(0)
    if x.size == 0:
        log_axes(ax, (0.1, 10.0), (0.1, 10.0))
        ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center", color="0.5")
        return None
    xlim = decades(x, y / slope) if slope is not None else decades(x)
    slopes = np.array([s for s in (slope, *also) if s is not None], dtype=float)
    log_axes(ax, xlim, decades(y, np.outer(slopes, xlim)))
    if slope is not None:  # None: the caller draws its own line or band
        line = np.geomspace(*xlim, 50)
        ax.plot(line, slope * line, "-", color="0.4", lw=1, gid="theory", label=label, zorder=0)
    return xlim
