"""Reliability round four: the one writer replaces only the user's output.

Only a regular file that is not an input of the command, not a study's own file and not
write-protected is replaced; anything else (a device, a FIFO, a link such as
/dev/stdout, the input under another name or a hard link, a mode-444 file) is refused in
one line, exit 2, before any work. A report directory holding files roughcontact did not
write is refused unless --force; what is written there is recorded, so a rerun goes
ahead. Devices are only ever reached through links made in a temporary directory: if the
rule regressed, the link would be replaced, never the device.
"""

import json
import os
import stat
from pathlib import Path

import numpy as np
import pytest
from _helpers import DATA, POSIX
from _helpers import cli_one_line_error as _one_line
from _helpers import random_surface as _surface
from click.testing import CliRunner

from roughcontact import ParameterError, _guard, _io
from roughcontact.cli.main import main

pytestmark = pytest.mark.skipif(not POSIX, reason="POSIX file kinds and permissions")


@pytest.fixture()
def no_work(monkeypatch):
    """Computing anything fails the test: refusals must come first."""
    import roughcontact.solvers as solvers
    import roughcontact.surfaces as surfaces

    def fail(*a, **k):
        raise AssertionError("computed before the output was checked")

    for module, name in ((solvers, "approach_retract"), (solvers, "solve"),
                         (surfaces, "self_affine")):  # fmt: skip
        monkeypatch.setattr(module, name, fail)


def _path_args(surface, out):
    return ["path", str(surface), "--loads", "1e-3", "2e-3", "1e-3", "-o", str(out)]


def _targets(tmp_path, surface):
    """(name, target, words, check) of every output the writer must refuse."""
    (tmp_path / "null").symlink_to("/dev/null")
    (tmp_path / "stdout").symlink_to("/dev/stdout")
    os.mkfifo(tmp_path / "fifo")
    os.link(surface, tmp_path / "hard.nc")
    (tmp_path / "ro.nc").write_bytes(b"protected")
    (tmp_path / "ro.nc").chmod(0o444)
    sub = tmp_path / "sub"
    sub.mkdir()
    before = surface.read_bytes()
    null, stdout, fifo = tmp_path / "null", tmp_path / "stdout", tmp_path / "fifo"
    return [
        ("null", null, ["symbolic link", "/dev/null"],
         lambda: stat.S_ISCHR(os.stat("/dev/null").st_mode) and null.is_symlink()),
        ("stdout", stdout, ["symbolic link"], stdout.is_symlink),
        ("fifo", fifo, ["FIFO"], lambda: stat.S_ISFIFO(os.lstat(fifo).st_mode)),
        ("input", surface, ["input"], lambda: surface.read_bytes() == before),
        ("input by another path", sub / ".." / surface.name, ["input"],
         lambda: surface.read_bytes() == before),
        ("hard link", tmp_path / "hard.nc", ["input", surface.name],
         lambda: surface.read_bytes() == before),
        ("mode 444", tmp_path / "ro.nc", ["write-protected", "0444"],
         lambda: (tmp_path / "ro.nc").read_bytes() == b"protected"),
    ]  # fmt: skip


def test_path_refuses_every_output_but_a_plain_file_before_any_work(tmp_path, no_work):
    surface = tmp_path / "s.npy"
    np.save(surface, _surface())
    for name, target, words, intact in _targets(tmp_path, surface):
        r = CliRunner().invoke(main, _path_args(surface, target))
        _one_line(r, *words)
        assert intact(), name
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_surface_contact_and_analyze_refuse_their_inputs_and_devices(tmp_path, no_work):
    surface = tmp_path / "s.npy"
    np.save(surface, _surface())
    (tmp_path / "null").symlink_to("/dev/null")
    gen = ["--size", "16", "--hurst", "0.8", "--rms-slope", "0.1", "--short-cutoff", "4"]
    _one_line(CliRunner().invoke(main, ["surface", str(tmp_path / "null"), *gen]), "symbolic")
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
    os.link(surface, tmp_path / "f.npz")
    r = CliRunner().invoke(main, ["contact", str(surface), "--load", "1e-2", "--save-fields",
                                  str(tmp_path / "f.npz")])  # fmt: skip
    _one_line(r, "--save-fields", "input")
    path_file = tmp_path / "p.nc"
    path_file.write_bytes(b"not read")
    os.link(path_file, tmp_path / "p.png")
    r = CliRunner().invoke(main, ["analyze", str(path_file), "--hysteresis-figure",
                                  str(tmp_path / "p.png")])  # fmt: skip
    _one_line(r, "--hysteresis-figure", "input")
    assert path_file.read_bytes() == b"not read"


def test_the_writer_itself_refuses_devices_fifos_and_protected_files(tmp_path):
    os.mkfifo(tmp_path / "fifo")
    with pytest.raises(ParameterError, match="FIFO"):
        _io.write_bytes_atomic(tmp_path / "fifo", b"x")
    (tmp_path / "null").symlink_to("/dev/null")
    with _guard.command_scope():
        _guard.name_output(tmp_path / "null")
        with pytest.raises(ParameterError, match="symbolic link"):
            _io.write_bytes_atomic(tmp_path / "null", b"x")
        _guard.protect(tmp_path / "fifo")
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)
    ro = tmp_path / "ro.txt"
    ro.write_text("keep")
    ro.chmod(0o444)
    with pytest.raises(ParameterError, match="write-protected"):
        _io.write_bytes_atomic(ro, b"x")
    assert ro.read_text() == "keep" and stat.S_IMODE(ro.stat().st_mode) == 0o444
    private = tmp_path / "private.txt"
    private.write_text("old")
    private.chmod(0o600)
    _io.write_bytes_atomic(private, b"new")  # a plain file is replaced, its mode kept
    assert private.read_bytes() == b"new" and stat.S_IMODE(private.stat().st_mode) == 0o600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fifo", "null", "private.txt", "ro.txt"]


def test_collect_never_replaces_a_file_of_the_study(tmp_path):
    out = tmp_path / "study"
    out.mkdir()
    source = tmp_path / "my-study.toml"
    source.write_text("[study]\n")
    (out / "study.json").write_text(json.dumps({"source": str(source)}))
    (out / "task-00000.nc").write_bytes(b"finished task")
    os.link(out / "task-00000.nc", tmp_path / "elsewhere.nc")
    for target, words in (
        (source, ["input"]),  # the study file it was run from
        (out / "task-00000.nc", ["file of the study"]),
        (out / "task-00007.nc", ["file of the study"]),
        (out / "study.json", ["file of the study"]),
        (tmp_path / "elsewhere.nc", ["task-00000.nc"]),
    ):
        r = CliRunner().invoke(main, ["study", "collect", str(out), "-o", str(target)])
        _one_line(r, "-o/--output", *words)
    # any command: a file of a study directory is never an output
    np.save(tmp_path / "s.npy", _surface())
    r = CliRunner().invoke(main, _path_args(tmp_path / "s.npy", out / "task-00000.nc"))
    _one_line(r, "file of the study")
    assert (out / "task-00000.nc").read_bytes() == b"finished task"
    assert not (out / "task-00007.nc").exists() and source.read_text() == "[study]\n"


# --- report directories: foreign files refused, our own rewritten ----------------------


def test_report_directories_holding_foreign_files_are_refused_before_any_work(tmp_path):
    proj = tmp_path / "proj"
    proj.mkdir()
    (proj / "README.md").write_text("the user's own")
    scan = str(DATA / "di-1.di")
    for args in (
        ["study", "report", str(tmp_path), "-o", str(proj)],
        ["figures", str(tmp_path), "-o", str(proj)],
        ["stick", scan, "--modulus", "1 GPa", "--work-of-adhesion", "50 mJ/m^2", "-o", str(proj)],
        ["demo", "--size", "16", "--study-size", "32", "--seeds", "1", "-o", str(proj)],
    ):
        _one_line(CliRunner().invoke(main, args), "README.md", "--force")
    assert (proj / "README.md").read_text() == "the user's own"
    assert sorted(p.name for p in proj.iterdir()) == ["README.md"]


def test_a_rerun_into_its_own_directory_works_and_force_writes_beside_foreign_files(tmp_path):
    scan = tmp_path / "scan.npy"
    np.save(scan, _surface(3, 64) * 1e-9)
    base = ["stick", str(scan), "--pixel-size", "5 nm", "--modulus", "10MPa",
            "--work-of-adhesion", "50mJ/m^2", "--format", "png"]  # fmt: skip
    rep = tmp_path / "rep"
    for _ in range(2):  # the second run finds only its own files
        r = CliRunner().invoke(main, [*base, "-o", str(rep)])
        assert r.exit_code == 0, r.output
    recorded = set(_guard._read_manifest(rep)[0])
    written = {p.name for p in rep.iterdir()} - {_guard.MANIFEST_NAME}
    assert recorded == written and "result.json" in written
    (rep / "notes.txt").write_text("mine")
    _one_line(CliRunner().invoke(main, [*base, "-o", str(rep)]), "notes.txt", "--force")
    r = CliRunner().invoke(main, [*base, "-o", str(rep), "--force"])
    assert r.exit_code == 0, r.output
    assert (rep / "notes.txt").read_text() == "mine"
    files, accepted = _guard._read_manifest(rep)
    assert "notes.txt" not in files and accepted == ["notes.txt"]  # kept, by the user's word
    r = CliRunner().invoke(main, [*base, "-o", str(rep)])  # so the same rerun needs no --force
    assert r.exit_code == 0, r.output
    assert (rep / "notes.txt").read_text() == "mine"
    (rep / "later.txt").write_text("new")  # a file that appeared since: foreign again
    _one_line(CliRunner().invoke(main, [*base, "-o", str(rep)]), "later.txt", "--force")


def test_the_manifest_records_any_file_the_writer_puts_below_a_claimed_directory(tmp_path):
    out = tmp_path / "report"
    with _guard.command_scope():
        _io.claim_directory(out)
        _io.write_bytes_atomic(_io.output_directory(out / "figures") / "a.png", b"png")
        _io.write_bytes_atomic(out / "report.html", b"<html>")  # any name, any writer call
        _io.write_bytes_atomic(tmp_path / "outside.txt", b"x")  # not below: not recorded
    assert _guard._read_manifest(out) == (["figures/a.png", "report.html"], [])
    with _guard.command_scope():
        assert _io.claim_directory(out) == out  # only its own files: accepted
    (out / "figures" / "user.png").write_bytes(b"mine")
    (out / "link").symlink_to(tmp_path / "outside.txt")
    with _guard.command_scope(), pytest.raises(ParameterError) as err:
        _io.claim_directory(out)
    assert "figures/user.png" in str(err.value) and "link" in str(err.value)
    with _guard.command_scope():  # nothing claimed: nothing recorded
        _io.write_bytes_atomic(out / "later.txt", b"x")
    assert "later.txt" not in _guard._read_manifest(out)[0]
    assert Path(out / _guard.MANIFEST_NAME).is_file()
