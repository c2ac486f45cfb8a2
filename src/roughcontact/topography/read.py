"""Reading measured topographies: instrument files through SurfaceTopography, in SI units.

SurfaceTopography (ContactEngineering, https://github.com/ContactEngineering/
SurfaceTopography) reads some 35 instrument formats (Bruker/DI Nanoscope, Nanosurf,
Zygo MetroPro, Dektak, Gwyddion, ...). It is an optional dependency
(``pip install "roughcontact[topography]"``), imported only when an instrument file is
read. ``.npy`` and plain text files are read by :mod:`roughcontact.surfaces.io` and
need nothing else.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..errors import ParameterError
from ._grid import uniform_positions
from ._metadata import instrument_info as _instrument_info
from .missing import MISSING_FILL_MAX, missing_policy
from .topography import Topography, length_factor, pixel_sizes

__all__ = ["MISSING_FILL_MAX", "file_kind", "load_topography", "missing_policy"]

_INSTALL = 'pip install "roughcontact[topography]"'
_ACCEPTED = (
    "a .npy file, plain text (numbers, one grid row per line) or an instrument file "
    "that SurfaceTopography reads"
)
#: How much of a file :func:`file_kind` looks at to tell plain text from other formats.
_SNIFF_BYTES = 1 << 16
#: Largest deviation (in steps) of a line scan's positions from a uniform grid that is
#: resampled without being asked (``resample=None``): rounded positions, as stylus
#: profilometers write them, stay within half a step.
_ROUNDING_STEPS = 0.5


def file_kind(path) -> str:
    """``"npy"``, ``"text"`` (plain numbers) or ``"instrument"`` (anything else).

    A file is plain text when its first 64 KiB decode as UTF-8 and every line there is
    empty, a ``#`` comment, or numbers separated by whitespace or commas (what
    :func:`roughcontact.load_heights` has always read).
    """
    p = Path(os.fspath(path))
    if p.suffix.lower() == ".npy":
        return "npy"
    from .._files import open_input

    try:  # a FIFO or device is never opened for reading (it could block forever)
        with open_input(p) as f:
            sample = f.read(_SNIFF_BYTES + 1)
    except (OSError, ParameterError):
        return "text"  # the reader reports the error, naming the file
    if b"\0" in sample:
        return "instrument"
    if len(sample) > _SNIFF_BYTES:  # judge complete lines only
        sample = sample[: sample.rfind(b"\n", 0, _SNIFF_BYTES) + 1]
    try:
        lines = sample.decode("utf-8").splitlines()
    except UnicodeDecodeError:
        return "instrument"
    for line in lines:
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        try:
            [float(v) for v in line.replace(",", " ").split()]
        except ValueError:
            return "instrument"
    return "text"


def load_topography(
    path,
    *,
    channel=None,
    periodic=False,
    pixel_size=None,
    height_unit=None,
    fill_missing=None,
    resample=None,
    outliers="keep",
) -> Topography:
    """Read a measured topography: heights and pixel size in metres, with the metadata.

    Instrument files are read with SurfaceTopography (``open_topography``, then the
    reader's channel): the reader's height scale factor is applied (raw counts to the
    file's height unit) and the file's height and lateral units are converted to metres.
    ``.npy`` and plain text files (see :func:`roughcontact.load_heights`) carry no units:
    they are read in lattice units (``pixel_size = 1``, heights as stored,
    ``info["length_unit"] = "a0"``) unless ``pixel_size`` (m) is given, and then
    heights in ``height_unit`` (default ``"m"``) are converted to metres.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    channel : str or int, optional
        Channel by name (or SurfaceTopography's channel id, e.g. ``"Height#2"`` when
        two channels share a name; the first of equal names is taken otherwise) or by
        index (an int, or a string of digits that names no channel). Default: the
        reader's default channel; ``channel`` of the result and ``info["channel_index"]``
        say which one was read.
    periodic : bool
        Whether the scan is one period of a periodic surface (measured scans are not).
    pixel_size : float or tuple of float, optional
        Grid spacing in metres of a ``.npy``/text file (one value, or one per axis), or
        of an instrument file that stores no lateral size. An instrument file's own
        pixel size is never overridden (ParameterError).
    height_unit : str, optional
        Unit of the heights of a ``.npy``/text file (with ``pixel_size``; default
        ``"m"``), or of an instrument file that stores none: ``"m"``, ``"mm"``,
        ``"um"``, ``"nm"``, ``"A"``, ``"pm"``, ...
    fill_missing : bool or None
        Missing points (NaN, or masked by the reader: e.g. invalid interferometer
        pixels): None (default) fills up to :data:`MISSING_FILL_MAX` (1 %) of the scan by
        harmonic interpolation (each takes the mean of its neighbours; a plane is kept
        exactly) and refuses more, naming the fraction; True fills any fraction; False
        refuses any (see :mod:`roughcontact.topography.missing`). A filling is recorded
        in ``info["missing_data"]``.
    resample : bool or None
        Non-uniformly sampled line scans (e.g. stylus profiles): True interpolates
        linearly onto as many uniformly spaced points, on the uniform grid fitted to the
        positions by least squares; False refuses them; None (default) does the former
        only where the positions deviate from that grid by at most half a step
        (positions rounded in the file) and refuses otherwise. A resampling is recorded
        in ``info["resampled"]``.

    Returns
    -------
    Topography
        ``heights`` shape (nx,) or (nx, ny); ``info`` holds ``format``, ``reader``,
        ``length_unit``, the channels, the instrument, ``tip_radius`` (m) when the file
        stores one, and ``scan_size`` (m).

    Raises
    ------
    ParameterError
        One line naming the file: missing, not a regular file (a FIFO, device or
        directory: refused before it is opened), corrupt or of an unknown format;
        implausible data (non-finite, flat, or of an instrument file a peak-to-valley
        height outside [1 fm, 1 m] or a pixel size outside [1 pm, 1 m], see
        :mod:`roughcontact._plausibility`); an unknown
        channel (listing the available ones) or a channel that holds no heights;
        more missing points than ``fill_missing`` allows; SurfaceTopography not installed.
    """
    from .._files import regular_input

    p = regular_input(path, "path", f"a .npy, text or instrument file ({_ACCEPTED})")
    from .outliers import OUTLIER_MODES

    if outliers not in OUTLIER_MODES:
        raise ParameterError(
            f"outliers must be one of {', '.join(OUTLIER_MODES)}, got {outliers!r}"
        )
    kind = file_kind(p)
    if kind == "instrument":
        try:
            topo = _read_instrument(
                p, channel, periodic, pixel_size, height_unit, fill_missing, resample, outliers
            )
        except ParameterError:
            raise
        except Exception as exc:  # noqa: BLE001 - a third-party parser on a damaged file
            raise ParameterError(
                f"path {str(p)!r}: corrupt or truncated instrument file, its channels could "
                f"not be read ({_why(exc)}); expected {_ACCEPTED}"
            ) from None
    else:
        topo = _read_plain(
            p, kind, channel, periodic, pixel_size, height_unit, fill_missing, outliers
        )
    _plausible(p, kind, topo)
    return topo


def _plausible(p, kind, topo) -> None:
    """Absurd data (damaged file, wrong unit, a constant) is refused at the reading edge."""
    from .._plausibility import check_header, check_heights, check_metres

    where = f"path {str(p)!r}"
    check_heights(topo.heights, where)
    if kind == "instrument":  # units from the file (a .npy's are the caller's)
        check_metres(topo.heights, topo.pixel_size, where)
        check_header(p, topo.info.get("format", ""), topo.shape)


def _read_plain(p, kind, channel, periodic, pixel_size, height_unit, fill_missing, outliers):
    from .._files import read_array

    if channel not in (None, 0, "0", "heights"):
        raise ParameterError(
            f"channel must be None, 0 or 'heights' for {str(p)!r} (a .npy or text file has "
            f"one channel), got {channel!r}"
        )
    expected = "a 1D or 2D array (at least 2 points per axis) of real heights"
    data = read_array(p, expected)
    if data.ndim not in (1, 2) or min(data.shape, default=0) < 2:
        raise ParameterError(f"path {str(p)!r}: expected {expected}, got shape {data.shape}")
    info = {"format": kind}
    if pixel_size is None and height_unit is None:
        px, unit = 1.0, "a0"
        info["length_unit"] = "a0"
        info["units"] = "lattice units: no pixel_size given (heights as stored, a0 = 1)"
    elif pixel_size is None:
        raise ParameterError(
            f"pixel_size (m) is needed with height_unit={height_unit!r} for {str(p)!r} "
            "(a .npy or text file stores no lateral size)"
        )
    else:
        unit = "m" if height_unit is None else str(height_unit).strip()
        data = data * length_factor("height_unit", unit)
        px = pixel_size
        info["length_unit"] = "m"
        info["units"] = f"from the caller: pixel_size in m, heights in {unit}"
    shown = "m" if info["length_unit"] == "m" else "(as stored)"
    data, info = _missing(p, data, fill_missing, periodic, info, outliers, shown)
    return _record(data, px, periodic, "heights", p, unit, info)


def _missing(p, data, fill_missing, periodic, info, outliers="keep", unit=""):
    """Look for outliers (:mod:`.outliers`; ``"remove"``: they become missing points),
    then fill or refuse the missing points (NaN or masked): :mod:`.missing`'s policy."""
    from .outliers import find_outliers

    missing = np.ma.getmaskarray(data) | ~np.isfinite(np.ma.getdata(data))
    values = np.array(np.ma.getdata(data), dtype=np.float64)
    found, report = find_outliers(values, missing, periodic=periodic)
    removed = outliers == "remove" and report["points"] > 0
    report["action"] = "removed" if removed else "kept"
    report["unit"] = str(unit)
    info = {**info, "outliers": report}
    if removed:
        data = np.ma.masked_array(values, mask=missing | found)
    values, new_info = missing_policy(
        f"path {str(p)!r}", data, fill_missing, periodic, info,
        outliers=report["points"] if removed else 0,
    )  # fmt: skip
    return values, info if new_info is None else new_info


def _record(heights, pixel_size, periodic, channel, p, unit, info):
    return Topography(
        heights=heights,
        pixel_size=pixel_size,
        periodic=periodic,
        channel=channel,
        source=str(p),
        height_unit=unit,
        info=info,
    )


def _open_reader(p):
    try:
        from SurfaceTopography import open_topography
    except ImportError:
        raise ParameterError(
            f"path {str(p)!r}: reading instrument files needs SurfaceTopography: "
            f"{_INSTALL} (or save the heights as .npy or plain text)"
        ) from None
    try:
        return open_topography(str(p))
    except Exception as exc:  # noqa: BLE001 - any reader failure is a bad file to the user
        why = _why(exc)
        if type(exc).__name__ == "CannotDetectFileFormat":  # its text lists every reader
            why = "no SurfaceTopography reader recognises it: corrupt, truncated or unsupported"
        raise ParameterError(
            f"path {str(p)!r}: unknown or unreadable file format ({why}){_as_text(p)}; "
            f"expected {_ACCEPTED}"
        ) from None


def _why(exc) -> str:
    text = " ".join(str(exc).split())
    return f"{type(exc).__name__}: {text[:200]}" if text else type(exc).__name__


def _as_text(p) -> str:
    """Why a text file is not plain numbers (numpy.loadtxt's reason), or '' if binary."""
    import io

    try:
        text = p.read_text(encoding="utf-8")
        if "\0" in text:
            return ""
        np.loadtxt(io.StringIO(text.replace(",", " ")), dtype=float)
    except (OSError, UnicodeDecodeError):
        return ""
    except ValueError as exc:
        return f"; as plain text: {' '.join(str(exc).split())[:200]}"
    return ""


def _units_of(ch):
    """(lateral unit, height unit) of a SurfaceTopography channel; either may be None."""
    unit = getattr(ch, "unit", None)
    if isinstance(unit, (tuple, list)):
        return (unit[0] if unit else None), (unit[1] if len(unit) > 1 else None)
    return unit, unit


def _is_length(unit) -> bool:
    try:
        length_factor("unit", unit)
    except ParameterError:
        return False
    return True


def _listing(channels) -> str:
    return ", ".join(f"{c.index} {c.name!r}" for c in channels)


def _choose_channel(p, reader, channel):
    channels = list(reader.channels)
    if channel is None:
        return reader.default_channel
    if isinstance(channel, str):
        for key in ("name", "channel_id"):
            for c in channels:
                if getattr(c, key, None) == channel:
                    return c
        if channel.strip().isdigit():
            channel = int(channel)
    if isinstance(channel, (int, np.integer)) and not isinstance(channel, (bool, np.bool_)):
        if 0 <= channel < len(channels):
            return channels[int(channel)]
    raise ParameterError(
        f"channel {channel!r} is not in {str(p)!r}: accepted a name or an index of "
        f"{_listing(channels)}"
    )


def _read_instrument(
    p, channel, periodic, pixel_size, height_unit, fill_missing, resample, outliers="keep"
):
    reader = _open_reader(p)
    try:
        ch = _choose_channel(p, reader, channel)
        lateral, unit = _channel_units(p, reader, ch, height_unit)
        kwargs = {"channel_index": ch.index, "periodic": bool(periodic)}
        if getattr(ch, "physical_sizes", None) is None:
            if pixel_size is None:
                raise ParameterError(
                    f"pixel_size (m) is needed for {str(p)!r}: the file stores no lateral size"
                )
            px = pixel_sizes(pixel_size, len(ch.nb_grid_pts))
            kwargs["physical_sizes"] = tuple(
                float(n * s) for n, s in zip(ch.nb_grid_pts, px, strict=True)
            )
            lateral = "m"
        elif pixel_size is not None:
            sizes = ", ".join(f"{float(s):g}" for s in ch.physical_sizes)
            raise ParameterError(
                f"pixel_size: {str(p)!r} stores its own lateral size ({sizes} {lateral}); "
                "leave pixel_size out"
            )
        if getattr(ch, "unit", None) is None:
            kwargs["unit"] = unit
        try:
            topo = reader.topography(**kwargs)
            info_in = dict(getattr(topo, "info", {}) or {})
            if topo.is_uniform:
                x, data = None, topo.heights()
                steps = np.broadcast_to(np.asarray(topo.pixel_size, dtype=float), (data.ndim,))
            else:
                x, data = topo.positions_and_heights()
        except Exception as exc:  # noqa: BLE001 - a truncated or corrupt file, one line
            raise ParameterError(
                f"path {str(p)!r}: corrupt or truncated {_format(reader)} file, channel "
                f"{ch.name!r} could not be read ({_why(exc)})"
            ) from None
    finally:
        close = getattr(reader, "close", None)
        if close is not None:
            close()
    info = _instrument_info(reader, ch, info_in)
    if x is not None:
        data, steps, info = _resample(p, np.asarray(x), data, resample, fill_missing, info)
    data, info = _missing(p, data, fill_missing, periodic, info, outliers, str(unit))
    px = tuple(float(s) * length_factor("lateral unit", lateral) for s in steps)
    info["scan_size"] = [n * s for n, s in zip(data.shape, px, strict=True)]
    heights = data * length_factor("height unit", unit)
    return _record(heights, px, periodic, ch.name, p, str(unit), info)


def _channel_units(p, reader, ch, height_unit):
    """(lateral unit, height unit) of a channel, both lengths, or a ParameterError.

    ``height_unit`` from the caller is taken only for a file that stores no unit at all.
    """
    lateral, unit = _units_of(ch)
    if unit is None and lateral is None and height_unit is not None:
        return str(height_unit).strip(), _checked_unit(height_unit)
    if height_unit is not None:
        raise ParameterError(
            f"height_unit: {str(p)!r} stores its own units ({unit!r}); leave height_unit out"
        )
    if not _is_length(unit):
        heights = [c for c in reader.channels if _is_length(_units_of(c)[1])]
        hint = "; height_unit= gives it" if unit is None and lateral is None else ""
        raise ParameterError(
            f"channel {ch.name!r} of {str(p)!r} holds no heights (its data unit is {unit!r}, "
            f"not a length){hint}; channels with heights: {_listing(heights) or 'none'}"
            f"{_as_text(p)}"
        )
    if lateral is not None and not _is_length(lateral):
        raise ParameterError(
            f"channel {ch.name!r} of {str(p)!r}: lateral unit {lateral!r} is not a length"
        )
    return lateral, unit


def _checked_unit(unit) -> str:
    """``unit`` stripped, if it is a length unit (ParameterError naming height_unit)."""
    length_factor("height_unit", unit)
    return str(unit).strip()


def _format(reader) -> str:
    try:
        return str(reader.name())
    except Exception:  # noqa: BLE001
        return type(reader).__name__


def _resample(p, x, heights, resample, fill_missing, info):
    """Uniform heights from a non-uniform line scan, or a ParameterError (see ``resample``).

    Missing points are refused as in :func:`_missing`, or (``fill_missing``) left out of
    the linear interpolation, which fills them.
    """
    try:
        start, step, deviation = uniform_positions(x)
    except ParameterError as exc:
        raise ParameterError(f"path {str(p)!r}: {exc}") from None
    if resample is False or (resample is None and deviation > _ROUNDING_STEPS):
        hint = "" if resample is False else f" (more than {_ROUNDING_STEPS} steps)"
        raise ParameterError(
            f"path {str(p)!r}: non-uniform sampling, positions deviate from a uniform grid "
            f"by up to {deviation:.3g} steps{hint}; resample=True interpolates linearly "
            f"onto {x.size} uniform points"
        )
    known = ~(np.ma.getmaskarray(heights) | ~np.isfinite(np.ma.getdata(heights)))
    info = dict(info)
    if not known.all():
        if not fill_missing and (fill_missing is not None or (~known).mean() > MISSING_FILL_MAX):
            _missing(p, heights, fill_missing, False, info)  # raises: count and fraction
        if known.sum() < 2:
            raise ParameterError(f"path {str(p)!r}: fewer than 2 points are defined")
        count = int((~known).sum())
        info["missing_data"] = {
            "points": count,
            "fraction": count / known.size,
            "filled": "linear (with the resampling)",
            "asked": bool(fill_missing),
        }
    values = np.asarray(np.ma.getdata(heights), dtype=np.float64)
    # the fitted grid may overhang the first or last position by a fraction of a step:
    # np.interp holds the end values there
    out = np.interp(start + step * np.arange(x.size), x[known], values[known])
    info["resampled"] = {
        "method": "linear",
        "points": int(x.size),
        "max_deviation_steps": deviation,
    }
    return out, (step,), info
