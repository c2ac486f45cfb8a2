"""stick --simulate's cycles in SI: a cycle worked by hand through simulation_hysteresis."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
import xarray as xr

from roughcontact.topography.hysteresis import simulation_hysteresis


def _cycle(scale=1.0):
    """d = 1, 0 (approach), 0, 1 (retract); N/A0 = 0, -1, -2, 0 in units of E* (× scale).

    -∮N dd by trapezoids: -(-0.5)(-1) + 0 + -(-1)(+1) = 0.5 E* a0 per A0 (× scale)."""
    ds = xr.Dataset(
        {
            "offset": ("step", np.array([1.0, 0.0, 0.0, 1.0])),
            "load": ("step", scale * np.array([0.0, -1.0, -2.0, 0.0])),
            "branch": ("step", np.array(["approach", "approach", "retract", "retract"])),
            "jump": ("step", np.array([False, False, True, False])),
        },
        attrs={"nominal_area": 64.0 * 64.0},
    )
    return ds


def test_cycle_by_hand_in_si():
    # E* = 1 GPa, a0 = 0.3 nm: 0.5 E* a0 = 0.15 J/m^2 (seed 1), 0.3 J/m^2 (seed 2)
    runs = [SimpleNamespace(seed=1, path=_cycle()), SimpleNamespace(seed=2, path=_cycle(2.0)),
            SimpleNamespace(seed=3, path=None)]  # fmt: skip
    sim = SimpleNamespace(runs=runs, path={"until_area": 0.05})
    hy = simulation_hysteresis(sim, atomic_spacing=0.3e-9, contact_modulus=1e9, scan_area=1e-12)
    assert [s["seed"] for s in hy["seeds"]] == [1, 2]  # seed 3 has no path
    assert hy["seeds"][0]["dissipated_energy"] == pytest.approx(0.5)
    assert hy["seeds"][0]["dissipated_energy_si"] == pytest.approx(0.15, rel=1e-12)
    assert hy["seeds"][1]["dissipated_energy_si"] == pytest.approx(0.3, rel=1e-12)
    assert hy["dissipated_energy_si"] == pytest.approx(0.225, rel=1e-12)
    assert hy["dissipated_energy_si_std"] == pytest.approx(0.15 / math.sqrt(2), rel=1e-12)
    assert hy["dissipated_energy_scan"] == pytest.approx(0.225e-12, rel=1e-12)
    # one jump per cycle; over the 64^2 a0^2 patch (3.6864e-16 m^2): 0.15 J/m^2 × patch
    assert hy["jumps_mean"] == 1
    assert hy["seeds"][0]["energy_per_jump_joules"] == pytest.approx(0.15 * 3.6864e-16)
    assert any("5 %" in n for n in hy["notes"]) and any("extrapolated" in n for n in hy["notes"])
    # the cycles are closed (zero load at both ends, same offset): nothing said about it
    assert not any("not closed" in n for n in hy["notes"])


def test_line_scan_and_no_path():
    sim = SimpleNamespace(runs=[SimpleNamespace(seed=1, path=_cycle())], path={})
    hy = simulation_hysteresis(sim, atomic_spacing=1e-10, contact_modulus=1e6)
    assert math.isnan(hy["dissipated_energy_scan"])
    assert any("line scan" in n for n in hy["notes"])
    none = SimpleNamespace(runs=[SimpleNamespace(seed=1, path=None)], path={})
    assert simulation_hysteresis(none, atomic_spacing=1e-10, contact_modulus=1e6) is None
