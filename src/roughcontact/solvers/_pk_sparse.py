"""Polonsky-Keer iterations on index arrays of the contact set (NumPy).

The NumPy (CPU) backend of the hard wall: the same steps as the compiled loop on full-grid
masks, :mod:`._pk_jax` (see :mod:`.polonsky_keer` for the method and the residual), with
the vector work on index arrays of the contact set: a few per cent of the grid at small
loads, so cheaper than full-grid passes on a CPU.
"""

from __future__ import annotations

import math

import numpy as np

from .._backend import dtype_name
from .fourier import point_response
from .loop_control import ReliableUpdates, StallGuard, stopping
from .pk_rules import JOINING_KEEPS_DIRECTIONS, POINT_CORRECTIONS, StepKind
from .reductions import dot as _dot
from .result import SolveStatus

__all__ = ["iterate_sparse"]


def _subtract_heights(u, hf):
    np.subtract(u, hf, out=u)
    return u


class _PointKernel:
    """Response of the substrate to unit point forces, added in real space (the response
    to one force, :func:`.fourier.point_response`, made on the first :meth:`add`: many
    solves never need it)."""

    def __init__(self, substrate, dtype):
        self.substrate, self.dtype, self.shape = substrate, dtype, substrate.shape
        self.g0 = None

    def add(self, s_flat, sites, coeffs):
        """s += sum_j coeffs[j] * G(x - x_j) on the patch; G is stored on the work grid
        at separation ``(x - x_j) mod work_shape`` (periodic, or Hockney's padded grid)."""
        if self.g0 is None:
            self.g0 = point_response(self.substrate, np.empty(0, dtype=self.dtype))
        nx, ny = self.shape
        mx, my = self.g0.shape
        s2, g0 = s_flat.reshape(self.shape), self.g0
        for site, c in zip(sites.tolist(), coeffs.tolist(), strict=True):
            i, j = divmod(site, ny)
            s2[i:, j:] += c * g0[: nx - i, : ny - j]
            s2[i:, :j] += c * g0[: nx - i, my - j :]
            s2[:i, j:] += c * g0[mx - i :, : ny - j]
            s2[:i, :j] += c * g0[mx - i :, my - j :]


def iterate_sparse(p, pb, substrate):
    """Iterate from pressure ``p`` on the problem ``pb``; see :mod:`.polonsky_keer`.

    Returns ``(p, deflection, iterations, residual, converged, message)``; the deflection
    ``G p`` when the last state is an exact evaluation (always after convergence), else
    None.
    """
    hf, conv, target, offset, tol = pb.hf, pb.conv, pb.target, pb.offset, pb.tol
    n = hf.size
    kernel = _PointKernel(substrate, hf.dtype)
    s = _subtract_heights(conv(p), hf)  # s = u - h, so that the gap is s + d
    idx = np.flatnonzero(p > 0)
    # full-grid buffer for what is convolved in fast precision (zero off the sites used)
    tb = np.zeros(n, dtype=pb.fast_dtype)
    fast_result = np.empty_like(tb)  # receives each fast convolution, used before the next
    work = np.empty_like(hf)  # full-grid scratch in the heights' precision
    t_c = None
    delta, g_old = False, 1.0
    kind = StepKind(pb.precondition is not None)
    status, message = SolveStatus.ITERATION_LIMIT, "iteration cap reached"
    residual, it = math.inf, 0
    stall = StallGuard(dtype_name(hf))
    exact = True  # s equals G p - h from a fresh convolution (not updated incrementally)
    reliable = ReliableUpdates(tol)
    winkler, scale, callback = pb.winkler, pb.scale, pb.callback

    def fast(op, sites, values):
        tb[sites] = values
        out = op(tb, out=fast_result)
        tb[sites] = 0.0
        return out

    while True:
        if idx.size == 0:  # displacement control lost all contact: restart from overlap
            ov = np.flatnonzero(s < -offset)
            if ov.size == 0:
                residual, status, message = 0.0, SolveStatus.CONVERGED, "no contact"
                break
            p[ov] = -(s[ov] + offset) * winkler
            s, idx, exact, delta = _subtract_heights(conv(p, out=s), hf), ov, True, False
            # if a preconditioned step lost all contact, plain steps until the residual
            # is well below where it was: this restart must not repeat the same path
            kind.lost_contact(residual)
            continue
        s_c = s[idx]
        d = -float(s_c.mean()) if target is not None else offset
        g_c = s_c + d
        cand = np.flatnonzero(s < -d)
        out = cand[p[cand] == 0]  # interpenetrating sites that carry no pressure
        viol = -float((s[out] + d).min()) if out.size else 0.0
        residual = max(float(np.abs(g_c).max()), viol) / scale
        if (update := reliable.check(residual, exact)) == "refresh":
            s, exact = _subtract_heights(conv(p, out=s), hf), True
            continue
        if update == "restart":
            delta = False
        if (end := stopping(residual <= tol, residual, stall, it, pb.max_iter)) is not None:
            status, message = end
            break
        it += 1
        reliable.step()

        if kind.resumes(residual):
            delta = False
        pre = kind.pre
        if pre and out.size:
            # the interpenetrating sites join the sites the step acts on: their pressure
            # comes from the preconditioned direction, sized with all others by the line
            # minimisation (I_ol's site-local pressure would overshoot on whole regions)
            idx, g_c = np.concatenate((idx, out)), np.concatenate((g_c, s[out] + d))
            if delta and out.size <= JOINING_KEEPS_DIRECTIONS * idx.size:
                t_c = np.concatenate((t_c, np.zeros(out.size)))  # new sites: no direction yet
            else:
                delta = False
            out = out[:0]
        if not pre:
            z_c = g_c
        else:
            z_c = fast(pb.precondition, idx, g_c)[idx].astype(hf.dtype)
            if target is not None:
                z_c -= z_c.mean()
            elif pb.rigid_mean:  # K has no uniform mode: see polonsky_keer's docstring
                z_c += pb.site_stiffness * float(g_c.sum()) / n
        g_z = _dot(g_c, z_c)
        t_c = z_c + (g_z / g_old) * t_c if delta else z_c.copy()
        if target is not None:
            t_c -= t_c.mean()  # keep the load fixed along the search direction
        g_old = g_z
        r = fast(pb.fast_conv, idx, t_c)
        r_c = r[idx].astype(hf.dtype)
        denom = _dot(r_c, t_c)
        tau = _dot(g_c, t_c) / denom if denom > 0 else math.nan
        if not math.isfinite(tau):
            status = SolveStatus.NON_FINITE
            message = f"breakdown at iteration {it}: non-finite step (check the inputs)"
            break

        p_c = p[idx] - tau * t_c
        clipped = p_c <= 0
        projected = clipped.any() or out.size > 0
        if projected:  # I_ol below needs the gaps before the step
            gap_ol = s[out] + d
            ol_c = clipped & (g_c < 0) if not pre else np.zeros_like(clipped)
        r *= tau
        s -= r  # G(p - tau t) - h = s - tau G t by linearity
        exact = False
        if not projected:
            p[idx] = p_c
            delta = True
        else:
            # Polonsky & Keer's projection, then (plain steps) their I_ol: unloaded sites
            # that interpenetrate get pressure back
            changed = np.concatenate((idx[clipped], out))  # where p differs from p - tau t
            linear = np.concatenate((p_c[clipped], np.zeros(out.size)))
            p_c[clipped] = 0.0
            p[idx] = p_c
            ol = np.concatenate((out, idx[ol_c]))
            p[ol] -= tau * np.concatenate((gap_ol, g_c[ol_c]))
            delta = ol.size == 0
            keep = p[idx] > 0
            t_c = t_c[keep]
            idx = np.concatenate((idx[keep], out[p[out] > 0]))
            correction = p[changed] - linear
            # s += G(correction): point responses for a few sites, else a convolution
            if changed.size <= POINT_CORRECTIONS:
                kernel.add(s, changed, correction)
            else:
                s += fast(pb.fast_conv, changed, correction)
            if target is not None:
                total = float(p[idx].sum())
                if not total > 0:  # everything was clipped: restart from uniform pressure
                    p[:], idx, delta = target / n, np.arange(n), False
                    kind.lost_contact(residual)  # (as above)
                    s, exact = _subtract_heights(conv(p, out=s), hf), True
                elif total != target:  # back to the load: s = lam (u + G c) - h
                    lam = target / total
                    p[idx] *= lam
                    s *= lam
                    s += np.multiply(hf, lam - 1.0, out=work)
        if callback is not None and callback(it, residual):
            status, message = SolveStatus.CALLBACK, "stopped by callback"
            break
        if not math.isfinite(float(p[idx].sum())):
            status, message = SolveStatus.NON_FINITE, f"non-finite pressure at iteration {it}"
            break

    return p, (s + hf if exact else None), it, residual, status, message
