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
@click.option(
    "--length-scale",
    default=None,
    callback=lambda ctx, param, value: _scale(value, "length", "--length-scale"),
    help="Metres per the path's length unit, e.g. '0.3 nm' (a lattice path of a0 = 0.3 nm); "
    "default 1 m for a path whose length_unit attribute is m (computed from an instrument "
    "file), else none. With --pressure-scale: the dissipated energy in J/m^2 and J.",
)
@click.option(
    "--pressure-scale",
    default=None,
    callback=lambda ctx, param, value: _scale(value, "pressure", "--pressure-scale"),
    help="Pascals per the path's pressure unit, e.g. '10 MPa' (a lattice path, E* = 1, of "
    "E* = 10 MPa) or '1 Pa' (--modulus was given in Pa).",
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
    length_scale=None,
    pressure_scale=None,
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
    jumps and energy_per_jump: the whole approach–retraction cycle's hysteresis. With
    --pressure-scale (and --length-scale, or a path of an instrument file, in metres) also
    in SI: dissipated_energy_si and dissipated_energy_bound_si [J/m^2],
    dissipated_energy_joules [J over the path's nominal area A0, nominal_area_si m^2] and
    energy_per_jump_joules [J]; si_scales says where the scales come from.
    Exit code 3 if the steps around the target area did not converge (unless
    --allow-unconverged), 2 on bad input.
    """
    from ..analysis.path_analysis import UnconvergedPathError, analyze_path, load_path

    if hysteresis_figure is not None:  # before any work: a device, the input, a bad suffix
        _figure_format(hysteresis_figure)
        from .._io import check_writable

        check_writable(hysteresis_figure, "--hysteresis-figure", inputs=(path_file,))
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
    summary.update(_si_energies(ds, length_scale, pressure_scale))
    if hysteresis_figure is not None:
        from ..plot.hysteresis import hysteresis_figure as _figure

        _save_figure(_figure(ds), hysteresis_figure)
    for message in summary["warnings"]:
        click.echo(f"roughcontact: warning: {message}", err=True)
    if as_json:
        click.echo(json.dumps(json_safe(summary), allow_nan=False))
    else:
        cycle = (
            "the whole cycle" if summary.get("cycle_closed") is not False
            else "the path, which is NOT a closed cycle (cycle_closed: False; see the note)"
        )  # fmt: skip
        click.echo(
            "units: areas per A0, loads N/A0 in units of E*, lengths (d_rep, band_width, "
            "offset) in the path's length unit; kappa = h'rms E* A_rep/N at the target area, "
            f"kappa_fit = the slope of A_rep(N); dissipated_energy = -∮N dd per A0 over {cycle}"
            " (load unit × length unit); *_si in J/m^2, *_joules in J over A0"
        )
        for message in summary["warnings"]:  # on stdout too: the text is the result
            if message.startswith("the cycle is not closed"):
                click.echo(f"note: {message}")
        for k, v in summary.items():
            if k != "warnings":
                click.echo(f"{k:>34}: {v}")


def _si_energies(ds, length_scale, pressure_scale) -> dict:
    """The cycle's dissipated energy in SI (J/m², J over A0), or why it is not given."""
    from .._validate import positive
    from ..analysis.hysteresis import hysteresis, hysteresis_in_si
    from ..criterion import parse_quantity

    keys = ("dissipated_energy_si", "dissipated_energy_bound_si", "dissipated_energy_joules",
            "energy_per_jump_joules", "nominal_area_si")  # fmt: skip
    source = "given"
    unit = _length_unit(ds)
    if length_scale is not None:
        ls = positive("--length-scale", parse_quantity(length_scale, "length", "--length-scale"))
    elif unit == "m":
        ls, source = 1.0, "the path's lengths are metres (its length_unit attribute)"
    else:
        ls = None
    if pressure_scale is None or ls is None:
        given = (("--pressure-scale", pressure_scale), ("--length-scale", ls))
        why = "not in SI: give " + " and ".join(o for o, v in given if v is None)
        if ls is None and unit is None:
            stored = (
                "the path's length unit is unknown: the file stores none (written by an "
                "older roughcontact or the library)"
            )
        elif ls is None:
            stored = f"the path's lengths are in units of its pixel size a0 (length_unit {unit!r})"
        else:
            stored = "the path stores no pressure unit"
        return {**dict.fromkeys(keys), "si_scales": f"{why} ({stored})"}
    ps = positive(
        "--pressure-scale", parse_quantity(pressure_scale, "pressure", "--pressure-scale")
    )
    si = hysteresis_in_si(hysteresis(ds), length_scale=ls, pressure_scale=ps,
                          nominal_area=float(ds.attrs["nominal_area"]))  # fmt: skip
    return {
        "dissipated_energy_si": si["dissipated_energy_per_area"],
        "dissipated_energy_bound_si": si["energy_uncertainty_per_area"],
        "dissipated_energy_joules": si["dissipated_energy"],
        "energy_per_jump_joules": si["energy_per_jump"],
        "nominal_area_si": si["nominal_area"],
        "si_scales": f"length unit = {ls:.6g} m ({source}), pressure unit = {ps:.6g} Pa (given)",
    }


def _length_unit(ds):
    """The path's length unit as stored (``length_unit``: "m" or "a0"), or None if the file
    says nothing (it is never guessed from files that happen to be around)."""
    unit = ds.attrs.get("length_unit")
    return str(unit) if unit not in (None, "") else None


def _scale(value, kind: str, option: str):
    """``value`` of --length-scale/--pressure-scale checked when given (a positive,
    finite quantity of ``kind``, e.g. '10 MPa'), whether or not it is used; kept as given."""
    if value is None:
        return None
    from .._validate import positive
    from ..criterion import parse_quantity

    positive(option, parse_quantity(value, kind, option))
    return value


def _figure_format(name) -> str:
    """The matplotlib format of the file ``name`` by its suffix (none: png)."""
    from pathlib import Path

    from .._validate import ParameterError

    fmt = Path(str(name)).suffix[1:].lower() or "png"
    if fmt not in ("png", "pdf", "svg", "eps", "ps", "jpg", "jpeg", "tif", "tiff", "webp"):
        raise ParameterError(
            f"--hysteresis-figure {str(name)!r}: unknown figure format {fmt!r}; name a .png, "
            ".pdf or .svg file"
        )
    return fmt


def _save_figure(fig, name) -> None:
    """Render ``fig`` in memory and write it with the one writer (atomic, checked)."""
    import io

    from .._io import write_bytes_atomic

    buffer = io.BytesIO()
    fig.savefig(buffer, format=_figure_format(name), dpi=150)
    write_bytes_atomic(name, buffer.getvalue())
