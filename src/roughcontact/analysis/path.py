"""Quantities read off a load path (a sequence of solved states)."""

from __future__ import annotations

import numpy as np

from .._validate import ParameterError, positive

__all__ = ["interpolate_at_area", "kappa"]


def interpolate_at_area(areas, values, target: float = 0.01) -> float:
    """Linearly interpolate ``values`` to the state where the repulsive area is ``target``.

    Parameters
    ----------
    areas : sequence of float
        Repulsive area fractions :math:`A_{rep}/A_0` along the path.
    values : sequence of float
        Any observable along the same path (load, repulsive load, ...).
    target : float
        Area fraction to interpolate to (default 1 %, as in Pastewka & Robbins 2014).

    Raises
    ------
    ParameterError
        If the path never brackets ``target``.
    """
    a = np.asarray(areas, dtype=float)
    v = np.asarray(values, dtype=float)
    order = np.argsort(a, kind="stable")
    a, v = a[order], v[order]
    if a.size < 2 or not (a[0] <= target <= a[-1]):
        raise ParameterError(
            f"target area {target} is not reached by the path (areas span "
            f"[{a.min() if a.size else 'nan'}, {a.max() if a.size else 'nan'}])"
        )
    return float(np.interp(target, a, v))


def kappa(area: float, load: float, rms_slope: float, contact_modulus: float = 1.0) -> float:
    r"""Dimensionless area–load prefactor :math:`\kappa = h'_{rms} E^* A / N`.

    Pastewka & Robbins 2014, Eqs. 2–3. Pass the repulsive load to get
    :math:`\kappa_{rep}` and the external load to get :math:`\kappa`; ``area`` and
    ``load`` per nominal area (fraction and mean pressure).
    """
    positive("rms_slope", rms_slope)
    positive("contact_modulus", contact_modulus)
    return float(rms_slope * contact_modulus * area / load)
