r"""Model checks the field uses beside the verdict of :func:`roughcontact.stick` (SI).

**Monti, Sanner & Pastewka (2021).** Pastewka & Robbins' theory assumes adhesion of
short range against the gaps of the rough contact. J. M. Monti, A. Sanner and
L. Pastewka ("Distribution of gaps and adhesive interaction between contacting rough
surfaces", Tribol. Lett. (2021), doi:10.1007/s11249-021-01454-6) measure the gap
on the scale of the contacts by

.. math::
    g_0 = \frac{16}{3}\,\frac{h'^2_{rms}}{h''_{rms}},

and ask :math:`\rho/g_0 <` :data:`MSP_MAX` = 0.1 (ρ the interaction range), as the
Adhesion package's example ``adhesive_simulation_rough`` evaluates it. The check is made
with the measured roughness (at the measured scale) and, where the verdict extrapolates,
with the roughness continued to the atomic spacing (g0 shrinks as finer roughness is
added: h''rms grows faster than h'rms²).
"""

from __future__ import annotations

import math

__all__ = ["MSP_MAX", "msp_gap", "model_checks"]

#: Largest rho/g0 for which the short-range assumption holds (Monti et al. 2021).
MSP_MAX = 0.1
_REFERENCE = (
    "J. M. Monti, A. Sanner and L. Pastewka, Tribol. Lett. (2021), "
    "doi:10.1007/s11249-021-01454-6: rho/g0 < 0.1, g0 = 16/3 h'rms^2/h''rms"
)


def msp_gap(rms_slope: float, rms_curvature: float) -> float:
    """``g0 = 16/3 h'rms²/h''rms`` [m] (h'rms dimensionless, h''rms in 1/m)."""
    return 16.0 / 3.0 * rms_slope**2 / rms_curvature


def _one(scale, slope, curvature, rho) -> dict:
    g0 = msp_gap(slope, curvature)
    ratio = rho / g0 if g0 > 0 else math.inf
    return {
        "scale": float(scale),
        "g0": float(g0),
        "rho_over_g0": float(ratio),
        "holds": bool(ratio < MSP_MAX),
    }


def model_checks(stats, verdict) -> dict:
    """The checks of the module docstring for a :class:`~.sweep.Verdict` (SI).

    Returns
    -------
    dict
        ``{"monti_sanner_pastewka": {"reference", "threshold", "measured",
        "extrapolated", "text"}}``; ``measured``/``extrapolated`` hold ``scale`` [m],
        ``g0`` [m], ``rho_over_g0`` [1] and ``holds``; ``extrapolated`` is None without
        an extrapolation.
    """
    from ._text import length_text

    m = verdict.measured
    rho = float(m.interaction_range)
    measured = _one(stats.measured_scale, stats.rms_slope, stats.rms_curvature, rho)
    extrapolated = None
    if verdict.extrapolated and verdict.scales.size > 1:
        c = verdict.centre
        extrapolated = _one(
            verdict.scales[-1], verdict.slopes[c, -1], verdict.curvatures[c, -1], rho
        )

    def words(d):
        state = "holds" if d["holds"] else "fails"
        return (
            f"rho/g0 = {d['rho_over_g0']:.3g} ({state}; g0 = {length_text(d['g0'])}) with the "
            f"roughness down to {length_text(d['scale'])}"
        )

    text = f"Monti, Sanner & Pastewka's short-range check rho/g0 < {MSP_MAX:g}: {words(measured)}"
    if extrapolated is not None:
        text += f"; {words(extrapolated)} (extrapolated)"
    if not measured["holds"] or (extrapolated is not None and not extrapolated["holds"]):
        text += (
            ": where it fails, the interaction range is not short against the gaps and "
            "Eq. 10's assumptions do not hold"
        )
    return {
        "monti_sanner_pastewka": {
            "reference": _REFERENCE,
            "threshold": MSP_MAX,
            "measured": measured,
            "extrapolated": extrapolated,
            "text": text,
        }
    }
