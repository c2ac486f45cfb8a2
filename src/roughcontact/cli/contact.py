"""``roughcontact contact SURFACE``: one contact state under a load or an offset."""

from __future__ import annotations

import click

from .._validate import ParameterError
from ._common import (
    EXIT_NOT_CONVERGED,
    _describe_surface,
    _fail,
    _interaction_options,
    _json,
    _line,
    _load_surface,
    _make_interaction,
    _substrate,
    _substrate_options,
    _surface_file_options,
    _units,
)
from ._outputs import check_fields_file, save_fields_file


@click.command()
@click.argument("surface_file", metavar="SURFACE", type=click.Path(dir_okay=False))
@click.option("--load", type=float, default=None, help="Mean pressure N/A0 (units of E*).")
@click.option("--offset", type=float, default=None, help="Offset d of the rigid surface.")
@_substrate_options
@_interaction_options
@click.option(
    "--save-fields",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write pressure, gap and deflection to this .npz file (the name must end in .npz).",
)
@_surface_file_options
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def contact(
    surface_file,
    load,
    offset,
    modulus,
    pixel_size,
    thickness,
    poisson,
    base,
    non_periodic,
    tol,
    max_iter,
    device,
    dtype,
    interaction,
    work,
    adhesion_length,
    range_,
    stiffness,
    core_stiffness,
    save_fields,
    channel,
    detrend,
    fill_missing,
    as_json,
):
    """Solve one contact state of SURFACE under --load or --offset.

    Exit code 3 if the solver did not converge, 2 on bad input.
    """
    from ..solvers import solve

    if (load is None) == (offset is None):
        raise ParameterError("give exactly one of --load or --offset")
    if save_fields is not None:
        check_fields_file(save_fields)
    h, pixel_size, surface = _load_surface(surface_file, channel, detrend, fill_missing, pixel_size)
    if non_periodic and min(h.shape) < 3:  # as path and the statistics refuse it
        raise ParameterError(
            f"heights must be at least 3 x 3 points for --non-periodic, got {h.shape}"
        )
    sub = _substrate(h.shape, modulus, pixel_size, thickness, poisson, base, not non_periodic)
    law = _make_interaction(
        interaction, work, range_, stiffness, core_stiffness, modulus, pixel_size, adhesion_length
    )
    res = solve(
        h, sub, law, load=load, offset=offset, tol=tol, max_iter=max_iter, device=device,
        dtype=dtype,
    )  # fmt: skip
    if save_fields:
        save_fields_file(save_fields, res)
    summary = res.summary()
    summary["periodic"] = sub.periodic  # False: a free boundary (--non-periodic)
    if surface is not None:
        summary["surface"] = surface  # instrument files: what was read, in which units
    if as_json:
        click.echo(_json(summary))
    else:
        units = _units(modulus, pixel_size, surface)
        for k, v in summary.items():
            v = _describe_surface(v) if k == "surface" else v
            click.echo(_line(k, v, units.get(k), 16))
    if not res.converged:
        _fail(
            f"solver did not converge: {res.message} "
            f"(residual {res.residual:.3g} > tol {res.tol:g})",
            EXIT_NOT_CONVERGED,
        )
