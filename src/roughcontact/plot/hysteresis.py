r"""The adhesion hysteresis of a path as a figure: N against the approach, the cycle shaded.

:func:`hysteresis_figure` draws the load per nominal area against the approach
``δ = -d`` (the path's offsets, reversed so that loading goes right), the approach and the
retraction in two colours, the steps flagged as jumps marked, and the area the cycle
encloses shaded: its size is the dissipated energy ``W = ∮ N dδ`` per A0
(:mod:`roughcontact.analysis.hysteresis`), written in the title with the number of jumps.
matplotlib is imported only when the figure is made (no pyplot state).
"""

from __future__ import annotations

import numpy as np

from .._validate import ParameterError

__all__ = ["hysteresis_figure"]


def hysteresis_figure(ds, *, label: str | None = None):
    """Load–approach cycle of one path with its dissipated energy.

    Parameters
    ----------
    ds : xarray.Dataset
        A path (:func:`roughcontact.approach_retract`) with a retraction; loads per A0
        (pressure), offsets in length.
    label : str, optional
        Title prefix (e.g. the surface's name).

    Returns
    -------
    matplotlib.figure.Figure
        One panel: N/A0 against δ = -d; the title gives W per A0 (pressure × length, the
        path's units), its bound from the jump steps, and the jumps in and out.
    """
    from matplotlib.figure import Figure

    from ..analysis.hysteresis import hysteresis

    if "branch" not in ds.variables or not np.any(ds["branch"].values == "retract"):
        raise ParameterError("the hysteresis figure needs a path with a retraction")
    hy = hysteresis(ds)
    d = -np.asarray(ds["offset"].values, dtype=float)
    n = np.asarray(ds["load"].values, dtype=float)
    b = np.asarray(ds["branch"].values).astype(str)
    jump = np.asarray(ds["jump"].values, dtype=bool) if "jump" in ds.variables else None
    fig = Figure(figsize=(5.0, 3.8), layout="constrained")
    ax = fig.subplots()
    ax.fill(d, n, color="0.85", zorder=0, label="dissipated: W = ∮N dδ")
    for name, colour in (("approach", "tab:blue"), ("retract", "tab:red")):
        on = b == name
        ax.plot(d[on], n[on], ".-", color=colour, ms=3, lw=1, label=name)
    if jump is not None and jump.any():
        ax.plot(d[jump], n[jump], "kx", ms=5, label="jump")
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.set_xlabel(r"approach $\delta = -d$")
    ax.set_ylabel(r"load $N/A_0$")
    title = (
        f"W = {hy.dissipated_energy:.3g} ± {hy.energy_uncertainty:.2g} per $A_0$, "
        f"jumps {hy.jumps_in} in / {hy.jumps_out} out"
    )
    if not hy.closed:
        title += " (cycle not closed)"
    ax.set_title(title if label is None else f"{label}: {title}", fontsize=9)
    ax.legend(fontsize=7, frameon=False)
    return fig
