"""``import roughcontact`` stays light: no scipy (the theory and the FFTs load it on first
use) and no array-API wrapper of NumPy (built on the first array the core sees)."""

import subprocess
import sys


def _modules_after(code: str) -> list[str]:
    probe = f"{code}; import sys; print(' '.join(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, check=True)
    return out.stdout.split()


def test_import_loads_no_scipy():
    loaded = _modules_after("import roughcontact, roughcontact.theory, roughcontact.elastic")
    assert "roughcontact.theory.persson" in loaded  # the modules that use scipy are imported
    assert [m for m in loaded if m == "scipy" or m.startswith("scipy.")] == []
    assert "array_api_compat.numpy" not in loaded
    assert [m for m in loaded if m == "jax" or m.startswith("jax.")] == []  # only for JAX input


def test_scipy_comes_when_a_theory_needs_it():
    code = (
        "import math, roughcontact.theory as t; "
        "assert math.isclose(t.persson_load(t.persson_area(0.01, 0.1), 0.1), 0.01); "
        "assert 1.5 < t.maugis_dugdale_pull_off(1.0).coefficient < 2"
    )
    assert "scipy.special" in _modules_after(code)
