"""Run a study: every task on Dask distributed, each result stored as soon as it arrives.

The workers compute and return each task's path dataset (:mod:`.task`); the driver (this
process) writes it atomically (:mod:`.store`), so the output directory needs to exist
only where the driver runs.
"""

from __future__ import annotations

import dataclasses
import sys
import time
from dataclasses import dataclass
from pathlib import Path

from .._accelerator import check_device
from .._signals import Terminated, deferred, exit_code, interruptible
from .._validate import ParameterError
from . import cluster, lock, store
from ._gpus import visible_gpus
from .spec import StudySpec, load_study

__all__ = ["StudySummary", "run_study"]

# how to proceed when the directory is locked (appended to the error)
_LOCKED_HINT = "continue the study with --resume (resume=True) or choose another directory"


@dataclass(frozen=True)
class StudySummary:
    """What a run did: task counts, steps that did not converge, wall time (s).

    ``analysis_errors`` counts the finished tasks without a path analysis (their
    ``analysis_error`` says why: the target area not reached, unconverged steps around
    it, ...); they are not failures, but they have no κ.
    """

    name: str
    out_dir: str
    tasks: int
    skipped: int
    completed: int
    failed: int
    unconverged_tasks: int
    unconverged_steps: int
    seconds: float
    analysis_errors: int = 0

    @property
    def ok(self) -> bool:
        """True when every task finished (some steps may still not have converged)."""
        return self.failed == 0

    def __str__(self) -> str:
        lines = [
            f"study {self.name!r}: {self.tasks} tasks, {self.skipped} already finished, "
            f"{self.completed} computed, {self.failed} failed, {self.analysis_errors} "
            f"without analysis in {self.seconds:.1f} s",
            f"results in {self.out_dir}",
        ]
        if self.analysis_errors:
            lines.append(
                f"{self.analysis_errors} finished tasks have no path analysis (no kappa): "
                "see their 'analysis_error' (collect: variable analysis_error)"
            )
        if self.unconverged_steps:
            lines.append(
                f"{self.unconverged_steps} path steps in {self.unconverged_tasks} tasks did "
                "not converge (see the 'converged' variable; not counted as failures)"
            )
        if self.failed:
            lines.append(f"failed tasks are recorded in {self.out_dir}/task-*.failed.json")
        return "\n".join(lines)


def _drive(spec, out, todo, client, done, progress):
    """Prepare the directory, run ``todo`` and store every outcome as it arrives."""
    from tqdm import tqdm

    out.mkdir(parents=True, exist_ok=True)
    store.clean_temporary(out)
    store.write_manifest(out, spec)
    for task in todo:  # partial, corrupt or stale files: never taken as finished
        store.task_path(out, task.id).unlink(missing_ok=True)
    unconverged = [int(a.get("steps_not_converged", 0)) for a in done.values()]
    analysis_errors = sum(1 for a in done.values() if a.get("analysis_error"))
    failed = 0
    with tqdm(
        total=len(spec.tasks),
        initial=len(done),
        unit="task",
        disable=not progress,
        desc=spec.name,
        dynamic_ncols=True,
    ) as bar:
        for task, outcome in cluster.outcomes(todo, client):
            if outcome["status"] == "done":
                ds = outcome["dataset"]
                ds.attrs.update(
                    study_name=spec.name, study_sha256=spec.sha256, study_source=spec.source
                )
                store.write_task(out, task, ds)
                unconverged.append(int(ds.attrs["steps_not_converged"]))
                analysis_errors += bool(ds.attrs.get("analysis_error"))
            else:
                failed += 1
                extra = {
                    k: v for k, v in outcome.items() if k not in ("status", "reason", "traceback")
                }
                store.write_failure(
                    out,
                    task,
                    outcome["reason"],
                    outcome.get("traceback", ""),
                    study_sha256=spec.sha256,
                    **extra,
                )
            bar.update(1)
    return unconverged, failed, analysis_errors


def run_study(
    study,
    out_dir,
    *,
    resume=False,
    scheduler=None,
    workers=None,
    progress=True,
    device=None,
    security=None,
    dashboard=False,
):
    """Run every task of a study and store each result as it finishes.

    Parameters
    ----------
    study : StudySpec or path-like
        A validated study or its TOML file (validated before anything else happens).
    out_dir : path-like
        Study directory (created). Without ``resume`` it must not hold a study yet.
        The run holds its lock (:mod:`.lock`) throughout: a second run into the same
        directory raises :class:`~.lock.DirectoryLocked` at once, while the lock of a
        killed run is gone with its process and does not block ``resume``. No file is
        written through a symbolic link found in the directory (:mod:`.store`); a link
        (or hard link) at the lock file's name is refused (:class:`~.lock.UnsafePath`).
    resume : bool
        Continue the study that ``out_dir`` holds: skip tasks whose file is finished
        (opens, has the completion marker and the task's parameter hash); recompute
        missing, partial, corrupt and failed ones. The study must be the one the
        directory was started with (the manifest's sha256 of the study file), else a
        :class:`ParameterError` naming both, before anything is written.
    scheduler : None, str or distributed.Client
        None: an in-process Dask cluster (processes, 1 thread each, on 127.0.0.1) that
        talks TLS with temporary credentials of this run, so that no other process can
        connect to it, and opens no HTTP port (see ``dashboard``); an address
        (``tcp://host:8786``, ``tls://host:8786``): an existing cluster, reached within
        ``cluster.CONNECT_TIMEOUT`` seconds or a :class:`ParameterError`;
        ``"synchronous"``: in this process, no Dask.
    workers : int, optional
        Worker processes of the local cluster (default: the usable CPU cores).
    progress : bool
        Show a progress bar over tasks (stderr).
    device : {None, "cpu", "cuda", "cuda:N"}
        Where the workers compute (see :func:`roughcontact.to_device`); checked before
        any work. Not part of the task keys: a study resumed on another device skips
        the tasks already done. ``"cuda"`` on the local cluster starts one worker per
        visible GPU (``CUDA_VISIBLE_DEVICES``, else ``nvidia-smi -L``), each seeing only
        its own (``workers`` more than GPUs share them in turn); ``"cuda:N"`` puts every
        worker on GPU N.
    security : distributed.security.Security, optional
        TLS settings to reach a remote ``scheduler`` (``tls://...``), e.g.
        ``cluster.tls_security(ca_file, cert, key)`` or
        ``Security(tls_ca_file=..., tls_client_cert=..., tls_client_key=...,
        require_encryption=True)``. Default: Dask's configuration
        (``distributed.comm.tls.*``). Not for the local cluster, which makes its own.
    dashboard : bool
        Open the local cluster's Dask dashboard on ``cluster.DASHBOARD_ADDRESS``
        (127.0.0.1:8787, or another port if taken; plain HTTP without authentication:
        any local user can read it); its link goes to stderr. Default False: no HTTP port.

    Returns
    -------
    StudySummary

    Raises
    ------
    DirectoryLocked
        Another process is running a study in ``out_dir``.
    KeyboardInterrupt
        Ctrl-C, or SIGTERM (:class:`roughcontact._signals.Terminated`, while the run
        holds the main thread's handler): raised once the cluster is shut down; every
        task finished before it is in its file (``resume`` continues).
    ParameterError
        Bad input (naming the parameter), an unreachable scheduler, ``resume`` with
        another study than the directory's, an unsafe file in ``out_dir``.
    """
    t0 = time.perf_counter()
    spec = study if isinstance(study, StudySpec) else load_study(study)
    if check_device(device) is not None:
        tasks = tuple(dataclasses.replace(t, device=device) for t in spec.tasks)
        spec = dataclasses.replace(spec, tasks=tasks)
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
    ):
        raise ParameterError(f"workers must be an integer >= 1, got {workers!r}")
    cluster.check_options(scheduler, workers, security, dashboard)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ParameterError(f"output {str(out)!r} exists and is not a directory")
    # taken before anything is read or written, so that a second run fails at once
    # and never deletes the first one's files in progress
    # SIGTERM (a scheduler's end of job, kill) stops the run as Ctrl-C does: the cluster
    # is shut down, the lock released, Terminated (a KeyboardInterrupt) raised
    with interruptible(), lock.directory_lock(out, hint=_LOCKED_HINT):
        # --device cuda on the local cluster: one worker per visible GPU, pinned to it
        gpus = visible_gpus() if device == "cuda" and scheduler is None else ()
        return _run_locked(
            spec, out, resume, (scheduler, workers, security, dashboard, gpus), progress, t0
        )


def _same_study(spec, out):
    """Refuse to resume ``out`` with another study than the one it holds."""
    manifest_path = out / store.MANIFEST
    if not manifest_path.exists() and not manifest_path.is_symlink():
        if store.existing_results(out):
            raise ParameterError(
                f"resume: {str(out)!r} holds task files but no {store.MANIFEST}, so it cannot "
                f"be told whether they belong to study {spec.name!r} ({spec.source!r}); "
                "choose another directory"
            )
        return  # nothing there yet: resume starts the study
    manifest = store.read_manifest(out)
    if manifest.get("sha256") == spec.sha256:
        return
    old = manifest.get("sha256")
    old = old[:12] if isinstance(old, str) else repr(old)
    raise ParameterError(
        f"resume: {str(out)!r} holds study {manifest.get('name')!r} from "
        f"{manifest.get('source')!r} (sha256 {old}...), not study {spec.name!r} from "
        f"{spec.source!r} (sha256 {spec.sha256[:12]}...); resume it with the study file it "
        f"was run with (a copy: {str(out / 'study.toml')!r}) or choose another directory"
    )


def _stopped(err, spec, out) -> KeyboardInterrupt:
    """The interruption (Ctrl-C) or :class:`Terminated` (SIGTERM) to raise, saying what
    is on disk: every task finished before it, in its file."""
    finished = sum(1 for t in spec.tasks if store.task_path(out, t.id).is_file())
    terminated = exit_code(err) == 143
    why = "terminated (SIGTERM)" if terminated else "interrupted (Ctrl-C)"
    message = (
        f"{why}: {finished} of {len(spec.tasks)} tasks are finished in {str(out)!r} (the "
        "cluster was shut down); continue with --resume (resume=True)"
    )
    return Terminated(message) if terminated else KeyboardInterrupt(message)


def _close(client, local, stopped: bool, spec, out) -> None:
    """Close the local cluster; once stopped, at once and without a second interruption
    (Ctrl-C pressed again while it closes) cutting the clean-up short. Ctrl-C or SIGTERM
    during an ordinary close: the close is finished at once and the interruption raised
    saying what is on disk."""
    if not stopped:
        try:
            cluster.close(client, local)
            return
        except KeyboardInterrupt as err:
            interrupted = err
        _close(client, local, True, spec, out)
        raise _stopped(interrupted, spec, out) from None
    try:
        with deferred():
            cluster.close(client, local, fast=True)
    except KeyboardInterrupt:
        pass  # the first interruption is on its way out already


def _pending(spec, out, resume):
    """``(done, todo)``: attributes of the finished tasks by id, the tasks left to run."""
    done, todo = {}, []
    for task in spec.tasks:
        path = store.task_path(out, task.id)
        if path.is_symlink() or (path.exists() and not path.is_file()):
            todo.append(task)  # never read through a link: removed and recomputed
            continue
        ok, info = store.check_task(out, task) if resume else (False, "")
        if ok:
            done[task.id] = info
        else:
            todo.append(task)
    # whole seeds first (Dask runs submissions in order): a study stopped part-way holds
    # complete realisations of the grid, not every seed of its first parameter sets
    seeds = list(spec.axes.get("seed", ()))
    todo.sort(key=lambda t: (seeds.index(t.params["seed"]) if seeds else 0, t.id))
    return done, todo


def _run_locked(spec, out, resume, where, progress, t0):
    """:func:`run_study` once the directory's lock is held (``where``: the cluster options)."""
    scheduler, workers, security, dashboard, gpus = where
    if not resume and store.existing_results(out):
        raise ParameterError(
            f"{str(out)!r} already holds study results; pass --resume (resume=True) to "
            "continue that study, or choose another directory"
        )
    if resume:
        _same_study(spec, out)
    done, todo = _pending(spec, out, resume)
    client = local = None
    if todo and scheduler != "synchronous":
        # an unreachable scheduler fails here
        client, local = cluster.connect(scheduler, workers, security, dashboard, gpus)
        if dashboard:
            print(f"Dask dashboard: {client.dashboard_link}", file=sys.stderr, flush=True)
    stopped = False
    try:
        unconverged, failed, analysis_errors = _drive(spec, out, todo, client, done, progress)
    except KeyboardInterrupt as err:  # Ctrl-C or SIGTERM; the cluster closes below
        stopped = True
        raise _stopped(err, spec, out) from None
    finally:
        if local is not None:  # and its private scratch directory; at once when stopped
            _close(client, local, stopped, spec, out)
        elif client is not None and client is not scheduler:
            client.close()
    return StudySummary(
        name=spec.name,
        out_dir=str(out),
        tasks=len(spec.tasks),
        skipped=len(done),
        completed=len(todo) - failed,
        failed=failed,
        unconverged_tasks=sum(1 for u in unconverged if u),
        unconverged_steps=sum(unconverged),
        seconds=time.perf_counter() - t0,
        analysis_errors=analysis_errors,
    )
