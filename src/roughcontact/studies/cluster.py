"""Where the tasks run: an in-process LocalCluster, a remote Dask scheduler, or here.

A remote address is checked (TCP connection and a Dask handshake, ``CONNECT_TIMEOUT``
seconds) before any work starts, so a wrong or unreachable address is one clear error.
"""

from __future__ import annotations

import os
import socket
import traceback

from .._validate import ParameterError
from .task import run_task

__all__ = ["CONNECT_TIMEOUT", "connect", "outcomes"]

CONNECT_TIMEOUT = 5.0  # seconds to reach a remote scheduler before giving up


def _default_workers() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - macOS, Windows
        return os.cpu_count() or 1


def connect(scheduler, workers):
    """A Dask client (and the cluster we own, or None); errors before any work starts."""
    import logging

    from distributed import Client, LocalCluster

    if scheduler is None:
        import dask

        n = _default_workers() if workers is None else workers
        # Dask starts its workers with MALLOC_TRIM_THRESHOLD_=65536, which also turns off
        # glibc's adaptive mmap threshold: every array above 128 kB is then mmapped and
        # unmapped: page faults and TLB shootdowns cost the demo 73 s of CPU time in the
        # kernel (83 s wall; 37 s without). Our workers keep glibc's defaults (an explicit
        # MALLOC_TRIM_THRESHOLD_ in the environment still wins, as in Dask).
        with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
            cluster = LocalCluster(
                n_workers=n,
                threads_per_worker=1,
                processes=True,
                dashboard_address=None,
                silence_logs=logging.ERROR,
            )
        return Client(cluster), cluster
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
    address = _reachable(scheduler.strip())
    try:
        return Client(address, timeout=CONNECT_TIMEOUT, set_as_default=False), None
    except (OSError, TimeoutError, ValueError) as err:
        raise ParameterError(
            f"cannot connect to the Dask scheduler at {scheduler!r} within "
            f"{CONNECT_TIMEOUT:g} s ({type(err).__name__}: {err})"
        ) from None


def _reachable(address: str) -> str:
    """``scheme://host:port`` of a scheduler that accepts TCP connections, else an error.

    A refused or unroutable address fails here at once (or after ``CONNECT_TIMEOUT``
    seconds), instead of after Dask's retries.
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
        _handshake(address)
    except Exception as err:  # noqa: BLE001 - anything but a Dask handshake
        raise ParameterError(
            f"{address!r} does not answer as a Dask scheduler within {CONNECT_TIMEOUT:g} s "
            f"({type(err).__name__}: {err})"
        ) from None
    return address


def _handshake(address: str) -> None:
    """Open and close one Dask comm to ``address`` (in a thread with its own event loop)."""
    import asyncio
    from concurrent.futures import ThreadPoolExecutor

    from distributed.comm import connect as dask_connect

    async def probe():
        comm = await dask_connect(address, timeout=CONNECT_TIMEOUT)
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
