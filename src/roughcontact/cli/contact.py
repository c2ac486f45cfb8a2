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
    _substrate_options,
    _surface_file_options,
    _surface_substrate_law,
    _units,
)
from ._outputs import check_fields_file, save_fields_file


@click.command()
@click.argument("surface_file", metavar="SURFACE", type=click.Path(dir_okay=False))
@click.option(
    "--load",
    type=float,
    default=None,
    help="Mean pressure N/A0, in the units of --modulus (lattice units, E* = 1, by default).",
)
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
def contact(surface_file, load, offset, save_fields, as_json, **options):
    """Solve one contact state of SURFACE under --load or --offset.

    Exit code 3 if the solver did not converge, 2 on bad input.
    """
    from ..solvers import solve

    if (load is None) == (offset is None):
        raise ParameterError("give exactly one of --load or --offset")
    if save_fields is not None:
        check_fields_file(save_fields, surface_file)
    h, pixel_size, surface, sub, law = _surface_substrate_law(surface_file, options)
    o = options
    res = solve(
        h, sub, law, load=load, offset=offset, tol=o["tol"], max_iter=o["max_iter"],
        device=o["device"], dtype=o["dtype"],
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
        units = _units(o["modulus"], pixel_size, surface)
        for k, v in summary.items():
            v = _describe_surface(v) if k == "surface" else v
            click.echo(_line(k, v, units.get(k), 16))
    if not res.converged:
        _fail(
            f"solver did not converge: {res.message} "
            f"(residual {res.residual:.3g} > tol {res.tol:g})",
            EXIT_NOT_CONVERGED,
        )
