"""``roughcontact figures DIR -o FIGDIR``: the paper's Figs. 1-4 from a study."""

from __future__ import annotations

from pathlib import Path

import click

from .._validate import DPI, TARGET_AREA, ParameterError
from ._common import _option, _output_option
from ._outputs import force_option


def _load(source: Path):
    """(collected dataset, contact-map paths) of a study directory or a collected .nc."""
    if source.is_dir():
        try:
            from ..studies.collect import collect_study
        except ImportError:  # pragma: no cover - studies without the collector
            raise ParameterError(
                f"{str(source)!r} is a directory but this roughcontact cannot collect "
                "studies; pass a collected .nc file"
            ) from None
        from ..plot import study_maps

        return collect_study(source), study_maps(source)
    from ..studies.collect import read_collected

    ds = read_collected(source)
    return ds, []


@click.command("figures")
@click.argument("source", metavar="DIR", type=click.Path(exists=True, path_type=Path))
@_output_option("Directory for the figure files (created).", "out_dir")
@force_option
@_option(
    "--format",
    "formats",
    multiple=True,
    default=("png", "pdf"),
    type=click.Choice(["png", "pdf", "svg"]),
    help="File format (repeatable).",
)
@_option(
    "--target-area",
    default=0.02,
    rng=TARGET_AREA,
    help="A_rep/A0 of the contact maps of Fig. 1 ({accepted}).",
)
@_option("--dpi", default=150, rng=DPI, help="PNG resolution (dots per inch, {accepted}).")
def figures(source, out_dir, formats, target_area, dpi):
    """Draw the paper's figures from DIR, a study directory or a collected .nc file.

    Fig. 2 (area against load with the fitted slopes κ_fit), Fig. 3 (collapse plots), Fig. 4
    (κ_att and A_rep/A_att against Eqs. 6-7) from the collected study; Fig. 1 (contact
    maps) when DIR is a study directory whose task files hold fields ([output] fields_at).
    """
    import matplotlib

    matplotlib.use("Agg")
    from ..plot import save_figures
    from ._outputs import claim_output_directory

    claim_output_directory(out_dir, source)  # before reading the study
    ds, maps = _load(source)
    written = save_figures(ds, out_dir, formats, maps=maps, dpi=dpi, target_area=target_area)
    for paths in written.values():
        for path in paths:
            click.echo(str(path))
    if "fig1_contact_maps" not in written:
        click.echo(
            "note: Fig. 1 (contact maps) not made: "
            + (
                "no task file holds pressure/gap fields (set [output] fields_at = [...])"
                if source.is_dir()
                else "a collected .nc holds no contact maps; pass the study directory"
            ),
            err=True,
        )
