"""Thread conditions of the benchmarks: set before NumPy loads, enforced, verified, recorded.

A benchmark that prints "BLAS threads 1" must run on one BLAS thread. OpenBLAS, MKL,
BLIS and OpenMP runtimes read their thread count from the environment once, when the
library is loaded (``import numpy``, ``import scipy``), so the variables must be set
before that; ``threadpoolctl`` can change it afterwards, but only for libraries already
loaded. Each script therefore does, at the very top (before NumPy, SciPy or a peer is
imported, and only when run as a script)::

    if __name__ == "__main__":
        import _threads

        _threads.preset_from_argv(sys.argv[1:], "--blas-threads", default=1)

and around its timed work::

    with _threads.enforced(args.blas_threads, preload=("scipy.optimize", "tamaas")) as rec:
        print(_threads.describe(rec))
        ...

``enforced`` sets the variables again (for libraries loaded later), applies
``threadpoolctl.threadpool_limits`` when threadpoolctl is installed, and verifies the
limit on every loaded pool (``threadpool_info``; without threadpoolctl, each loaded
OpenBLAS is asked ``openblas_get_num_threads`` through ctypes, else only the environment
is checked). Without threadpoolctl the limit holds only if the variables were set before
NumPy was loaded (by ``preset`` or by the caller's environment); otherwise, or if a pool
runs on another count, it refuses to run (``SystemExit``) rather than print a condition
it did not enforce. ``threads=None`` enforces nothing and records the
libraries' own defaults. The record (threads per library, how they were set and
verified, variables, CPU count, versions) is JSON-ready.
"""

from __future__ import annotations

import contextlib
import importlib
import os
import sys
from importlib import metadata

ENV_VARS = (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "GOTO_NUM_THREADS",
    "MKL_NUM_THREADS",
    "BLIS_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
    "NUMEXPR_NUM_THREADS",
)
# loading any of these loads a BLAS (NumPy's, SciPy's own) or an OpenMP runtime
NUMERIC_MODULES = ("numpy", "scipy", "roughcontact", "tamaas", "ContactMechanics", "Adhesion")
VERSIONS = (
    "numpy",
    "scipy",
    "roughcontact",
    "Adhesion",
    "ContactMechanics",
    "SurfaceTopography",
    "NuMPI",
    "muFFT",
    "tamaas",
    "cupy",
)

# the thread count in the environment before any numeric library was loaded: the
# caller's environment if it already held it when this module was first imported, or
# what preset() set before NumPy was loaded
_LOADED_AT_IMPORT = [m for m in NUMERIC_MODULES if m in sys.modules]
_EARLY: dict = {"threads": None, "source": None}


def _env_threads() -> int | None:
    """The common value of all ENV_VARS, or None if one is unset or they differ."""
    values = {os.environ.get(v) for v in ENV_VARS}
    if len(values) != 1 or None in values:
        return None
    with contextlib.suppress(ValueError):
        return int(values.pop())
    return None


if not _LOADED_AT_IMPORT and _env_threads() is not None:
    _EARLY.update(threads=_env_threads(), source="caller's environment")


def numeric_loaded() -> list[str]:
    """Numeric modules (each loads a BLAS or OpenMP runtime) already imported."""
    return [m for m in NUMERIC_MODULES if m in sys.modules]


def threads_from_argv(argv, flag: str = "--blas-threads", default: int | None = None):
    """The value of ``flag N`` / ``flag=N`` in ``argv`` (the last one), else ``default``.

    A cheap look-ahead for ``preset`` before argparse runs: an abbreviated or invalid
    flag is left to argparse, and ``enforced`` catches the difference.
    """
    value = default
    for i, arg in enumerate(argv):
        if arg == "--":
            break
        if arg == flag and i + 1 < len(argv):
            value = argv[i + 1]
        elif arg.startswith(flag + "="):
            value = arg.split("=", 1)[1]
    try:
        return None if value is None else int(value)
    except ValueError:
        return default


def _set_env(threads: int) -> None:
    for var in ENV_VARS:
        os.environ[var] = str(threads)


def preset(threads: int | None) -> None:
    """Set every thread variable to ``threads`` (None: leave the environment alone).

    Takes effect for a library only if it is loaded afterwards: call it before NumPy.
    """
    if threads is None:
        return
    _set_env(threads)
    if not numeric_loaded():
        _EARLY.update(threads=threads, source="set before NumPy was loaded")


def preset_from_argv(argv=None, flag: str = "--blas-threads", default: int | None = None):
    """``preset`` with the value of ``flag`` on the command line (``sys.argv[1:]``)."""
    preset(threads_from_argv(sys.argv[1:] if argv is None else argv, flag, default))


def _library(path: str) -> str:
    """Which package ships a shared library, from its path (``numpy.libs/...`` -> numpy)."""
    parts = path.replace("\\", "/").split("/")
    for part in reversed(parts[:-1]):
        if part.endswith(".libs"):
            return part[: -len(".libs")]
        if part in ("site-packages", "dist-packages", "lib", "lib64"):
            break
    return parts[-1]


def _threadpoolctl_pools() -> list[dict] | None:
    try:
        from threadpoolctl import threadpool_info
    except ImportError:
        return None
    return [
        dict(
            library=_library(p.get("filepath", "")),
            user_api=p.get("user_api"),
            internal_api=p.get("internal_api"),
            version=p.get("version"),
            threading_layer=p.get("threading_layer"),
            num_threads=p.get("num_threads"),
            filepath=p.get("filepath"),
        )
        for p in threadpool_info()
    ]


def _openblas_pools() -> list[dict] | None:
    """Loaded OpenBLAS libraries and their thread counts, asked through ctypes (Linux).

    The check without threadpoolctl: the libraries mapped into this process (from
    ``/proc/self/maps``) whose name contains "openblas", each asked
    ``openblas_get_num_threads`` under the symbol names NumPy's and SciPy's wheels use
    (``scipy_`` prefix, ``64_`` suffix). None where that cannot be done.
    """
    import ctypes

    try:
        with open("/proc/self/maps") as fh:
            maps = fh.read()
    except OSError:
        return None
    paths = sorted(
        {
            fields[5].strip()
            for fields in (line.split(None, 5) for line in maps.splitlines())
            if len(fields) == 6 and "openblas" in os.path.basename(fields[5]).lower()
        }
    )
    noload = getattr(os, "RTLD_NOLOAD", 0) | getattr(os, "RTLD_LAZY", 1)
    pools = []
    for path in paths:
        try:
            lib = ctypes.CDLL(path, mode=noload)  # already loaded: the same handle
        except OSError:
            continue
        for symbol in (
            f"{prefix}openblas_get_num_threads{suffix}"
            for prefix in ("scipy_", "")
            for suffix in ("64_", "")
        ):
            func = getattr(lib, symbol, None)
            if func is not None:
                func.restype = ctypes.c_int
                pools.append(
                    dict(
                        library=_library(path),
                        user_api="blas",
                        internal_api="openblas",
                        version=None,
                        threading_layer=None,
                        num_threads=int(func()),
                        filepath=path,
                    )
                )
                break
    return pools or None


def threadpools() -> tuple[list[dict] | None, str | None]:
    """Every loaded BLAS / OpenMP pool with its thread count, and how it was found.

    threadpoolctl's ``threadpool_info`` when installed, else OpenBLAS asked through
    ctypes, else ``(None, None)``.
    """
    pools = _threadpoolctl_pools()
    if pools is not None:
        return pools, "threadpoolctl.threadpool_info"
    with contextlib.suppress(Exception):
        pools = _openblas_pools()
    if pools is not None:
        return pools, "openblas_get_num_threads via ctypes (threadpoolctl not installed)"
    return None, None


def versions(names=VERSIONS) -> dict:
    """Installed versions of ``names`` (distribution names; None where not installed)."""
    out = {}
    for name in names:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = None
    return out


def cpus() -> dict:
    usable = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else None
    return dict(cpu_count=os.cpu_count(), cpus_usable=usable)


def _refuse(threads: int, why: str):
    raise SystemExit(
        f"refusing to run: cannot enforce {threads} BLAS/OpenMP thread(s): {why}. Install "
        f"threadpoolctl (pip install threadpoolctl; part of the test extra), or start Python "
        f"with {', '.join(f'{v}={threads}' for v in ENV_VARS[:3])} (and the other "
        f"*_NUM_THREADS) set, or run the script directly with the thread flag spelled out."
    )


@contextlib.contextmanager
def enforced(threads: int | None, preload=()):
    """Run the body on ``threads`` threads per BLAS / OpenMP pool; yield the record.

    ``preload``: modules imported first (quietly skipped if missing) so that their pools
    are limited and verified too (threadpoolctl only sees loaded libraries). Raises
    ``SystemExit`` when the limit cannot be enforced or verified. ``threads=None``:
    nothing is limited; the record holds the libraries' defaults. After the body the
    pools are checked again (``threadpools_after``, ``verified_after``), which catches
    a library loaded during the run with another count.
    """
    if threads is not None and threads < 1:
        raise SystemExit(f"thread count must be >= 1, got {threads}")
    early = threads is not None and _EARLY["threads"] == threads and _env_threads() == threads
    if threads is not None:
        _set_env(threads)  # for libraries loaded from here on
    for mod in preload:
        with contextlib.suppress(ImportError):
            importlib.import_module(mod)
    try:
        import threadpoolctl
        from threadpoolctl import threadpool_limits
    except ImportError:
        threadpoolctl = threadpool_limits = None
    record = dict(
        requested=threads,
        enforced_by=[],
        verified_by=None,
        threadpoolctl=getattr(threadpoolctl, "__version__", None),
        env={v: os.environ.get(v) for v in (*ENV_VARS, "ROUGHCONTACT_FFT_WORKERS")},
        threadpools=None,
        **cpus(),
        versions=versions(),
    )
    if early:
        record["enforced_by"].append(f"environment ({_EARLY['source']})")
    limiter, ran = None, False
    if threads is not None and threadpool_limits is not None:
        limiter = threadpool_limits(limits=threads)  # every loaded BLAS and OpenMP pool
        record["enforced_by"].append("threadpoolctl.threadpool_limits")
    try:
        pools, how = threadpools()
        record["threadpools"] = pools
        if pools is not None:
            record["verified_by"] = how
            if threads is not None:
                wrong = [p for p in pools if p["num_threads"] != threads]
                if wrong:
                    _refuse(
                        threads,
                        ", ".join(f"{p['library']} {p['num_threads']}" for p in wrong)
                        + f" threads found by {how}",
                    )
                if not pools:
                    record["verified_by"] += " (no BLAS/OpenMP pool loaded)"
        if threads is not None and (pools is None or threadpool_limits is None):
            # no limit was applied from here: only the early environment can hold it (for
            # libraries not inspected, e.g. an OpenMP runtime, MKL)
            if not early:
                _refuse(
                    threads,
                    "threadpoolctl is not installed and NumPy was loaded before the thread "
                    f"variables were set to {threads}",
                )
            if pools is None:
                record["verified_by"] = "environment (threadpoolctl not installed)"
        ran = True
        yield record
    finally:
        after = threadpools()[0] if ran else None
        record["threadpools_after"] = after
        if threads is not None and after is not None:
            record["verified_after"] = all(p["num_threads"] == threads for p in after)
            if not record["verified_after"]:
                print(
                    "# WARNING: a thread pool loaded during the run has "
                    + ", ".join(
                        f"{p['library']} {p['num_threads']}"
                        for p in after
                        if p["num_threads"] != threads
                    )
                    + f" threads, not {threads}",
                    file=sys.stderr,
                    flush=True,
                )
        if limiter is not None:
            limiter.restore_original_limits()


def describe(record: dict) -> str:
    """Two header lines (``#``-prefixed): the thread conditions, then CPUs and versions."""
    threads = record["requested"]
    pools = record["threadpools"]
    if pools is None:
        found = "pools not inspectable (no threadpoolctl, no OpenBLAS found)"
    elif not pools:
        found = "no BLAS/OpenMP pool loaded"
    else:
        found = ", ".join(
            f"{p['library']} {p['internal_api']}{f' {v}' if (v := p['version']) else ''}: "
            f"{p['num_threads']}"
            for p in pools
        )
    if threads is None:
        line = f"# threads: BLAS/OpenMP not limited (library defaults): {found}"
    else:
        env = f"{', '.join(ENV_VARS[:3])} and {len(ENV_VARS) - 3} more = {threads}"
        line = (
            f"# threads: BLAS/OpenMP {threads} per library, enforced by "
            f"{' + '.join(record['enforced_by']) or '-'} [{env}]; verified by "
            f"{record['verified_by']}: {found}"
        )
    vers = ", ".join(f"{k} {v}" for k, v in record["versions"].items() if v is not None)
    vers += f", threadpoolctl {record['threadpoolctl'] or '(not importable)'}"
    usable = record["cpus_usable"]
    return (
        f"{line}\n# {record['cpu_count']} CPUs"
        f"{f' ({usable} usable)' if usable is not None else ''}; {vers}"
    )
