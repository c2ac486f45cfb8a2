"""``roughcontact analyze PATH.nc``: the paper's analysis of a load path."""

from __future__ import annotations

import json
import sys

import click

from .._validate import FIT_MAX_AREA, TARGET_AREA, click_check, json_safe


@click.command("analyze")
@click.argument("path_file", metavar="PATH.nc", type=click.Path(dir_okay=False))
@click.option(
    "--target-area",
    type=float,
    default=0.01,
    show_default=True,
    callback=click_check(TARGET_AREA),
    help=f"A_rep/A0 at which κ, κ_rep, κ_att are measured, {TARGET_AREA.accepted} (the "
    "paper: 1 %).",
)
@click.option(
    "--branch",
    type=click.Choice(["approach", "retract"]),
    default="approach",
    show_default=True,
    help="Branch of the path to analyse.",
)
@click.option(
    "--fit-max-area",
    type=float,
    default=0.05,
    show_default=True,
    callback=click_check(FIT_MAX_AREA),
    help=f"Largest A_rep/A0 in the linear fit of A_rep against N, {FIT_MAX_AREA.accepted}.",
)
@click.option(
    "--allow-unconverged",
    is_flag=True,
    help="Interpolate across unconverged steps anyway (the result says reliable: false).",
)
@click.option(
    "--hard-wall-reference/--no-hard-wall-reference",
    default=True,
    show_default=True,
    help="Also solve the hard wall on the same surface (kappa_rep_hard_wall, band_width).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option(
    "--hysteresis-figure",
    type=click.Path(dir_okay=False),
    default=None,
    help="Also save the load-approach cycle with its dissipated energy (PNG/PDF by suffix).",
)
def analyze(
    path_file,
    target_area,
    branch,
    fit_max_area,
    allow_unconverged,
    hard_wall_reference,
    as_json,
    hysteresis_figure=None,
):
    """Measure κ, κ_rep, κ_att, A_rep/A_att, d_rep and pull-off on a path, next to theory.

    Areas and loads per A0 (loads in units of E*), lengths in the path's units; non-finite
    values (no attraction, no pull-off) print as null. ``kappa`` is the ratio
    h'rms E* A_rep/N at the target area, ``kappa_fit`` the slope of A_rep(N): two
    quantities. ``sticky``/``verdict``: κ < 0 at the target area (the pull-off force is
    reported beside it). The predicted_* keys are Pastewka & Robbins' Eqs. 6, 7 and 10
    for the path's surface and interaction (with the measured κ_rep and d_rep;
    ``*_from_curvature``: d_rep = 4h'/h''; ``*_continuum``: κ_rep = 2).
    kappa_rep_hard_wall(_corrected) and band_width: the hard wall on the same surface.
    dissipated_energy (-∮N dd per A0, pressure × length in the path's units; NaN without
    a retraction), dissipated_energy_bound (the trapezoid's bound over the jump steps),
    jumps and energy_per_jump: the whole approach–retraction cycle's hysteresis.
    Exit code 3 if the steps around the target area did not converge (unless
    --allow-unconverged), 2 on bad input.
    """
    from ..analysis.path_analysis import UnconvergedPathError, analyze_path, load_path

    ds = load_path(path_file)
    try:
        result = analyze_path(
            ds,
            target_area=target_area,
            branch=branch,
            fit_max_area=fit_max_area,
            allow_unconverged=allow_unconverged,
            hard_wall_reference=hard_wall_reference,
        )
    except UnconvergedPathError as err:
        click.echo(f"roughcontact: error: {err}", err=True)
        sys.exit(3)
    summary = result.to_dict()
    if hysteresis_figure is not None:
        from ..plot.hysteresis import hysteresis_figure as _figure

        _figure(ds).savefig(hysteresis_figure, dpi=150)
    for message in summary["warnings"]:
        click.echo(f"roughcontact: warning: {message}", err=True)
    if as_json:
        click.echo(json.dumps(json_safe(summary), allow_nan=False))
    else:
        click.echo(
            "units: areas per A0, loads N/A0 in units of E*, lengths (d_rep, band_width, "
            "offset) in the path's length unit; kappa = h'rms E* A_rep/N at the target area, "
            "kappa_fit = the slope of A_rep(N); dissipated_energy = -∮N dd per A0 over the "
            "whole cycle (load unit × length unit)"
        )
        for k, v in summary.items():
            if k != "warnings":
                click.echo(f"{k:>34}: {v}")
