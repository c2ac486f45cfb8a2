"""``roughcontact criterion``: JSON output, units, and bad input (ParameterError, exit 2)."""

import json

import click
import pytest
from click.testing import CliRunner

from roughcontact import ParameterError
from roughcontact.cli.criterion import criterion

RUBBER = ["--work-of-adhesion", "50 mJ/m^2", "--rms-slope", "1", "--range", "0.5 nm"]


def _group():
    """A stand-in for the ``roughcontact`` group: ParameterError -> one line, exit 2."""

    class G(click.Group):
        def invoke(self, ctx):
            try:
                return super().invoke(ctx)
            except ParameterError as err:
                click.echo(f"roughcontact: error: {err}", err=True)
                ctx.exit(2)

    g = G()
    g.add_command(criterion)
    return g


def test_json_output_rubber():
    res = CliRunner().invoke(
        criterion, ["--modulus", "10 MPa", "--d-rep", "10 nm", "--json", *RUBBER]
    )
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    for key in ("kappa_att", "area_ratio", "kappa", "sticky", "margin", "necessary_condition_met",
                "adhesion_length", "contact_modulus", "work_of_adhesion", "rms_slope",
                "interaction_range", "d_rep"):  # fmt: skip
        assert key in out
    assert out["contact_modulus"] == pytest.approx(1e7)
    assert out["work_of_adhesion"] == pytest.approx(0.05)
    assert out["interaction_range"] == pytest.approx(5e-10)
    assert out["adhesion_length"] == pytest.approx(5e-9)
    assert out["sticky"] is True and out["margin"] == pytest.approx(7.04, rel=0.01)
    assert out["kappa"] < 0


def test_json_output_youngs_modulus_and_curvature():
    args = ["--youngs-modulus", "1.5 GPa", "--poisson", "0.3", "--rms-curvature", "0.4 1/nm"]
    res = CliRunner().invoke(criterion, [*args, "--kappa-rep", "2.2", "--json", *RUBBER])
    assert res.exit_code == 0, res.output
    out = json.loads(res.output)
    assert out["contact_modulus"] == pytest.approx(1.5e9 / (1 - 0.09))
    assert out["d_rep"] == pytest.approx(1e-8) and out["d_rep_source"] == "predicted"
    assert out["kappa_rep"] == 2.2 and out["sticky"] is False


def test_human_readable_output():
    res = CliRunner().invoke(criterion, ["--modulus", "1 GPa", "--d-rep", "10 nm", *RUBBER])
    assert res.exit_code == 0, res.output
    assert "NOT sticky" in res.output and "kappa_att" in res.output


@pytest.mark.parametrize(
    ("args", "match"),
    [
        (["--modulus", "10 MPa", "--d-rep", "10 MPa"], "d_rep must be a length"),
        (["--modulus", "10 nm", "--d-rep", "10 nm"], "contact_modulus must be a pressure"),
        (["--modulus", "10 MPa"], "exactly one of --d-rep and --rms-curvature"),
        (["--modulus", "1 MPa", "--d-rep", "1 nm", "--rms-curvature", "1 1/nm"], "exactly one"),
        (["--d-rep", "10 nm"], "--modulus"),
        (["--modulus", "1 MPa", "--youngs-modulus", "1 MPa", "--d-rep", "1 nm"], "excludes"),
        (["--youngs-modulus", "1 MPa", "--d-rep", "1 nm"], "--poisson"),
        (["--modulus", "-3 MPa", "--d-rep", "10 nm"], "contact_modulus must be > 0"),
        (["--modulus", "3 Mpa", "--d-rep", "10 nm"], "unknown unit"),
    ],
)
def test_bad_input_raises_parameter_error(args, match):
    res = CliRunner().invoke(criterion, [*args, *RUBBER])
    assert isinstance(res.exception, ParameterError)
    assert match in str(res.exception)
    # through a group like roughcontact's: one readable line on stderr, exit code 2
    res = CliRunner().invoke(_group(), ["criterion", *args, *RUBBER])
    assert res.exit_code == 2
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and match in lines[0]


def test_missing_required_option_is_a_usage_error():
    res = CliRunner().invoke(criterion, ["--modulus", "1 MPa", "--d-rep", "1 nm"])
    assert res.exit_code == 2 and "--work-of-adhesion" in res.output
