"""A substrate describes itself (to_attrs) and is rebuilt from the description (from_attrs),
including the attribute sets that earlier versions wrote into path files."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.analysis.path_analysis import analyze_path
from roughcontact.elastic import (
    ElasticOperator,
    register_substrate_kind,
    substrate_from_attrs,
    substrate_kind,
)
from roughcontact.solvers.path import provenance

xr = pytest.importorskip("xarray")
TASKS = Path(__file__).resolve().parents[2] / "reproduction" / "tasks"

KINDS = {
    "half-space": dict(shape=(16, 12), contact_modulus=2.5, pixel_size=0.3),
    "bonded layer": dict(shape=(16, 16), thickness=3.0, poisson=0.3, pixel_size=0.5),
    "incompressible layer": dict(shape=(16, 16), thickness=40.0, poisson=0.5),
    "frictionless layer": dict(shape=(12, 16), thickness=2.0, poisson=0.2, base="frictionless"),
    "free half-space": dict(shape=(12, 10), contact_modulus=3.0, pixel_size=2.0, periodic=False),
}


@pytest.mark.parametrize("kind", KINDS)
def test_round_trip_gives_the_same_operator(kind, tmp_path):
    sub = rc.Substrate(**KINDS[kind])
    attrs = sub.to_attrs()
    assert isinstance(sub, ElasticOperator)
    json.dumps(attrs)  # JSON-safe (inf as Infinity, as Python's json writes it)
    # through a NetCDF file, as a path's attributes travel
    xr.Dataset(attrs=attrs).to_netcdf(tmp_path / "a.nc")
    with xr.open_dataset(tmp_path / "a.nc") as ds:
        read = dict(ds.attrs)
    for again in (substrate_from_attrs(attrs), substrate_from_attrs(read)):
        assert type(again) is rc.Substrate and again == sub and repr(again) == repr(sub)
        np.testing.assert_array_equal(again.stiffness, sub.stiffness)
        np.testing.assert_array_equal(again.compliance, sub.compliance)
        p = np.random.default_rng(1).random(sub.shape)
        np.testing.assert_array_equal(again.deflection(p), sub.deflection(p))
        assert again.to_attrs() == attrs


def test_provenance_writes_the_description_in_the_old_names_and_order():
    h = rc.self_affine((32, 32), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=2)
    sub = rc.Substrate((32, 32), thickness=8.0, poisson=0.3)
    attrs = provenance(h, sub, None)
    described = sub.to_attrs()
    assert {k: attrs[k] for k in described} == described
    # the order of the committed path files (written before to_attrs existed)
    with xr.open_dataset(TASKS / "task-00002.nc") as ds:
        old = [k for k in ds.attrs if k in attrs]
    assert [k for k in attrs if k in old] == old


@pytest.mark.parametrize("name", ["task-00000.nc", "task-00002.nc"])
def test_committed_path_files_rebuild_their_substrate(name):
    # task-00000 predates the periodic attribute; both record the repr of the substrate
    # that wrote them: an oracle from the version that wrote the file
    with xr.open_dataset(TASKS / name) as ds:
        attrs = dict(ds.attrs)
    sub = substrate_from_attrs(attrs)
    assert repr(sub) == attrs["substrate"]
    assert sub.periodic and sub.thickness == 1024.0 and sub.shape == (1024, 1024)


def test_oldest_attribute_sets():
    # no tag, no layer keys, no periodic: a periodic half-space
    oldest = {"grid": np.array([8, 6]), "contact_modulus": 2.0, "pixel_size": 0.5}
    sub = substrate_from_attrs(oldest)
    assert sub == rc.Substrate((8, 6), contact_modulus=2.0, pixel_size=0.5)
    # a half-space as written with base "" and thickness inf
    old = {"grid": [8, 8], "contact_modulus": 1.0, "pixel_size": 1.0, "thickness": math.inf,
           "poisson": 0.5, "base": "", "substrate": "Substrate(shape=(8, 8), ...)"}  # fmt: skip
    assert substrate_from_attrs(old) == rc.Substrate((8, 8))


def test_bad_attributes_say_what_is_wrong():
    with pytest.raises(rc.ParameterError, match="grid"):
        substrate_from_attrs({"contact_modulus": 1.0, "pixel_size": 1.0})
    good = rc.Substrate((8, 8)).to_attrs()
    with pytest.raises(rc.ParameterError, match="Viscoelastic.*unknown.*Substrate"):
        substrate_from_attrs({**good, "substrate": "Viscoelastic(shape=(8, 8))"})
    with pytest.raises(rc.ParameterError, match="kind name"):
        substrate_from_attrs({**good, "substrate": "<a substrate>"})


def test_a_registered_kind_is_rebuilt_by_its_own_from_attrs():
    class Doubled(rc.Substrate):
        @classmethod
        def from_attrs(cls, attrs):
            doubled = 2 * attrs["contact_modulus"]
            return rc.Substrate.from_attrs({**attrs, "contact_modulus": doubled})

    register_substrate_kind(Doubled)
    try:
        attrs = {**rc.Substrate((8, 8)).to_attrs(), "substrate": "Doubled(shape=(8, 8))"}
        assert substrate_kind(attrs) == "Doubled"
        assert substrate_from_attrs(attrs).contact_modulus == 2.0
    finally:
        from roughcontact.elastic import attrs as module

        module._KINDS.pop("Doubled")


def test_a_free_path_is_analysed_on_its_free_substrate():
    # the hard-wall reference rebuilt from the path's attributes keeps the free boundary
    n, radius = 48, 60.0
    h = rc.sphere((n, n), radius)
    sub = rc.Substrate((n, n), periodic=False)
    law = rc.SmoothLJ93.from_adhesion_length(1e-7)
    ds = rc.approach_retract(h, sub, law, offsets=1.0 - np.linspace(0.0, 1.0, 11), retract=False)
    assert substrate_from_attrs(ds.attrs) == sub
    target = 0.02
    alone = analyze_path(ds, target_area=target, heights=h)
    given = analyze_path(ds, target_area=target, heights=h, substrate=sub)
    periodic = analyze_path(ds, target_area=target, heights=h, substrate=rc.Substrate((n, n)))
    assert alone.kappa_rep_hard_wall == given.kappa_rep_hard_wall
    assert alone.kappa_rep_hard_wall != periodic.kappa_rep_hard_wall
