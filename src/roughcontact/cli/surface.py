"""``roughcontact surface OUT``: generate a self-affine surface and print its statistics."""

from __future__ import annotations

import click

from .._io import check_writable
from .._validate import GRID_SIZE, SEED, ParameterError
from ._common import _json, _option, _pixel_size_option


@click.command()
@click.argument("out", type=click.Path(dir_okay=False))
@_option(
    "--size",
    required=True,
    rng=GRID_SIZE,
    help="Grid size n (n x n sites; at most what fits in memory).",
)
@_option("--size-y", rng=GRID_SIZE, help="Second grid size (default: --size).")
@click.option("--hurst", type=float, required=True, help="Hurst exponent H in (0, 1].")
@click.option("--rms-slope", type=float, default=None, help="rms slope h'rms (spectral).")
@click.option("--rms-height", type=float, default=None, help="rms height (length).")
@click.option("--short-cutoff", type=float, required=True, help="λs (length, >= 2 a0).")
@click.option("--long-cutoff", type=float, default=None, help="λL (length; default L/2).")
@click.option("--no-rolloff", is_flag=True, help="Zero power below 2π/λL instead of flat.")
@_option("--seed", rng=SEED, help="Random seed (reproducible; {accepted}).")
@_pixel_size_option()
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def surface(
    out,
    size,
    size_y,
    hurst,
    rms_slope,
    rms_height,
    short_cutoff,
    long_cutoff,
    no_rolloff,
    seed,
    pixel_size,
    as_json,
):
    """Generate a self-affine surface, write it to OUT (.npy or text), print statistics.

    The statistics include max_height and min_height (length) of the heights written.
    """
    from ..surfaces import save_heights, self_affine, statistics

    if (rms_slope is None) == (rms_height is None):
        raise ParameterError("give exactly one of --rms-slope or --rms-height")
    check_writable(out, "OUT")  # before any work: a missing or read-only directory
    h = self_affine(
        (size, size_y or size),
        hurst=hurst,
        rms_slope=rms_slope,
        rms_height=rms_height,
        short_cutoff=short_cutoff,
        long_cutoff=long_cutoff,
        rolloff=not no_rolloff,
        pixel_size=pixel_size,
        seed=seed,
    )
    path = save_heights(out, h)
    stats = statistics(h, pixel_size=pixel_size).to_dict()
    stats["max_height"] = float(h.max())  # length: the summit, first contact at d = max(h)
    stats["min_height"] = float(h.min())
    stats["path"] = str(path)
    stats["shape"] = list(h.shape)
    if as_json:
        click.echo(_json(stats))
    else:
        for k, v in stats.items():
            click.echo(f"{k:>18}: {v}")
