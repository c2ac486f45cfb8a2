"""Helpers shared by test modules (importable because pyproject's pytest ``pythonpath``
holds ``tests``): CLI one-line errors, small surfaces, repository test data."""

import os
from pathlib import Path

import numpy as np
import pytest

from roughcontact.errors import ParameterError

POSIX = pytest.mark.skipif(os.name != "posix", reason="FIFOs, signals")
#: Real instrument files kept in the repository (data/topographies/README.md).
DATA = Path(__file__).parent / "data" / "topographies"
#: The smallest example study of the repository.
SMOKE = Path(__file__).parents[1] / "studies" / "smoke.toml"


def cli_one_line_error(result, *words, code=2, start=""):
    """A click result that failed with exit ``code``: one stderr line
    ``roughcontact: error: <start>...`` naming every one of ``words``, no traceback and no
    uncaught exception. Returns the line."""
    assert result.exit_code == code, (result.exit_code, result.output, result.exception)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.output
    assert lines[0].startswith("roughcontact: error: " + start), result.output
    for word in words:
        assert word in lines[0], (word, lines[0])
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    return lines[0]


def one_line_message(err, *words):
    """The message of a raised error (the exception or pytest's ``ExceptionInfo``): one
    line naming every one of ``words``. Returns it."""
    text = str(getattr(err, "value", err))
    assert "\n" not in text, text
    for word in words:
        assert word in text, (word, text)
    return text


def raises_one_line(call, *words, error=ParameterError):
    """``call()`` raises ``error`` with a one-line message naming ``words``; returns it."""
    with pytest.raises(error) as err:
        call()
    return one_line_message(err, *words)


def random_surface(seed=1, n=16):
    """An n x n surface of standard-normal heights."""
    return np.random.default_rng(seed).normal(size=(n, n))


def assert_numbers_close(actual, expected, *, rel=1e-9, abs=1e-15, where="$"):
    """Two JSON-like trees agree: the same keys, lengths, strings, booleans, integers and
    ``None``s, and floats to ``rel`` relative (plus ``abs`` absolute, for values at zero).

    For results computed on another machine (another numpy/scipy, another CPU): their last
    digits are rounding, not meaning, so an exact comparison fails there (e.g. a fit's
    minimum that differs in the 16th digit).
    """
    import math

    if isinstance(expected, dict):
        assert isinstance(actual, dict), (where, actual)
        assert list(actual) == list(expected), (where, sorted(set(actual) ^ set(expected)))
        for key, value in expected.items():
            assert_numbers_close(actual[key], value, rel=rel, abs=abs, where=f"{where}.{key}")
    elif isinstance(expected, list | tuple):
        assert isinstance(actual, list | tuple) and len(actual) == len(expected), where
        for i, (a, e) in enumerate(zip(actual, expected, strict=True)):
            assert_numbers_close(a, e, rel=rel, abs=abs, where=f"{where}[{i}]")
    elif isinstance(expected, float) and not isinstance(actual, bool):
        assert isinstance(actual, int | float), (where, actual, expected)
        assert math.isclose(actual, expected, rel_tol=rel, abs_tol=abs) or (
            math.isnan(actual) and math.isnan(expected)
        ), (where, actual, expected)
    else:  # str, bool, int, None: exact (an int that became a float is a change)
        assert type(actual) is type(expected) and actual == expected, (where, actual, expected)


def donatable(state, count: int):
    """``count`` independent copies of a compiled loop's state record: ``run`` takes its
    argument's buffers over (donated, deleted after the call), so each call needs its own."""
    jax = pytest.importorskip("jax")
    return [jax.tree.map(lambda x: x.copy(), state) for _ in range(count)]


def assert_donated(state):
    """The loop reused the state's buffers (its memory is not held twice)."""
    jax = pytest.importorskip("jax")
    leaves = [x for x in jax.tree.leaves(state) if getattr(x, "ndim", 0) >= 1]
    assert leaves and all(x.is_deleted() for x in leaves)


def warm_steps_by_load_and_offset(h, sub, law, loads):
    """A load-controlled approach through ``loads`` (every step converged, each load
    carried to 1e-8 E*) and the offset-controlled approach through the offsets it found:
    ``(by_load, median warm load step, median warm offset step)`` in iterations."""
    import roughcontact as rc

    by_load = rc.approach_retract(h, sub, law, loads=loads, retract=False)
    assert all(by_load["converged"].values)
    np.testing.assert_allclose(by_load["load"].values, loads, atol=1e-8)
    by_offset = rc.approach_retract(h, sub, law, offsets=by_load["offset"].values, retract=False)
    warm = [float(np.median(ds["iterations"].values[1:])) for ds in (by_load, by_offset)]
    return by_load, *warm


def flat_through_contact():
    """A gentle surface (h'rms 0.05) pushed to a mean gap of 0.02 a0: every site deep in the
    core, uniform pressures ~6e12 E*, whose force balance rounds to exactly 0."""
    import roughcontact as rc

    h = rc.self_affine((64, 64), hurst=0.8, rms_slope=0.05, short_cutoff=4.0, seed=11)
    law = rc.SmoothLJ93.from_adhesion_length(0.05)
    return h, law, float(h.max()) - 0.5
