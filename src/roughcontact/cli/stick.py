"""``roughcontact stick SCAN``: is this measured surface sticky?

Pastewka & Robbins, PNAS 111, 3298 (2014), Eq. 10, evaluated from a topography file
(:func:`roughcontact.stick`): the statistics at the smallest reliable scale, their
self-affine extrapolation down to the atomic spacing, and the verdict with its
uncertainty. Values take units (``--modulus 10MPa --work-of-adhesion 50mJ/m^2``); plain
numbers are SI. Bad input is one line on stderr and exit code 2 (the ``roughcontact``
group turns :class:`roughcontact.ParameterError` into it).
"""

from __future__ import annotations

import json
import sys

import click

from .._validate import DPI, click_check
from ..topography.prepare import DETREND_MODES
from ..topography.simulate import ADHESION_RANGE_GIVEN, SEEDS, SIZE
from ._outputs import force_option

__all__ = ["stick"]


def _pixel_size(text):
    """``"10 nm"`` or ``"10nm,20nm"`` (one per axis), checked and passed on as text (a
    bare number is metres, and the library says so next to the result); None stays None."""
    if text is None:
        return None
    from ..criterion import parse_quantity

    parts = tuple(p.strip() for p in str(text).split(",") if p.strip())
    for p in parts:  # one-line errors naming the option; the library reads the text
        parse_quantity(p, "length", "--pixel-size")
    return parts[0] if len(parts) == 1 else parts


@click.command("stick")
@click.argument("scan", metavar="SCAN")
@click.option("--channel", default=None, help="Data channel of a multi-channel file.")
@click.option(
    "--modulus",
    required=True,
    help="Contact modulus E*, e.g. '10 MPa'; Young's modulus E with --poisson.",
)
@click.option("--work-of-adhesion", "work", required=True, help="w, e.g. '50 mJ/m^2'.")
@click.option(
    "--poisson", default=None, help="Poisson ratio: --modulus is then E, E* = E/(1-nu^2)."
)
@click.option(
    "--counter-modulus",
    default=None,
    help="The counter-surface's Young's modulus (with --counter-poisson) or E/(1-nu^2); "
    "default: rigid. 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2.",
)
@click.option("--counter-poisson", default=None, help="The counter-surface's Poisson ratio.")
@click.option(
    "--range", "range_", default="0.5 nm", show_default=True, help="Interaction range Δr."
)
@click.option("--tip-radius", default=None, help="Probe radius (reliability cutoff), e.g. '20 nm'.")
@click.option(
    "--reliability-cutoff",
    default=None,
    help="Shortest reliable wavelength, instead of --tip-radius, e.g. '50 nm' (then no "
    "search for a noise floor or resolution limit in the PSD).",
)
@click.option(
    "--detrend",
    type=click.Choice(DETREND_MODES),
    default="plane",
    show_default=True,
    help="What to remove before the analysis.",
)
@click.option(
    "--kappa-rep",
    type=float,
    default=2.0,
    show_default=True,
    help="Non-adhesive κ_rep (2: the paper's choice).",
)
@click.option(
    "--atomic-spacing",
    default="0.3 nm",
    show_default=True,
    help="a0: the smallest roughness scale of the extrapolation.",
)
@click.option(
    "--pixel-size",
    default=None,
    help="Grid spacing of a .npy/text file, e.g. '2 nm' (or 'X,Y' per axis); a bare "
    "number is metres (said in the output).",
)
@click.option(
    "--height-unit", default=None, help="Unit of a .npy/text file's heights (m, nm, ...)."
)
@click.option("--periodic", is_flag=True, help="The scan is one period of a periodic surface.")
@click.option(
    "--fill-missing/--no-fill-missing",
    default=None,
    help="Fill missing points of any fraction (harmonic interpolation) / refuse any. "
    "Default: fill up to 1 % of the scan, refuse more.",
)
@click.option(
    "--outliers",
    type=click.Choice(["remove", "keep"]),
    default="remove",
    show_default=True,
    help="Spikes, sentinel values and isolated pixels (a robust rule, counted in a note): "
    "remove them (filled like missing points) or keep them as heights.",
)
@click.option(
    "--fit-range",
    nargs=2,
    default=None,
    metavar="SHORT LONG",
    help="Wavelengths of the Hurst fit, e.g. '10nm 1um' (default: 4 pixels, the "
    "reliability cutoff or the instrument's limit found in the PSD, to a quarter of the scan).",
)
@click.option(
    "--hurst-sigmas",
    type=click.FloatRange(min=0),
    default=2.0,
    show_default=True,
    help="Half-width of the Hurst exponent's band in standard errors.",
)
@click.option(
    "-o",
    "--output",
    "out_dir",
    type=click.Path(file_okay=False),
    default=None,
    help="Report directory: report.html (one self-contained page), result.json, "
    "summary.txt and figures (created).",
)
@force_option
@click.option(
    "--format",
    "formats",
    multiple=True,
    default=("png",),
    show_default=True,
    type=click.Choice(["png", "pdf", "svg"]),
    help="Figure format with -o (repeatable).",
)
@click.option(
    "--dpi",
    type=int,
    default=150,
    show_default=True,
    help=f"PNG resolution with -o ({DPI.accepted}).",
)
@click.option(
    "--simulate",
    is_flag=True,
    help="Also run the paper's simulation on synthetic surfaces continuing the scan's "
    "spectrum to a0 (seconds to minutes; needs l_a/a0 = w/(E* a0) in "
    f"{ADHESION_RANGE_GIVEN.accepted[3:]}).",
)
@click.option(
    "--simulate-size",
    type=int,
    default=256,
    show_default=True,
    callback=click_check(SIZE),
    help=f"Sites per axis of the synthetic surfaces ({SIZE.accepted}).",
)
@click.option(
    "--simulate-seeds",
    type=int,
    default=3,
    show_default=True,
    callback=click_check(SEEDS),
    help=f"Number of synthetic surfaces ({SEEDS.accepted}).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units).")
def stick(scan, channel, modulus, work, poisson, counter_modulus, counter_poisson, range_,
          tip_radius, reliability_cutoff, detrend, kappa_rep, atomic_spacing, pixel_size,
          height_unit, periodic, fill_missing, outliers, fit_range, hurst_sigmas, out_dir,
          formats, dpi, simulate, simulate_size, simulate_seeds, as_json):  # fmt: skip
    """Is the surface in SCAN sticky? (Pastewka & Robbins 2014, Eq. 10.)

    SCAN is an instrument file (AFM, interferometer, stylus profilometer; read with
    SurfaceTopography), or a .npy/text file with --pixel-size. The rms slope and
    curvature are measured down to the reliability cutoff (--tip-radius; else the
    Nyquist wavelength, or the instrument's resolution limit or noise floor found in the
    PSD) and extrapolated with the Hurst exponent fitted above it down to
    --atomic-spacing. The verdict is "sticky" or "not sticky" when it holds for every
    smallest roughness scale in between (and every H within its uncertainty), else
    "depends on roughness below X". A spectrum that is not self-affine there (H outside
    (0, 1), or a poor fit) gets the verdict at the measured scale only. Every note is
    printed. Up to 1 % missing points are filled (said so); more need --fill-missing.
    The counter-surface is rigid unless --counter-modulus is given.

    --simulate adds the measured answer of Pastewka & Robbins' simulation: synthetic
    surfaces with the scan's H and its h'rms extrapolated to 4 a0, the paper's 9-3 wall
    with the --range asked for (its stiffness from w = k Δr²/12), kappa at 1 % contact
    over the seeds. It takes seconds (--simulate-size 64) to minutes (256, the default).
    """
    from ..topography.report import summary, write_report
    from ..topography.verdict import stick as run

    DPI.check("--dpi", dpi)  # checked when given, with or without -o
    if out_dir is not None:
        from ._outputs import claim_output_directory

        claim_output_directory(out_dir, scan)  # before the analysis
    result = run(
        scan,
        modulus=modulus,
        work_of_adhesion=work,
        interaction_range=range_,
        poisson=poisson,
        tip_radius=tip_radius,
        channel=channel,
        detrend=detrend,
        kappa_rep=kappa_rep,
        atomic_spacing=atomic_spacing,
        pixel_size=_pixel_size(pixel_size),
        height_unit=height_unit,
        periodic=periodic,
        reliability_cutoff=reliability_cutoff,
        fit_range=_fit_range(fit_range),
        hurst_sigmas=hurst_sigmas,
        simulate=simulate,
        simulate_size=simulate_size,
        simulate_seeds=simulate_seeds,
        simulate_progress=_progress if simulate and sys.stderr.isatty() else None,
        fill_missing=fill_missing,
        counter_modulus=counter_modulus,
        counter_poisson=counter_poisson,
        outliers=outliers,
    )
    if out_dir is not None:
        from ..htmlreport import command_line

        write_report(result, out_dir, formats=formats, dpi=dpi, command=command_line())
    if as_json:
        click.echo(json.dumps(result.to_dict(), allow_nan=False))
        return
    for line in summary(result):
        click.echo(line)
    if out_dir is not None:
        click.echo(f"report: {out_dir}")


def _progress(k, n):
    """One line per realisation on a terminal (stdout stays the result)."""
    click.echo(f"simulating surface {k}/{n} ...", err=True)


def _fit_range(values):
    if not values:
        return None
    from ..criterion import parse_quantity

    return tuple(parse_quantity(v, "length", "--fit-range") for v in values)
