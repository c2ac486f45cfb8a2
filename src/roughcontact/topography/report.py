"""The answer of :func:`roughcontact.stick` in words, figures and a report folder.

* :func:`summary` -- a few lines: the verdict, the margin measured and extrapolated, what
  is measured and what extrapolated, and the scale the verdict depends on;
* :func:`figure_scan`, :func:`figure_psd`, :func:`figure_slope`, :func:`figure_margin`
  -- matplotlib figures (imported only here, no pyplot state);
* :func:`simulation_summary`, :func:`figure_contact_map` -- the simulation's lines and
  its contact map (``stick(..., simulate=True)``);
* :func:`write_report` -- ``result.json``, the figures and ``report.html`` in one
  directory, each file written atomically (:func:`roughcontact._io.write_bytes_atomic`).

Everything is in SI units in the data; the figures label lengths in nm or um.
"""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np

from .._validate import DPI, ParameterError
from ._text import length_text as _length_text
from ._text import range_text
from .result import StickResult

__all__ = [
    "FIGURES",
    "figure_contact_map",
    "figure_margin",
    "figure_psd",
    "figure_scan",
    "figure_slope",
    "hysteresis_summary",
    "simulation_summary",
    "summary",
    "write_report",
]

MEASURED = {"color": "C0", "lw": 1.5}
EXTRAPOLATED = {"color": "C0", "lw": 1.5, "linestyle": "--"}
BAND = {"color": "C0", "alpha": 0.2, "lw": 0}
CUTOFF = {"color": "0.4", "lw": 1, "linestyle": ":"}


def summary(result: StickResult) -> list[str]:
    """The verdict and every note, in lines of text (SI values with readable prefixes)."""
    s, v, fit = result.statistics, result.verdict, result.statistics.fit
    c = v.centre
    lam_c, a0 = s.measured_scale, float(result.inputs["atomic_spacing"])
    lines = [f"verdict: {v.text}"]
    first = [
        n
        for n in result.notes
        if n.startswith("no extrapolated verdict") or n.startswith("pixel_size '")
    ]
    lines += first
    lines.append(_answers(v, lam_c))
    lines.append(
        f"measured down to {_length_text(lam_c)}: h'rms = {s.rms_slope:.3g}, "
        f"h''rms = {s.rms_curvature:.3g} 1/m, d_rep = {_length_text(s.d_rep)}, margin "
        f"kappa_rep/kappa_att = {v.margin:.3g} (> 1 sticks)"
    )
    if v.extrapolated and v.scales.size > 1:
        lo, hi = v.margin_atomic_range
        band = range_text(v.hurst[0], v.hurst[-1], ".2f")
        lines.append(
            f"extrapolated down to {_length_text(a0)} with H = {fit.hurst:.2f} +- "
            f"{fit.hurst_stderr:.2f}: h'rms = {v.slopes[c, -1]:.3g}, "
            f"h''rms = {v.curvatures[c, -1]:.3g} 1/m, "
            f"d_rep = {_length_text(4 * v.slopes[c, -1] / v.curvatures[c, -1])}, margin "
            f"{v.margin_atomic:.3g} ({range_text(lo, hi)} within H = {band})"
        )
    good = result.good_range
    lines.append(
        f"fit range: {_length_text(fit.scale_range[0])} to {_length_text(fit.scale_range[1])}"
        + (
            ""
            if good is None
            else f" (the instrument's limits: good data from {_length_text(good.short)})"
            if good.reasons
            else " (no resolution limit or noise floor found in the PSD)"
        )
    )
    if v.sticky is None and v.depends_below is not None:
        lines.append(
            f"the verdict depends on roughness below {_length_text(v.depends_below)}, "
            f"below the measured {_length_text(lam_c)}: measure finer or with a sharper tip"
        )
    lines += [f"note: {n}" for n in result.notes if n not in first]
    if result.simulation is not None:
        lines += simulation_summary(result.simulation)
    if result.hysteresis is not None:
        lines += hysteresis_summary(result.hysteresis)
    if result.criteria is not None:
        from ..stickiness import format_table

        lines.append(
            f"the field's criteria side by side, with the roughness down to the measured "
            f"{_length_text(result.criteria['scale'])} (no extrapolation):"
        )
        lines += format_table(result.criteria).splitlines()
    return lines


def _answers(v, lam_c) -> str:
    """The whole surface's answer (``sticky``) beside the measured scale's
    (``sticky_measured_scale``), as the JSON keys hold them."""
    words = {True: "sticky", False: "not sticky", None: "undecided"}
    whole = words[v.sticky]
    if v.sticky is None and v.scope == "measured scale":
        whole += " (nothing extrapolated below the measured scale)"
    elif v.sticky is None:
        whole += " (depends on unmeasured roughness)"
    return (
        f"answer for the whole surface (sticky): {whole}; with the roughness down to the "
        f"measured {_length_text(lam_c)} only (sticky_measured_scale): "
        f"{words[v.sticky_measured_scale]}"
    )


def simulation_summary(sim) -> list[str]:
    """Three lines on the simulation of :mod:`roughcontact.topography.simulate`."""
    s, i, inv = sim.surface, sim.interaction, sim.inverse_kappa
    interval = "" if inv.n < 2 else f", 1/kappa in [{inv.low:.3g}, {inv.high:.3g}]"
    from .notes import predicted_reason, seed_status

    seeds = "; ".join(seed_status(r) for r in sim.runs)
    why = predicted_reason(sim)
    pull = sim.pull_off_pressure
    how = (
        f"over {inv.n} of {len(sim.runs)} seeds{interval}"
        if inv.n
        else f"({len(sim.runs)} seeds, none analysed at 1 %: see the notes)"
    )
    return [
        f"simulated: {sim.verdict} {how}; Eq. 10 on the same surfaces: {sim.predicted_verdict}"
        + (f" ({why})" if why else ""),
        f"simulation: {s['size']}^2 sites of a0 = {_length_text(s['atomic_spacing'])}, "
        f"lambda_s = {s['short_cutoff_over_a0']:g} a0, H = {s['hurst']:.2f}, "
        f"h'rms = {s['rms_slope']:.3g}; wall l_a/a0 = {i['adhesion_length_over_a0']:.3g}, "
        f"range {_length_text(i['range'])} ({i.get('parametrisation', '')})",
        f"per seed kappa (kappa_rep, kappa_att) at A_rep = 1 %: {seeds}; pull-off pressure "
        + (f"{pull:.3g} Pa" if np.isfinite(pull) else "not measured"),
    ] + [f"note: {n}" for n in sim.notes]


def hysteresis_summary(hy) -> list[str]:
    """The simulation's approach–retraction cycles in SI
    (:func:`roughcontact.topography.hysteresis.simulation_hysteresis`)."""
    w, sd = hy["dissipated_energy_si"], hy["dissipated_energy_si_std"]
    if not np.isfinite(w):
        return ["hysteresis: not measured (no seed's cycle has a retraction)"]
    seeds = hy["seeds"]
    if seeds and all(s.get("zero_within_tolerance") for s in seeds):
        bound = max(float(s["energy_uncertainty_si"]) for s in seeds)
        return [
            f"hysteresis: none: no seed's cycle has a jump, so the energy dissipated per "
            f"approach–retraction cycle is 0 within ± {bound:.2g} J/m^2 (the solver's "
            "tolerance)",
            f"hysteresis per seed: {'; '.join(_seed_energy(s) for s in seeds)}",
        ] + [f"note: {n}" for n in hy["notes"]]
    spread = f" ± {sd:.3g}" if np.isfinite(sd) else " (1 seed: no spread)"
    scan = hy["dissipated_energy_scan"]
    per_seed = "; ".join(_seed_energy(s) for s in hy["seeds"])
    return [
        f"hysteresis: energy dissipated per approach–retraction cycle {w:.3g}{spread} J/m^2 "
        f"(mean ± sd over seeds), {hy['jumps_mean']:.3g} jumps per cycle"
        + (f"; over the scanned area {scan:.3g} J" if np.isfinite(scan) else ""),
        f"hysteresis per seed: {per_seed}",
    ] + [f"note: {n}" for n in hy["notes"]]


def _seed_energy(s) -> str:
    """One seed's dissipated energy: a jump-free cycle as 0 within its bound."""
    if s.get("zero_within_tolerance"):
        return (
            f"seed {s['seed']}: 0 (within ± {s['energy_uncertainty_si']:.2g}) J/m^2, "
            f"{s['jumps']} jumps"
        )
    return f"seed {s['seed']}: {s['dissipated_energy_si']:.3g} J/m^2, {s['jumps']} jumps"


# --------------------------------------------------------------------------- figures


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


def write_report(
    result: StickResult, out_dir, *, formats=("png",), dpi: int = 150, command=None
) -> dict:
    """Write ``result.json``, the figures and ``report.html`` into ``out_dir`` (created).

    Only these files are written, each atomically: ``result.json`` (``to_dict()``),
    ``summary.txt`` (:func:`summary`), ``scan``, ``psd``, ``slope``, ``margin`` in
    every format; with a simulation also ``contact_map`` (:func:`figure_contact_map`);
    ``report.html``, the same record as one self-contained page
    (:func:`roughcontact.topography.html.stick_html`).

    Parameters
    ----------
    result : StickResult
    out_dir : path-like
        The report directory.
    formats : sequence of str
        matplotlib formats (``png``, ``pdf``, ``svg``).
    dpi : int
        Resolution of raster formats, in [10, 2400].
    command : str, optional
        The command line, for the page's provenance.

    Returns
    -------
    dict
        ``{"result": path, "summary": path, "<figure>": [paths], "html": path}``.
    """
    from .._io import write_bytes_atomic

    dpi = DPI.check("dpi", dpi)
    formats = tuple(formats)
    if not formats or any(f not in ("png", "pdf", "svg") for f in formats):
        raise ParameterError(f"formats must be some of png, pdf, svg, got {formats!r}")
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ParameterError(f"report directory {str(out)!r} exists and is not a directory")
    out.mkdir(parents=True, exist_ok=True)
    text = json.dumps(result.to_dict(), indent=1, allow_nan=False) + "\n"
    written = {
        "result": write_bytes_atomic(out / "result.json", text.encode()),
        "summary": write_bytes_atomic(
            out / "summary.txt", ("\n".join(summary(result)) + "\n").encode()
        ),
    }
    from .html import SCAN_PERCENTILES, stick_html

    figures = dict(FIGURES)
    if result.simulation is not None:
        figures["contact_map"] = figure_contact_map
    made = {}  # each figure made once: for its files and for report.html
    for name, make in figures.items():
        fig = make(result, percentiles=SCAN_PERCENTILES) if name == "scan" else make(result)
        made[name] = fig
        if fig is None:
            continue
        written[name] = []
        for fmt in formats:
            buffer = io.BytesIO()
            fig.savefig(buffer, format=fmt, dpi=dpi)
            written[name].append(write_bytes_atomic(out / f"{name}.{fmt}", buffer.getvalue()))
    page = stick_html(result, command=command, dpi=min(dpi, 150), figures=made)
    written["html"] = write_bytes_atomic(out / "report.html", page.encode())
    return written
