"""Study files: validation before any work (key, value, range named), expansion."""

import hashlib
import subprocess
import sys
from pathlib import Path

import pytest

from roughcontact import ParameterError
from roughcontact.studies import load_study, study_from_dict
from roughcontact.studies.task import path_values

ROOT = Path(__file__).resolve().parents[2]


def base():
    return {
        "surface": {"size": 32, "hurst": 0.8, "rms_slope": 0.1, "short_cutoff": 4.0, "seeds": [1]},
        "interaction": {"adhesion_length": 0.005},
        "path": {"start": 0.5, "stop": -1.0, "step": 0.5},
    }


def with_(section, **values):
    d = base()
    d.setdefault(section, {}).update(values)
    return d


@pytest.mark.parametrize(
    ("data", "words"),
    [
        (with_("surface", roughness=1.0), ["unknown key", "roughness", "[surface]", "hurst"]),
        ({**base(), "solvers": {}}, ["unknown section", "[solvers]", "solver"]),
        (with_("surface", hurst="0.8"), ["hurst", "'0.8'", "wrong type", "a number", "(0, 1]"]),
        (with_("surface", size=32.0), ["size", "32.0", "wrong type", "an integer", ">= 8"]),
        (with_("path", retract=1), ["retract", "wrong type", "true or false"]),
        (with_("surface", hurst=[]), ["hurst", "[]", "empty"]),
        (with_("surface", seeds=[]), ["seeds", "[]", "empty"]),
        (with_("surface", hurst=1.5), ["hurst", "1.5", "(0, 1]"]),
        (with_("surface", hurst=[0.5, 0.0]), ["hurst", "0.0", "(0, 1]"]),
        (with_("surface", size=4), ["size", "4", ">= 8"]),
        (with_("surface", short_cutoff=1.0), ["short_cutoff", "1.0", ">= 2 * pixel_size"]),
        (with_("surface", long_cutoff=64.0), ["long_cutoff", "64.0", "(4.0, 32.0]"]),
        (with_("interaction", adhesion_length=-0.1), ["adhesion_length", "-0.1", "> 0"]),
        (with_("substrate", poisson=0.7), ["poisson", "0.7", "[0, 0.5]"]),
        (with_("interaction", law="jkr"), ["law", "'jkr'", "lj93smooth", "dugdale"]),
        (with_("interaction", law="lj93", range=0.3), ["range", "0.3", "lj93"]),
        (with_("interaction", law="exponential"), ["exponential", "needs range"]),
        (with_("solver", tol=2.0), ["tol", "2.0", "(0, 1)"]),
        (with_("surface", seeds=[1, 1]), ["seeds", "[1, 1]", "repeated"]),
        (with_("path", values=[1.0, 0.0]), ["[path]", "values", "start"]),
        (
            with_("path", unit="modulus"),
            ["unit", "'modulus'", "'length', 'rms_height', 'bearing_area'"],
        ),
        ({**base(), "cases": [{"hurst": [0.3]}]}, ["[[cases]] #1", "hurst", "wrong type"]),
        (with_("output", fields_at_area=[0.02, 1.0]), ["fields_at_area", "1.0", "(0, 1)"]),
        (with_("output", fields_at_area=0.02), ["fields_at_area", "0.02", "expected a list"]),
        (with_("solver", dtype="float16"), ["dtype", "'float16'", "'float64' or 'float32'"]),
        (with_("solver", dtype="float32"), ["[solver] tol", "1e-08", "float32", ">= 1e-06"]),
    ],
)
def test_bad_study_names_key_value_and_range(data, words):
    with pytest.raises(ParameterError) as err:
        study_from_dict(data)
    message = str(err.value)
    assert "\n" not in message
    for word in words:
        assert word in message, (word, message)


def test_bad_toml_and_missing_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[surface\nsize = 3")
    with pytest.raises(ParameterError, match="bad.toml: not valid TOML"):
        load_study(bad)
    with pytest.raises(ParameterError, match="cannot read study file"):
        load_study(tmp_path / "absent.toml")


def test_grid_expansion_count_and_order(tmp_path, make_study):
    spec = load_study(make_study())
    assert len(spec.tasks) == 2 * 2 * 2
    assert [t.id for t in spec.tasks] == [f"{i:05d}" for i in range(8)]
    order = [(t.params["hurst"], t.params["adhesion_length"], t.params["seed"]) for t in spec.tasks]
    assert order == sorted(order)  # axes in schema order, seeds innermost
    assert spec.axes == {"hurst": [0.5, 0.8], "adhesion_length": [0.005, 0.05], "seed": [1, 2]}
    again = load_study(tmp_path / "tiny.toml")
    assert [(t.id, t.key) for t in again.tasks] == [(t.id, t.key) for t in spec.tasks]
    assert spec.sha256 == hashlib.sha256((tmp_path / "tiny.toml").read_bytes()).hexdigest()
    assert len({t.key for t in spec.tasks}) == 8
    p = spec.tasks[0].params  # derived interaction values are filled in
    assert p["long_cutoff"] == 16.0 and p["stiffness"] == 0.5
    assert p["range"] == pytest.approx((24 * 0.005) ** 0.5)


def test_fields_at_area_leaves_the_keys_of_other_studies_alone():
    # the key of base()'s task before [output] fields_at_area existed: directories
    # written then must still --resume
    spec = study_from_dict(base())
    assert spec.tasks[0].key == "9df334700c1c6b4e970ec7e41acbfeacfa3b0eac5b018f3d5209383f4890c9da"
    assert "fields_at_area" not in spec.settings["output"]
    assert study_from_dict(with_("output", fields_at_area=[])).tasks[0].key == spec.tasks[0].key
    maps = study_from_dict(with_("output", fields_at_area=[0.02, 0.05]))
    assert maps.settings["output"]["fields_at_area"] == [0.02, 0.05]
    assert maps.tasks[0].key != spec.tasks[0].key


def test_cases_times_grid_times_seeds():
    d = with_("interaction", adhesion_length=[0.0005, 0.005, 0.05])
    d["cases"] = [{"hurst": 0.3, "rms_slope": 0.3}, {"hurst": 0.8}]
    d["surface"]["seeds"] = [3, 4]
    spec = study_from_dict(d)
    assert len(spec.tasks) == 2 * 3 * 2
    assert {(t.params["hurst"], t.params["rms_slope"]) for t in spec.tasks} == {
        (0.3, 0.3),
        (0.8, 0.1),
    }
    d["cases"].append({"adhesion_length": 0.1})
    with pytest.raises(ParameterError, match="already a grid axis"):
        study_from_dict(d)


def test_laws_and_path_values():
    import numpy as np

    from roughcontact.studies.spec import make_interaction

    d = with_("interaction", law="dugdale", range=0.5)
    spec = study_from_dict(d)
    law = make_interaction(spec.tasks[0].params)
    assert law.name == "dugdale" and law.work_of_adhesion == 0.005
    h = np.zeros((8, 8))
    h[0, 0] = 1.0
    offsets = path_values(spec.settings["path"], h, law, spec.tasks[0].params)
    np.testing.assert_allclose(offsets, [1.5, 1.0, 0.5, 0.0])  # max(h) + 0 for a hard core
    path = {"unit": "bearing_area", "values": [0.0, 1 / 64, 0.5], "lead_in": [2.0, 0.5]}
    bearing = {**d, "path": path}
    spec = study_from_dict(bearing)
    h = np.arange(64.0).reshape(8, 8)
    offsets = path_values(spec.settings["path"], h, law, spec.tasks[0].params)
    # lead-in above the summit, then the quantiles 1, 63/64, 1/2 of the heights
    np.testing.assert_allclose(offsets, [65.0, 63.5, 63.0, 62.015625, 31.5])
    bearing["path"]["values"] = [0.0, 1.5]
    with pytest.raises(ParameterError, match=r"bearing_area.*\[0, 1\]"):
        study_from_dict(bearing)
    hw = study_from_dict({**base(), "interaction": {"law": "hardwall"}})
    assert hw.tasks[0].params["adhesion_length"] is None
    loads = with_("path", control="load", unit="rms_slope_modulus")
    loads["path"] = {
        "control": "load",
        "unit": "rms_slope_modulus",
        "start": 1e-3,
        "stop": 1e-2,
        "num": 3,
        "spacing": "geometric",
    }
    spec = study_from_dict(loads)
    assert spec.settings["path"]["spacing"] == "geometric"
    loads["path"]["lead_in"] = [1.0]
    with pytest.raises(ParameterError, match="lead_in.*offset"):
        study_from_dict(loads)


def test_shipped_studies_validate():
    smoke = load_study(ROOT / "studies" / "smoke.toml")
    assert len(smoke.tasks) == 8 and smoke.tasks[0].params["size"] <= 96
    paper = load_study(ROOT / "studies" / "paper.toml")
    assert len(paper.tasks) == 3 * 2 * 5 * 3
    p = paper.tasks[0].params
    assert p["size"] == 4096 and p["long_cutoff"] == 2048 and p["thickness"] == 4096
    assert {t.params["short_cutoff"] for t in paper.tasks} == {4.0, 8.0, 16.0, 32.0, 64.0}


def test_importing_roughcontact_loads_neither_dask_nor_xarray():
    code = (
        "import sys, roughcontact, roughcontact.studies, roughcontact.cli.main; "
        "bad = [m for m in ('dask', 'distributed', 'xarray') if m in sys.modules]; "
        "assert not bad, bad"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_dtype_enters_the_task_keys_only_when_not_the_default():
    plain = study_from_dict(base()).tasks[0].key
    assert study_from_dict(with_("solver", dtype="float64")).tasks[0].key == plain
    single = study_from_dict(with_("solver", dtype="float32", tol=1e-6)).tasks[0]
    assert single.key != plain and single.settings["solver"]["dtype"] == "float32"
