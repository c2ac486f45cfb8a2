"""How much memory a new allocation here can have: RAM, the address-space limit, the cgroup.

:func:`available_memory` is the smallest of

* the RAM available (``MemAvailable`` of ``/proc/meminfo``, else ``sysconf``);
* the address space left under ``RLIMIT_AS`` (``ulimit -v``): its soft limit less the
  process's current size (``VmSize``);
* what the memory cgroup still allows: ``memory.max`` less ``memory.current`` (cgroup v2)
  or ``memory.limit_in_bytes`` less ``memory.usage_in_bytes`` (v1), each less the
  reclaimable page cache (``inactive_file``), for the process's cgroup and its parents.

None when none of them is known. Only the standard library is used.
"""

from __future__ import annotations

import os

__all__ = ["address_space_left", "available_memory", "cgroup_memory_left", "ram_available"]

_UNLIMITED = 1 << 60  # cgroup v1 writes "no limit" as a huge page-rounded number


def ram_available() -> int | None:
    """Bytes of RAM available to a new allocation (None if unknown)."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return int(os.sysconf("SC_AVPHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, OSError, ValueError):
        pass
    try:  # pragma: no cover - platforms without sysconf
        import psutil

        return int(psutil.virtual_memory().available)
    except Exception:  # noqa: BLE001
        return None


def _vm_size() -> int:
    """The process's current virtual size in bytes (0 if unknown)."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return 0


def address_space_left() -> int | None:
    """Bytes of address space left under the soft ``RLIMIT_AS`` (None: no limit)."""
    try:
        import resource

        soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    except (ImportError, OSError, ValueError, AttributeError):  # pragma: no cover - Windows
        return None
    if soft == resource.RLIM_INFINITY or soft < 0:
        return None
    return max(int(soft) - _vm_size(), 0)


def _read_int(path: str) -> int | None:
    try:
        with open(path) as f:
            text = f.read().strip()
    except OSError:
        return None
    if not text or text == "max":
        return None
    try:
        value = int(text)
    except ValueError:
        return None
    return None if value >= _UNLIMITED else value


def _inactive_file(directory: str, key: str) -> int:
    try:
        with open(os.path.join(directory, "memory.stat")) as f:
            for line in f:
                name, _, value = line.partition(" ")
                if name == key:
                    return int(value)
    except (OSError, ValueError):
        pass
    return 0


def _cgroup_dirs(root: str, relative: str):
    """The cgroup directory of the process under ``root`` and its parents (existing only);
    ``root`` itself too (inside a cgroup namespace the process's own is mounted there)."""
    relative = relative.strip("/")
    seen = []
    while True:
        directory = os.path.join(root, relative) if relative else root
        if os.path.isdir(directory) and directory not in seen:
            seen.append(directory)
        if not relative:
            break
        relative = os.path.dirname(relative)
    return seen


def cgroup_memory_left(proc_cgroup: str = "/proc/self/cgroup", mount="/sys/fs/cgroup"):
    """Bytes the memory cgroup still lets this process use (None: no limit found)."""
    try:
        with open(proc_cgroup) as f:
            lines = f.read().splitlines()
    except OSError:
        return None
    left = []
    for line in lines:
        parts = line.split(":", 2)
        if len(parts) != 3:
            continue
        _, controllers, relative = parts
        if controllers == "":  # v2: the unified hierarchy
            dirs = _cgroup_dirs(mount, relative)
            files = ("memory.max", "memory.current", "inactive_file")
        elif "memory" in controllers.split(","):  # v1
            dirs = _cgroup_dirs(os.path.join(mount, "memory"), relative)
            files = ("memory.limit_in_bytes", "memory.usage_in_bytes", "total_inactive_file")
        else:
            continue
        for directory in dirs:
            limit = _read_int(os.path.join(directory, files[0]))
            if limit is None:
                continue
            used = _read_int(os.path.join(directory, files[1])) or 0
            used -= min(_inactive_file(directory, files[2]), used)
            left.append(max(limit - used, 0))
    return min(left) if left else None


def available_memory() -> int | None:
    """Bytes of memory available to a new allocation here (None if unknown): the least
    of the RAM available, the address space left under RLIMIT_AS and the cgroup's room."""
    known = [
        v for v in (ram_available(), address_space_left(), cgroup_memory_left()) if v is not None
    ]
    return min(known) if known else None
