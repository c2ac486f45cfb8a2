"""Workflows: the library's jobs end to end (compute, collect, report), for any front end.

:func:`run_path` (:mod:`.pipeline`) follows one path end to end: surface → substrate →
law → values → path → analysis; the study's tasks, the ``stick`` simulation, the
``roughcontact path`` command and the demo all run through it. :mod:`.demo` is
``roughcontact demo``: a non-adhesive load path and a built-in adhesive study reproducing
the substance of Pastewka & Robbins, PNAS 111, 3298 (2014), Figs. 1-4; :mod:`.report`
writes its Markdown report. The command line only parses, calls and prints. Nothing heavy
is imported until a workflow runs.
"""

from .pipeline import AreaFields, PathRun, approach_offsets, run_path

__all__ = ["AreaFields", "PathRun", "approach_offsets", "run_path"]
