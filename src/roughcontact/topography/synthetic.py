"""The synthetic surface of :mod:`roughcontact.topography.simulate` (lattice units, a0)."""

from __future__ import annotations

from .._validate import HURST, Range

__all__ = ["HURST_MIN", "SHORT_CUTOFF", "SIZE", "synthetic_surface"]

#: Grid size n of the synthetic surface (sites per axis). Below 64 the 1 % contact area
#: holds too few sites; above 1024 a CPU needs hours.
SIZE = Range(64, 1024, integer=True)

#: lambda_s/a0 of the synthetic surface: the paper's smallest short cutoff.
SHORT_CUTOFF = 4.0
#: Smallest Hurst exponent of the synthetic surface (``self_affine`` takes (0, 1]).
HURST_MIN = 0.05


def synthetic_surface(stats, *, atomic_spacing: float, size: int = 256, seed=1):
    """The synthetic surface of seed ``seed`` and how it was chosen (module docstring).

    Parameters
    ----------
    stats : ScaleStatistics
        The scan's statistics (SI).
    atomic_spacing : float
        a0 [m], the lattice spacing.
    size : int
        n (sites per axis), in :data:`SIZE`.
    seed : int
        Seed of :func:`roughcontact.self_affine`.

    Returns
    -------
    heights : ndarray, shape (n, n)
        Heights in units of a0.
    params : dict
        ``hurst`` (used), ``hurst_fitted``, ``hurst_clipped``, ``rms_slope``,
        ``short_cutoff``, ``long_cutoff`` (a0).
    """
    from ..surfaces import self_affine

    n = SIZE.check("simulate_size", size)
    a0 = float(atomic_spacing)
    fitted = float(stats.fit.hurst)
    H = min(max(fitted, HURST_MIN), HURST.hi)
    slope = stats.extrapolated_at(SHORT_CUTOFF * a0)[0]
    params = {
        "hurst": H,
        "hurst_fitted": fitted,
        "hurst_clipped": H != fitted,
        "rms_slope": float(slope),
        "short_cutoff": SHORT_CUTOFF,
        "long_cutoff": n / 2,
    }
    h = self_affine((n, n), hurst=H, rms_slope=slope, short_cutoff=SHORT_CUTOFF,
                    long_cutoff=n / 2, seed=seed)  # fmt: skip
    return h, params
