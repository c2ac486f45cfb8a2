"""Ctrl-C while the command line starts: one line and exit code 130, no traceback.

Imported first by the package (before NumPy, SciPy, Dask load: the first second or so
of every command). When the program is the ``roughcontact`` console script, SIGINT
then ends the process at once with ``roughcontact: error: interrupted (Ctrl-C)`` and
code 130: nothing has been computed or written yet, so nothing is lost, and exiting
without unwinding keeps an import half-done from turning the interruption into an
``ImportError`` (NumPy reports any failure of its C modules as a broken install).
Once a command runs, :func:`roughcontact._signals.interruptible` takes over (Ctrl-C
then saves the finished work). A library import (a notebook, another program) changes
nothing. Only the standard library's ``atexit``, ``os``, ``signal`` and ``sys`` are used
here. A Ctrl-C while the finished command's process exits is ignored.
"""

import atexit
import os
import signal
import sys

PROGRAM = "roughcontact"
EXIT_INTERRUPTED = 128 + signal.SIGINT  # 130


def exit_interrupted(signum, frame):  # pragma: no cover - runs in a killed subprocess
    """SIGINT before a command runs: flush what was printed, one line, exit 130."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:  # noqa: BLE001 - closed or broken: nothing more to say
            pass
    try:
        os.write(2, f"{PROGRAM}: error: interrupted (Ctrl-C)\n".encode())
    except OSError:
        pass
    os._exit(EXIT_INTERRUPTED)


def install(argv0=None) -> bool:
    """Install :func:`exit_interrupted` for SIGINT if the program is the console script.

    ``argv0`` defaults to ``sys.argv[0]``. Nothing changes off the main thread, for
    another program, or when SIGINT is ignored or has a handler of the program's own.
    Returns whether the handler was installed.
    """
    if argv0 is None:
        argv0 = sys.argv[0] if sys.argv else ""
    if os.path.basename(str(argv0)).removesuffix(".exe") != PROGRAM:
        return False
    mp = sys.modules.get("multiprocessing")
    if mp is not None and mp.current_process().name != "MainProcess":
        # a worker process of the local Dask cluster, spawned from the console script
        # (it imports it again as __mp_main__): Ctrl-C in the terminal reaches it too,
        # but the command's own process stops the work and closes the cluster; a line or
        # a traceback from here would only repeat it
        try:
            signal.signal(signal.SIGINT, signal.SIG_IGN)
        except ValueError:  # pragma: no cover - not the main thread
            pass
        return False
    try:
        if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
            return False
        signal.signal(signal.SIGINT, exit_interrupted)
    except ValueError:  # not the main thread
        return False
    atexit.register(_ignore_at_exit)
    return True


def _ignore_at_exit() -> None:  # pragma: no cover - runs as a subprocess exits
    """Ctrl-C once the command has finished (and said so) is ignored: Python's
    finalisation would otherwise restore the default action, and a Ctrl-C in its last
    moments would kill the process without a word (exit status -2)."""
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
    except (ValueError, OSError):
        pass


install()
