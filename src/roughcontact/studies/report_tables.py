"""The data tables of a study report (``data/tasks.csv``, ``steps.csv``,
``parameter_sets.csv``) from a collected study (:func:`~.collect.collect_study`)."""

from __future__ import annotations

import numpy as np

from .collect import STEP_VARIABLES, TIMINGS

__all__ = ["csv_bytes", "sets_frame", "steps_frame", "tasks_frame"]

#: The per-step variables of the steps table (no wall-clock times).
STEP_COLUMNS = tuple(v for v in STEP_VARIABLES if v not in TIMINGS)


def tasks_frame(ds):
    """One row per task: every per-task variable of a collected study."""
    import pandas as pd

    cols = {"task": np.asarray(ds["task"].values)}
    for name, var in {**ds.coords, **ds.data_vars}.items():
        if var.dims == ("task",):
            cols[name] = np.asarray(var.values)
    return pd.DataFrame(cols)


def steps_frame(ds):
    """One row per step of every task (no wall-clock times)."""
    import pandas as pd

    frames = []
    task_ids = np.asarray(ds["task"].values)
    n_steps = np.asarray(ds["n_steps"].values, dtype=int)
    for i, tid in enumerate(task_ids):
        n = n_steps[i]
        if n == 0:
            continue
        block = {"task": np.repeat(tid, n), "step": np.arange(n)}
        for name in STEP_COLUMNS:
            if name in ds.variables:
                block[name] = np.asarray(ds[name].values)[i, :n]
        frames.append(pd.DataFrame(block))
    return pd.concat(frames, ignore_index=True) if frames else pd.DataFrame()


def sets_frame(ds):
    """One row per parameter set: the seeds combined by the one rule."""
    import pandas as pd

    from .aggregate import aggregate_seeds

    rows = aggregate_seeds(ds)
    return pd.DataFrame([{k: v for k, v in r.items() if not isinstance(v, list)} for r in rows])


def csv_bytes(frame) -> bytes:
    """The CSV text of a table (10 significant digits), as bytes."""
    return frame.to_csv(index=False, float_format="%.10g").encode()
