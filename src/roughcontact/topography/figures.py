"""The answer of :func:`roughcontact.stick` in figures (matplotlib, imported only here; no
pyplot state).

* :func:`figure_scan`, :func:`figure_psd`, :func:`figure_slope`, :func:`figure_margin`
  (:data:`FIGURES`) -- the scan and its analysis;
* :func:`figure_contact_map` -- the simulation's contact map (``stick(..., simulate=True)``).

The data are in SI units; the figures label lengths in nm or um.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._text import range_text
from .result import StickResult

__all__ = ["FIGURES", "figure_contact_map", "figure_margin", "figure_psd", "figure_scan",
           "figure_slope"]  # fmt: skip

MEASURED = {"color": "C0", "lw": 1.5}
EXTRAPOLATED = {"color": "C0", "lw": 1.5, "linestyle": "--"}
BAND = {"color": "C0", "alpha": 0.2, "lw": 0}
CUTOFF = {"color": "0.4", "lw": 1, "linestyle": ":"}


def _figure(width=5.0, height=3.6):
    from ..plot.axes import figure

    return figure(width, height)


def figure_scan(result: StickResult, *, percentiles=None):
    """The analysed (detrended) heights: a map in nm over um, or the profile.

    ``percentiles`` ``(lo, hi)`` (e.g. ``(1, 99)``): the map's colour scale spans these
    percentiles of the heights (robust to spikes; the colour bar extends at both ends);
    default: the full range.
    """
    topo, s = result.topography, result.statistics
    fig = _figure()
    ax = fig.add_subplot()
    h = np.asarray(topo.heights) / 1e-9
    if s.dim == 2:
        Lx, Ly = (n * a / 1e-6 for n, a in zip(s.shape, s.pixel_size, strict=True))
        vmin = vmax = None
        if percentiles is not None:
            vmin, vmax = np.nanpercentile(h, percentiles)
        im = ax.imshow(h.T, origin="lower", extent=(0, Lx, 0, Ly), cmap="viridis",
                       vmin=vmin, vmax=vmax)  # fmt: skip
        fig.colorbar(im, ax=ax, label="height (nm)",
                     extend="neither" if percentiles is None else "both")  # fmt: skip
        ax.set_xlabel("x (um)")
        ax.set_ylabel("y (um)")
    else:
        x = np.arange(h.size) * s.pixel_size[0] / 1e-6
        ax.plot(x, h, lw=0.6, color="C0")
        ax.set_xlabel("x (um)")
        ax.set_ylabel("height (nm)")
    detrend = result.inputs.get("detrend")
    ax.set_title(f"{Path(getattr(topo, 'source', '') or 'scan').name} (detrend: {detrend})",
                 fontsize=9)  # fmt: skip
    return fig


def figure_psd(result: StickResult):
    """The PSD with the self-affine fit, its extrapolation and the cutoffs (log-log)."""
    from ..plot.axes import decades, log_axes

    s, v, fit = result.statistics, result.verdict, result.statistics.fit
    fig = _figure()
    ax = fig.add_subplot()
    p = s.psd
    unit = "m^4" if p.dim == 2 else "m^3"
    ax.plot(p.q, p.psd, "o", ms=3, color="0.2", label=f"PSD ({p.window} window)")
    q_fit = 2 * np.pi / np.array(fit.scale_range[::-1])
    qf = np.geomspace(*q_fit, 20)
    ax.plot(qf, fit.psd(qf), **MEASURED, label=f"fit H = {fit.hurst:.2f} +- {fit.hurst_stderr:.2f}")
    q_c, q_a = 2 * np.pi / s.measured_scale, 2 * np.pi / float(v.scales[-1])
    ys = [p.psd]
    if q_a > q_c and v.extrapolated:
        qe = np.geomspace(q_c, q_a, 30)
        lo, hi = fit.psd(qe, v.hurst[0]), fit.psd(qe, v.hurst[-1])
        ax.fill_between(qe, np.minimum(lo, hi), np.maximum(lo, hi), **BAND)
        ax.plot(qe, fit.psd(qe), **EXTRAPOLATED, label="extrapolated")
        ys.append(fit.psd(qe))
    ax.axvspan(*q_fit, color="C2", alpha=0.1, lw=0, label="fit range")
    ax.axvline(q_c, **CUTOFF)
    ax.text(q_c, 0.02, " measured scale", rotation=90, fontsize=7,
            transform=ax.get_xaxis_transform(), va="bottom")  # fmt: skip
    good = result.good_range
    if good is not None and good.resolution is not None:
        ax.axvline(2 * np.pi / good.resolution, color="C3", lw=1, linestyle="--",
                   label="resolution limit")  # fmt: skip
    if good is not None and good.noise_level is not None:
        ax.axhline(good.noise_level, color="C3", lw=1, linestyle="-.", label="noise floor")
    if v.no_extrapolation:
        ax.set_title("not self-affine in the fit range: nothing extrapolated", fontsize=8)
    xs = decades(p.q, [q_a])
    log_axes(ax, xs, decades(*ys))
    ax.set_xlabel("wavevector q (1/m)")
    ax.set_ylabel(f"C{'' if p.dim == 2 else '1D'}(q) ({unit})")
    ax.legend(fontsize=7, frameon=False)
    return fig


def figure_slope(result: StickResult):
    """Scale-dependent rms slope and curvature against the smallest roughness scale."""
    from ..plot.axes import decades, log_axes

    s, v = result.statistics, result.verdict
    fig = _figure(5.0, 5.0)
    axes = fig.subplots(2, 1, sharex=True)
    c = v.centre
    for ax, measured, extra, name in (
        (axes[0], s.slopes, v.slopes, "h'rms"),
        (axes[1], s.curvatures, v.curvatures, "h''rms (1/m)"),
    ):
        ax.plot(s.scales, measured, **MEASURED, label="measured")
        ys = [measured]
        if v.scales.size > 1:
            ax.fill_between(v.scales, extra.min(axis=0), extra.max(axis=0), **BAND)
            ax.plot(v.scales, extra[c], **EXTRAPOLATED, label="extrapolated")
            ys.append(extra)
        ax.axvline(s.measured_scale, **CUTOFF)
        log_axes(ax, decades(s.scales, v.scales), decades(*ys))
        ax.set_ylabel(name)
    axes[0].legend(fontsize=7, frameon=False)
    axes[1].set_xlabel("smallest roughness scale lambda_s (m)")
    return fig


def figure_margin(result: StickResult):
    """The margin kappa_rep/kappa_att against the smallest roughness scale, sticky above 1."""
    from ..plot.axes import decades, log_axes

    v = result.verdict
    fig = _figure()
    ax = fig.add_subplot()
    c = v.centre
    if v.scales.size > 1:
        ax.fill_between(v.scales, v.margins.min(axis=0), v.margins.max(axis=0), **BAND,
                        label=f"H = {range_text(v.hurst[0], v.hurst[-1], '.2f')}")  # fmt: skip
        ax.plot(v.scales, v.margins[c], **EXTRAPOLATED, label=f"H = {v.hurst[c]:.2f}")
    ax.plot(v.scales[:1], v.margins[c, :1], "o", color="C0", label="measured")
    ax.axhline(1.0, color="C3", lw=1, gid="threshold")
    xs = decades(v.scales)
    ys = decades(v.margins, [1.0])
    ax.axhspan(1.0, ys[1], color="C2", alpha=0.08, lw=0)
    ax.text(0.02, 0.97, "sticky", transform=ax.transAxes, fontsize=8, va="top", color="C2")
    for flip in v.flip_scales:
        ax.axvline(flip, **CUTOFF)
    log_axes(ax, xs, ys)
    ax.set_xlabel("smallest roughness scale lambda_s (m)")
    ax.set_ylabel("margin kappa_rep/kappa_att")
    ax.set_title(v.text if len(v.text) < 60 else v.text.split(" (")[0], fontsize=9)
    ax.legend(fontsize=7, frameon=False, loc="lower left")
    return fig


#: File stem -> figure function, in the order they are written.
FIGURES = {
    "scan": figure_scan,
    "psd": figure_psd,
    "slope": figure_slope,
    "margin": figure_margin,
}


def figure_contact_map(result: StickResult):
    """Repulsive (orange) and attractive (black) sites of the first simulated seed in the
    approach's state nearest A_rep = 1 % (Fig. 1's style, :func:`roughcontact.plot.figure1`;
    the panel title and the legend give that state's own A_rep/A0); None if none kept or
    the state has no repulsive site."""
    from ..plot import figure1

    sim = result.simulation
    found = None if sim is None else sim.contact_map
    if found is None:
        return None
    seed, pressure = found
    la = sim.interaction["adhesion_length_over_a0"]
    # the state kept is the approach's nearest to 1 %: title and legend give its own area
    area = float(np.mean(np.asarray(pressure) > 0))
    if area == 0:  # e.g. a soft solid jumping into contact: nothing repulsive to show
        return None
    label = rf"seed {seed}, $\ell_a/a_0 = {la:.3g}$ ({sim.verdict}; the state nearest 1 %)"
    return figure1([pressure], labels=[label], target_area=float(f"{area:.2g}"))
