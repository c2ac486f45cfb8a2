"""The interaction registry: one owner of the law names, parameters and checks."""

import pytest

import roughcontact as rc
from roughcontact.cli.main import INTERACTIONS, _make_interaction
from roughcontact.interactions._base import Interaction
from roughcontact.interactions.registry import REGISTRY, lookup, make_law, names
from roughcontact.studies.schema import LAWS, SCHEMA, make_interaction

DIRECT = {
    "hardwall": ({}, rc.HardWall()),
    "lj93smooth": (
        {"range": 1.5, "contact_modulus": 2.0, "pixel_size": 0.5},
        rc.SmoothLJ93(contact_modulus=2.0, pixel_size=0.5, range=1.5),
    ),
    "lj93": (
        {"work_of_adhesion": 0.1, "pixel_size": 2.0},
        rc.LennardJones93(work_of_adhesion=0.1, equilibrium_distance=2.0),
    ),
    "exponential": (
        {"adhesion_length": 0.05, "contact_modulus": 2.0, "range": 0.3, "core_stiffness": 4.0},
        rc.Exponential(work_of_adhesion=0.1, range=0.3, core_stiffness=4.0),
    ),
    "dugdale": (
        {"work_of_adhesion": 0.1, "range": 0.3},
        rc.MaugisDugdale(work_of_adhesion=0.1, range=0.3),
    ),
}


def test_registry_names_in_cli_order():
    assert names() == ("hardwall", "lj93smooth", "lj93", "exponential", "dugdale")
    assert set(DIRECT) == set(REGISTRY)


@pytest.mark.parametrize("name", list(DIRECT))
def test_every_name_builds_the_class_law(name):
    params, expected = DIRECT[name]
    law = make_law(name, **params)
    assert law == expected
    assert type(law) is REGISTRY[name].cls
    assert law.name == name
    assert isinstance(law.adhesive, bool) and law.adhesive == (name != "hardwall")
    if name != "hardwall":
        assert isinstance(law, Interaction)


def test_cli_choices_equal_the_registry():
    from roughcontact.cli.main import main

    assert INTERACTIONS == list(names())
    seen = 0
    for command in main.commands.values():
        for param in command.params:
            if param.name == "interaction":
                assert list(param.type.choices) == list(names())
                seen += 1
    assert seen


def test_schema_choices_equal_the_registry():
    assert set(LAWS) == set(names()) and len(LAWS) == len(names())
    key = SCHEMA["interaction"]["law"]
    assert key.default == "lj93smooth"
    assert all(key.test(n) for n in names()) and not key.test("nope")


def test_cli_and_study_build_the_same_laws():
    law = _make_interaction("exponential", None, 0.3, None, 4.0, 2.0, 1.0, 0.05)
    assert law == DIRECT["exponential"][1]
    p = {"law": "dugdale", "contact_modulus": 1.0, "pixel_size": 1.0, "adhesion_length": 0.1}
    p["range"] = 0.3
    assert make_interaction(p) == DIRECT["dugdale"][1]


@pytest.mark.parametrize(
    ("name", "params", "words"),
    [
        ("nope", {}, "one of hardwall, lj93smooth"),
        ("hardwall", {"range": 1.0}, "range does not apply to interaction 'hardwall'"),
        ("lj93", {"work_of_adhesion": 0.1, "range": 1.0}, "range does not apply"),
        ("exponential", {"range": 0.3}, "'exponential' needs work_of_adhesion"),
        ("dugdale", {"work_of_adhesion": 0.1}, "'dugdale' needs range"),
        ("exponential", {"work_of_adhesion": 0.1, "adhesion_length": 0.1}, "not both"),
        ("lj93", {"adhesion_length": -1.0}, "adhesion_length must be > 0"),
        ("lj93", {"bogus": 1.0}, "bogus is not a parameter of interaction 'lj93'"),
        ("dugdale", {"work_of_adhesion": 0.1, "range": -1.0}, "range"),
    ],
)
def test_bad_or_missing_parameters_are_one_line_errors(name, params, words):
    with pytest.raises(rc.ParameterError, match=words) as err:
        make_law(name, **params)
    assert "\n" not in str(err.value)


def test_spellings_keep_the_cli_and_study_messages():
    with pytest.raises(rc.ParameterError, match=r"^--interaction dugdale needs --range \("):
        make_law("dugdale", spelling="cli", work_of_adhesion=0.1)
    with pytest.raises(rc.ParameterError, match=r"^--stiffness does not apply to --interaction"):
        make_law("lj93", spelling="cli", stiffness=1.0)
    with pytest.raises(rc.ParameterError, match=r"^law = 'exponential' needs range"):
        make_law("exponential", spelling="study", adhesion_length=0.1)
    with pytest.raises(rc.ParameterError, match=r"^range = 1.0 does not apply to law = 'lj93'"):
        make_law("lj93", spelling="study", adhesion_length=0.1, range=1.0)
    with pytest.raises(rc.ParameterError, match=r"^law = 'lj93smooth' needs adhesion_length"):
        make_law("lj93smooth", spelling="study")


def test_entries_state_required_parameters():
    assert lookup("exponential").required == ("work_of_adhesion", "range")
    assert lookup("exponential").takes == (
        "adhesion_length",
        "work_of_adhesion",
        "range",
        "core_stiffness",
    )
    assert lookup("hardwall").takes == ()
    assert lookup("lj93smooth").required == ()


def test_no_import_cycle_between_backend_and_validate():
    from pathlib import Path

    import roughcontact._backend as backend

    text = Path(backend.__file__).read_text()
    assert "_validate" not in text
    from roughcontact._validate import ParameterError

    assert ParameterError is rc.ParameterError


def test_every_place_that_names_law_parameters_reads_the_registry_list():
    from roughcontact.cli.main import main
    from roughcontact.interactions.registry import LAW_ATTRIBUTES, LAW_PARAMETERS, PARAMETERS
    from roughcontact.pathdata import ATTRIBUTES
    from roughcontact.plot._data import ADHESION_KEYS

    given = [p.name for p in LAW_PARAMETERS if p.given]
    # the contract: these spellings never change
    assert PARAMETERS == ("adhesion_length", "work_of_adhesion", "range", "stiffness",
                          "core_stiffness")  # fmt: skip
    assert LAW_ATTRIBUTES == ("work_of_adhesion", "range", "stiffness",
                              "equilibrium_distance", "core_stiffness")  # fmt: skip
    options = {o for p in main.commands["contact"].params for o in p.opts}
    assert {"--" + k.replace("_", "-") for k in given} <= options
    assert list(SCHEMA["interaction"]) == ["law", *given]
    assert ADHESION_KEYS == ("law", *given)
    recorded = [a.name for a in ATTRIBUTES if a.name in LAW_ATTRIBUTES]
    assert recorded == list(LAW_ATTRIBUTES)


def test_provenance_records_the_built_law_under_the_registry_names():
    from roughcontact.solvers.path import provenance

    law = rc.Exponential(work_of_adhesion=0.1, range=0.3, core_stiffness=4.0)
    attrs = provenance(rc.sinusoid(16, 8.0, 0.1), rc.Substrate((16, 16)), law)
    assert {k: attrs[k] for k in ("work_of_adhesion", "range", "core_stiffness")} == {
        "work_of_adhesion": 0.1, "range": 0.3, "core_stiffness": 4.0}  # fmt: skip
    assert "stiffness" not in attrs and "equilibrium_distance" not in attrs
    lj = provenance(rc.sinusoid(16, 8.0, 0.1), rc.Substrate((16, 16)), rc.SmoothLJ93(range=1.5))
    assert lj["equilibrium_distance"] == 1.0 and lj["range"] == 1.5
