"""The demo's adhesive study and report: :mod:`roughcontact.workflows.demo` and ``.report``.

Kept for the names it always offered; the workflow lives in :mod:`roughcontact.workflows`,
the command (parsing and printing) in :mod:`.demo_command`.
"""

from __future__ import annotations

from ..workflows.demo import ADHESION_LENGTHS, MAP_AREA, SHORT_CUTOFF, demo_study, run_demo_study
from ..workflows.report import summary_lines

__all__ = [
    "ADHESION_LENGTHS",
    "MAP_AREA",
    "SHORT_CUTOFF",
    "demo_study",
    "run_demo_study",
    "summary_lines",
]
