"""The demo's non-adhesive load path: :func:`roughcontact.workflows.demo.demo_path`.

Kept for the name ``roughcontact.cli.demo.demo``; the workflow lives in
:mod:`roughcontact.workflows.demo`, the command (parsing and printing) in :mod:`.demo_command`.
"""

from __future__ import annotations

from ..workflows.demo import demo_path as demo

__all__ = ["demo"]
