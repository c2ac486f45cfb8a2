"""Shared test helpers: a tiny study (32² or 64² grids, short paths)."""

import textwrap

import pytest

TINY = """
[study]
name = "tiny"

[surface]
size = {size}
hurst = [0.5, 0.8]
rms_slope = 0.1
short_cutoff = 4.0
seeds = [1, 2]

[interaction]
adhesion_length = [0.005, 0.05]

[path]
unit = "rms_height"
start = 0.5
stop = -2.0
num = {num}
retract = true

[solver]
tol = 1e-6
{extra}
"""


def tiny_study(directory, *, size=32, num=6, extra="", name="tiny.toml"):
    """Write a 2 x 2 x 2-seed study (8 tasks) and return its path."""
    path = directory / name
    path.write_text(textwrap.dedent(TINY.format(size=size, num=num, extra=extra)))
    return path


@pytest.fixture()
def make_study(tmp_path):
    """``make_study(size=32, num=6, extra="")``: write a tiny study into ``tmp_path``."""
    return lambda **kwargs: tiny_study(tmp_path, **kwargs)
