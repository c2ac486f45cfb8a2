"""Persson–Tosatti's elastic energy of full contact against the peer libraries (test-only).

Adhesion 0.93 has no Persson–Tosatti or Eq. 10 function (its
``ReferenceSolutions.PastewkaRobbins`` is the Maugis–Dugdale wedge model); what it has is
Johnson's sinusoid, whose ``sinewave.JKR.elastic_energy(a, P)`` at full contact
(``a = 1/2``) is the elastic energy of full contact in units of ``h p_wfc`` for the
profile ``2h sin^2(pi x/lambda)`` (``p_wfc = pi E* h/lambda``). SurfaceTopography
(the same authors' surface library, Adhesion's dependency) computes
``U/A = (E*/4) <|grad^(1/2) h|^2>`` on any periodic map (``elastic_energy``).
"""

from __future__ import annotations

import numpy as np
import pytest

import roughcontact as rc
from roughcontact.stickiness import evaluate, inputs_from_heights

pytestmark = pytest.mark.peers


def test_full_contact_energy_of_a_sinusoid_matches_adhesion():
    JKR = pytest.importorskip("Adhesion.ReferenceSolutions.sinewave.JKR")
    n, lam, h, E = 128, 32.0, 0.7, 3.0
    x = np.arange(n)
    z = np.tile((2 * h * np.sin(np.pi * x / lam) ** 2)[:, None], (1, n))
    inp = inputs_from_heights(z, contact_modulus=E, work_of_adhesion=0.2, interaction_range=1)
    ours = evaluate("persson_tosatti", inp).values["elastic_energy_per_area"]
    p_wfc = np.pi * E * h / lam
    theirs = JKR.elastic_energy(0.5, 0.0) * h * p_wfc
    assert ours == pytest.approx(theirs, rel=1e-10)


def test_full_contact_energy_of_a_rough_surface_matches_surfacetopography():
    st = pytest.importorskip("SurfaceTopography")
    z = rc.self_affine((128, 128), hurst=0.7, rms_slope=0.2, short_cutoff=4, seed=5)
    inp = inputs_from_heights(z, contact_modulus=2.0, work_of_adhesion=0.1)
    ours = evaluate("persson_tosatti", inp).values["elastic_energy_per_area"]
    topo = st.Topography(z, physical_sizes=(128.0, 128.0), periodic=True)
    assert ours == pytest.approx(topo.elastic_energy(2.0), rel=1e-6)
