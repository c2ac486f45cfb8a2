r"""Outliers of a measured scan: spikes, sentinel values, isolated pixels (one stated rule).

Optical profilers and AFMs write a few heights that are not the surface: **spikes**
(single pixels or small clusters far above or below their neighbours: dust, bat wings
at steep edges, a lost fringe order), **sentinel values** (the one number an instrument
writes where it measured nothing, left unmasked by the reader) and **isolated pixels**
(a lone "valid" pixel inside a missing region). A few of them set the rms slope and
curvature: a spike of height A over one pixel a adds about (A/a)² to h'rms² over its
pixel, so 0.5 % spike pixels can dominate a smooth scan. The rule, robust because it
rests on medians:

1. **Spike.** Along a direction (the axis of a profile; both axes and both diagonals of
   a map) a pixel's *excursion* is how far it stands above (or below) its neighbours
   on *both* sides: on each side the larger of the drop to the neighbour at distance 1
   and a quarter of the drop to the one at distance 2 (a smooth summit's drops grow as
   the distance squared; a cluster of two or three pixels has its drop there), and of
   the two sides the smaller; 0 for a pixel that is no extremum (on a slope, at a
   step), none for a pixel without a neighbour on one side. Its scale is that of the
   second differences ``h - (h_-1 + h_+1)/2`` along the direction over the scan,
   ``s = 1.4826 MAD`` (the standard deviation of Gaussian residuals; ``Q90/1.645`` of
   the deviations when more than half of them are equal, from quantised or interpolated
   data). A pixel is a spike when its excursion exceeds :data:`SPIKE_THRESHOLD` ``s``
   along *every* direction in which it can be tested (in a map, at least along both
   axes: at an edge a line cannot be told from a point), with one sign. Requiring every
   direction keeps what belongs to the surface or the scanner along one direction (a
   step, a ridge, a scratch, a scan line offset); a tilt adds no excursion. On the
   four real scans of ``tests/data/topographies`` the rule flags nothing on the AFM
   map ``di-1.di`` and the stylus profile, 45 pixels of dust on the interferometer
   map and 6 pixels of two particles on ``nid-1.nid``; none on self-affine surfaces
   of any H or on white noise (``tests/topography/test_outliers.py``).
2. **Sentinel value.** A height shared exactly by at least :data:`SENTINEL_MIN_POINTS`
   pixels and by at least :data:`SENTINEL_RATIO` times as many pixels as any other
   height (a measurement does not repeat one number that often; quantised data repeat
   every level alike), held by fewer than half of the valid pixels: every pixel with
   it is an outlier (an instrument's "no data" value or a saturated reading).
3. **Isolated pixel.** A valid pixel in a group of at most :data:`ISLAND_MAX` valid
   pixels surrounded by missing ones cannot be tested by 1: it is an outlier when it
   deviates from the harmonic interpolation of the valid points around the group by
   more than :data:`ISLAND_THRESHOLD` robust standard deviations of the scan's heights
   (1.4826 MAD about their plane): inside a hole the surface may differ from the
   interpolation by its roughness, not by six times its rms height.

**What is done.** ``outliers="remove"`` (the default of :func:`roughcontact.stick` and
the CLI's ``--outliers remove``) treats them as missing points: they are filled with
the instrument's missing points by harmonic interpolation, under the same limit
(:data:`~roughcontact.topography.missing.MISSING_FILL_MAX`; more needs
``--fill-missing``). ``"keep"`` analyses them as heights. Either way the counts are
reported (``info["outliers"]``, the notes). The default removes: a height that fails
every test above is far more likely an artefact than a feature of the surface, and
keeping it can flip the verdict (issue 41: h'rms 0.0198 with 0.5 % spike pixels,
0.0027 without), while removing a real feature of one or two pixels changes the
statistics by about its share of the area.
"""

from __future__ import annotations

import warnings

import numpy as np

__all__ = [
    "OUTLIER_MODES",
    "SENTINEL_MIN_POINTS",
    "SENTINEL_RATIO",
    "ISLAND_MAX",
    "ISLAND_THRESHOLD",
    "SPIKE_THRESHOLD",
    "find_outliers",
    "outlier_note",
]

#: What to do with the outliers found: treat them as missing points, or keep them.
OUTLIER_MODES = ("remove", "keep")
#: Robust z-score above which a pixel is a spike (rule 1 of the module docstring).
SPIKE_THRESHOLD = 12.0
#: Fewest pixels holding one value for it to be a sentinel (rule 2).
SENTINEL_MIN_POINTS = 10
#: A sentinel value is held by this many times as many pixels as any other value.
SENTINEL_RATIO = 10.0
#: Largest group of valid pixels inside missing ones tested as isolated (rule 3).
ISLAND_MAX = 4
#: Robust standard deviations of the heights by which an island must differ from the
#: interpolation of its surroundings (rule 3): a surface within its own height
#: distribution is not; a Gaussian one exceeds 6 sd with a probability of 2e-9.
ISLAND_THRESHOLD = 6.0
#: Gaussian: sd = 1.4826 MAD = Q90(|x|)/1.645.
_MAD_SD, _Q90_SD = 1.4826, 1.0 / 1.6449


def _shifted(vals, step, k, periodic):
    """``vals`` at ``x + k * step`` (NaN outside a non-periodic grid)."""
    out = vals
    for axis, d in enumerate(step):
        if d == 0:
            continue
        out = np.roll(out, -k * d, axis=axis)
        if not periodic:
            n = vals.shape[axis]
            idx = np.arange(n) + k * d
            shape = [1] * vals.ndim
            shape[axis] = n
            out = np.where(((idx < 0) | (idx >= n)).reshape(shape), np.nan, out)
    return out


def _direction(h, missing, step, periodic):
    """Along one direction: the pixel's excursion above (or below) *both* sides, and the
    second-difference residual whose robust scale measures it.

    On each side the neighbours at distance 1 and 2 are looked at; the excursion on a
    side is the larger of the drop to the first and a quarter of the drop to the second
    (a smooth summit's drops grow as the distance squared; a cluster of two or three
    pixels has its drop at the second), the excursion along the direction the smaller
    of the two sides' (a step has none on its flat side, a slope none on its uphill
    side; a spike has one on both). 0 where the pixel is no extremum, NaN where a side
    has no valid neighbour.
    """
    vals = np.where(missing, np.nan, h)
    near = {k: _shifted(vals, step, k, periodic) for k in (-2, -1, 1, 2)}
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        # the drop to the neighbour at distance 2 counts a quarter: a smooth summit's
        # drops grow as the distance squared, a cluster's neighbour is not a drop
        up = np.fmin(
            np.fmax(vals - near[-1], (vals - near[-2]) / 4),
            np.fmax(vals - near[1], (vals - near[2]) / 4),
        )
        down = np.fmin(
            np.fmax(near[-1] - vals, (near[-2] - vals) / 4),
            np.fmax(near[1] - vals, (near[2] - vals) / 4),
        )
        both = (np.isfinite(near[-1]) | np.isfinite(near[-2])) & (
            np.isfinite(near[1]) | np.isfinite(near[2])
        )
        signed = np.where(up > 0, up, np.where(down > 0, -down, 0.0))  # 0: no extremum
        excursion = np.where(both & ~missing, signed, np.nan)
        second = vals - 0.5 * (near[-1] + near[1])
    direct = np.isfinite(near[-1]) | np.isfinite(near[1])
    return excursion, second, direct


def _islands(valid, periodic):
    """Valid pixels in connected groups (edge neighbours) of at most :data:`ISLAND_MAX`
    pixels: islands inside missing regions, which the spike test cannot judge."""
    from scipy import ndimage

    labels, n = ndimage.label(valid)
    if n == 0:
        return None
    sizes = np.bincount(labels.ravel())
    small = sizes <= ISLAND_MAX
    small[0] = False  # the missing points' label
    if periodic:  # a group cut by the edge is one group: leave it to the spike test
        edge = np.zeros(valid.shape, bool)
        for axis in range(valid.ndim):
            idx = [slice(None)] * valid.ndim
            idx[axis] = [0, -1]
            edge[tuple(idx)] = True
        small[np.unique(labels[edge])] = False
    return small[labels]


def _height_scale(h, valid) -> float:
    """1.4826 MAD of the valid heights about their least-squares plane (a tilt is no
    roughness): the scale of rule 3."""
    idx = np.nonzero(valid)
    cols = [np.ones(idx[0].size)] + [i.astype(float) for i in idx]
    coef, *_ = np.linalg.lstsq(np.stack(cols, axis=1), h[idx], rcond=None)
    _, s = _scale(h[idx] - np.stack(cols, axis=1) @ coef)
    return s


def _scale(r):
    """Robust scale of the finite residuals: 1.4826 MAD, or Q90/1.645 if MAD is 0."""
    x = r[np.isfinite(r)]
    if x.size < 8:
        return 0.0, 0.0
    centre = float(np.median(x))
    dev = np.abs(x - centre)
    s = _MAD_SD * float(np.median(dev))
    if not s > 0:
        s = _Q90_SD * float(np.quantile(dev, 0.9))
    return centre, s


def _sentinel(h, valid):
    values, counts = np.unique(h[valid], return_counts=True)
    if counts.size < 2:
        return None, 0
    order = np.argsort(counts)
    c1, c2 = int(counts[order[-1]]), int(counts[order[-2]])
    if c1 >= SENTINEL_MIN_POINTS and c1 >= SENTINEL_RATIO * c2 and c1 < 0.5 * valid.sum():
        return float(values[order[-1]]), c1
    return None, 0


def find_outliers(heights, missing=None, *, periodic=False):
    """The outliers of a scan by the rule of the module docstring.

    Parameters
    ----------
    heights : ndarray, 1D or 2D
        Heights (any unit; missing points may hold anything).
    missing : ndarray of bool, optional
        Points without a measurement (NaN or masked by the instrument).
    periodic : bool
        Whether the neighbours wrap around.

    Returns
    -------
    (ndarray of bool, dict)
        The outliers (never a missing point) and a JSON-ready report: ``points``,
        ``spikes``, ``sentinel_value`` (heights' unit, None if none),
        ``sentinel_points``, ``isolated``, ``threshold``, ``scale`` (the residual
        scale s per axis, heights' unit) and ``rule`` (in words).
    """
    h = np.asarray(heights, dtype=np.float64)
    missing = ~np.isfinite(h) if missing is None else (np.asarray(missing, bool) | ~np.isfinite(h))
    valid = ~missing
    flagged = np.zeros(h.shape, bool)
    # 2. sentinel values
    sentinel, n_sentinel = _sentinel(h, valid)
    sentinel_mask = valid & (h == sentinel) if sentinel is not None else np.zeros(h.shape, bool)
    work_missing = missing | sentinel_mask
    # 1. spikes: an extremum beyond the threshold along every testable direction
    steps = [(1,)] if h.ndim == 1 else [(1, 0), (0, 1), (1, 1), (1, -1)]
    spike = np.ones(h.shape, bool)
    tested = np.zeros(h.shape, bool)
    sign = np.zeros(h.shape)
    has_neighbour = np.zeros(h.shape, bool)
    scales = []
    axes_tested = np.ones(h.shape, bool)  # a map's edge pixel: a line or a point?
    for step in steps:
        excursion, second, direct = _direction(h, work_missing, step, periodic)
        if len(step) == 1 or 0 in step:  # the axes: direct neighbours
            has_neighbour |= direct
            axes_tested &= np.isfinite(excursion)
        _, s = _scale(second)
        scales.append(s)
        ok = np.isfinite(excursion)
        if not s > 0:
            spike &= ~ok
            continue
        z = np.where(ok, excursion, 0.0) / s
        big = ok & (np.abs(z) > SPIKE_THRESHOLD)
        same = (sign == 0) | (np.sign(z) == sign)
        spike &= ~ok | (big & same)
        sign = np.where(big & (sign == 0), np.sign(z), sign)
        tested |= ok
    spike &= tested & ~work_missing & axes_tested
    # 3. isolated pixels inside missing regions
    isolated = _islands(valid & ~sentinel_mask, periodic) if work_missing.any() else None
    isolated = np.zeros(h.shape, bool) if isolated is None else isolated & ~spike
    n_isolated = 0
    rest = valid & ~isolated & ~sentinel_mask
    if isolated.any() and rest.sum() >= 8:
        from ._grid import harmonic_fill

        s_h = _height_scale(h, rest)
        filled = harmonic_fill(np.where(work_missing | isolated, 0.0, h),
                               work_missing | isolated, periodic=periodic)  # fmt: skip
        off = isolated & (np.abs(h - filled) > ISLAND_THRESHOLD * s_h)
        n_isolated = int(off.sum())
        flagged |= off
    flagged |= spike | sentinel_mask
    report = {
        "points": int(flagged.sum()),
        "fraction": float(flagged.sum() / h.size),
        "spikes": int(spike.sum()),
        "sentinel_value": sentinel,
        "sentinel_points": int(n_sentinel),
        "isolated": n_isolated,
        "threshold": SPIKE_THRESHOLD,
        "scale": [float(s) for s in scales],
        "rule": (
            f"spike: above (or below) the neighbours on both sides by > {SPIKE_THRESHOLD:g} "
            "x 1.4826 MAD of the second differences, along every axis and diagonal, one "
            "sign; sentinel: one value "
            f"held by >= {SENTINEL_MIN_POINTS} pixels and >= {SENTINEL_RATIO:g}x any other; "
            f"isolated: a group of <= {ISLAND_MAX} valid pixels inside missing ones, more than "
            f"{ISLAND_THRESHOLD:g} robust sd of the heights from the interpolation around it"
        ),
    }
    return flagged, report


def outlier_note(report: dict, total: int | None = None, unit: str = "m") -> str:
    """One line on the outliers found and what was done (``info["outliers"]``)."""
    n = int(report["points"])
    of = f" of {total}" if total else ""
    parts = [f"{report['spikes']} spikes"]
    if report.get("sentinel_value") is not None:
        parts.append(
            f"{report['sentinel_points']} pixels holding the sentinel value "
            f"{report['sentinel_value']:.6g} {unit}"
        )
    if report.get("isolated"):
        parts.append(f"{report['isolated']} isolated pixels in missing regions")
    action = report.get("action", "removed")
    did = (
        "removed and filled with the missing points (--outliers keep keeps them)"
        if action == "removed"
        else "kept as heights (--outliers remove removes them)"
    )
    return (
        f"outliers: {n}{of} points ({report['fraction']:.3%} of the scan): {', '.join(parts)}; "
        f"{did}; rule: above or below its neighbours on both sides by more than "
        f"{report['threshold']:g} robust standard deviations of the second differences, "
        "along every axis and diagonal; a value repeated 10x more than any other "
        "(roughcontact.topography.outliers)"
    )
