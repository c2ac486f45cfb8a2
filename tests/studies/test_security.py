"""Reliability and security: links planted in a study directory, the local cluster's TLS
and HTTP ports, remote TLS settings, --resume with another study."""

import dataclasses
import http.client
import os
import socket
import time
import urllib.request

import psutil
import pytest
from _helpers import cli_one_line_error
from click.testing import CliRunner

from roughcontact import ParameterError, _io
from roughcontact.cli.main import main
from roughcontact.studies import cluster, load_study, run_study, store
from roughcontact.studies.lock import LOCK_NAME, UnsafePath, directory_lock

VICTIM = "important\n"


@pytest.fixture()
def victim(tmp_path):
    """A file of the user's outside the study directory, that a planted link points to."""
    path = tmp_path / "victim.txt"
    path.write_text(VICTIM)
    return path


def _unchanged(victim):
    assert victim.read_text() == VICTIM and victim.stat().st_nlink == 1


def _run(study, out, **kwargs):
    return run_study(study, out, scheduler="synchronous", progress=False, **kwargs)


def _cli(*args):
    return CliRunner().invoke(main, ["study", "run", *map(str, args), "--no-progress"])


# -- links planted in the output directory -------------------------------------------


@pytest.mark.parametrize("kind", ["symlink", "dangling symlink", "hard link", "fifo"])
def test_lock_file_that_is_not_a_plain_file_is_refused(tmp_path, make_study, victim, kind):
    out = tmp_path / "out"
    out.mkdir()
    lock = out / LOCK_NAME
    if kind == "symlink":
        lock.symlink_to(victim)
    elif kind == "dangling symlink":
        lock.symlink_to(tmp_path / "created.txt")
    elif kind == "hard link":
        os.link(victim, lock)
    else:
        os.mkfifo(lock)
    with pytest.raises(UnsafePath) as err:
        _run(make_study(), out)
    message = str(err.value)
    assert repr(str(lock)) in message and "\n" not in message
    assert victim.read_text() == VICTIM and not (tmp_path / "created.txt").exists()
    assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME]  # nothing else written
    r = _cli(make_study(), "-o", out)  # the command line
    cli_one_line_error(r, str(lock), "refusing")
    assert victim.read_text() == VICTIM


def test_lock_of_a_regular_file_is_still_taken(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / LOCK_NAME).write_text("PID 1 on elsewhere since 2020\n")
    with directory_lock(out) as path:
        assert f"PID {os.getpid()} " in path.read_text()


def test_manifest_and_study_copy_replace_links_instead_of_following(tmp_path, make_study, victim):
    out = tmp_path / "out"
    out.mkdir()
    # a dangling link is not taken as an existing study; a link to a file would be
    (out / "study.json").symlink_to(tmp_path / "created.json")
    (out / "study.toml").symlink_to(victim)
    summary = _run(make_study(), out)
    assert summary.ok and summary.completed == 8
    _unchanged(victim)
    assert not (tmp_path / "created.json").exists()
    for name in ("study.json", "study.toml"):
        assert not (out / name).is_symlink() and (out / name).is_file()
    assert store.read_manifest(out)["sha256"] == load_study(make_study()).sha256
    # a manifest that is a link is never read (nor followed by --resume)
    (out / "study.json").unlink()
    (out / "study.json").symlink_to(victim)
    with pytest.raises(UnsafePath, match="study.json"):
        store.read_manifest(out)
    with pytest.raises(UnsafePath, match="study.json"):
        _run(make_study(), out, resume=True)
    _unchanged(victim)


def test_task_files_failure_records_and_temporaries_replace_links(tmp_path, make_study, victim):
    spec = load_study(make_study())
    bad = dataclasses.replace(spec.tasks[2], params={**spec.tasks[2].params, "hurst": 1.5})
    spec = dataclasses.replace(spec, tasks=(*spec.tasks[:2], bad, *spec.tasks[3:]))
    out = tmp_path / "out"
    first = _run(spec, out)
    assert (first.completed, first.failed) == (7, 1)
    # a finished task's file, a failure record and a temporary file become links
    finished = store.task_path(out, "00000")
    elsewhere = tmp_path / "finished-elsewhere.nc"
    finished.rename(elsewhere)
    finished.symlink_to(elsewhere)  # would pass as finished if it were followed
    before = elsewhere.stat().st_mtime_ns
    (out / "task-00005.nc").unlink()
    (out / "task-00005.nc").symlink_to(victim)
    failure = store.failure_path(out, "00002")
    failure.unlink()
    failure.symlink_to(victim)
    tmp = out / ".task-00003.nc.0123456789ab.tmp"
    tmp.symlink_to(victim)
    again = _run(spec, out, resume=True)
    assert (again.skipped, again.completed, again.failed) == (5, 2, 1)
    _unchanged(victim)
    assert elsewhere.stat().st_mtime_ns == before
    assert not any(p.is_symlink() for p in out.iterdir()), sorted(os.listdir(out))
    assert "hurst" in failure.read_text() and not tmp.exists()
    for task_id in ("00000", "00005"):
        assert store.check_task(out, spec.tasks[int(task_id)])[0] is True


def test_temporary_file_is_never_opened_through_a_link(tmp_path, monkeypatch, victim):
    class Fixed:
        hex = "0123456789ab" * 3

    monkeypatch.setattr(_io.uuid, "uuid4", lambda: Fixed)
    out = tmp_path / "out"
    out.mkdir()
    (out / ".study.json.0123456789ab.tmp").symlink_to(victim)
    with pytest.raises(UnsafePath, match="symbolic link"):
        store._write_json(out / "study.json", {"a": 1})
    (out / ".task-00000.nc.0123456789ab.tmp").symlink_to(victim)
    with pytest.raises(UnsafePath, match="symbolic link"):
        store._write_bytes(out / "task-00000.nc", b"x")
    _unchanged(victim)
    assert not (out / "study.json").exists() and not (out / "task-00000.nc").exists()


# -- --resume with another study --------------------------------------------------------


def _snapshot(out):
    return {
        p.name: (p.stat().st_mtime_ns, p.read_bytes())
        for p in sorted(out.iterdir())
        if p.name != LOCK_NAME  # holds the PID of the last run that took the lock
    }


def test_resume_with_another_study_is_refused_and_writes_nothing(tmp_path, make_study):
    first, out = make_study(), tmp_path / "out"
    assert _run(first, out).ok
    other = make_study(num=5, name="other.toml")
    before = _snapshot(out)
    r = _cli(other, "-o", out, "--resume")
    cli_one_line_error(r, "resume", str(first), str(other), "tiny", "sha256")
    with pytest.raises(ParameterError, match="resume: .* holds study 'tiny' from"):
        _run(other, out, resume=True)
    assert _snapshot(out) == before
    # the study file it was run with, or its copy in the directory, resumes it
    assert _run(out / "study.toml", out, resume=True).skipped == 8
    r = _cli(first, "-o", out, "--resume")
    assert r.exit_code == 0 and "8 already finished" in r.output, r.output


def test_resume_of_task_files_without_a_manifest_is_refused(tmp_path, make_study):
    out = tmp_path / "out"
    assert _run(make_study(), out).ok
    (out / "study.json").unlink()
    before = _snapshot(out)
    with pytest.raises(ParameterError, match="task files but no study.json"):
        _run(make_study(), out, resume=True)
    assert _snapshot(out) == before
    assert _run(make_study(), tmp_path / "new", resume=True).completed == 8  # a new study


# -- the local cluster: TLS, no HTTP ----------------------------------------------------


def _listening(procs):
    ports = set()
    for proc in procs:
        try:
            conns = proc.net_connections(kind="inet")
        except psutil.Error:
            continue
        ports |= {c.laddr.port for c in conns if c.status == psutil.CONN_LISTEN}
    return ports


def _port(address):
    return int(address.rsplit(":", 1)[1])


@pytest.fixture(scope="module")
def secured():
    """``(client, cluster)``: the run's own local cluster with 2 workers."""
    client, own = cluster.connect(None, 2)
    yield client, own
    client.close()
    own.close()


def test_foreign_clients_are_refused_by_the_local_cluster(secured):
    from distributed import Client
    from distributed.security import Security

    client, own = secured
    address = own.scheduler_address
    assert address.startswith("tls://127.0.0.1:") and client.submit(abs, -3).result() == 3
    workers = list(client.scheduler_info()["workers"])
    assert workers and all(w.startswith("tls://127.0.0.1:") for w in workers)
    for target, security in [
        (address.replace("tls://", "tcp://"), None),  # plain Dask protocol
        (address, Security.temporary()),  # TLS, but credentials of another cluster
        (workers[0], Security.temporary()),  # straight to a worker
    ]:
        t0 = time.perf_counter()
        with pytest.raises((OSError, TimeoutError, ValueError)):
            Client(target, security=security, timeout=3, set_as_default=False)
        assert time.perf_counter() - t0 < 5
    with pytest.raises(ParameterError, match="does not answer as a Dask scheduler"):
        cluster.connect(address, None, Security.temporary())
    with pytest.raises(ParameterError, match="needs TLS credentials"):
        cluster.connect(address, None)


def test_local_cluster_opens_no_http_port():
    me = psutil.Process()
    old_children = {p.pid for p in me.children(recursive=True)}
    before = _listening([me])
    client, own = cluster.connect(None, 2)
    try:
        info = client.scheduler_info()
        comm = {_port(own.scheduler_address)}
        for address, worker in info["workers"].items():
            comm |= {_port(address), _port(worker["nanny"])}
        children = [p for p in me.children(recursive=True) if p.pid not in old_children]
        assert len(children) >= 2
        opened = (_listening([me]) - before) | _listening(children)
        assert opened == comm and len(comm) == 5
        assert info.get("services", {}) == {}
        for port in sorted(opened):  # none of them speaks HTTP
            with pytest.raises((OSError, http.client.HTTPException)):
                urllib.request.urlopen(f"http://127.0.0.1:{port}/health", timeout=3)
    finally:
        client.close()
        own.close()


def test_dashboard_is_an_explicit_opt_in(tmp_path, make_study):
    client, own = cluster.connect(None, 1, None, True)
    try:
        link = client.dashboard_link
        assert link.startswith("http://127.0.0.1:")
        port = int(link.split(":")[2].split("/")[0])
        with urllib.request.urlopen(f"http://127.0.0.1:{port}/health", timeout=3) as r:
            assert r.read() == b"ok"
    finally:
        client.close()
        own.close()
    with pytest.raises(ParameterError, match="dashboard .* local cluster only"):
        _run(make_study(), tmp_path / "out", dashboard=True)
    assert not (tmp_path / "out").exists()


# -- a remote TLS scheduler: security= and --tls-* --------------------------------------


def test_remote_tls_scheduler_with_security_and_cli_options(tmp_path, make_study, secured):
    client, own = secured
    address, sec = own.scheduler_address, own.security
    study = make_study()
    summary = run_study(study, tmp_path / "api", scheduler=address, security=sec, progress=False)
    assert summary.ok and summary.completed == 8
    pem = {}
    for name, text in [
        ("ca", sec.tls_ca_file),
        ("cert", sec.tls_client_cert),
        ("key", sec.tls_client_key),
    ]:
        pem[name] = tmp_path / f"{name}.pem"
        pem[name].write_text(text)
    tls = ["--tls-ca-file", pem["ca"], "--tls-cert", pem["cert"], "--tls-key", pem["key"]]
    r = _cli(study, "-o", tmp_path / "cli", "--scheduler", address, *tls)
    assert r.exit_code == 0 and "8 computed" in r.output, r.output
    # bad TLS options: one line, exit 2, nothing written
    bad = tmp_path / "bad"
    cli_one_line_error(_cli(study, "-o", bad, "--scheduler", address), "needs TLS credentials")
    r = _cli(study, "-o", bad, "--scheduler", address, "--tls-cert", pem["cert"])
    cli_one_line_error(r, "tls_ca_file", "--tls-ca-file")
    r = _cli(study, "-o", bad, "--scheduler", address, *tls[:2], "--tls-cert", tmp_path / "no")
    cli_one_line_error(r, "tls_cert", "readable PEM file")
    cli_one_line_error(_cli(study, "-o", bad, *tls), "applies to a remote scheduler")
    cli_one_line_error(_cli(study, "-o", bad, "--scheduler", address, "--dashboard"), "dashboard")
    assert not bad.exists()
    with pytest.raises(ParameterError, match="security must be a distributed.security"):
        run_study(study, bad, scheduler=address, security={"tls_ca_file": "x"})


def test_unreachable_tls_scheduler_fails_fast(tmp_path, make_study, secured):
    _, own = secured
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    t0 = time.perf_counter()
    with pytest.raises(ParameterError, match="cannot reach the Dask scheduler"):
        run_study(
            make_study(), tmp_path / "o", scheduler=f"tls://127.0.0.1:{port}", security=own.security
        )
    assert time.perf_counter() - t0 < 5 and not (tmp_path / "o").exists()
