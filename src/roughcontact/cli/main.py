"""``roughcontact`` command line. Lattice units by default (a0 = 1, E* = 1); loads are
mean pressures N/A0 in units of the contact modulus.

The group, its entry point :func:`main` (the console script) and the registration of the
commands. Each command lives in its own module of :mod:`roughcontact.cli`, what they share
(options, exit codes, the surface loader, the units of the text output) in :mod:`._common`;
the names this module always offered are re-exported from there.
"""

from __future__ import annotations

import warnings

import click

from .. import _guard
from .._io import WriteError
from .._signals import exit_code, interruptible
from .._validate import ParameterError
from ._common import EXIT_BAD_INPUT as EXIT_BAD_INPUT
from ._common import EXIT_FAILURE as EXIT_FAILURE
from ._common import EXIT_NOT_CONVERGED as EXIT_NOT_CONVERGED
from ._common import EXIT_TARGET_NOT_REACHED as EXIT_TARGET_NOT_REACHED
from ._common import INTERACTIONS as INTERACTIONS
from ._common import _describe_surface as _describe_surface
from ._common import _fail as _fail
from ._common import _filled as _filled
from ._common import _interaction_options as _interaction_options
from ._common import _interrupted as _interrupted
from ._common import _json as _json
from ._common import _line as _line
from ._common import _load_surface as _load_surface
from ._common import _make_interaction as _make_interaction
from ._common import _substrate as _substrate
from ._common import _substrate_options as _substrate_options
from ._common import _surface_file_options as _surface_file_options
from ._common import _units as _units
from ._common import _warning_line as _warning_line
from .analyze import analyze
from .contact import contact as contact
from .criterion import criterion
from .demo_command import demo as demo
from .figures import figures
from .path import DEFAULT_APPROACH as DEFAULT_APPROACH
from .path import MAX_STEPS as MAX_STEPS
from .path import OFFSET_UNITS as OFFSET_UNITS
from .path import _path_values as _path_values
from .path import _write_path as _write_path
from .path import path as path
from .stick import stick
from .study import study
from .surface import surface as surface


class _Group(click.Group):
    """Turns our parameter errors into one readable line and a non-zero exit code."""

    def invoke(self, ctx):
        try:
            # SIGTERM stops a command as Ctrl-C does (exit 143, 130); warnings in one line
            with _guard.command_scope(), interruptible(), warnings.catch_warnings():
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
        except MemoryError as err:  # past the estimates made before the work
            why = " ".join(str(err).split()) or "an allocation failed"
            _fail(f"out of memory: {why}; try a smaller grid", EXIT_FAILURE)
        except KeyboardInterrupt as err:
            _fail(_interrupted(err), exit_code(err))


@click.group(cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="roughcontact")
def main():
    """Contact of rough elastic surfaces with adhesion (Pastewka & Robbins, PNAS 2014)."""


for _command in (analyze, contact, criterion, demo, figures, path, stick, study, surface):
    main.add_command(_command)
