"""Units: the one table of unit symbols and the one parser of quantities with units.

Every place that reads a number with a unit (the stickiness criterion, the moduli, the
topography readers' ``height_unit`` / instrument-file units, the CLI) goes through
:func:`parse_quantity` or :func:`length_factor` here, so a symbol accepted in one place is
accepted in all of them with the same value.

A unit is a product of symbols, each with an optional SI prefix and integer power
(``m^2``, ``m2``, ``m^-1``), ``/`` dividing by every following symbol: ``mJ/m^2``,
``J/m2``, ``N/m``, ``1/nm``, ``GPa``, ``um``, ``µm`` (micro sign), ``μm`` (Greek mu).
Instruments also write ``A``, ``Å`` or ``angstrom`` for 1e-10 m and ``micron`` for 1e-6 m.
Dimensions are exponents of (kg, m, s).
"""

from __future__ import annotations

import re

from .errors import ParameterError

__all__ = [
    "DIMENSIONS",
    "LENGTH_UNITS",
    "PREFIXES",
    "SYMBOLS",
    "format_quantity",
    "length_factor",
    "parse_quantity",
    "unit_factor",
]

_LENGTH = (0, 1, 0)
_PRESSURE = (1, -1, -2)

#: Dimension name: (exponents of kg, m, s; SI unit; an example for error messages).
DIMENSIONS = {
    "pressure": (_PRESSURE, "Pa", "10 MPa"),
    "energy per area": ((1, 0, -2), "J/m^2", "50 mJ/m^2"),
    "length": (_LENGTH, "m", "0.5 nm"),
    "inverse length": ((0, -1, 0), "1/m", "0.2 1/nm"),
    "dimensionless": ((0, 0, 0), "", "0.1"),
}

#: Unit symbols: (factor to SI, dimension, whether an SI prefix may precede it). ``A`` and
#: ``micron`` take no prefix: ``mA`` or ``kmicron`` would only be typing errors.
SYMBOLS = {
    "m": (1.0, _LENGTH, True),
    "Pa": (1.0, _PRESSURE, True),
    "N": (1.0, (1, 1, -2), True),
    "J": (1.0, (1, 2, -2), True),
    "bar": (1e5, _PRESSURE, True),
    "\u00c5": (1e-10, _LENGTH, True),  # Latin capital A with ring (what keyboards type)
    "\u212b": (1e-10, _LENGTH, True),  # the Angstrom sign some instruments write
    "angstrom": (1e-10, _LENGTH, True),
    "A": (1e-10, _LENGTH, False),
    "micron": (1e-6, _LENGTH, False),
}
#: SI prefixes; micro as ``u``, the micro sign (U+00B5) or the Greek mu (U+03BC).
PREFIXES = {"T": 1e12, "G": 1e9, "M": 1e6, "k": 1e3, "d": 1e-1, "c": 1e-2, "m": 1e-3,
            "u": 1e-6, "\u00b5": 1e-6, "\u03bc": 1e-6, "n": 1e-9, "p": 1e-12,
            "f": 1e-15}  # fmt: skip

_NUMBER = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.*?)\s*$")
_TERM = re.compile(r"^([A-Za-z\u00b5\u03bc\u00c5\u212b]+)(?:\^?([+-]?\d+))?$")
_KNOWN = (
    "m, Pa, N, J, bar, Å/angstrom with prefixes T G M k d c m u/µ n p f; A, micron; "
    "e.g. '10 MPa', '50 mJ/m^2', '0.5 nm', '2 um', '3 A'"
)


def _symbol(symbol: str, name: str, text: str):
    """(factor to SI, dimension) of one symbol, possibly prefixed."""
    if symbol in SYMBOLS:
        return SYMBOLS[symbol][:2]
    base = SYMBOLS.get(symbol[1:])
    if len(symbol) > 1 and symbol[0] in PREFIXES and base is not None and base[2]:
        return PREFIXES[symbol[0]] * base[0], base[1]
    raise ParameterError(f"{name}: unknown unit {symbol!r} in {text!r} (known: {_KNOWN})")


def unit_factor(unit: str, name: str = "unit", text: str | None = None):
    """Factor to SI and dimension of a unit expression such as ``"mJ/m^2"``.

    Parameters
    ----------
    unit : str
        The unit alone (no number); ``""`` is dimensionless with factor 1.
    name : str
        The parameter's name, used in error messages.
    text : str, optional
        The full text the unit came from, quoted in error messages (default: ``unit``).

    Returns
    -------
    (float, tuple of int)
        SI units per ``unit`` and the dimension as exponents of (kg, m, s).

    Raises
    ------
    ParameterError
        Unreadable unit or unknown symbol (one line naming the parameter and the symbols).
    """
    text = unit if text is None else text
    unit = unit.strip().replace("·", "*").replace(" ", "*")
    factor, dim = 1.0, [0, 0, 0]
    for i, part in enumerate(unit.split("/")):
        sign = 1 if i == 0 else -1
        for term in filter(None, part.split("*")):
            if term == "1" and sign == 1:
                continue
            t = _TERM.match(term)
            if not t:
                raise ParameterError(f"{name}: cannot read the unit {unit!r} in {text!r}")
            f, d = _symbol(t.group(1), name, text)
            p = sign * int(t.group(2) or 1)
            factor *= f**p
            dim = [a + p * b for a, b in zip(dim, d, strict=True)]
    return factor, tuple(dim)


def _a(noun: str) -> str:
    return ("an " if noun[:1] in "aeiou" else "a ") + noun


def _dimension_name(dim) -> str:
    for k, (d, _, _) in DIMENSIONS.items():
        if d == tuple(dim):
            return k
    other = {(1, 2, -2): "energy (J)", (1, 1, -2): "force (N)", (0, 2, 0): "area (m^2)"}
    if tuple(dim) in other:
        return other[tuple(dim)]
    return " ".join(f"{b}^{e}" for b, e in zip(("kg", "m", "s"), dim, strict=True) if e)


def parse_quantity(value, dimension: str, name: str = "value") -> float:
    """Convert a number or a string with units to SI, checking its dimension.

    Parameters
    ----------
    value : float or str
        A plain number (already SI) or ``"<number> <unit>"``. The unit is a product of
        symbols with optional SI prefix and integer power (``m^2``, ``m2``, ``m^-1``),
        with ``/`` dividing by every following symbol: ``mJ/m^2``, ``J/m2``, ``N/m``,
        ``1/nm``, ``GPa``, ``um`` or ``µm``. Symbols: m, Pa, N, J, bar, Å (also
        ``angstrom`` and ``A``), ``micron``.
    dimension : str
        One of ``DIMENSIONS``: ``"pressure"``, ``"energy per area"``, ``"length"``,
        ``"inverse length"``, ``"dimensionless"``.
    name : str
        The parameter's name, used in error messages.

    Returns
    -------
    float
        The value in SI units (Pa, J/m^2 = N/m, m, 1/m).

    Raises
    ------
    ParameterError
        Unparseable text, an unknown unit, or a unit of another dimension (the message
        names the parameter and the expected dimension).
    """
    if dimension not in DIMENSIONS:
        raise ParameterError(f"dimension must be one of {list(DIMENSIONS)}, got {dimension!r}")
    expected, si_unit, example = DIMENSIONS[dimension]
    if isinstance(value, bool):
        raise ParameterError(f"{name} must be a number or a string with units, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    text = str(value).strip()
    m = _NUMBER.match(text)
    if not m:
        raise ParameterError(
            f"{name}: cannot read {text!r}; expected a number with {dimension} units, "
            f"e.g. {example!r}"
        )
    number, unit = float(m.group(1)), m.group(2)
    if not unit:
        return number  # a plain number is SI
    factor, dim = unit_factor(unit, name, text)
    if dim != expected:
        got = _dimension_name(dim)
        got = "dimensionless number" if got == "dimensionless" else got
        hint = f" (SI: {si_unit})" if si_unit else ""
        raise ParameterError(
            f"{name} must be {_a(dimension)}{hint}, e.g. {example!r}; got {text!r}, {_a(got)}"
        )
    return number * factor


#: The length symbols instruments and users write, and their value in metres (all of them
#: are also accepted by :func:`parse_quantity`, which derives these values).
_LENGTH_SYMBOLS = ("km", "m", "dm", "cm", "mm", "\u00b5m", "\u03bcm", "um", "micron", "nm",
                   "\u00c5", "\u212b", "A", "angstrom", "pm")  # fmt: skip
LENGTH_UNITS = {s: unit_factor(s)[0] for s in _LENGTH_SYMBOLS}


def length_factor(name: str, unit) -> float:
    """Metres per ``unit``, a length unit such as ``"um"``, ``"A"`` or ``"micron"``.

    Parameters
    ----------
    name : str
        The parameter's name, used in the error message.
    unit : str
        Any unit :func:`parse_quantity` reads as a length (the keys of
        :data:`LENGTH_UNITS` and every prefixed metre).

    Returns
    -------
    float
        The length of one ``unit`` in metres.

    Raises
    ------
    ParameterError
        ``unit`` is not a string naming a length unit (one line naming ``name``).
    """
    if isinstance(unit, str) and unit.strip():
        try:
            factor, dim = unit_factor(unit, name)
        except ParameterError:
            dim = None
        if dim == _LENGTH:
            return factor
    accepted = ", ".join(sorted({"km", "m", "mm", "um", "nm", "A", "pm"}))
    raise ParameterError(f"{name} must be a length unit ({accepted}, ...), got {unit!r}")


def format_quantity(value: float, unit: str) -> str:
    """``value`` (in SI ``unit``) with an SI prefix and 4 digits: ``5e-09, "m"`` -> ``"5 nm"``.

    Parameters
    ----------
    value : float
        The value in the SI unit ``unit``.
    unit : str
        The SI unit symbol, e.g. ``"m"`` or ``"Pa"``; the prefix goes in front of it.

    Returns
    -------
    str
        Text that :func:`parse_quantity` reads back (to 4 significant digits); zero,
        non-finite values and magnitudes below 1e-12 carry no prefix, those of 1e9 and
        more the prefix G.
    """
    if value == 0 or not (abs(value) < float("inf")):
        return f"{value:.4g} {unit}"
    for factor, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k"), (1, ""), (1e-3, "m"),
                           (1e-6, "u"), (1e-9, "n"), (1e-12, "p")):  # fmt: skip
        if abs(value) >= factor:
            return f"{value / factor:.4g} {prefix}{unit}"
    return f"{value:.4g} {unit}"
