"""``roughcontact study run|collect``: parameter studies on Dask, one combined NetCDF."""

from __future__ import annotations

import sys

import click

from ._common import _option, _output_option
from ._outputs import claim_output_directory, force_option

EXIT_TASKS_FAILED = 1


@click.group("study")
def study():
    """Run a parameter study (TOML) on Dask and collect its results."""


@study.command("run")
@click.argument("study_file", metavar="STUDY.toml", type=click.Path(dir_okay=False))
@_output_option(
    "Study directory: one NetCDF file per task, the manifest, failure records.", "out_dir"
)
@click.option("--resume", is_flag=True, help="Continue a study: skip finished tasks.")
@click.option(
    "--scheduler",
    default=None,
    metavar="ADDRESS",
    help="Run on an existing Dask cluster (tcp://host:8786, tls://host:8786) instead of a "
    "local one.",
)
@click.option(
    "--tls-ca-file",
    default=None,
    metavar="PEM",
    help="CA certificate of a tls:// --scheduler (with --tls-cert; default: Dask's config "
    "distributed.comm.tls.*).",
)
@click.option(
    "--tls-cert",
    default=None,
    metavar="PEM",
    help="This client's certificate for a tls:// --scheduler (may hold the key too).",
)
@click.option(
    "--tls-key",
    default=None,
    metavar="PEM",
    help="This client's private key for a tls:// --scheduler, if not in --tls-cert.",
)
@click.option(
    "--workers",
    type=int,
    default=None,
    help="Worker processes of the local cluster (default: the CPU cores).",
)
@click.option("--no-progress", is_flag=True, help="No progress bar.")
@click.option(
    "--device",
    default=None,
    help="Where the workers compute: cpu (default), cuda or cuda:N (the compiled JAX loops "
    "on an NVIDIA GPU; pip install 'jax[cuda12]'). cuda on the local cluster: one worker "
    "per visible GPU (CUDA_VISIBLE_DEVICES, else nvidia-smi), each pinned to its own; "
    "cuda:N: every worker on GPU N.",
)
@click.option(
    "--dashboard",
    is_flag=True,
    help="Open the local cluster's Dask dashboard on 127.0.0.1:8787 (plain HTTP, readable "
    "by any local user; default: no HTTP port).",
)
def run(
    study_file,
    out_dir,
    resume,
    scheduler,
    tls_ca_file,
    tls_cert,
    tls_key,
    workers,
    no_progress,
    device,
    dashboard,
):
    """Run every task of STUDY.toml; store each result in the -o directory as it finishes.

    The local cluster talks TLS with temporary credentials (no other process can connect
    to it) and opens no HTTP port unless --dashboard. A tls:// --scheduler is reached
    with --tls-ca-file/--tls-cert/--tls-key or Dask's configuration.

    Exit code 0 when all tasks finished (steps that did not converge are reported in
    the summary, not counted as failures), 1 if any task failed, 2 on bad input.
    """
    from ..studies import load_study, run_study
    from ..studies.cluster import check_options, tls_security

    spec = load_study(study_file)  # validated before anything starts
    security = tls_security(tls_ca_file, tls_cert, tls_key)
    check_options(scheduler, workers, security, dashboard)  # --workers too: before any output
    if not no_progress:
        click.echo(f"study {spec.name!r}: {len(spec.tasks)} tasks -> {out_dir}", err=True)
    summary = run_study(
        spec,
        out_dir,
        resume=resume,
        scheduler=scheduler,
        workers=workers,
        progress=not no_progress,
        device=device,
        security=security,
        dashboard=dashboard,
    )
    click.echo(str(summary))
    if not summary.ok:
        sys.exit(EXIT_TASKS_FAILED)


@study.command("collect")
@click.argument("out_dir", metavar="DIR", type=click.Path(file_okay=False))
@_output_option("NetCDF file for the combined dataset (task x step).", file=True)
@click.option("--no-timings", is_flag=True, help="Leave out wall-clock times (reproducible files).")
def collect(out_dir, output, no_timings):
    """Combine the task files of study directory DIR into one NetCDF file."""
    from .._io import check_writable, write_netcdf_atomic
    from ..studies import collect_study
    from ..studies.store import check_not_study_file

    check_not_study_file(out_dir, output, "-o/--output")  # a task file, study.json, ...
    check_writable(output, "-o/--output")  # before reading every task file
    ds = collect_study(out_dir, include_timings=not no_timings)
    write_netcdf_atomic(ds, output)  # a full disk: one line, exit 1, no file half-written
    click.echo(
        f"{ds.sizes['task']} tasks ({ds.attrs['tasks_done']} done, "
        f"{ds.attrs['tasks_failed']} failed, {ds.attrs['tasks_missing']} missing), "
        f"{ds.sizes['step']} steps -> {output}"
    )


@study.command("report")
@click.argument("source", metavar="DIR|COLLECTED.nc", type=click.Path(exists=True))
@_output_option(
    "Report directory: README.md, report.html, claims.json, versions.json, data/, figures/.",
    "out_dir",
)
@force_option
@_option("--confidence", default=0.95, help="Level of the intervals over seeds, in (0, 1).")
@_option("--dpi", default=120, help="Figure resolution.")
def report(source, out_dir, confidence, dpi):
    """Check the paper's claims on a study: data, figures and a Markdown report.

    SOURCE is a study directory or its collected NetCDF file. Writes into the -o
    directory only: data/collected.nc and data/{tasks,steps,parameter_sets}.csv (per task
    and per step scalars, no field maps), claims.json (every number of the report),
    versions.json, figures/fig2-4 (PNG) and README.md, which takes the claims of
    Pastewka & Robbins (2014) one by one and puts the study's numbers beside them.
    """
    from .._validate import DPI
    from ..studies.report import write_report

    if not 0 < confidence < 1:
        raise click.BadParameter(
            f"must be in (0, 1), got {confidence!r}", param_hint="--confidence"
        )
    DPI.check("dpi", dpi)
    claim_output_directory(out_dir, source)  # before reading the study
    from ..htmlreport import command_line

    result = write_report(source, out_dir, confidence=confidence, dpi=dpi, command=command_line())
    c = result["claims"]
    crit = c["eq10_criterion"]["measured_kappa_rep"]
    click.echo(
        f"{c['eq3_linearity']['tasks']} analysed tasks; Eq. 10 agrees in {crit['agree']} of "
        f"{crit['decided']} decided parameter sets -> {out_dir}/README.md, {out_dir}/report.html"
    )
