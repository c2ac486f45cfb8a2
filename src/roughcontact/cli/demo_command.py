"""``roughcontact demo``: the main job on built-in defaults (a hard-wall load path and an
adhesive study).

The command's module; :mod:`.demo` and :mod:`.demo_study` keep the older names of the
workflow, which lives in :mod:`roughcontact.workflows.demo`.
"""

from __future__ import annotations

import json
from pathlib import Path

import click

from .._validate import ParameterError, json_safe
from ._common import _fail, _option, _output_option
from ._outputs import force_option


@click.command()
@_option("--size", default=512, help="Grid size n (hard wall).")
@_option("--seed", default=2014, help="Surface seed.")
@_option("--study-size", default=256, help="Grid size of the adhesive study (0: skip the study).")
@_option("--seeds", default=5, help="Study realisations.")
@_output_option(
    "Directory for the study's results, figures, report.md and study-report/report.html "
    "(resumed if present).",
    default="roughcontact-demo",
)
@force_option
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def demo(size, seed, study_size, seeds, output, as_json):
    """The main job on built-in defaults.

    \b
    1. A non-adhesive load path: A_rep/A0 against load and κ_rep at 1 % contact.
    2. An adhesive study (the paper's Figs. 1-4): κ, κ_rep, κ_att, A_rep/A_att and
       pull-off for adhesion lengths from non-sticky to sticky, against the theory, with
       figures and a Markdown report in --output.
    """
    from ..workflows.demo import demo_path as run

    if seeds < 1:  # checked before any work
        raise ParameterError(f"--seeds must be >= 1, got {seeds}")
    if study_size and study_size < 8:
        raise ParameterError(f"--study-size must be 0 (no study) or >= 8, got {study_size}")
    if study_size:
        from ..workflows.demo import check_demo_study
        from ._outputs import claim_output_directory

        check_demo_study(study_size, seeds)  # before the path is computed
        claim_output_directory(output)

    def progress(i, n, res):
        if not as_json:
            click.echo(
                f"  step {i}/{n}: N/A0 = {res.load:.3e}  A_rep/A0 = "
                f"{res.repulsive_area:.4f}  ({res.iterations} it, "
                f"{res.solve_seconds:.2f} s)",
                err=True,
            )

    out = run(size=size, seed=seed, progress=progress)
    study = None
    if study_size:
        from ..workflows.demo import run_demo_study

        study = run_demo_study(
            output,
            size=study_size,
            seeds=range(1, seeds + 1),
            progress=not as_json,
            hard_wall=out,
        )
        out["study"] = {k: v for k, v in study.items() if k != "table_markdown"}
    if as_json:
        click.echo(json.dumps(json_safe(out), default=lambda v: None, allow_nan=False))
        return
    from ..workflows.report import hard_wall_lines

    for line in hard_wall_lines(out):  # the same lines as report.md's first section
        click.echo(line)
    if study is not None:
        click.echo("\nAdhesive study (smoothed 9-3 LJ wall), measured at A_rep = 1 % of A0:")
        for line in study["table_markdown"]:
            click.echo(line)
        click.echo("")
        for line in study["summary"]:
            click.echo(f"* {line}")
        click.echo(f"report: {study['report']}  figures: {Path(study['report']).parent}/figures")
        click.echo(f"the study's report, one page to open or share: {study['report_html']}")
        if study["failed"]:
            _fail(f"{study['failed']} study tasks failed (see {output}/tasks)", 1)
