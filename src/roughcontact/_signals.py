"""SIGTERM stops a command like Ctrl-C, and neither cuts a file write in half.

Schedulers (SLURM at the end of a job's time, Kubernetes, systemd) and ``kill`` send
SIGTERM, whose default action ends the process at once: everything since the last
checkpoint would be lost. Inside :func:`interruptible` (the command line's commands,
:func:`roughcontact.studies.run_study`) SIGTERM raises :class:`Terminated`, a
:class:`KeyboardInterrupt`, so the code that saves the finished work on Ctrl-C
(:class:`roughcontact.PathInterrupted`, the study driver closing its cluster) does the
same on SIGTERM; the command then exits with :data:`EXIT_TERMINATED` (143 = 128 + 15)
instead of :data:`EXIT_INTERRUPTED` (130 = 128 + 2). Inside :func:`deferred` (the
atomic file writes of :mod:`roughcontact._io`) either signal is held back until the
write is complete, then raised.

Before a command runs (while the modules load), :mod:`roughcontact._startup` makes
Ctrl-C on the command line exit with one line and code 130, without a traceback.

Signal handlers belong to the main thread: elsewhere both are no-ops. Only default
dispositions are replaced: a signal the process ignores (``SIG_IGN``, e.g. SIGINT of a
background job) stays ignored, and a program's own handler stays in charge.
"""

from __future__ import annotations

import contextlib
import signal
import threading

from ._startup import exit_interrupted

__all__ = [
    "EXIT_INTERRUPTED",
    "EXIT_TERMINATED",
    "Terminated",
    "deferred",
    "exit_code",
    "interruptible",
]

EXIT_INTERRUPTED = 128 + signal.SIGINT  # 130: Ctrl-C
EXIT_TERMINATED = 128 + signal.SIGTERM  # 143: SIGTERM


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived (a scheduler or ``kill``): stop as on Ctrl-C, exit code 143."""


class _State:
    installed = False  # our handlers are in place
    depth = 0  # nesting of deferred()
    pending: BaseException | None = None  # the signal held back by deferred()


_state = _State()
#: the dispositions :func:`interruptible` replaces: Python's and the system's defaults
#: (None: a handler not installed from Python), and the start-up handler of
#: :mod:`roughcontact._startup` (exit at once: nothing to save before a command runs)
_DEFAULTS = (signal.SIG_DFL, signal.default_int_handler, None, exit_interrupted)


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def _handler(signum, frame):
    exc = Terminated("terminated (SIGTERM)") if signum == signal.SIGTERM else KeyboardInterrupt()
    if _state.depth:
        if _state.pending is None or isinstance(exc, Terminated):
            _state.pending = exc
        return
    raise exc


@contextlib.contextmanager
def interruptible():
    """SIGTERM raises :class:`Terminated` and SIGINT :class:`KeyboardInterrupt` inside.

    The previous handlers are restored on the way out; nested uses and uses off the
    main thread change nothing.
    """
    if _state.installed or not _main_thread():
        yield
        return
    previous = {}
    try:
        for signum in (signal.SIGINT, signal.SIGTERM):
            current = signal.getsignal(signum)
            if current in _DEFAULTS:  # a program's own handler (or SIG_IGN) is kept
                previous[signum] = current
                signal.signal(signum, _handler)
        _state.installed, _state.depth, _state.pending = True, 0, None
        yield
    finally:
        _state.installed = False
        for signum, handler in previous.items():
            signal.signal(signum, handler if handler is not None else signal.SIG_DFL)


@contextlib.contextmanager
def deferred():
    """Hold SIGINT/SIGTERM back (inside :func:`interruptible`) until the block is done.

    For short critical sections such as writing and renaming a file: the signal is
    raised at the end of the outermost block, after its own clean-up has run.
    """
    if not (_state.installed and _main_thread()):
        yield
        return
    _state.depth += 1
    try:
        yield
    finally:
        _state.depth -= 1
        if _state.depth == 0 and _state.pending is not None:
            exc, _state.pending = _state.pending, None
            raise exc


def exit_code(err: BaseException) -> int:
    """143 when ``err`` is (or was caused by) :class:`Terminated`, else 130."""
    seen = set()
    while err is not None and id(err) not in seen:
        if isinstance(err, Terminated):
            return EXIT_TERMINATED
        seen.add(id(err))
        err = err.__cause__ or err.__context__
    return EXIT_INTERRUPTED
