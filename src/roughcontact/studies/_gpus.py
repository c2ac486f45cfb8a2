"""One local Dask worker per GPU: which GPUs this process sees, and a worker pinned to one.

``study run --device cuda`` on the local cluster starts one worker process per visible GPU
and gives each its own through ``CUDA_VISIBLE_DEVICES`` (set in the worker's environment
before it starts, so CUDA, CuPy and JAX in that process see that GPU alone, as device 0).
More workers than GPUs share them in turn; ``--device cuda:N`` keeps every worker on GPU N.
"""

from __future__ import annotations

import os
import shutil
import subprocess

__all__ = ["pinned_worker", "visible_gpus"]

#: seconds ``nvidia-smi -L`` may take to list the GPUs
NVIDIA_SMI_TIMEOUT = 10.0


def visible_gpus(environ=None) -> tuple[str, ...]:
    """The GPUs this process may use, as ``CUDA_VISIBLE_DEVICES`` entries.

    ``CUDA_VISIBLE_DEVICES`` when it is set (its entries, indices or UUIDs; empty, ``-1``
    or ``NoDevFiles`` hide every GPU); else one index per GPU that ``nvidia-smi -L`` lists;
    else none (no driver here). ``environ``: the environment to read (default ``os.environ``).
    """
    env = os.environ if environ is None else environ
    if "CUDA_VISIBLE_DEVICES" in env:
        ids = tuple(x.strip() for x in env["CUDA_VISIBLE_DEVICES"].split(",") if x.strip())
        return () if not ids or ids[0] in ("-1", "NoDevFiles") else ids
    smi = shutil.which("nvidia-smi")
    if smi is None:
        return ()
    try:
        out = subprocess.run([smi, "-L"], capture_output=True, text=True, check=True,
                             timeout=NVIDIA_SMI_TIMEOUT).stdout  # fmt: skip
    except (OSError, subprocess.SubprocessError):
        return ()
    count = sum(1 for line in out.splitlines() if line.startswith("GPU "))
    return tuple(str(i) for i in range(count))


def pinned_worker(spec: dict, gpus, index: int) -> dict:
    """The Dask worker ``spec`` (``{"cls": Nanny, "options": {...}}``) of worker ``index``,
    pinned to ``gpus[index % len(gpus)]`` through its environment; ``spec`` itself when
    ``gpus`` is empty."""
    if not gpus:
        return spec
    env = {**spec["options"].get("env", {}), "CUDA_VISIBLE_DEVICES": gpus[index % len(gpus)]}
    return {**spec, "options": {**spec["options"], "env": env}}
