"""The paper's figures (matplotlib) from collected studies and path datasets.

>>> from roughcontact.plot import figure2, save_figures
>>> fig = figure2(collected)                     # a matplotlib Figure, nothing shown
>>> save_figures(collected, "figs", maps=paths)  # Figs. 1-4 as PNG and PDF

matplotlib is imported only when a figure is made; no pyplot state is used, so the
functions work headless (Agg) and in parallel.
"""

from .figures import figure1, figure2, figure3, figure4, save_figures
from .maps import contact_masks, study_maps

__all__ = [
    "contact_masks",
    "figure1",
    "figure2",
    "figure3",
    "figure4",
    "save_figures",
    "study_maps",
]
