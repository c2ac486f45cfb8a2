"""The peers' runs of ``adhesive.py``: Adhesion 0.93 and tamaas 2.9 (see adhesive.py's docstring).

Each runner takes the approach of ``adhesive.py`` (heights, law, offsets, tolerance,
iteration cap) and returns one dict per step in the same columns as roughcontact's run.
The peers are benchmark-only dependencies, imported inside the functions.
"""

from __future__ import annotations

import math
import time

import numpy as np
from hardwall import capture_stderr_fd

A0 = 1.0  # pixel size = equilibrium distance (lattice units), as in adhesive.py
ES = 1.0  # contact modulus E*, as in adhesive.py


def adhesion_potential(law, core: str = "linear"):
    """Adhesion 0.93's smoothed LJ93 wall with the same V(g) as ``law``.

    ``LJ93(eps, sigma)`` is the same 9-3 wall as ours (same eps, sigma: minimum at a0,
    V''(a0) = k); ``spline_cutoff(gamma=w)`` (transition at the minimum) continues it
    by the quartic that reaches zero with zero slope and curvature, whose range is
    2 sqrt(3 w / k) = Delta_r: the paper's potential. ``core="linear"`` adds Adhesion's
    own ``linearize_core()`` at its default r_ti = r_min / 2 = a0 / 2 (constant
    repulsive pressure 84 E* below it): identical to ours wherever g >= a0 / 2, which
    every converged state satisfies (the smallest gap is printed), but without it the
    bare 9-3 wall changes sign at g = 0 and runs to -infinity for g < 0, where an
    L-BFGS-B trial step can land (``core="bare"`` shows this).
    """
    from Adhesion.Interactions import LJ93

    pot = LJ93(law.epsilon, law.sigma).spline_cutoff(gamma=law.work_of_adhesion)
    if core == "linear":
        pot = pot.linearize_core(r_ti=0.5 * law.equilibrium_distance)
    return pot


def check_potential(law, core: str = "linear") -> dict:
    """Compare Adhesion's V, V', V'' with ours on gaps across core, well, tail."""
    pot = adhesion_potential(law, core)
    a0, dr = law.equilibrium_distance, law.range
    g = np.concatenate([np.linspace(0.5 * a0, a0, 21), a0 + dr * np.linspace(0.0, 1.3, 27)])
    v, dv, ddv = pot.evaluate(g, potential=True, gradient=True, curvature=True)
    spline = pot.parent_potential if core == "linear" else pot

    def energy(x):
        return float(pot.evaluate(np.array([x]))[0][0])

    return dict(
        gaps=len(g),
        gap_range=[float(g.min()), float(g.max())],
        cutoff_adhesion=float(spline.cutoff_radius),
        cutoff_rc=float(law.cutoff),
        max_abs_energy_diff=float(np.abs(v - law.energy(g)).max()),
        max_abs_pressure_diff=float(np.abs(-dv - law.pressure(g)).max()),
        max_rel_curvature_diff=float(
            np.abs(ddv - law.curvature(g)).max() / np.abs(law.curvature(g)).max()
        ),
        sample=[
            (x, float(law.energy(np.array([x]))[0]), energy(x))
            for x in (0.5 * a0, 0.8 * a0, a0, a0 + dr / 3, a0 + 0.9 * dr, a0 + 1.1 * dr)
        ],
    )


def run_adhesion(h, law, offsets, tol, max_iter, time_cap=math.inf, core="linear", **_) -> dict:
    """Adhesion 0.93 SmoothContactSystem + scipy L-BFGS-B, warm-started.

    Conventions: ContactMechanics' gap is ``u - h - offset_CM`` with u positive into the
    substrate, ours ``d - h + w``; with a rigid uniform mode (mean u = 0, as our w)
    u = w and offset_CM = -d. The substrate gets ``stiffness_q0=0`` (no energy in the
    uniform mode) and the objective is evaluated at ``x - mean(x)`` with its gradient's
    mean removed, so the minimisation runs over the same mean-free displacements as
    ours (without it the uniform mode would be free or a spring, a different problem).
    The gradient is the force imbalance per pixel (area a0^2 = 1), so L-BFGS-B's
    ``gtol`` (max |g|) equals our residual times E* a0^2. ``ftol = 0`` so that it stops
    on the gradient only (or the iteration cap, or a failed line search).
    """
    import scipy.optimize
    from Adhesion.System import SmoothContactSystem
    from ContactMechanics import PeriodicFFTElasticHalfSpace
    from SurfaceTopography import Topography

    n0, n1 = h.shape
    size = (n0 * A0, n1 * A0)
    sub = PeriodicFFTElasticHalfSpace((n0, n1), ES, physical_sizes=size, stiffness_q0=0.0)
    topo = Topography(np.asarray(h, dtype=np.float64), physical_sizes=size)
    system = SmoothContactSystem(sub, adhesion_potential(law, core), topo)
    gtol = tol * ES * A0 * A0
    x = np.zeros(n0 * n1)
    steps = []
    for d in offsets:
        fun = system.objective(-float(d), gradient=True)

        def objective(x, fun=fun):
            e, g = fun(x - x.mean())
            return e, g - g.mean()

        t0 = time.perf_counter()

        def stop_after_cap(intermediate_result, t0=t0):
            if time.perf_counter() - t0 > time_cap:
                raise StopIteration

        with np.errstate(all="ignore"):
            res = scipy.optimize.minimize(
                objective,
                x,
                jac=True,
                method="L-BFGS-B",
                callback=stop_after_cap,
                options=dict(gtol=gtol, ftol=0.0, maxiter=max_iter, maxfun=10 * max_iter),
            )
        t = time.perf_counter() - t0
        x = np.asarray(res.x) - np.mean(res.x)
        _, grad = objective(x)
        residual = float(np.abs(grad).max()) / (ES * A0 * A0)
        gap = np.asarray(system.gap).copy()
        p_int = np.asarray(system.interaction_force) / (A0 * A0)  # pressure, > 0 repulsive
        a0, dr = law.equilibrium_distance, law.range
        capped = t > time_cap
        steps.append(
            dict(
                offset=float(d),
                seconds=t,
                iterations=int(res.nit),
                evaluations=int(res.nfev),
                converged=residual <= tol,
                residual=residual,
                message=("time cap reached" if capped else str(res.message)),
                repulsive_area=float(np.mean(gap < a0)),
                attractive_area=float(np.mean((gap > a0) & (gap < a0 + dr))),
                load=float(p_int.mean()),
                min_gap=float(gap.min()),
            )
        )
    return dict(steps=steps, pressure=p_int, gap=gap)


def run_tamaas(h, law, offsets, tol, max_iter, **_) -> dict:
    """tamaas 2.9 PolonskyKeerRey (gap primal, mean-gap constraint) + exponential adhesion.

    Conventions as in hardwall.py (heights point at the body, no sign flip; E* = E with
    nu = 0; ``model.displacement`` is the surface position, gap = displacement - h >= 0;
    ``model.traction`` > 0 compressive). ``solve(target)`` imposes the mean gap.
    """
    import tamaas as tm

    n0, n1 = h.shape
    heights = np.ascontiguousarray(h, dtype=np.float64)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [n0 * A0, n1 * A0], [n0, n1])
    model.E = ES
    model.nu = 0.0
    solver = tm.PolonskyKeerRey(model, heights, tol, tm.PolonskyKeerRey.gap, tm.PolonskyKeerRey.gap)
    solver.dump_freq = 10**9  # tamaas still logs the last iteration: parse it
    solver.max_iter = max_iter
    rho = 9.0 * law.range / 16.0
    gamma = law.work_of_adhesion
    adhesion = tm.ExponentialAdhesionFunctional(heights)
    adhesion.parameters = {"rho": rho, "surface_energy": gamma}
    solver.addFunctionalTerm(adhesion)
    mean_h = float(np.mean(h))
    steps = []
    for d in offsets:
        with capture_stderr_fd() as box:
            t0 = time.perf_counter()
            err = solver.solve(float(d) - mean_h - law.equilibrium_distance)
            t = time.perf_counter() - t0
        rows = [line.split() for line in box["text"].splitlines()]
        counts = [int(r[0]) for r in rows if r and r[0].isdigit()]
        traction = np.array(model.traction, copy=True)
        gap = np.array(model.displacement, copy=True) - heights
        free = gap > 0
        # force imbalance off the hard wall in our measure (elastic minus adhesive traction)
        imb = traction + gamma / rho * np.exp(-gap / rho)
        residual = float(np.abs(imb[free] - imb[free].mean()).max()) / ES if free.any() else 0.0
        steps.append(
            dict(
                offset=float(d),
                seconds=t,
                iterations=counts[-1] if counts else None,
                evaluations=None,
                converged=bool(err <= tol),
                residual=residual,
                own_error=float(err),
                message="",
                repulsive_area=float(np.mean(~free)),
                attractive_area=float(np.mean(free)),
                load=float(traction.mean()),
                min_gap=float(gap.min()),
            )
        )
    return dict(steps=steps, pressure=traction, gap=gap, rho=rho, surface_energy=gamma)
