"""``roughcontact path SURFACE``: a quasi-static approach (and retraction) path, written to
a NetCDF file with checkpoints."""

from __future__ import annotations

import sys

import click

from .._io import WriteError, check_writable
from .._signals import EXIT_TERMINATED, deferred, exit_code
from .._validate import MAX_PATH_STEPS, ParameterError
from ..pathdata import load_libraries
from ._common import (
    EXIT_FAILURE,
    EXIT_NOT_CONVERGED,
    EXIT_TARGET_NOT_REACHED,
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


@click.command()
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
    help="Load control: mean pressures N/A0 from START to STOP by STEP, in the units of --modulus.",
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
    callback=lambda ctx, param, value: _finite_seconds(value),
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

    from ..solvers import PathError, PathInterrupted
    from ..workflows.pipeline import run_path

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
    given = _path_values(option, start, stop, step)  # in --offset-unit
    check_writable(output, "-o/--output", inputs=(surface_file,))  # before any work
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
    from tqdm import tqdm

    bars = []  # made at the first step: a refused input shows no empty bar

    def show(i, n, res):
        if not bars:
            # only on a terminal, never with --json
            bars.append(tqdm(unit="step", disable=None if not as_json else True, file=sys.stderr))
        bar = bars[0]
        bar.total = n
        bar.set_postfix_str(
            f"d={res.offset:.4f} N/A0={res.load:.3e} Arep={res.repulsive_area:.4f} "
            f"it={res.iterations}",
            refresh=False,
        )
        bar.update(1)

    def close():
        for bar in bars:
            bar.close()

    if offsets is not None:
        kwargs = {"offsets": given, "offset_unit": offset_unit}
    else:
        kwargs = {"loads": given}
    saved = {"steps": None}  # steps in the last file this run wrote

    def save(partial):
        """Write ``partial`` (Ctrl-C/SIGTERM held back meanwhile); a full disk exits 1."""
        if surface is not None:  # an instrument file: lengths in metres
            partial.attrs.update(length_unit="m", surface_channel=surface["channel"])
        else:  # a heights file: lengths in the unit of --pixel-size (analyze reads it)
            partial.attrs["length_unit"] = "a0"
        try:
            with deferred():
                _write_path(partial, output, surface_file)
        except WriteError as err:
            close()
            kept = saved["steps"]
            kept = f"; it holds the {kept} steps of the last checkpoint" if kept else ""
            _fail(f"{err}{kept}", EXIT_FAILURE)
        saved["steps"] = int(partial.sizes["step"])

    load_libraries(write=True)  # before the first step (its docstring: why)
    try:
        run = run_path(
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
        close()
        save(err.partial)
        done = f"the {err.partial.sizes['step']} steps before it are in {output}"
        code = exit_code(err) if isinstance(err, PathInterrupted) else EXIT_FAILURE
        why = "terminated (SIGTERM): " if code == EXIT_TERMINATED else ""
        _fail(f"{why}{err} ({done})", code)
    with deferred():  # a signal once the path is done: written first, then raised
        close()
        ds = run.path
        if offsets is not None:
            ds.attrs["offset_unit"] = offset_unit
        save(ds)
    summary = {**run.summary(), "output": str(output), "periodic": sub.periodic}
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


def _finite_seconds(value):
    """--checkpoint-seconds: a finite number of seconds >= 0 (NaN, inf refused)."""
    import math

    if value is not None and not math.isfinite(value):
        raise ParameterError(
            f"--checkpoint-seconds must be a finite number of seconds >= 0, got {value!r}"
        )
    return value


def _write_path(ds, output, surface_file):
    """Write a path dataset atomically: a reader never sees a half-written file.

    Through :func:`roughcontact.pathdata.write_path` (built in memory, then written and
    renamed over ``output``), with the attribute ``surface_file``: a full disk raises
    :class:`roughcontact._io.WriteError` (one line) with ``output`` as it was and no
    temporary file left.
    """
    from ..pathdata import write_path

    write_path(ds, output, attrs={"surface_file": str(surface_file)})
