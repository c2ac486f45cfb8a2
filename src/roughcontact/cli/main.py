"""``roughcontact`` command line. Lattice units by default (a0 = 1, E* = 1); loads are
mean pressures N/A0 in units of the contact modulus."""

from __future__ import annotations

import json
import math
import sys
import warnings
from pathlib import Path

import click

from .._io import WriteError, check_writable
from .._signals import EXIT_TERMINATED, deferred, exit_code, interruptible
from .._validate import (
    GRID_SIZE,
    MAX_ITER,
    MAX_PATH_STEPS,
    PIXEL_SIZE,
    SEED,
    TOL,
    ParameterError,
    click_check,
    json_safe,
)
from ..interactions.registry import make_law
from ..interactions.registry import names as interaction_names
from ._outputs import check_fields_file, save_fields_file

EXIT_BAD_INPUT = 2
EXIT_NOT_CONVERGED = 3
EXIT_TARGET_NOT_REACHED = 4
EXIT_FAILURE = 1  # a step, a task or a write failed (a full disk): nothing finished is lost


def _interrupted(err) -> str:
    """The one-line message of a command stopped by Ctrl-C or SIGTERM."""
    why = "terminated (SIGTERM)" if exit_code(err) == EXIT_TERMINATED else "interrupted (Ctrl-C)"
    text = str(err).strip()
    return text if text.startswith(why) else f"{why}: {text}" if text else why


def _fail(message: str, code: int = EXIT_BAD_INPUT):
    message = " ".join(str(message).split())  # one line, whatever the message holds
    click.echo(f"roughcontact: error: {message}", err=True)
    sys.exit(code)


def _warning_line(message, category, filename, lineno, file=None, line=None):
    """A warning as one line on stderr (not Python's two, with the source line)."""
    text = " ".join(str(message).split())
    click.echo(f"roughcontact: warning: {text}", err=True)


def _json(obj) -> str:
    """One JSON object: NaN and infinities become null (JSON has neither)."""
    return json.dumps(json_safe(obj), allow_nan=False)


class _Group(click.Group):
    """Turns our parameter errors into one readable line and a non-zero exit code."""

    def invoke(self, ctx):
        try:
            # SIGTERM stops a command as Ctrl-C does (exit 143, 130); warnings in one line
            with interruptible(), warnings.catch_warnings():
                warnings.showwarning = _warning_line
                return super().invoke(ctx)
        except ParameterError as err:
            _fail(str(err))
        except click.UsageError as err:  # click's own parsing: one line too, with --help's hint
            where = f"{err.ctx.command_path}: " if err.ctx is not None else ""
            _fail(f"{where}{err.format_message()} (see --help)")
        except WriteError as err:  # a full disk: one line, what was finished is intact
            _fail(str(err), EXIT_FAILURE)
        except OSError as err:
            _fail(str(err))
        except KeyboardInterrupt as err:
            _fail(_interrupted(err), exit_code(err))


def _interaction_options(f):
    opts = [
        click.option(
            "--interaction",
            type=click.Choice(INTERACTIONS),
            default="hardwall",
            show_default=True,
            help="Surface interaction law.",
        ),
        click.option(
            "--work-of-adhesion",
            "work",
            type=float,
            default=None,
            help="w (energy per area, units of E* x length).",
        ),
        click.option(
            "--adhesion-length",
            "adhesion_length",
            type=float,
            default=None,
            help="ℓa = w/E* (length, > 0): w = ℓa x --modulus; instead of --work-of-adhesion.",
        ),
        click.option(
            "--range",
            "range_",
            type=float,
            default=None,
            help="Δr (lj93smooth), ρ (exponential), cohesive width (dugdale).",
        ),
        click.option(
            "--stiffness",
            type=float,
            default=None,
            help="lj93smooth site stiffness per area k = V''(a0) (default E*/(2 a0)).",
        ),
        click.option(
            "--core-stiffness",
            type=float,
            default=None,
            help="exponential: soft repulsive core k_c for g < 0 (default: hard wall).",
        ),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


INTERACTIONS = list(interaction_names())  # hardwall, lj93smooth, lj93, exponential, dugdale


def _make_interaction(
    name, work, range_, stiffness, core_stiffness, modulus, pixel_size, adhesion_length=None
):
    """The law of the ``--interaction`` options (checked and built by the registry)."""
    return make_law(
        name,
        contact_modulus=modulus,
        pixel_size=pixel_size,
        spelling="cli",
        adhesion_length=adhesion_length,
        work_of_adhesion=work,
        range=range_,
        stiffness=stiffness,
        core_stiffness=core_stiffness,
    )


def _substrate(shape, modulus, pixel_size, thickness, poisson, base, periodic=True):
    from ..elastic import Substrate

    return Substrate(
        shape,
        contact_modulus=modulus,
        pixel_size=pixel_size,
        thickness=thickness,
        poisson=poisson,
        base=base,
        periodic=periodic,
    )


def _substrate_options(f):
    opts = [
        click.option(
            "--modulus",
            type=float,
            default=1.0,
            show_default=True,
            help="Contact modulus E* = E/(1-ν²).",
        ),
        click.option(
            "--pixel-size",
            type=float,
            default=1.0,
            show_default=True,
            callback=click_check(PIXEL_SIZE),
            help=f"a0 (length, {PIXEL_SIZE.accepted}).",
        ),
        click.option(
            "--thickness", type=float, default=None, help="Layer thickness (default: half-space)."
        ),
        click.option(
            "--poisson",
            type=float,
            default=0.5,
            show_default=True,
            help="ν in [0, 0.5] (layers only).",
        ),
        click.option(
            "--base",
            type=click.Choice(["bonded", "frictionless"]),
            default="bonded",
            show_default=True,
            help="Layer attachment to its rigid base.",
        ),
        click.option(
            "--non-periodic",
            "non_periodic",
            is_flag=True,
            default=False,
            help="Free boundary: press the surface as measured, without periodic images "
            "(a half-space on a zero-padded grid; not with --thickness).",
        ),
        click.option(
            "--tol",
            type=float,
            default=None,
            callback=click_check(TOL),
            help=f"Solver tolerance, {TOL.accepted} (default 1e-8; 1e-6, its floor, with "
            "--dtype float32).",
        ),
        click.option(
            "--max-iter",
            type=int,
            default=5000,
            show_default=True,
            callback=click_check(MAX_ITER),
            help=f"Iteration cap per state ({MAX_ITER.accepted}).",
        ),
        click.option(
            "--device",
            default="cpu",
            show_default=True,
            help="Where to compute: cpu, cuda or cuda:N (an NVIDIA GPU through CuPy).",
        ),
        click.option(
            "--dtype",
            type=click.Choice(["float64", "float32"]),
            default="float64",
            show_default=True,
            help="Floating-point precision of the computation.",
        ),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def _surface_file_options(f):
    """--channel, --detrend and --fill-missing of the commands that read a SURFACE file."""
    opts = [
        click.option(
            "--channel",
            default=None,
            help="Channel of an instrument file, by name or index (default: the file's "
            "default channel).",
        ),
        click.option(
            "--detrend",
            type=click.Choice(["none", "height", "plane", "curvature"]),
            default="none",
            show_default=True,
            help="Least-squares mean, tilt or 2nd-order polynomial removed from SURFACE.",
        ),
        click.option(
            "--fill-missing/--no-fill-missing",
            default=None,
            help="Fill missing points of an instrument file of any fraction (harmonic "
            "interpolation) / refuse any. Default: fill up to 1 % (said on stderr), refuse more.",
        ),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="roughcontact")
def main():
    """Contact of rough elastic surfaces with adhesion (Pastewka & Robbins, PNAS 2014)."""


@main.command()
@click.argument("out", type=click.Path(dir_okay=False))
@click.option(
    "--size",
    type=int,
    required=True,
    callback=click_check(GRID_SIZE),
    help="Grid size n (n x n sites; at most what fits in memory).",
)
@click.option(
    "--size-y",
    type=int,
    default=None,
    callback=click_check(GRID_SIZE),
    help="Second grid size (default: --size).",
)
@click.option("--hurst", type=float, required=True, help="Hurst exponent H in (0, 1].")
@click.option("--rms-slope", type=float, default=None, help="rms slope h'rms (spectral).")
@click.option("--rms-height", type=float, default=None, help="rms height (length).")
@click.option("--short-cutoff", type=float, required=True, help="λs (length, >= 2 a0).")
@click.option("--long-cutoff", type=float, default=None, help="λL (length; default L/2).")
@click.option("--no-rolloff", is_flag=True, help="Zero power below 2π/λL instead of flat.")
@click.option(
    "--seed",
    type=int,
    default=None,
    callback=click_check(SEED),
    help=f"Random seed (reproducible; {SEED.accepted}).",
)
@click.option(
    "--pixel-size",
    type=float,
    default=1.0,
    show_default=True,
    callback=click_check(PIXEL_SIZE),
    help=f"a0 (length, {PIXEL_SIZE.accepted}).",
)
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


@main.command()
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


def _load_surface(surface_file, channel, detrend, fill_missing, pixel_size):
    """Heights, pixel size and (instrument files) a summary dict of SURFACE.

    A .npy or text file is read as always, in the length unit of --pixel-size (summary
    None). An instrument file (AFM, interferometer, ...: anything else) is read through
    SurfaceTopography in metres with the file's own pixel size, which wins: a
    --pixel-size given that differs from it is a one-line error.
    """
    import numpy as np

    from .._plausibility import check_heights
    from ..surfaces import load_heights
    from ..topography import Topography, file_kind, load_topography
    from ..topography import detrend as remove_trend

    if file_kind(surface_file) != "instrument":
        try:
            h = load_heights(surface_file, channel=channel)
        except ParameterError as err:  # NaN points: the missing-data policy of every reader
            if "found NaN" not in str(err):
                raise
            h = np.array(_filled(load_topography(surface_file, fill_missing=fill_missing)).heights)
            if h.ndim != 2:
                raise ParameterError(f"{err} (and a line scan: expected a 2D height map)") from None
        if detrend != "none":
            h = np.array(remove_trend(Topography(h, pixel_size), detrend).heights)
        check_heights(h, f"SURFACE {str(surface_file)!r}")  # a flat surface: no contact path
        return h, pixel_size, None
    topo = _filled(load_topography(surface_file, channel=channel, fill_missing=fill_missing))
    if topo.dim != 2:
        raise ParameterError(
            f"SURFACE {str(surface_file)!r} is a line scan of {topo.shape[0]} points; "
            "expected a 2D height map"
        )
    px = topo.pixel_size[0]
    if not math.isclose(px, topo.pixel_size[1], rel_tol=1e-9):
        raise ParameterError(
            f"SURFACE {str(surface_file)!r} has non-square pixels {topo.pixel_size} m; "
            "accepted: square pixels"
        )
    source = click.get_current_context().get_parameter_source("pixel_size")
    if source is not click.core.ParameterSource.DEFAULT and not math.isclose(
        pixel_size, px, rel_tol=1e-6
    ):
        raise ParameterError(
            f"--pixel-size {pixel_size:g} conflicts with the pixel size {px:.6g} m stored in "
            f"{str(surface_file)!r}; leave --pixel-size out (instrument files: lengths in m)"
        )
    topo = remove_trend(topo, detrend)
    return np.array(topo.heights), px, topo.to_dict()


def _filled(topo):
    """``topo``, after saying on stderr what was filled (the line every scan reader prints)."""
    if topo.info.get("missing_data"):
        from ..topography.missing import fill_note

        click.echo(f"note: {fill_note(topo.info['missing_data'], topo.heights.size)}", err=True)
    return topo


def _describe_surface(s) -> str:
    """One line on an instrument file's channel, grid and units (text output)."""
    nx, ny = s["shape"]
    return (
        f"{s['source']}, channel {s['channel']!r}, {nx} x {ny} points, pixel size "
        f"{s['pixel_size'][0]:.6g} m (from the file), heights in m (file: "
        f"{s['height_unit']}), detrend {s['info'].get('detrend', 'none')}"
    )


def _units(modulus, pixel_size, surface=None) -> dict:
    """The unit, in words, of every number the text output prints (lattice units: 1, 1).

    ``surface``: the summary of an instrument file (lengths in metres), or None.
    """
    length = "length, a0 units" if pixel_size == 1 else f"length, units of a0 = {pixel_size:g}"
    if surface is not None:
        length = "length, m"
    pressure = "N/A0, units of E*" if modulus == 1 else f"N/A0, pressure, units of E* = {modulus:g}"
    area = "fraction of A0"
    inverse_length = "per A0, 1/length" + ("" if pixel_size == 1 else f" (a0 = {pixel_size:g})")
    if surface is not None:
        inverse_length = "per A0, 1/m"
    return {
        "offset": length,
        "mean_gap": length,
        "load": pressure,
        "repulsive_load": pressure,
        "attractive_load": pressure,
        "pull_off": pressure,
        "repulsive_area": area,
        "attractive_area": area,
        "corrected_repulsive_area": area,
        "perimeter": inverse_length,
        "perimeter_edges": "nearest-neighbour bonds",
        "residual": "the solver's convergence measure",
        "solve_seconds": "s",
        "jumps": "step indices",
    }


def _line(key, value, unit, width) -> str:
    """``key: value (unit)`` for the text output."""
    return f"{key:>{width}}: {value}" + (f" ({unit})" if unit else "")


#: The most steps ``roughcontact path`` takes (approach; the retraction doubles it).
MAX_STEPS = MAX_PATH_STEPS  # 100_000, shared with the studies' [path]
OFFSET_UNITS = ("absolute", "length", "rms_height", "bearing_area")
#: The approach of ``roughcontact path --until-area A`` without --offsets/--loads: START STOP
#: STEP in rms heights relative to the first contact (the studies' default path, deeper).
DEFAULT_APPROACH = (0.5, -4.0, 0.125)


def _path_values(option, start, stop, step):
    """START, START ± |STEP|, ... up to STOP (inclusive), or a one-line ParameterError."""
    from ..solvers.offsets import stepped_values

    return stepped_values(start, stop, step, name=option)


@main.command()
@click.argument("surface_file", metavar="SURFACE", type=click.Path(dir_okay=False))
@click.option(
    "--offsets",
    nargs=3,
    type=float,
    default=None,
    metavar="START STOP STEP",
    help="Approach values START, START ± abs(STEP), ... towards STOP (inclusive), in the units "
    "of --offset-unit (absolute: offsets d, length; decreasing d approaches).",
)
@click.option(
    "--offset-unit",
    type=click.Choice(OFFSET_UNITS),
    default="absolute",
    show_default=True,
    help="absolute: --offsets are d (length). length, rms_height: relative to the first "
    "contact max(h) + d0 (d0: a0 for the LJ walls, else 0) in units of length or of the "
    "rms height (negative: into contact). bearing_area: fractions in [0, 1] of A0 that "
    "the undeformed surfaces overlap, growing into contact (as in studies' [path] unit).",
)
@click.option(
    "--loads",
    nargs=3,
    type=float,
    default=None,
    metavar="START STOP STEP",
    help="Load control: mean pressures from START to STOP by STEP.",
)
@click.option(
    "--until-area",
    type=float,
    default=None,
    metavar="A",
    help="Stop the approach at the first step with A_rep/A0 >= A (0 < A <= 1); STOP is "
    "then the farthest value tried. Exit code 4 if STOP comes first. Alone (no --offsets, "
    "--loads): the approach --offsets 0.5 -4 0.125 --offset-unit rms_height.",
)
@click.option(
    "--retract/--no-retract",
    default=False,
    show_default=True,
    help="Retract through the same offsets after the approach.",
)
@_substrate_options
@_interaction_options
@click.option(
    "-o",
    "--output",
    type=click.Path(dir_okay=False),
    required=True,
    help="NetCDF file for the path.",
)
@click.option(
    "--fields-at",
    type=int,
    multiple=True,
    help="Steps whose fields are stored (repeatable), in [-n, n) for a path of n steps "
    "(negative: from the end); with --until-area, steps past the end are ignored.",
)
@click.option(
    "--checkpoint-seconds",
    type=click.FloatRange(min=0),
    default=60.0,
    show_default=True,
    help="Rewrite -o with the steps done so far at most this often (s; 0: every step).",
)
@_surface_file_options
@click.option("--json", "as_json", is_flag=True, help="Print a JSON summary.")
def path(
    surface_file,
    offsets,
    offset_unit,
    loads,
    until_area,
    retract,
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
    output,
    fields_at,
    checkpoint_seconds,
    channel,
    detrend,
    fill_missing,
    as_json,
):
    """Follow a quasi-static approach (and retraction) path; write it to a NetCDF file.

    The file is rewritten atomically with the steps done so far every
    --checkpoint-seconds, so a crash or kill -9 loses at most that much work; Ctrl-C
    writes the finished steps and exits with code 130, SIGTERM (a scheduler, kill) the
    same with code 143. Exit code 3 if any state did not converge, 4 if --until-area was
    not reached by STOP (the file is written), 2 on bad input, 1 if a step failed (the
    steps before it are in the file) or the disk is full (the file keeps its last
    complete version). pull_off is null
    when it was not measured: without --retract, or when the retraction never separated
    the surfaces (its last step still has repulsive contact).
    """
    import numpy as np

    from ..solvers import PathError, PathInterrupted, approach_retract

    default_approach = None
    if offsets is None and loads is None and until_area is not None:
        # --until-area alone: the approach the studies use, from 0.5 rms heights above the
        # first contact inwards by 1/8 rms height; --until-area ends it
        if offset_unit not in ("absolute", "rms_height"):
            raise ParameterError(f"--offset-unit {offset_unit} needs --offsets START STOP STEP")
        offsets, offset_unit = DEFAULT_APPROACH, "rms_height"
        default_approach = (
            "default approach --offsets {:g} {:g} {:g} --offset-unit rms_height "
            "(no --offsets or --loads given)".format(*DEFAULT_APPROACH)
        )
    if (offsets is None) == (loads is None):
        raise ParameterError(
            "give exactly one of --offsets or --loads (or --until-area alone: a default approach)"
        )
    option = "--offsets" if offsets is not None else "--loads"
    if loads is not None and offset_unit != "absolute":
        raise ParameterError(f"--offset-unit {offset_unit} applies to --offsets only")
    if until_area is not None and not (0 < until_area <= 1):
        raise ParameterError(f"--until-area must be in (0, 1] (A_rep/A0), got {until_area:g}")
    start, stop, step = offsets if offsets is not None else loads
    values = _path_values(option, start, stop, step)
    check_writable(output, "-o/--output")  # before any work, not at the first checkpoint
    if offset_unit == "bearing_area" and not (0 <= start <= 1 and 0 <= stop <= 1):
        raise ParameterError(
            f"--offsets START and STOP must be in [0, 1] with --offset-unit bearing_area "
            f"(fractions of A0), got {start:g} {stop:g}"
        )
    h, pixel_size, surface = _load_surface(surface_file, channel, detrend, fill_missing, pixel_size)
    sub = _substrate(h.shape, modulus, pixel_size, thickness, poisson, base, not non_periodic)
    law = _make_interaction(
        interaction, work, range_, stiffness, core_stiffness, modulus, pixel_size, adhesion_length
    )
    if offsets is not None and offset_unit != "absolute":
        from ..solvers.offsets import relative_offsets

        given, values = values, relative_offsets(h, values, offset_unit, law, pixel_size)
    else:
        given = values
    from tqdm import tqdm

    bar = tqdm(
        unit="step",
        disable=None if not as_json else True,  # only on a terminal, never with --json
        file=sys.stderr,
    )

    def show(i, n, res):
        bar.total = n
        bar.set_postfix_str(
            f"d={res.offset:.4f} N/A0={res.load:.3e} Arep={res.repulsive_area:.4f} "
            f"it={res.iterations}",
            refresh=False,
        )
        bar.update(1)

    kwargs = {"offsets": values} if offsets is not None else {"loads": values}
    saved = {"steps": None}  # steps in the last file this run wrote

    def save(partial):
        """Write ``partial`` (Ctrl-C/SIGTERM held back meanwhile); a full disk exits 1."""
        if surface is not None:  # an instrument file: lengths in metres
            partial.attrs.update(length_unit="m", surface_channel=surface["channel"])
        try:
            with deferred():
                _write_path(partial, output, surface_file)
        except WriteError as err:
            bar.close()
            kept = saved["steps"]
            kept = f"; it holds the {kept} steps of the last checkpoint" if kept else ""
            _fail(f"{err}{kept}", EXIT_FAILURE)
        saved["steps"] = int(partial.sizes["step"])

    try:
        ds = approach_retract(
            h,
            sub,
            law,
            retract=retract,
            tol=tol,
            max_iter=max_iter,
            fields_at=fields_at,
            progress=show,
            device=device,
            dtype=dtype,
            checkpoint=save,
            checkpoint_seconds=checkpoint_seconds,
            until_area=until_area,
            **kwargs,
        )
    except (PathError, PathInterrupted) as err:
        bar.close()
        save(err.partial)
        done = f"the {err.partial.sizes['step']} steps before it are in {output}"
        code = exit_code(err) if isinstance(err, PathInterrupted) else EXIT_FAILURE
        why = "terminated (SIGTERM): " if code == EXIT_TERMINATED else ""
        _fail(f"{why}{err} ({done})", code)
    bar.close()
    if offsets is not None:
        ds.attrs["offset_unit"] = offset_unit
    save(ds)
    pull_off = float(ds.attrs["pull_off"])
    summary = {
        "pull_off": pull_off if math.isfinite(pull_off) else None,
        "steps": int(ds.sizes["step"]),
        "all_converged": bool(ds.attrs["all_converged"]),
        "solve_seconds": float(ds["solve_seconds"].sum()),
        "jumps": [int(i) for i in np.flatnonzero(ds["jump"].values)],
        "output": str(output),
        "periodic": sub.periodic,
    }
    if default_approach is not None:
        summary["approach"] = default_approach  # a choice made for the user: said so
    if surface is not None:
        summary["surface"] = surface  # instrument files: what was read, in which units
    if as_json:
        click.echo(_json(summary))
    else:
        units = _units(modulus, pixel_size, surface)
        for k, v in summary.items():
            if k == "pull_off" and v is None:
                why = "the surfaces never separated" if retract else "no --retract"
                v, units[k] = "null", f"not measured: {why}"
            v = _describe_surface(v) if k == "surface" else v
            click.echo(_line(k, v, units.get(k), 14))
    missed = None
    if until_area is not None and not ds.attrs["until_area_reached"]:
        approach = ds["branch"].values == "approach"
        area = ds["repulsive_area"].values[approach]
        i = int(np.argmax(area))
        where = (
            f"offset {float(ds['offset'].values[i]):.6g} (length)"
            if offsets is not None
            else f"load {float(ds['load'].values[i]):.6g} (N/A0)"
        )
        if offsets is not None and offset_unit != "absolute":
            where = where[:-1] + f"; {given[i]:g} in --offset-unit {offset_unit})"
        missed = (
            f"--until-area {until_area:g} not reached: the largest A_rep/A0 was "
            f"{float(area[i]):.6g}, at {where}; extend STOP of {option} (the path is in "
            f"{output})"
        )
    if not summary["all_converged"]:
        if missed:
            click.echo(f"roughcontact: error: {missed}", err=True)
        _fail("some states did not converge (see the 'converged' variable)", EXIT_NOT_CONVERGED)
    if missed:
        _fail(missed, EXIT_TARGET_NOT_REACHED)


def _write_path(ds, output, surface_file):
    """Write a path dataset atomically: a reader never sees a half-written file.

    Through :func:`roughcontact.pathdata.write_path` (built in memory, then written and
    renamed over ``output``), with the attribute ``surface_file``: a full disk raises
    :class:`roughcontact._io.WriteError` (one line) with ``output`` as it was and no
    temporary file left.
    """
    from ..pathdata import write_path

    write_path(ds, output, attrs={"surface_file": str(surface_file)})


@main.command()
@click.option("--size", type=int, default=512, show_default=True, help="Grid size n (hard wall).")
@click.option("--seed", type=int, default=2014, show_default=True, help="Surface seed.")
@click.option(
    "--study-size",
    type=int,
    default=256,
    show_default=True,
    help="Grid size of the adhesive study (0: skip the study).",
)
@click.option("--seeds", type=int, default=5, show_default=True, help="Study realisations.")
@click.option(
    "-o",
    "--output",
    type=click.Path(file_okay=False),
    default="roughcontact-demo",
    show_default=True,
    help="Directory for the study's results, figures and report.md (resumed if present).",
)
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
        from .._io import check_directory_writable
        from ..workflows.demo import check_demo_study

        check_demo_study(study_size, seeds)  # before the path is computed
        check_directory_writable(output, "-o/--output")

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
        if study["failed"]:
            _fail(f"{study['failed']} study tasks failed (see {output}/tasks)", 1)


def _register_commands():
    from .analyze import analyze
    from .criterion import criterion
    from .figures import figures
    from .stick import stick
    from .study import study

    main.add_command(analyze)
    main.add_command(criterion)
    main.add_command(figures)
    main.add_command(stick)
    main.add_command(study)


_register_commands()
