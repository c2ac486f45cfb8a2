"""The command line's output files: checked before any work, written by the one writer.

Every file a command writes goes through :func:`roughcontact._io.write_bytes_atomic`
(a temporary file in the same directory, fsync'ed and renamed over the name: a full
disk leaves an old file as it was; a symbolic link at the name is replaced, never
written through), and its directory is checked (:func:`roughcontact._io.check_writable`)
before the computation starts, not when its result is ready.
"""

from __future__ import annotations

import click

from .._io import check_writable
from .._validate import ParameterError

__all__ = ["check_fields_file", "claim_output_directory", "force_option", "save_fields_file"]

_FORCE = "roughcontact.force"


def force_option(f):
    """``--force``: write into a -o directory holding files roughcontact did not write."""

    def remember(ctx, param, value):
        ctx.meta[_FORCE] = bool(value)

    return click.option(
        "--force",
        is_flag=True,
        expose_value=False,
        callback=remember,
        help="Write into a -o directory that holds files roughcontact did not write there "
        "(files of the names it writes are replaced; the inputs never are). Default: such a "
        "directory is refused; one roughcontact wrote before is written again.",
    )(f)


def claim_output_directory(out_dir, *inputs):
    """Check and claim the -o directory before any work (a directory holding foreign
    files is refused unless --force; see :func:`roughcontact._guard.claim_directory`);
    ``inputs`` (files read) are never replaced by what is written there."""
    from .. import _guard, _io

    ctx = click.get_current_context(silent=True)
    force = bool(ctx is not None and ctx.meta.get(_FORCE))
    _guard.protect(*inputs)
    return _io.claim_directory(out_dir, "-o/--output", force=force)


def check_fields_file(name, *inputs) -> None:
    """--save-fields names a .npz file in a writable directory (checked before solving)."""
    if not str(name).lower().endswith(".npz"):
        raise ParameterError(
            f"--save-fields must name a .npz file (NumPy's archive, written under exactly "
            f"that name), got {str(name)!r}"
        )
    check_writable(name, "--save-fields", inputs=inputs)


def save_fields_file(name, res) -> None:
    """Pressure, gap and deflection as a compressed .npz, written atomically to ``name``:
    built in memory, then a temporary file renamed over it (a full disk leaves an old
    file as it was; a symbolic link there is replaced, never written through)."""
    import io

    import numpy as np

    from .._io import write_bytes_atomic

    host = res.to_numpy()  # the fields stay on the compute device until here
    buffer = io.BytesIO()
    np.savez_compressed(buffer, pressure=host.pressure, gap=host.gap, deflection=host.deflection)
    write_bytes_atomic(name, buffer.getbuffer())
