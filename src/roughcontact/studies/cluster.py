"""Where the tasks run: an in-process cluster, a remote Dask scheduler, or here.

The in-process cluster (one scheduler, single-threaded worker processes) talks TLS with
temporary credentials (``distributed.security.Security.temporary()``, made for each run
and held in memory only): every connection must present a certificate of that run, so
another local process cannot connect a client and run code as the user. It opens no
HTTP port (no dashboard, no Prometheus or health routes; Dask would open one on the
scheduler, 8787, and one on every worker even with ``dashboard_address=None``) unless the
dashboard is asked for (``dashboard=True``, ``--dashboard``: the scheduler's, on
127.0.0.1, plain HTTP without authentication).

A remote address is checked (TCP connection and a Dask handshake, ``CONNECT_TIMEOUT``
seconds) before any work starts, so a wrong or unreachable address is one clear error.
A ``tls://`` scheduler is reached with the given ``security`` (a
``distributed.security.Security``, e.g. from :func:`tls_security`) or, without one, with
the TLS settings of Dask's configuration (``distributed.comm.tls.*``).

The local workers keep their scratch files (spilled data, worker directories) in a
directory of their own, made fresh for each run by :func:`tempfile.mkdtemp` (mode 0700:
no other user can list, rename or replace what is in it, as they could in a shared
``$TMPDIR/dask-scratch-space`` created by someone else with mode 0777) and removed when
the cluster closes (:func:`close`). Dask's ``temporary-directory`` points there while the
cluster is made, so the scheduler's scratch space (``dask-scratch-space/global.lock``,
``purge.lock``) is inside it too: nothing touches the shared path, where a planted link
could make the run create a file elsewhere with the user's rights. A run holds an
advisory lock on :data:`SCRATCH_LOCK` in its directory; at the next start, directories
left by a killed run (ours by owner, older than :data:`STALE_SCRATCH_SECONDS`, their lock
free) are removed (:func:`remove_stale_scratch`). Their number is at most
:data:`MAX_WORKERS_PER_CORE` per CPU core.
"""

from __future__ import annotations

import os
import socket
import sys
import tempfile
import traceback
import weakref
from pathlib import Path

from .._validate import ParameterError
from ._gpus import pinned_worker
from ._scratch import SCRATCH_LOCK as SCRATCH_LOCK
from ._scratch import SCRATCH_PREFIX, lock_scratch, remove_scratch, remove_stale_scratch
from ._scratch import STALE_SCRATCH_SECONDS as STALE_SCRATCH_SECONDS
from .task import run_task

__all__ = [
    "CONNECT_TIMEOUT",
    "DASHBOARD_ADDRESS",
    "check_options",
    "close",
    "connect",
    "outcomes",
    "remove_stale_scratch",
    "tls_security",
]


CONNECT_TIMEOUT = 5.0  # seconds to reach a remote scheduler before giving up
DASHBOARD_ADDRESS = "127.0.0.1:8787"  # the local dashboard, when asked for (loopback only)
_QUIET = ("_QuietScheduler", "_QuietWorker")
#: local worker processes per CPU core at most: more only thrash (and exhaust memory)
MAX_WORKERS_PER_CORE = 4


def _default_workers() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - macOS, Windows
        return os.cpu_count() or 1


def _no_http_server(self, routes, dashboard_address, default_port=0, ssl_options=None):
    """``Node.start_http_server`` that listens nowhere (an unbound server, no routes)."""
    from distributed.http.routing import RoutingApplication
    from tornado.httpserver import HTTPServer

    self.http_application = RoutingApplication([])
    self.http_server = HTTPServer(self.http_application)  # never bound: no socket


def _quiet_classes() -> dict:
    """A Scheduler and a Worker that open no HTTP port (made on first use: Dask is imported
    only when a study runs). Reached as module attributes, so that the worker processes
    find the class by name when they unpickle it."""
    from distributed import Scheduler, Worker

    classes = {}
    for name, base in zip(_QUIET, (Scheduler, Worker), strict=True):
        cls = type(name, (base,), {"start_http_server": _no_http_server, "__module__": __name__})
        cls.__qualname__ = name
        classes[name] = cls
    return classes


def __getattr__(name):
    if name in _QUIET:
        globals().update(_quiet_classes())
        return globals()[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _local_cluster(n: int, dashboard: bool, gpus=()):
    """An in-process cluster on 127.0.0.1 with TLS (temporary credentials), no HTTP port;
    with ``gpus``, worker i sees only ``gpus[i % len(gpus)]`` (:mod:`._gpus`)."""
    import logging

    from distributed import Nanny, Scheduler, SpecCluster
    from distributed.security import Security
    from distributed.worker_memory import parse_memory_limit

    try:
        security = Security.temporary()
    except ImportError as err:  # pragma: no cover - cryptography is a dependency
        raise ParameterError(
            f"the local Dask cluster needs the 'cryptography' package for its TLS "
            f"credentials ({err}); install it (pip install cryptography)"
        ) from None
    import dask

    this = sys.modules[__name__]  # the quiet classes: module attributes, made on first use
    remove_stale_scratch()  # what a killed run left behind (ours, old, unlocked)
    # private scratch space: fresh, mode 0700, locked while in use, removed by close()
    scratch = tempfile.mkdtemp(prefix=SCRATCH_PREFIX)
    try:  # Ctrl-C right now: the fresh directory goes too
        os.chmod(scratch, 0o700)
        held = lock_scratch(scratch)
    except BaseException:
        remove_scratch(scratch, None)
        raise
    scheduler = {
        "cls": Scheduler if dashboard else this._QuietScheduler,
        "options": {
            "host": "127.0.0.1",
            "port": 0,
            "protocol": "tls://",
            "security": security,
            "dashboard": dashboard,
            "dashboard_address": DASHBOARD_ADDRESS if dashboard else None,
        },
    }
    worker = {
        "cls": Nanny,
        "options": {
            "host": "127.0.0.1",
            "protocol": "tls://",
            "security": security,
            "nthreads": 1,
            "worker_class": this._QuietWorker,
            "dashboard": False,
            "dashboard_address": None,
            "silence_logs": logging.ERROR,
            "local_directory": scratch,
            "memory_limit": parse_memory_limit(
                "auto", 1, n, logger=logging.getLogger("distributed.worker_memory")
            ),
        },
    }
    try:
        # the scheduler's scratch space (Dask: temporary-directory/dask-scratch-space) in
        # the private directory too, never in the shared $TMPDIR/dask-scratch-space
        with dask.config.set({"temporary-directory": scratch}):
            cluster = SpecCluster(
                scheduler=scheduler,
                workers={i: pinned_worker(worker, gpus, i) for i in range(n)},
                worker=worker,
                security=security,
                silence_logs=logging.ERROR,
            )
    except BaseException:  # Ctrl-C while it starts: nothing left for Dask's exit hook
        _quiet_dask(interrupted=True)
        _forget(security=security)
        remove_scratch(scratch, held)
        raise
    cluster._roughcontact_scratch = weakref.finalize(cluster, remove_scratch, scratch, held)
    return cluster


#: seconds the closing of the local cluster may take after Ctrl-C or SIGTERM
FAST_CLOSE_TIMEOUT = 5.0


def close(client, cluster, *, fast: bool = False) -> None:
    """Close ``client`` and the local ``cluster`` (if any), then remove its scratch space.

    ``fast`` (after Ctrl-C or SIGTERM): the worker processes are killed first (the tasks
    they run are lost anyway; every finished one is on disk) and the closing is bounded
    by :data:`FAST_CLOSE_TIMEOUT`, so the command exits at once instead of waiting for
    tasks in the middle of a solve. Dask's own log lines about the connections that
    then break are not printed, and Dask's exit hook is not left a cluster to close again.
    """
    _quiet_dask(interrupted=fast)
    try:
        if client is not None:
            client.close(timeout=FAST_CLOSE_TIMEOUT) if fast else client.close()
    except Exception:  # noqa: BLE001 - a scheduler gone already: nothing to close
        if not fast:
            raise
    finally:
        if cluster is not None:
            try:
                if fast:
                    _kill_workers(cluster)
                    try:
                        cluster.close(timeout=FAST_CLOSE_TIMEOUT)
                    except Exception:  # noqa: BLE001 - half-started or timed out
                        pass
                else:
                    cluster.close()
            finally:
                _forget(cluster)
                remove = getattr(cluster, "_roughcontact_scratch", None)
                if remove is not None:
                    remove()


def _quiet_dask(interrupted: bool = False) -> None:
    """No more log lines from Dask in this process (its cluster is being closed); when
    ``interrupted`` (Ctrl-C, SIGTERM), none from asyncio either: the nannies whose worker
    processes the interruption stopped leave "Task exception was never retrieved"."""
    import logging

    logging.getLogger("distributed").setLevel(logging.CRITICAL + 1)
    if interrupted:
        logging.getLogger("asyncio").setLevel(logging.CRITICAL + 1)


def _kill_workers(cluster) -> None:
    """SIGKILL the local worker processes (their nannies then find them gone)."""
    import signal

    for nanny in list(getattr(cluster, "workers", {}).values()):
        try:
            pid = nanny.pid
        except Exception:  # noqa: BLE001 - not started (yet)
            pid = None
        if pid:
            try:
                os.kill(pid, signal.SIGKILL)
            except OSError:
                pass


def _forget(cluster=None, security=None) -> None:
    """Take ``cluster`` (or every cluster made with ``security``, e.g. one whose start
    was interrupted) off Dask's list of clusters to close at exit: closed here already,
    a second close would only print errors (``AssertionError: Status.init``)."""
    try:
        from distributed.deploy.spec import SpecCluster
    except ImportError:  # pragma: no cover - distributed is a dependency
        return
    for instance in list(SpecCluster._instances):
        spec = getattr(instance, "scheduler_spec", None) or {}
        ours = security is not None and spec.get("options", {}).get("security") is security
        if instance is cluster or ours:
            SpecCluster._instances.discard(instance)


def max_workers() -> int:
    """The most local worker processes accepted: :data:`MAX_WORKERS_PER_CORE` per core."""
    return MAX_WORKERS_PER_CORE * _default_workers()


def tls_security(ca_file=None, cert=None, key=None):
    """A ``distributed.security.Security`` for a ``tls://`` scheduler, from PEM files.

    Parameters
    ----------
    ca_file : path-like
        The cluster's CA certificate (``--tls-ca-file``): the scheduler must present a
        certificate that it signed.
    cert : path-like
        This client's certificate (``--tls-cert``), signed by that CA; it may hold the
        private key as well.
    key : path-like, optional
        This client's private key (``--tls-key``), when not in ``cert``.

    Returns
    -------
    distributed.security.Security or None
        None when no file is given (then Dask's configuration applies,
        ``distributed.comm.tls.*``); else TLS required, with these files.

    Raises
    ------
    ParameterError
        A file is missing or unreadable, or ``ca_file`` or ``cert`` is missing while the
        other is given (Dask needs both: the connection authenticates both ends).
    """
    given = {"tls_ca_file": ca_file, "tls_cert": cert, "tls_key": key}
    if all(v is None for v in given.values()):
        return None
    for name in ("tls_ca_file", "tls_cert"):
        if given[name] is None:
            others = ", ".join(n for n, v in given.items() if v is not None)
            raise ParameterError(
                f"{name} is required with {others} (TLS to the scheduler needs the CA file "
                "and this client's certificate: --tls-ca-file and --tls-cert)"
            )
    for name, value in given.items():
        if value is not None and not (Path(value).is_file() and os.access(value, os.R_OK)):
            raise ParameterError(f"{name} must be a readable PEM file, got {str(value)!r}")
    from distributed.security import Security

    return Security(
        require_encryption=True,
        tls_ca_file=str(ca_file),
        tls_client_cert=str(cert),
        tls_client_key=None if key is None else str(key),
    )


def check_options(scheduler, workers, security, dashboard) -> None:
    """Reject options that do not apply to ``scheduler`` (before anything is written)."""
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
    ):
        raise ParameterError(f"workers must be an integer >= 1, got {workers!r}")
    if workers is not None and scheduler is None and workers > max_workers():
        raise ParameterError(
            f"workers must be an integer in [1, {max_workers()}] ({MAX_WORKERS_PER_CORE} per "
            f"CPU core of the {_default_workers()} here), got {workers!r}"
        )
    if security is not None:
        from distributed.security import Security

        if not isinstance(security, Security):
            raise ParameterError(
                "security must be a distributed.security.Security (or None), got "
                f"{type(security).__name__}"
            )
        if not isinstance(scheduler, str) or scheduler == "synchronous":
            raise ParameterError(
                "security (--tls-ca-file, --tls-cert, --tls-key) applies to a remote "
                "scheduler (--scheduler tls://host:port) only; the local cluster makes "
                "its own temporary TLS credentials"
            )
    if dashboard not in (True, False):
        raise ParameterError(f"dashboard must be True or False, got {dashboard!r}")
    if dashboard and scheduler is not None:
        raise ParameterError(
            "dashboard (--dashboard) applies to the local cluster only, not to --scheduler "
            "(the remote scheduler serves its own) or 'synchronous'"
        )


def connect(scheduler, workers, security=None, dashboard=False, gpus=()):
    """A Dask client (and the cluster we own, or None); errors before any work starts.

    ``security`` (a ``distributed.security.Security``) is used to reach a remote
    scheduler; ``dashboard`` opens the local cluster's dashboard on
    :data:`DASHBOARD_ADDRESS` (else the local cluster opens no HTTP port); ``gpus``
    (``CUDA_VISIBLE_DEVICES`` entries): the local cluster's workers, by default one per
    GPU, each pinned to its own.
    """
    from distributed import Client

    check_options(scheduler, workers, security, dashboard)
    if scheduler is None:
        import dask

        n = (len(gpus) or _default_workers()) if workers is None else workers
        # Dask starts its workers with MALLOC_TRIM_THRESHOLD_=65536, which also turns off
        # glibc's adaptive mmap threshold: every array above 128 kB is then mmapped and
        # unmapped: page faults and TLB shootdowns cost the demo 73 s of CPU time in the
        # kernel (83 s wall; 37 s without). Our workers keep glibc's defaults (an explicit
        # MALLOC_TRIM_THRESHOLD_ in the environment still wins, as in Dask).
        client = cluster = None
        try:
            with dask.config.set(
                {"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}
            ):
                cluster = _local_cluster(n, dashboard, gpus)
            # not the default client: dask work of this process (xarray's NetCDF writes of
            # the task files, a notebook's computations) stays local, no distributed locks
            client = Client(cluster, set_as_default=False)
        except BaseException:  # Ctrl-C while it starts too: closed, its scratch removed
            close(client, cluster, fast=True)
            raise
        return client, cluster
    if isinstance(scheduler, Client):
        return scheduler, None
    if not isinstance(scheduler, str) or not scheduler.strip():
        raise ParameterError(
            f"scheduler must be an address like tcp://host:8786, got {scheduler!r}"
        )
    if workers is not None:
        raise ParameterError(
            f"workers = {workers!r} applies to the local cluster only, not to --scheduler "
            "(the remote cluster has its own workers)"
        )
    if security is None:
        from distributed.security import Security

        security = Security()  # Dask's configuration: distributed.comm.tls.*
    address = _reachable(scheduler.strip(), security)
    try:
        return (
            Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False, security=security),
            None,
        )
    except (OSError, TimeoutError, ValueError) as err:
        raise ParameterError(
            f"cannot connect to the Dask scheduler at {scheduler!r} within "
            f"{CONNECT_TIMEOUT:g} s ({type(err).__name__}: {err})"
        ) from None


def _reachable(address: str, security=None) -> str:
    """``scheme://host:port`` of a scheduler that accepts TCP connections, else an error.

    A refused or unroutable address fails here at once (or after ``CONNECT_TIMEOUT``
    seconds), instead of after Dask's retries. ``security``: the TLS settings of a
    ``tls://`` address.
    """
    from distributed.comm.addressing import parse_address, parse_host_port, unparse_host_port

    try:
        scheme, location = parse_address(address, strict=False)
        host, port = parse_host_port(location, default_port=8786)
    except ValueError as err:
        raise ParameterError(
            f"scheduler = {address!r} is not a Dask address (tcp://host:port): {err}"
        ) from None
    if scheme in ("tcp", "tls"):
        try:
            socket.create_connection((host, port), timeout=CONNECT_TIMEOUT).close()
        except OSError as err:
            raise ParameterError(
                f"cannot reach the Dask scheduler at {address!r} within {CONNECT_TIMEOUT:g} s "
                f"({type(err).__name__}: {err}); start it or check the address"
            ) from None
    address = f"{scheme}://{unparse_host_port(host, port)}"
    try:
        args = {} if security is None else security.get_connection_args("client")
    except (OSError, ValueError) as err:  # unreadable or mismatched certificate and key
        raise ParameterError(
            f"cannot load the TLS credentials for {address!r} ({type(err).__name__}: {err}); "
            "check --tls-ca-file, --tls-cert and --tls-key"
        ) from None
    if scheme == "tls" and args.get("ssl_context") is None:
        raise ParameterError(
            f"scheduler = {address!r} needs TLS credentials: pass --tls-ca-file and "
            "--tls-cert (and --tls-key) or security=distributed.security.Security(...), "
            "or set distributed.comm.tls.* in Dask's configuration"
        )
    try:
        _handshake(address, args)
    except Exception as err:  # noqa: BLE001 - anything but a Dask handshake
        raise ParameterError(
            f"{address!r} does not answer as a Dask scheduler within {CONNECT_TIMEOUT:g} s "
            f"({type(err).__name__}: {err})"
        ) from None
    return address


def _handshake(address: str, connection_args=None) -> None:
    """Open and close one Dask comm to ``address`` (in a thread with its own event loop)."""
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect as dask_connect

    async def probe():
        comm = await dask_connect(address, timeout=CONNECT_TIMEOUT, **(connection_args or {}))
        await comm.close()

    def run():
        return asyncio.run(asyncio.wait_for(probe(), CONNECT_TIMEOUT + 1))

    with ThreadPoolExecutor(1) as pool:
        pool.submit(run).result()


def outcomes(todo, client):
    """Yield ``(task, outcome)`` as tasks finish, on Dask (``client``) or in this process."""
    if client is None:
        for task in todo:
            yield task, run_task(task)
        return
    from distributed import as_completed

    futures = {
        client.submit(run_task, t, key=f"roughcontact-task-{t.id}-{os.urandom(6).hex()}"): t
        for t in todo
    }
    for future in as_completed(futures, loop=client.loop):
        task = futures.pop(future)
        try:
            outcome = future.result()
        except Exception as err:  # noqa: BLE001 - a worker died (KilledWorker), ...
            outcome = {
                "status": "failed",
                "reason": f"{type(err).__name__}: {err}",
                "traceback": traceback.format_exc(),
            }
        future.release()
        yield task, outcome
