"""One unit table, one parser: ``roughcontact.units`` and its two old entry points
(``criterion.parse_quantity``, ``topography.length_factor``) agree on every symbol.

The expected values are the SI definitions (BIPM SI brochure: prefixes; 1 Å = 1e-10 m;
1 micron = 1 µm = 1e-6 m; 1 bar = 1e5 Pa), written out here, not taken from the code.
"""

import json

import pytest
from click.testing import CliRunner

from roughcontact import ParameterError, criterion, topography, units
from roughcontact.cli.criterion import criterion as criterion_command
from roughcontact.topography import topography as topo_module

# The length table as topography.LENGTH_UNITS held it before the merge: every key must
# keep its value (metres).
OLD_LENGTH_UNITS = {
    "km": 1e3, "m": 1.0, "dm": 1e-1, "cm": 1e-2, "mm": 1e-3, "\u00b5m": 1e-6,
    "\u03bcm": 1e-6, "um": 1e-6, "micron": 1e-6, "nm": 1e-9, "\u00c5": 1e-10,
    "\u212b": 1e-10, "A": 1e-10, "angstrom": 1e-10, "pm": 1e-12,
}  # fmt: skip

# symbol, dimension, SI value of 1 symbol: what criterion accepted before, plus the new ones.
QUANTITIES = [
    ("Pa", "pressure", 1.0),
    ("kPa", "pressure", 1e3),
    ("MPa", "pressure", 1e6),
    ("GPa", "pressure", 1e9),
    ("bar", "pressure", 1e5),
    ("N/m^2", "pressure", 1.0),
    ("J/m^2", "energy per area", 1.0),
    ("mJ/m^2", "energy per area", 1e-3),
    ("mJ/m2", "energy per area", 1e-3),
    ("N/m", "energy per area", 1.0),
    ("mN/m", "energy per area", 1e-3),
    ("1/m", "inverse length", 1.0),
    ("1/nm", "inverse length", 1e9),
    ("1/um", "inverse length", 1e6),
    ("1/A", "inverse length", 1e10),
    ("m^-1", "inverse length", 1.0),
    ("1/micron", "inverse length", 1e6),
]


@pytest.mark.parametrize(("symbol", "metres"), OLD_LENGTH_UNITS.items())
def test_both_entry_points_agree_on_every_length_symbol(symbol, metres):
    assert units.LENGTH_UNITS[symbol] == pytest.approx(metres, rel=1e-15)
    assert topo_module.length_factor("unit", symbol) == pytest.approx(metres, rel=1e-15)
    assert topo_module.length_factor("unit", f" {symbol} ") == pytest.approx(metres, rel=1e-15)
    for text in (f"1 {symbol}", f"2.5{symbol}"):
        value = float(text.split(symbol)[0])
        got = criterion.parse_quantity(text, "length", "x")
        assert got == pytest.approx(value * metres, rel=1e-15)
        assert units.parse_quantity(text, "length", "x") == got


def test_old_names_are_the_one_owner():
    assert criterion.parse_quantity is units.parse_quantity
    assert criterion.DIMENSIONS is units.DIMENSIONS
    assert topo_module.length_factor is units.length_factor
    assert topo_module.LENGTH_UNITS is units.LENGTH_UNITS
    assert topography.LENGTH_UNITS is units.LENGTH_UNITS
    assert set(units.LENGTH_UNITS) == set(OLD_LENGTH_UNITS)


@pytest.mark.parametrize(("symbol", "dimension", "si"), QUANTITIES)
def test_quantities(symbol, dimension, si):
    assert criterion.parse_quantity(f"3 {symbol}", dimension, "x") == pytest.approx(3 * si)


@pytest.mark.parametrize(
    ("text", "metres"), [("1 A", 1e-10), ("1 micron", 1e-6), ("4 Å", 4e-10), ("2 dm", 0.2)]
)
def test_symbols_criterion_refused_before(text, metres):
    assert criterion.parse_quantity(text, "length", "d_rep") == pytest.approx(metres)


def test_cli_criterion_reads_angstrom_and_micron():
    common = ["--modulus", "10 MPa", "--work-of-adhesion", "50 mJ/m^2", "--rms-slope", "1"]
    out = {}
    for rng, d_rep in (("5 A", "0.01 micron"), ("0.5 nm", "10 nm")):
        res = CliRunner().invoke(
            criterion_command, [*common, "--range", rng, "--d-rep", d_rep, "--json"]
        )
        assert res.exit_code == 0, res.output
        out[rng] = json.loads(res.output)
    a, b = out.values()
    assert a["interaction_range"] == pytest.approx(b["interaction_range"])
    assert a["d_rep"] == pytest.approx(b["d_rep"])
    assert a["kappa"] == pytest.approx(b["kappa"])


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: units.parse_quantity("1 mA", "length", "d_rep"), "d_rep: unknown unit 'mA'"),
        (lambda: units.parse_quantity("1 kmicron", "length", "d_rep"), "d_rep: unknown unit"),
        (lambda: units.parse_quantity("1 furlong", "length", "a0"), "a0: unknown unit"),
        (lambda: units.parse_quantity("1 A", "pressure", "modulus"), "modulus must be a press"),
        (lambda: units.length_factor("height_unit", "s"), "height_unit must be a length unit"),
        (lambda: units.length_factor("height_unit", "Pa"), "height_unit must be a length unit"),
        (lambda: units.length_factor("height_unit", "1/m"), "height_unit must be a length unit"),
        (lambda: units.length_factor("height_unit", ""), "height_unit must be a length unit"),
        (lambda: units.length_factor("height_unit", None), "height_unit must be a length unit"),
        (lambda: units.length_factor("height_unit", 1e-9), "height_unit must be a length unit"),
    ],
)
def test_bad_units_give_one_line_naming_the_parameter(call, match):
    with pytest.raises(ParameterError, match=match) as err:
        call()
    assert "\n" not in str(err.value)
    if "unknown unit" in match:  # the accepted symbols are named
        assert "micron" in str(err.value) and "Pa" in str(err.value)
    if "length unit" in match:
        assert "um" in str(err.value) and "nm" in str(err.value)


@pytest.mark.parametrize("value", [5e-9, 3.2e7, 0.05, 1.0, 2e-13, 0.0, 4.5e10])
@pytest.mark.parametrize(("unit", "dimension"), [("m", "length"), ("Pa", "pressure")])
def test_format_quantity_reads_back(value, unit, dimension):
    text = units.format_quantity(value, unit)
    assert units.parse_quantity(text, dimension, "x") == pytest.approx(value, rel=1e-3)


def test_format_quantity_prefixes():
    assert units.format_quantity(5e-9, "m") == "5 nm"
    assert units.format_quantity(1e7, "Pa") == "10 MPa"
