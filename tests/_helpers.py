"""Helpers shared by test modules (importable because pyproject's pytest ``pythonpath``
holds ``tests``): CLI one-line errors, small surfaces, repository test data."""

import os
from pathlib import Path

import numpy as np
import pytest

POSIX = pytest.mark.skipif(os.name != "posix", reason="FIFOs, signals")
#: Real instrument files kept in the repository (data/topographies/README.md).
DATA = Path(__file__).parent / "data" / "topographies"
#: The smallest example study of the repository.
SMOKE = Path(__file__).parents[1] / "studies" / "smoke.toml"


def cli_one_line_error(result, *words, code=2):
    """A click result that failed with ``code`` and one stderr line naming ``words``."""
    assert result.exit_code == code, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.output
    assert lines[0].startswith("roughcontact: error: "), result.output
    for word in words:
        assert word in lines[0], (word, lines[0])
    assert "Traceback" not in result.output


def random_surface(seed=1, n=16):
    """An n x n surface of standard-normal heights."""
    return np.random.default_rng(seed).normal(size=(n, n))
