"""What the ``roughcontact`` commands share: exit codes, the one-line error, the options of
the substrate, interaction and surface file, the surface loader and the text output's units.

Lattice units by default (a0 = 1, E* = 1); loads are mean pressures N/A0 in units of the
contact modulus.
"""

from __future__ import annotations

import json
import math
import sys

import click

from .._signals import EXIT_TERMINATED, exit_code
from .._validate import MAX_ITER, PIXEL_SIZE, TOL, ParameterError, click_check, json_safe
from ..interactions.registry import LAW_PARAMETERS, PARAMETERS, make_law
from ..interactions.registry import names as interaction_names

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


def _option(*decls, help, rng=None, **kwargs):
    """``click.option`` as every command writes it: a default (not None, not a flag's) is
    shown in ``--help`` and gives the type unless ``type`` is given; with ``rng`` (a
    :class:`~roughcontact._validate.Range`) the value is checked (a one-line error naming
    the option and its accepted range) and ``{accepted}`` in ``help`` is that range."""
    default = kwargs.get("default")
    if default is not None and not kwargs.get("is_flag"):
        kwargs.setdefault("show_default", True)
        kwargs.setdefault("type", type(default))
    if rng is not None:
        kwargs["callback"] = click_check(rng)
        kwargs.setdefault("type", int if rng.integer else float)
        help = help.format(accepted=rng.accepted)
    return click.option(*decls, help=help, **kwargs)


def _output_option(help, *dest, file=False, **kwargs):
    """``-o/--output``: a directory to write (a file with ``file``), required unless it
    has a default."""
    kind = click.Path(dir_okay=False) if file else click.Path(file_okay=False)
    kwargs.setdefault("required", "default" not in kwargs)
    return _option("-o", "--output", *dest, type=kind, help=help, **kwargs)


def _pixel_size_option():
    return _option("--pixel-size", default=1.0, rng=PIXEL_SIZE, help="a0 (length, {accepted}).")


def _stacked(f, options):
    """``f`` under the click options, the first one listed first in ``--help``."""
    for o in reversed(list(options)):
        f = o(f)
    return f


#: the commands' argument of a law parameter's option, where it is not the parameter's name
_LAW_OPTION_DEST = {"work_of_adhesion": "work", "range": "range_"}


def _law_options():
    """``--interaction`` and one option per law parameter of the registry's one list (w
    first: the help lists it before its alternative, ℓa)."""
    given = sorted(
        (p for p in LAW_PARAMETERS if p.given), key=lambda p: p.name != "work_of_adhesion"
    )
    yield _option(
        "--interaction",
        type=click.Choice(INTERACTIONS),
        default="hardwall",
        help="Surface interaction law.",
    )
    for p in given:
        yield click.option(
            "--" + p.name.replace("_", "-"),
            _LAW_OPTION_DEST.get(p.name, p.name),
            type=float,
            default=None,
            help=p.option_help,
        )


def _interaction_options(f):
    return _stacked(f, _law_options())


INTERACTIONS = list(interaction_names())  # hardwall, lj93smooth, lj93, exponential, dugdale


def _make_interaction(
    name, work, range_, stiffness, core_stiffness, modulus, pixel_size, adhesion_length=None
):
    """The law of the ``--interaction`` options (checked and built by the registry)."""
    given = dict(work=work, range_=range_, stiffness=stiffness, core_stiffness=core_stiffness,
                 adhesion_length=adhesion_length)  # fmt: skip
    law = {k: given[_LAW_OPTION_DEST.get(k, k)] for k in PARAMETERS}
    return make_law(name, contact_modulus=modulus, pixel_size=pixel_size, spelling="cli", **law)


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
    return _stacked(f, (
        _option("--modulus", default=1.0, help="Contact modulus E* = E/(1-ν²)."),
        _pixel_size_option(),
        _option("--thickness", type=float, help="Layer thickness (default: half-space)."),
        _option("--poisson", default=0.5, help="ν in [0, 0.5] (layers only)."),
        _option("--base", type=click.Choice(["bonded", "frictionless"]), default="bonded",
                help="Layer attachment to its rigid base."),
        _option("--non-periodic", "non_periodic", is_flag=True, default=False,
                help="Free boundary: press the surface as measured, without periodic images "
                "(a half-space on a zero-padded grid; not with --thickness)."),
        _option("--tol", rng=TOL, help="Solver tolerance, {accepted} (default 1e-8; 1e-6, its "
                "floor, with --dtype float32)."),
        _option("--max-iter", default=5000, rng=MAX_ITER,
                help="Iteration cap per state ({accepted})."),
        _option("--device", default="cpu",
                help="Where to compute: cpu, cuda or cuda:N (the compiled JAX loops on an "
                "NVIDIA GPU; pip install 'jax[cuda12]')."),
        _option("--dtype", type=click.Choice(["float64", "float32"]), default="float64",
                help="Floating-point precision of the computation."),
    ))  # fmt: skip


def _surface_file_options(f):
    """--channel, --detrend and --fill-missing of the commands that read a SURFACE file."""
    return _stacked(f, (
        _option("--channel", help="Channel of an instrument file, by name or index (default: "
                "the file's default channel)."),
        _option("--detrend", type=click.Choice(["none", "height", "plane", "curvature"]),
                default="none",
                help="Least-squares mean, tilt or 2nd-order polynomial removed from SURFACE."),
        _option("--fill-missing/--no-fill-missing", default=None,
                help="Fill missing points of an instrument file of any fraction (harmonic "
                "interpolation) / refuse any. Default: fill up to 1 % (said on stderr), "
                "refuse more."),
    ))  # fmt: skip


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


def _surface_substrate_law(surface_file, options):
    """SURFACE's heights, pixel size and summary (:func:`_load_surface`), the substrate and
    the law of a command's surface-file, substrate and interaction options (``options``:
    their click arguments by name)."""
    o = options
    h, pixel_size, surface = _load_surface(
        surface_file, o["channel"], o["detrend"], o["fill_missing"], o["pixel_size"]
    )
    if o["non_periodic"] and min(h.shape) < 3:  # as the path and the statistics refuse it
        raise ParameterError(
            f"heights must be at least 3 x 3 points for --non-periodic, got {h.shape}"
        )
    sub = _substrate(
        h.shape, o["modulus"], pixel_size, o["thickness"], o["poisson"], o["base"],
        not o["non_periodic"],
    )  # fmt: skip
    law = _make_interaction(
        o["interaction"], o["work"], o["range_"], o["stiffness"], o["core_stiffness"],
        o["modulus"], pixel_size, o["adhesion_length"],
    )  # fmt: skip
    return h, pixel_size, surface, sub, law


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
    pressure = (
        "N/A0, units of E*"
        if modulus == 1
        else f"N/A0, pressure, in the units of --modulus (E* = {modulus:g})"
    )
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
