"""Fixtures shared by the compiled loops' tests: JAX's global x64 switch set for one test."""

import pytest


def _x64(value: bool):
    jax = pytest.importorskip("jax")
    old = bool(jax.config.jax_enable_x64)
    jax.config.update("jax_enable_x64", value)
    yield
    jax.config.update("jax_enable_x64", old)


@pytest.fixture()
def x64():
    """float64 in JAX for the test, the setting restored afterwards."""
    yield from _x64(True)


@pytest.fixture()
def x32():
    """JAX's default float32 for the test, the setting restored afterwards."""
    yield from _x64(False)
