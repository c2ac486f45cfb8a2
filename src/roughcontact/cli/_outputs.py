"""The command line's output files: checked before any work, written by the one writer.

Every file a command writes goes through :func:`roughcontact._io.write_bytes_atomic`
(a temporary file in the same directory, fsync'ed and renamed over the name: a full
disk leaves an old file as it was; a symbolic link at the name is replaced, never
written through), and its directory is checked (:func:`roughcontact._io.check_writable`)
before the computation starts, not when its result is ready.
"""

from __future__ import annotations

from .._io import check_writable
from .._validate import ParameterError

__all__ = ["check_fields_file", "save_fields_file"]


def check_fields_file(name) -> None:
    """--save-fields names a .npz file in a writable directory (checked before solving)."""
    if not str(name).lower().endswith(".npz"):
        raise ParameterError(
            f"--save-fields must name a .npz file (NumPy's archive, written under exactly "
            f"that name), got {str(name)!r}"
        )
    check_writable(name, "--save-fields")


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
