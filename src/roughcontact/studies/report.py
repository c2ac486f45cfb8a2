"""``roughcontact study report``: a study's data, figures and the paper's claims checked.

From a study directory (or its collected NetCDF file) it writes, inside the output
directory only and each file atomically:

* ``data/collected.nc`` — the collected dataset without wall-clock times (per task and
  per step scalars, no field maps); ``data/tasks.csv`` (one row per task: parameters,
  path analysis), ``data/steps.csv`` (one row per computed step), ``data/
  parameter_sets.csv`` (seeds combined, :func:`~roughcontact.studies.aggregate.
  aggregate_seeds`);
* ``claims.json`` — every number of :mod:`roughcontact.studies.claims`;
* ``versions.json`` — the study (name, sha256, tasks done) and the software versions;
* ``figures/fig2_area_load.png``, ``fig3_collapse.png``, ``fig4_theory.png`` — the
  paper's Figs. 2-4 in its symbol code;
* ``README.md`` — the claims one by one with our numbers beside them.

The report is size-agnostic: the same command makes it for L = 1024 a0 or 4096 a0.
"""

from __future__ import annotations

import json
import platform
from pathlib import Path

import numpy as np

from .._io import output_directory, write_bytes_atomic, write_netcdf_atomic
from .._validate import json_safe
from ..htmlreport import Figure, Heading, Para, data_uri, markdown_lines
from . import claims as _claims
from .collect import read_collected
from .report_tables import STEP_COLUMNS as STEP_COLUMNS  # public, kept here too
from .report_tables import csv_bytes, sets_frame, steps_frame, tasks_frame

__all__ = ["render_html", "render_report", "report_blocks", "write_report"]


from .report_text import _n, claim_blocks, header_blocks


def _figure_blocks(figures) -> list:
    """Figs. 2-4: ``{name: png bytes}`` inline (and linked from the Markdown)."""
    if not figures:
        return []
    return [
        Heading("Figures"),
        Para(
            "Symbols as in the paper: shape by H (triangle 0.3, square 0.5, circle 0.8), colour "
            "by ℓa/a0 (black, blue, red), filled/open by h′rms (0.1/0.3), size by λs."
        ),
        *[
            Figure(data_uri(png, "image/png") if png else "", FIGURE_ALT.get(name, name),
                   FIGURE_ALT.get(name, ""), f"figures/{name}.png")
            for name, png in figures.items()
        ],
    ]  # fmt: skip


#: Alt text and caption of each figure of the report.
FIGURE_ALT = {
    "fig2_area_load": "Fig. 2: repulsive area A_rep/A0 against the load N/(A0 h′rms E*) on "
    "the approach, one surface, every adhesion length, with the linear fits",
    "fig3_collapse": "Fig. 3: (a) attractive load against (ℓa/Δr) A_att/A0 with Eq. 4, "
    "(b) repulsive load against A_rep/A0 with Eq. 2, (c) P d_rep/(π A0) against A_rep/A0",
    "fig4_theory": "Fig. 4: (a) A_rep/A_att against Eq. 6, (b) κ_att against Eq. 7, the "
    "sticky region κ_att < κ_rep shaded",
}


def report_blocks(claims: dict, meta: dict, figures=None) -> list:
    """The report as blocks (:mod:`roughcontact.htmlreport`): header, claims, figures
    (``figures``: ``{name: png bytes}`` or names)."""
    figs = figures if isinstance(figures, dict) else dict.fromkeys(figures or (), b"")
    return [*header_blocks(meta), *claim_blocks(claims), *_figure_blocks(figs)]


def render_report(claims: dict, meta: dict, figures=()) -> str:
    """The Markdown report of :func:`roughcontact.studies.claims.all_claims` numbers."""
    return "\n".join(markdown_lines(report_blocks(claims, meta, figures))) + "\n"


def render_html(claims: dict, meta: dict, figures=None, *, command=None) -> str:
    """The same report as one self-contained HTML page (figures inline)."""
    from .. import htmlreport

    blocks = report_blocks(claims, meta, figures)
    return htmlreport.render_html(meta["title"], blocks[1:], provenance_rows=[
        *htmlreport.provenance(command),
        ("study", f"{meta['study_name']} (sha256 {meta['study_sha256']})"),
    ])  # fmt: skip


def _versions() -> dict:
    import scipy
    import xarray

    from .. import __version__

    return {
        "roughcontact": __version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "xarray": xarray.__version__,
    }


def _meta(ds, source, out, claims) -> dict:
    a = ds.attrs
    done = (np.asarray(ds["status"].values) == "done") if "status" in ds.variables else None
    seeds = []
    if "seed" in ds.coords:  # the realisations with data
        seed = np.asarray(ds["seed"].values)
        seeds = sorted(set((seed if done is None else seed[done]).tolist()))
    grid = []
    for key, label in (
        ("size", "n"),
        ("hurst", "H"),
        ("rms_slope", "h′rms"),
        ("short_cutoff", "λs/a0"),
        ("adhesion_length", "ℓa/a0"),
    ):
        if key in ds.coords:
            levels = ", ".join(_n(v) for v in sorted(set(ds[key].values.tolist())))
            grid.append(f"{label} ∈ {{{levels}}}")
    settings = json.loads(a.get("study_settings", "{}") or "{}")
    study_dir = str(source) if Path(source).is_dir() else "STUDY_DIR"
    study_file = f"{study_dir}/study.toml" if Path(source).is_dir() else "STUDY.toml"
    return {
        "title": f"Reproduction of Pastewka & Robbins (2014): study '{a.get('study_name', '?')}'",
        "study_name": a.get("study_name", "?"),
        "study_sha256": a.get("study_sha256", "?"),
        "tasks_done": int(a.get("tasks_done", done.sum() if done is not None else 0)),
        "tasks_failed": int(a.get("tasks_failed", 0)),
        "tasks_missing": int(a.get("tasks_missing", 0)),
        "analysed": claims["eq3_linearity"]["tasks"],
        "seeds": seeds,
        "grid": "; ".join(grid),
        "unconverged_steps": int(np.nansum(ds["steps_not_converged"].values))
        if "steps_not_converged" in ds.variables
        else 0,
        "target_area": settings.get("analysis", {}).get("target_area", 0.01),
        "study_file": study_file,
        "study_dir": study_dir,
        "report_dir": str(out),
        "versions": _versions(),
    }


def write_report(
    source, out_dir, *, confidence: float = 0.95, dpi: int = 120, command: str | None = None
) -> dict:
    """Write the data, claims, figures, ``README.md`` and ``report.html`` of a study.

    Parameters
    ----------
    source : path-like
        A study directory (``roughcontact study run -o DIR``) or a collected ``.nc``.
    out_dir : path-like
        Output directory (created); nothing is written elsewhere.
    confidence : float
        Level of the intervals over seeds, in (0, 1).
    dpi : int
        Resolution of the PNG figures.
    command : str, optional
        The command line, for the provenance of ``report.html``.

    Returns
    -------
    dict
        ``{"claims": ..., "files": [written paths]}``.
    """
    ds = read_collected(source, include_timings=False)  # a report of the same data is the same file
    out = Path(out_dir)
    claims = _claims.all_claims(ds, confidence=confidence)
    meta = _meta(ds, source, out, claims)
    files = []
    out.mkdir(parents=True, exist_ok=True)
    # a link planted at data/ or figures/ is replaced: nothing lands outside the report
    data = output_directory(out / "data")
    files.append(write_netcdf_atomic(ds, data / "collected.nc"))
    for name, frame in (
        ("tasks", tasks_frame(ds)),
        ("steps", steps_frame(ds)),
        ("parameter_sets", sets_frame(ds)),
    ):
        files.append(write_bytes_atomic(data / f"{name}.csv", csv_bytes(frame)))
    text = json.dumps(json_safe(claims), indent=1, sort_keys=True, allow_nan=False)
    files.append(write_bytes_atomic(out / "claims.json", (text + "\n").encode()))
    versions = {
        k: meta[k]
        for k in (
            "study_name",
            "study_sha256",
            "tasks_done",
            "tasks_failed",
            "tasks_missing",
            "seeds",
            "versions",
        )
    }
    text = json.dumps(json_safe(versions), indent=1, sort_keys=True)
    files.append(write_bytes_atomic(out / "versions.json", (text + "\n").encode()))
    from ..plot.figures import save_figures

    written = save_figures(ds, output_directory(out / "figures"), ("png",), dpi=dpi)
    files += [p for paths in written.values() for p in paths]
    figures = {name: Path(paths[0]).read_bytes() for name, paths in written.items() if paths}
    readme = render_report(claims, meta, figures)
    files.append(write_bytes_atomic(out / "README.md", readme.encode()))
    page = render_html(claims, meta, figures, command=command)
    files.append(write_bytes_atomic(out / "report.html", page.encode()))
    return {"claims": claims, "files": [str(f) for f in files]}
