"""Nothing already computed is lost: checkpoints and Ctrl-C along a path."""

import importlib

import numpy as np
import pytest
import xarray as xr
from click.testing import CliRunner

import roughcontact as rc
from roughcontact.cli.main import main

path_module = importlib.import_module("roughcontact.solvers.path")
H = rc.sphere((32, 32), 12.0)
SUB = rc.Substrate((32, 32))
LOADS = [1e-3, 2e-3, 4e-3, 8e-3, 1.6e-2]


def failing_solve(monkeypatch, at_call, exc):
    """Make the path's ``solve`` raise ``exc`` on its ``at_call``-th call (0-based)."""
    calls = {"n": 0}
    real = path_module.solve

    def solve(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] - 1 == at_call:
            raise exc
        return real(*args, **kwargs)

    monkeypatch.setattr(path_module, "solve", solve)


def test_checkpoint_gets_every_finished_step():
    seen = []
    ds = rc.approach_retract(
        H, SUB, loads=LOADS, retract=False, checkpoint=seen.append, checkpoint_seconds=0
    )
    assert [c.sizes["step"] for c in seen] == [1, 2, 3, 4, 5]
    xr.testing.assert_allclose(seen[-1].drop_attrs(), ds.drop_attrs())
    rarely = []
    rc.approach_retract(H, SUB, loads=LOADS, retract=False, checkpoint=rarely.append)
    assert rarely == []  # the default: at most once a minute


def test_ctrl_c_keeps_the_finished_steps(monkeypatch):
    failing_solve(monkeypatch, 3, KeyboardInterrupt())
    with pytest.raises(rc.PathInterrupted, match="interrupted in step 3") as info:
        rc.approach_retract(H, SUB, loads=LOADS, retract=False)
    assert isinstance(info.value, KeyboardInterrupt)  # Ctrl-C semantics kept
    partial = info.value.partial
    assert partial.sizes["step"] == 3
    np.testing.assert_allclose(partial["load"], LOADS[:3], rtol=1e-9)


def test_ctrl_c_between_steps_or_at_the_end_keeps_every_step(monkeypatch):
    # a signal outside a step's solve (here: while the finished rows are read at the end)
    # is the path's interruption too, not a bare KeyboardInterrupt losing the path
    calls = {"n": 0}
    real = path_module.fetch

    def fetch(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 1:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(path_module, "fetch", fetch)
    with pytest.raises(rc.PathInterrupted, match="interrupted after step 4") as info:
        rc.approach_retract(H, SUB, loads=LOADS, retract=False)
    partial = info.value.partial
    assert partial.sizes["step"] == len(LOADS)
    np.testing.assert_allclose(partial["load"], LOADS, rtol=1e-9)
    assert (partial["repulsive_patches"].values >= 1).all()  # settled on the second try


def test_ctrl_c_that_breaks_the_dataset_is_the_plain_interruption(monkeypatch):
    # a signal inside an import (xarray's, pandas') leaves the module half-made: making the
    # partial dataset then fails too, and the interruption is raised as it came (the CLI:
    # one line, 130), never that second error
    calls = {"n": 0}

    def broken(*args, **kwargs):
        calls["n"] += 1
        if calls["n"] == 1:
            raise KeyboardInterrupt
        raise AttributeError("partially initialized module 'pandas'")

    monkeypatch.setattr(path_module, "path_dataset", broken)
    with pytest.raises(KeyboardInterrupt) as info:
        rc.approach_retract(H, SUB, loads=LOADS[:2], retract=False)
    assert type(info.value) is KeyboardInterrupt and calls["n"] == 2


@pytest.fixture()
def surface_file(tmp_path):
    out = tmp_path / "s.npy"
    np.save(out, H)
    return out


def test_cli_ctrl_c_writes_the_finished_steps_and_exits_130(surface_file, tmp_path, monkeypatch):
    failing_solve(monkeypatch, 3, KeyboardInterrupt())
    out = tmp_path / "p.nc"
    args = ["path", str(surface_file), "--loads", "1e-3", "5e-3", "1e-3", "-o", str(out)]
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 130, r.output
    assert "interrupted in step 3" in r.output and "3 steps before it" in r.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.sizes["step"] == 3 and ds.attrs["surface_file"] == str(surface_file)


def test_cli_crash_leaves_the_last_checkpoint(surface_file, tmp_path, monkeypatch):
    failing_solve(monkeypatch, 4, MemoryError("out of memory"))
    out = tmp_path / "p.nc"
    args = ["path", str(surface_file), "--loads", "1e-3", "5e-3", "1e-3", "-o", str(out)]
    r = CliRunner().invoke(main, [*args, "--checkpoint-seconds", "0"])
    # out of memory is one line and exit code 1, not a traceback
    assert r.exit_code == 1 and "out of memory" in r.output, r.output
    assert len(r.output.strip().splitlines()) == 1, r.output
    with xr.open_dataset(out, engine="h5netcdf") as ds:
        assert ds.sizes["step"] == 4  # every step before the crash
    assert [p.name for p in tmp_path.iterdir() if p.name.endswith(".tmp")] == []
