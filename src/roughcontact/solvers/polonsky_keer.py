r"""Constrained conjugate gradients for the non-adhesive hard wall.

Minimises the complementary energy :math:`\tfrac12 p^T G p - p^T (h - d)` over
pressures :math:`p \ge 0` (Polonsky & Keer, Wear 231, 206 (1999)), where ``G`` is the
substrate's periodic Green's function applied by FFT. Under load control the mean
pressure is held at the requested load and the offset ``d`` is the Lagrange multiplier
of that constraint; under displacement control ``d`` is given.

Convergence measure (``residual``): the largest violation of the Signorini conditions,

.. math::
    r = \max\Big(\max_{p_i > 0} |g_i|,\; \max_{p_i = 0} (-g_i)\Big) \,/\, h_{rms},

i.e. the largest gap on a loaded site or interpenetration on an unloaded one, relative
to the rms height (``pixel_size`` for a flat surface). Pressures satisfy ``p >= 0``
exactly and, under load control, the load exactly.

Cost per iteration: one FFT convolution, plus a second one only on iterations where the
projection changed the contact set (the deflection is otherwise updated from the
convolution of the search direction, which is exact by linearity).
"""

from __future__ import annotations

import math
import time

import numpy as np

from .._validate import ParameterError
from ._ops import check_hard_wall_offset, check_problem, compliance_operator
from ._ops import dot as _dot
from .observables import make_result

__all__ = ["polonsky_keer"]
# up to this many changed sites, point responses are cheaper than a convolution
_POINT_CORRECTIONS = 8


def _subtract_heights(u, hf):
    np.subtract(u, hf, out=u)
    return u


class _PointKernel:
    """Response of the substrate to unit point forces, added in real space."""

    def __init__(self, substrate, conv):
        n = substrate.shape[0] * substrate.shape[1]
        unit = np.zeros(n)
        unit[0] = 1.0
        self.g0 = conv(unit).reshape(substrate.shape)
        self.shape = substrate.shape

    def add(self, s_flat, sites, coeffs):
        """s += sum_j coeffs[j] * G(x - x_j), periodic."""
        nx, ny = self.shape
        s2, g0 = s_flat.reshape(self.shape), self.g0
        for site, c in zip(sites.tolist(), coeffs.tolist(), strict=True):
            i, j = divmod(site, ny)
            s2[i:, j:] += c * g0[: nx - i, : ny - j]
            s2[i:, :j] += c * g0[: nx - i, ny - j :]
            s2[:i, j:] += c * g0[nx - i :, : ny - j]
            s2[:i, :j] += c * g0[nx - i :, ny - j :]


def _initial_pressure(initial, heights, substrate, load, offset):
    n = heights.size
    if initial is not None:
        p0 = getattr(initial, "pressure", initial)
        p0 = np.array(p0, dtype=float).ravel()
        if p0.size != n:
            raise ParameterError(
                f"initial must have the substrate's shape {substrate.shape}, got {p0.size} sites"
            )
        np.maximum(p0, 0.0, out=p0)
        if load is not None:
            total = p0.sum()
            return p0 * (load * n / total) if total > 0 else np.full(n, load)
        if p0.any():
            return p0
    if load is not None:
        return np.full(n, float(load))
    # displacement control: a local (Winkler) guess, E*/a0 per unit interpenetration
    scale = 0.5 * substrate.contact_modulus / substrate.pixel_size
    return np.maximum(heights.ravel() - offset, 0.0) * scale


def polonsky_keer(
    heights,
    substrate,
    *,
    load=None,
    offset=None,
    initial=None,
    tol=1e-8,
    max_iter=5000,
    callback=None,
):
    """Solve hard-wall contact by constrained conjugate gradients.

    Parameters
    ----------
    heights : (nx, ny) array
        Rigid surface heights ``h`` (length; summits point at the substrate).
    substrate : Substrate
    load : float, optional
        Mean pressure :math:`N/A_0 \\ge 0` (pressure units). Exactly one of load/offset.
    offset : float, optional
        Offset ``d`` of the rigid surface (length); gap ``g = d - h + w``.
    initial : ContactResult or array, optional
        Warm start (its pressure; rescaled to ``load`` under load control).
    tol : float
        Tolerance on the residual defined in the module docstring.
    max_iter : int
        Iteration cap; reaching it gives ``converged=False``.
    callback : callable, optional
        ``callback(iteration, residual)`` after every iteration; return True to stop.

    Returns
    -------
    ContactResult
    """
    t_start = time.perf_counter()
    h = check_problem(heights, substrate, tol, offset)
    if (load is None) == (offset is None):
        raise ParameterError("give exactly one of load (mean pressure) or offset")
    if load is not None:
        load = float(load)
        if not math.isfinite(load) or load < 0:
            raise ParameterError(f"load must be finite and >= 0 for a hard wall, got {load!r}")
    else:
        offset = float(offset)
        check_hard_wall_offset(h, substrate, offset)
    tol = float(tol)

    hf = h.ravel()
    n = hf.size
    scale = float(np.std(hf)) or substrate.pixel_size
    conv = compliance_operator(substrate)
    kernel = _PointKernel(substrate, conv)

    if load == 0.0 or (offset is not None and substrate.rigid_mean and offset >= hf.max()):
        # no contact: nothing to solve (the rigid surface just touches or is apart)
        p = np.zeros(n)
        d = float(hf.max()) if offset is None else offset
        return make_result(
            h,
            substrate,
            p.reshape(h.shape),
            np.zeros_like(h),
            d,
            0,
            0.0,
            True,
            "no contact",
            tol,
            "polonsky-keer",
            time.perf_counter() - t_start,
        )

    target = None if load is None else load * n
    p = _initial_pressure(initial, h, substrate, load, offset)
    s = _subtract_heights(conv(p), hf)  # s = u - h, so that the gap is s + d
    idx = np.flatnonzero(p > 0)
    tb = np.zeros(n)  # full-grid buffer for the search direction (zero off the set)
    t_c = None
    delta, g_old = False, 1.0
    converged, message, residual, it = False, "iteration cap reached", math.inf, 0
    exact = True  # s equals G p - h from a fresh convolution (not updated incrementally)
    winkler = 0.5 * substrate.contact_modulus / substrate.pixel_size

    while True:
        if idx.size == 0:  # displacement control lost all contact: restart from overlap
            ov = np.flatnonzero(s < -offset)
            if ov.size == 0:
                residual, converged, message = 0.0, True, "no contact"
                break
            p[ov] = -(s[ov] + offset) * winkler
            s, idx, exact, delta = _subtract_heights(conv(p), hf), ov, True, False
            continue
        s_c = s[idx]
        d = -float(s_c.mean()) if target is not None else offset
        g_c = s_c + d
        cand = np.flatnonzero(s < -d)
        out = cand[p[cand] == 0]  # interpenetrating sites that carry no pressure
        viol = -float((s[out] + d).min()) if out.size else 0.0
        residual = max(float(np.abs(g_c).max()), viol) / scale
        if residual <= tol:
            if exact:
                converged, message = True, "converged"
                break
            s, exact = _subtract_heights(conv(p), hf), True  # confirm without round-off drift
            continue
        if it >= max_iter:
            break
        it += 1

        g_norm = _dot(g_c, g_c)
        t_c = g_c + (g_norm / g_old) * t_c if delta else g_c.copy()
        if target is not None:
            t_c -= t_c.mean()  # keep the load fixed along the search direction
        g_old = g_norm
        tb[idx] = t_c
        r = conv(tb)
        tb[idx] = 0.0
        r_c = r[idx]
        denom = _dot(r_c, t_c)
        tau = _dot(g_c, t_c) / denom if denom > 0 else math.nan
        if not math.isfinite(tau):
            message = f"breakdown at iteration {it}: non-finite step (check the inputs)"
            break

        p_c = p[idx] - tau * t_c
        clipped = p_c <= 0
        if not clipped.any() and out.size == 0:
            p[idx] = p_c
            r *= tau
            s -= r  # exact by linearity: G(p - tau t) - h = s - tau G t
            exact, delta = False, True
        else:
            # Polonsky & Keer's projection, then their I_ol: unloaded sites that
            # interpenetrate get pressure back
            changed = np.concatenate((idx[clipped], out))  # where p differs from p - tau t
            linear = np.concatenate((p_c[clipped], np.zeros(out.size)))
            p_c[clipped] = 0.0
            p[idx] = p_c
            ol = np.concatenate((out, idx[clipped & (g_c < 0)]))
            p[ol] -= tau * (s[ol] + d)
            delta = ol.size == 0
            keep = p[idx] > 0
            t_c = t_c[keep]
            idx = np.concatenate((idx[keep], out[p[out] > 0]))
            correction = p[changed] - linear
            lam = 1.0
            if target is not None:
                total = float(p[idx].sum())
                if not total > 0:  # everything was clipped: restart from uniform pressure
                    p[:], idx, delta, changed = load, np.arange(n), False, np.arange(n)
                else:
                    lam = target / total
                    p[idx] *= lam
            if changed.size <= _POINT_CORRECTIONS:
                # few sites changed: add their point responses instead of a convolution
                r *= tau
                s -= r
                kernel.add(s, changed, correction)
                if lam != 1.0:  # s = lam * (u + G c) - h
                    s *= lam
                    s += (lam - 1.0) * hf
                exact = False
            else:
                s, exact = _subtract_heights(conv(p), hf), True
        if callback is not None and callback(it, residual):
            message = "stopped by callback"
            break
        if not math.isfinite(float(p[idx].sum())):
            message = f"non-finite pressure at iteration {it}"
            break

    u = conv(p)
    s = u - hf
    c = p > 0
    d = (
        -float(s[c].mean())
        if (target is not None and c.any())
        else (offset if offset is not None else float(hf.max()))
    )
    return make_result(
        h,
        substrate,
        p.reshape(h.shape),
        u.reshape(h.shape),
        d,
        it,
        residual,
        converged,
        message,
        tol,
        "polonsky-keer",
        time.perf_counter() - t_start,
    )
