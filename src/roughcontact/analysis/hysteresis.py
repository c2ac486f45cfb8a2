r"""Adhesion hysteresis: the energy an approach–retraction cycle dissipates.

On a quasi-static, displacement-controlled path the elastic energy and the interaction
energy are a potential of the offset d on every stable branch, so the work done on the
system over a closed cycle is dissipated entirely in the jumps (instabilities) between
branches:

.. math::
    W = \oint N\, d\delta = -\oint N\, dd
    \quad(\delta = -d \text{ the approach; } N > 0 \text{ pushes the bodies together}).

With loads per nominal area (the path's ``load`` = N/A0, pressure) and offsets in
length, ``W`` is an energy per A0 (pressure × length: in lattice units E* a0; J/m² in
SI). It is integrated with the trapezoid rule over the path's steps in order (approach,
then retraction). Inside a step that contains a jump the load changes abruptly at an
offset the steps do not resolve; the trapezoid takes the mean, and the largest error
it can make is ``|ΔN| |Δd|/2`` per such step: ``energy_uncertainty`` sums it.

The number of jumps is the number of steps the path flags as instabilities
(``jump``); ``energy_per_jump = W/jumps`` is the mean (the cycle's work does not tell
how it divides among the jumps). The cycle is closed when the retraction ends where
the approach began with no load; otherwise the result says ``closed = False`` (the
work then also holds elastic energy still stored).

**Oracle** (:func:`jkr_cycle_dissipation`): the JKR sphere under displacement control
jumps into contact at ``delta = 0`` (to ``a_in^3 = 2 pi w R^2/E*``, ``N = -(4/3) pi w R``)
and out at ``a_d^3 = pi w R^2/(8 E*)`` (``delta_d = -(3/4)(pi^2 w^2 R/E*^2)^(1/3)``);
between the two the loading and unloading branches coincide (the JKR curve), and the
cycle's work is the area under the tensile part of the curve:

.. math::
    W_{JKR} = -\int_{a_d}^{a_{in}} N(a)\,\delta'(a)\,da
            = \Bigl(\frac{1}{10} + \frac{3}{5}2^{2/3}\Bigr)
              \frac{\pi^{5/3} w^{5/3} R^{4/3}}{E^{*2/3}}
            = 1.05244\,\frac{\pi^{5/3} w^{5/3} R^{4/3}}{E^{*2/3}}

(with ``N(a) = 4E*a^3/(3R) - (8 pi w E* a^3)^(1/2)``, ``delta(a) = a^2/R -
(2 pi w a/E*)^(1/2)``; the antiderivative of ``N delta'`` is ``8E*a^5/(15R^2) -
(4/(3R))(2 pi w E*)^(1/2) a^(7/2) + pi w a^2``), independent of how deep the approach went.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validate import ParameterError, json_ready, positive

__all__ = [
    "JKR_CYCLE_COEFFICIENT",
    "RELATIVE_TOLERANCE",
    "Hysteresis",
    "hysteresis",
    "hysteresis_from_steps",
    "hysteresis_in_si",
    "jkr_cycle_dissipation",
]

#: Without the solver's tolerance: the numerical bound of a cycle's W as a fraction of
#: the path's work scale ``∫|N| |dd|`` (float64 sums of converged loads stay far below it).
RELATIVE_TOLERANCE = 1e-6
#: ``1/10 + (3/5) 2^(2/3)``: W_JKR in units of ``pi^(5/3) w^(5/3) R^(4/3)/E*^(2/3)``.
JKR_CYCLE_COEFFICIENT = 0.1 + 0.6 * 2.0 ** (2.0 / 3.0)


def jkr_cycle_dissipation(radius, contact_modulus, work_of_adhesion) -> float:
    """Energy a displacement-controlled JKR sphere cycle dissipates [energy].

    ``radius`` R [length], ``contact_modulus`` E* [pressure], ``work_of_adhesion`` w
    [pressure × length]; the module docstring derives ``1.05244 pi^(5/3) w^(5/3)
    R^(4/3)/E*^(2/3)`` (jump-in at contact, jump-out at the displacement-control
    instability).
    """
    R = positive("radius", radius)
    E = positive("contact_modulus", contact_modulus)
    w = positive("work_of_adhesion", work_of_adhesion)
    return JKR_CYCLE_COEFFICIENT * math.pi ** (5 / 3) * w ** (5 / 3) * R ** (4 / 3) / E ** (2 / 3)


@dataclass(frozen=True)
class Hysteresis:
    """Energy dissipated by one approach–retraction cycle (module docstring).

    Attributes
    ----------
    dissipated_energy : float
        ``W = -∮ N dd`` per A0 [pressure × length]; NaN without a retraction.
    energy_uncertainty : float
        Bound on the trapezoid's error in the steps that contain a jump (same unit).
    approach_work, retract_work : float
        ``-∫ N dd`` over each branch (their sum is W; the retraction's is negative
        when the surfaces pull on the indenter).
    jumps, jumps_in, jumps_out : int
        Steps flagged as instabilities: all, on the approach, on the retraction.
    energy_per_jump : float
        ``W/jumps`` (NaN without jumps).
    closed : bool
        The retraction returns to the first offset with ``|N|`` below ``load_tolerance``.
    dissipated_energy_si : float
        W in J/m² when the path's length and pressure scales are given, else NaN.
    warnings : tuple of str
        Why the number may not be the cycle's dissipation.
    raw_dissipated_energy : float
        The trapezoid's ``-∮ N dd`` before the rule below (same unit).
    zero_within_tolerance : bool
        True when ``dissipated_energy`` is reported as 0: a cycle without jumps that
        returns to its first offset dissipates nothing elastically (its states are on
        one branch, where the energy is a potential), so what the trapezoid gives is
        numerical (the solver's tolerance); also a slightly negative W within
        ``energy_uncertainty``. ``energy_uncertainty`` is then the bound it lies within.
    tolerance : float
        The numerical bound of W: ``solver_tolerance × Σ|Δd|``, or without the solver's
        tolerance :data:`RELATIVE_TOLERANCE` × ``∫|N| |dd|``.
    """

    dissipated_energy: float
    energy_uncertainty: float
    approach_work: float
    retract_work: float
    jumps: int
    jumps_in: int
    jumps_out: int
    energy_per_jump: float
    closed: bool
    dissipated_energy_si: float = math.nan
    warnings: tuple = ()
    raw_dissipated_energy: float = math.nan
    zero_within_tolerance: bool = False
    tolerance: float = math.nan

    def to_dict(self) -> dict:
        """JSON-ready (non-finite numbers become None)."""
        out = json_ready(self)
        out["warnings"] = list(self.warnings)
        return out


def _work(d, n) -> float:
    if d.size < 2:
        return 0.0
    return float(-np.sum(0.5 * (n[1:] + n[:-1]) * np.diff(d)))


def hysteresis_from_steps(
    offset,
    load,
    branch,
    jump=None,
    converged=None,
    *,
    length_scale: float | None = None,
    pressure_scale: float | None = None,
    load_tolerance: float | None = None,
    solver_tolerance: float | None = None,
) -> Hysteresis:
    """:class:`Hysteresis` of one path given as arrays over its steps (in path order).

    Parameters
    ----------
    offset : array
        Offsets d [length] (decreasing d approaches); NaN steps (not computed) are dropped.
    load : array
        N/A0 [pressure], > 0 compressive.
    branch : array of str
        ``"approach"``/``"retract"`` per step.
    jump, converged : array of bool, optional
        Instability flags and convergence per step.
    length_scale, pressure_scale : float, optional
        Metres per length unit and pascals per pressure unit, for ``dissipated_energy_si``.
    load_tolerance : float, optional
        ``|N/A0|`` below which the end of the retraction counts as separated; default 1e-6
        of the largest ``|N/A0|`` on the path.
    solver_tolerance : float, optional
        How far a converged step's N/A0 may be from the exact one [pressure] (the
        solver's tolerance on the force balance per site): the bound of a jump-free
        cycle's W is ``solver_tolerance × Σ|Δd|``.

    A cycle without jumps (``jump`` given, none flagged) that returns to its first offset
    dissipates nothing: a W within the numerical bound (``solver_tolerance × Σ|Δd|``, or
    without it :data:`RELATIVE_TOLERANCE` × ``∫|N| |dd|``) is reported as 0
    (``zero_within_tolerance``, ``energy_uncertainty`` the bound); beyond it W is kept with
    a warning (an unflagged instability?). A negative W within the trapezoid's and the
    numerical bound is 0 too; beyond them it is 0 within ``|raw W|`` with a warning:
    W is never negative.
    """
    d = np.asarray(offset, dtype=float).ravel()
    n = np.asarray(load, dtype=float).ravel()
    b = np.asarray(branch).astype(str).ravel()
    if not d.size == n.size == b.size:
        raise ParameterError("offset, load and branch must have one value per step")
    j = np.zeros(d.size, bool) if jump is None else np.asarray(jump, dtype=bool).ravel()
    keep = np.isfinite(d) & np.isfinite(n)
    d, n, b, j = d[keep], n[keep], b[keep], j[keep]
    warnings = []
    if converged is not None:
        bad = int((~np.asarray(converged, dtype=bool).ravel()[keep]).sum())
        if bad:
            warnings.append(f"{bad} steps did not converge: their loads enter the integral")
    app, ret = b == "approach", b == "retract"
    ja, jr = int((j & app).sum()), int((j & ret).sum())
    if not ret.any():
        return Hysteresis(math.nan, math.nan, _work(d[app], n[app]), math.nan, ja + jr, ja,
                          jr, math.nan, False,
                          warnings=(*warnings, "no retraction: no cycle"))  # fmt: skip
    W = _work(d, n)
    dd, dn = np.abs(np.diff(d)), np.abs(np.diff(n))
    err = float(np.sum(0.5 * dn * dd * j[1:]))
    tol = load_tolerance
    if tol is None:
        tol = 1e-6 * max(float(np.max(np.abs(n))), 1e-300)
    closed = bool(abs(n[-1]) <= tol and abs(n[0]) <= tol and np.isclose(d[-1], d[0]))
    if not closed:
        warnings.append(
            "the cycle is not closed (the path does not start and end at the same offset "
            "with zero load): W includes energy still stored"
        )
    jumps = ja + jr
    raw, zero = W, False
    path_length = float(np.sum(dd))
    if solver_tolerance is not None:  # the solver's tolerance on N/A0 along the path
        solver = float(solver_tolerance) * path_length
    else:  # unknown: a relative tolerance of the path's own work scale, ∫|N| |dd|
        solver = RELATIVE_TOLERANCE * float(np.sum(0.5 * (np.abs(n[1:]) + np.abs(n[:-1])) * dd))
    if jump is not None and jumps == 0 and np.isclose(d[-1], d[0]):
        if abs(raw) <= solver:  # one stable branch: nothing dissipated, up to the solver
            zero, W, err = True, 0.0, solver
        else:
            warnings.append(
                f"a cycle without flagged jumps gives W = {raw:.3g}, beyond its numerical "
                f"bound {solver:.3g}: an instability smaller than the jump detector's "
                "threshold, or unconverged steps"
            )
    if W < 0 and abs(W) <= err + solver:  # never negative within the bounds
        zero, W, err = True, 0.0, err + solver
    elif W < 0:  # never negative: 0, with the deficit as its uncertainty, and why
        warnings.append(
            f"W = {W:.3g} is negative beyond its bound {err + solver:.3g}: a cycle cannot "
            "produce energy; reported as 0 within that deficit (the steps are too coarse "
            "or did not converge)"
        )
        W, err = 0.0, max(err + solver, abs(raw))
    si = math.nan
    if length_scale is not None and pressure_scale is not None:
        si = W * positive("length_scale", length_scale) * positive("pressure_scale", pressure_scale)
    # the approach's work up to the turning point, the rest is the retraction's
    turn = int(np.flatnonzero(app)[-1]) if app.any() else 0
    wa = _work(d[: turn + 1], n[: turn + 1])
    return Hysteresis(
        dissipated_energy=W,
        energy_uncertainty=err,
        approach_work=wa,
        retract_work=raw - wa,
        jumps=jumps,
        jumps_in=ja,
        jumps_out=jr,
        energy_per_jump=W / jumps if jumps else math.nan,
        closed=closed,
        dissipated_energy_si=si,
        warnings=tuple(warnings),
        raw_dissipated_energy=raw,
        zero_within_tolerance=zero,
        tolerance=solver,
    )


def hysteresis(ds, *, length_scale=None, pressure_scale=None, solver_tolerance=None):
    """:func:`hysteresis_from_steps` of a path dataset (:func:`roughcontact.approach_retract`).

    ``solver_tolerance``: the bound on a step's N/A0 from the solver's tolerance (see
    :func:`hysteresis_from_steps`).

    ``length_scale``/``pressure_scale``: metres per the path's length unit and pascals per
    its pressure unit (for a scan simulated in lattice units: a0 in m and E* in Pa); the
    SI value is NaN without them.
    """
    get = lambda k: np.asarray(ds[k].values) if k in ds.variables else None  # noqa: E731
    return hysteresis_from_steps(
        get("offset"),
        get("load"),
        get("branch"),
        get("jump"),
        get("converged"),
        length_scale=length_scale,
        pressure_scale=pressure_scale,
        solver_tolerance=solver_tolerance,
    )


def hysteresis_in_si(h: Hysteresis, *, length_scale, pressure_scale, nominal_area) -> dict:
    """The cycle's energies of ``h`` in SI: per area [J/m²] and over the nominal area [J].

    Parameters
    ----------
    h : Hysteresis
        In the path's units (W per A0: pressure × length).
    length_scale : float
        Metres per the path's length unit (a lattice path: a0 in m; a path of an
        instrument file: 1).
    pressure_scale : float
        Pascals per the path's pressure unit (a lattice path: E* in Pa).
    nominal_area : float
        A0 in the path's length unit squared.

    Returns
    -------
    dict
        ``dissipated_energy_per_area`` and ``energy_uncertainty_per_area`` [J/m²] (W, its
        jump bound), ``nominal_area`` [m²], ``dissipated_energy`` [J] (W A0) and
        ``energy_per_jump`` [J] (NaN without jumps or without a retraction).
    """
    ls = positive("length_scale", length_scale)
    ps = positive("pressure_scale", pressure_scale)
    area = positive("nominal_area", nominal_area) * ls**2
    per_area = h.dissipated_energy * ls * ps  # pressure × length -> J/m^2
    return {
        "dissipated_energy_per_area": per_area,
        "energy_uncertainty_per_area": h.energy_uncertainty * ls * ps,
        "nominal_area": area,
        "dissipated_energy": per_area * area,
        "energy_per_jump": per_area * area / h.jumps if h.jumps else math.nan,
    }
