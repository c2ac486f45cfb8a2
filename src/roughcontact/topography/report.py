"""The answer of :func:`roughcontact.stick` in words, figures and a report folder (the
text lives in :mod:`roughcontact.topography.summaries`, the figures in
:mod:`roughcontact.topography.figures`; their names are kept here).

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

from .._validate import DPI, ParameterError
from .figures import (
    FIGURES,
    figure_contact_map,
    figure_margin,
    figure_psd,
    figure_scan,
    figure_slope,
)
from .result import StickResult
from .summaries import hysteresis_summary, simulation_summary, summary

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
