"""Parameter studies: a TOML definition, a resumable Dask runner, one collected dataset.

>>> from roughcontact.studies import load_study, run_study, collect_study
>>> spec = load_study("studies/smoke.toml")          # validated before any work
>>> summary = run_study(spec, "out/smoke")           # LocalCluster sized to the machine
>>> ds = collect_study("out/smoke")                  # xarray.Dataset: task x step

Dask and xarray are imported only when a study runs or is collected.
"""

from .collect import collect_study
from .lock import DirectoryLocked
from .runner import StudySummary, run_study
from .spec import StudySpec, Task, load_study, study_from_dict
from .task import run_task

__all__ = [
    "DirectoryLocked",
    "StudySpec",
    "StudySummary",
    "Task",
    "collect_study",
    "load_study",
    "run_study",
    "run_task",
    "study_from_dict",
]
