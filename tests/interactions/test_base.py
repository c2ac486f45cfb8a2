"""The Interaction protocol's members: every law has them, read directly, defaults on GapLaw.

Oracle: the laws' definitions (the parameters they are built with; Pastewka & Robbins,
PNAS 111, 3298 (2014), Methods, for the smoothed 9-3 wall's w = k Δr²/12) and the
first-contact convention d = max(h) + d0 (d0 = a0 for the Lennard-Jones walls, 0 for hard
cores).
"""

import dataclasses

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.interactions._base import GapLaw, Interaction
from roughcontact.interactions.registry import REGISTRY, law_parameters, make_law
from roughcontact.solvers.offsets import first_contact_offset

LAWS = {
    "lj93smooth": rc.SmoothLJ93(work_of_adhesion=0.01),
    "lj93": rc.LennardJones93(work_of_adhesion=0.01, equilibrium_distance=0.7),
    "exponential": rc.Exponential(work_of_adhesion=0.01, range=0.5),
    "dugdale": rc.MaugisDugdale(work_of_adhesion=0.01, range=0.5),
}
MEMBERS = ("equilibrium_distance", "range", "work_of_adhesion", "stiffness")


def test_every_registered_law_but_the_hard_wall_is_an_interaction():
    assert set(LAWS) == set(REGISTRY) - {"hardwall"}
    for law in LAWS.values():
        assert isinstance(law, Interaction)
        for name in MEMBERS:
            getattr(law, name)  # present on every law: callers read them directly


@pytest.mark.parametrize("name", LAWS)
def test_members_are_the_law_parameters_or_none(name):
    law = LAWS[name]
    for member in MEMBERS:
        value = getattr(law, member)
        # a default (None) is not a parameter: the recorded parameters stay the law's own
        assert (value is None) == (member not in law_parameters(law)), member
    assert law.work_of_adhesion == 0.01


def test_the_defaults_and_the_laws_own_values():
    lj, smooth = LAWS["lj93"], LAWS["lj93smooth"]
    assert lj.range is None and lj.equilibrium_distance == 0.7
    assert lj.stiffness == pytest.approx(27 * 0.01 / 0.7**2)  # its own property wins
    assert smooth.stiffness * smooth.range**2 / 12 == pytest.approx(smooth.work_of_adhesion)
    for name in ("exponential", "dugdale"):
        assert LAWS[name].equilibrium_distance is None and LAWS[name].stiffness is None
    assert LAWS["dugdale"].core_stiffness is None


def test_dataclass_laws_keep_their_required_fields():
    # the defaults live on GapLaw without becoming dataclass defaults of its subclasses
    for cls in (rc.Exponential, rc.MaugisDugdale, rc.LennardJones93):
        required = [
            f.name for f in dataclasses.fields(cls) if f.init and f.default is dataclasses.MISSING
        ]
        assert "work_of_adhesion" in required
        with pytest.raises(TypeError):
            cls()
    with pytest.raises(TypeError):
        rc.Exponential(work_of_adhesion=0.01)  # range stays required
    assert not hasattr(GapLaw, "range")  # nothing a dataclass could take as a default


def test_a_new_gap_law_gets_the_defaults():
    class Linear(GapLaw):
        name = "linear"

        @property
        def cutoff(self):
            return 1.0

        def _evaluate(self, gap):
            g = np.asarray(gap, dtype=float)
            return -(1 - g), np.ones_like(g), np.zeros_like(g)

    law = Linear()
    assert isinstance(law, Interaction)
    assert [getattr(law, m) for m in MEMBERS] == [None] * 4
    assert law_parameters(law) == {}


@pytest.mark.parametrize(("name", "d0"), [("lj93", 0.7), ("exponential", 0.0), ("dugdale", 0.0)])
def test_first_contact_reads_the_equilibrium_distance(name, d0):
    h = rc.self_affine((16, 16), hurst=0.8, rms_slope=0.1, short_cutoff=4, seed=1)
    assert first_contact_offset(h, LAWS[name]) == float(h.max()) + d0
    assert first_contact_offset(h, make_law("hardwall")) == float(h.max())
