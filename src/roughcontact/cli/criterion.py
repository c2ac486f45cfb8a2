"""``roughcontact criterion``: is a rough contact between real materials sticky?

Pastewka & Robbins, PNAS 111, 3298 (2014), Eq. 10, in SI units; values accept units
(``--modulus "10 MPa" --work-of-adhesion "50 mJ/m^2" --range "0.5 nm"``), plain numbers
are SI. Bad input raises :class:`roughcontact.ParameterError` (the ``roughcontact``
group prints it as one line and exits with code 2).
"""

from __future__ import annotations

import json

import click

from .._validate import ParameterError
from ..units import format_quantity

__all__ = ["criterion"]


# one SI-prefix formatter for the package, in roughcontact.units
_fmt = format_quantity


def _report(r) -> str:
    verdict = "STICKY" if r.sticky else "NOT sticky"
    lines = [
        f"contact modulus E*          {_fmt(r.contact_modulus, 'Pa')}",
        f"work of adhesion w          {r.work_of_adhesion:.4g} J/m^2",
        f"adhesion length l_a = w/E*  {_fmt(r.adhesion_length, 'm')}"
        f"  (l_a/a0 = {r.adhesion_length_over_atomic_spacing:.3g})",
        f"{'d_rep (' + r.d_rep_source + ')':28s}{_fmt(r.d_rep, 'm')}",
        f"pressures p_rep, w/dr       {_fmt(r.repulsive_pressure, 'Pa')}, "
        f"{_fmt(r.attractive_pressure, 'Pa')}",
        f"area ratio A_rep/A_att      {r.area_ratio:.4g}   (Eq. 6)",
        f"kappa_att                   {r.kappa_att:.4g}   (Eq. 7; kappa_rep = {r.kappa_rep:g})",
        f"kappa                       {r.kappa:.4g}",
        f"Eq. 10: {r.stickiness_parameter:.4g} vs {r.threshold:.4g}  ->  {verdict}, "
        f"margin {r.margin:.3g} (kappa_rep/kappa_att; > 1 sticks)",
        f"sticky if E* < {_fmt(r.max_sticky_contact_modulus, 'Pa')} or "
        f"d_rep < {_fmt(r.max_sticky_d_rep, 'm')} (the other inputs fixed)",
        f"necessary condition l_a/a0 > 0.49 h'rms (a0 = {_fmt(r.atomic_spacing, 'm')}): "
        + ("met" if r.necessary_condition_met else "NOT met"),
    ]
    return "\n".join(lines)


@click.command("criterion")
@click.option("--modulus", default=None, help="Contact modulus E* = E/(1-nu^2), e.g. '10 MPa'.")
@click.option("--youngs-modulus", default=None, help="Young's modulus E (with --poisson).")
@click.option("--poisson", default=None, help="Poisson ratio nu (with --youngs-modulus).")
@click.option(
    "--counter-modulus",
    default=None,
    help="Counter-surface's E (with --counter-poisson) or E/(1-nu^2); default rigid.",
)
@click.option("--counter-poisson", default=None, help="Counter-surface's Poisson ratio.")
@click.option("--work-of-adhesion", "work", required=True, help="w, e.g. '50 mJ/m^2'.")
@click.option("--rms-slope", required=True, help="h'rms (dimensionless).")
@click.option("--range", "range_", required=True, help="Interaction range Δr, e.g. '0.5 nm'.")
@click.option("--d-rep", default=None, help="Mean contact diameter d_rep, e.g. '10 nm'.")
@click.option("--rms-curvature", default=None, help="h''rms, e.g. '0.4 1/nm' (d_rep = 4h'/h'').")
@click.option("--kappa-rep", default=2.0, show_default=True, type=float, help="Non-adhesive κ_rep.")
@click.option("--atomic-spacing", default="0.3 nm", show_default=True, help="a0 (necessary cond.).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI units).")
@click.option("--rms-height", default=None, help="h_rms, e.g. '20 nm' (Fuller & Tabor's summits).")
@click.option("--hurst", default=None, type=float, help="H: with the cutoffs, the spectrum.")
@click.option("--short-cutoff", default=None, help="λs, e.g. '10 nm' (with --hurst).")
@click.option("--long-cutoff", default=None, help="L, e.g. '10 um' (with --hurst).")
def criterion(modulus, youngs_modulus, poisson, work, rms_slope, range_, d_rep, rms_curvature,
              kappa_rep, atomic_spacing, as_json, rms_height=None, hurst=None,
              short_cutoff=None, long_cutoff=None, counter_modulus=None,
              counter_poisson=None):  # fmt: skip
    """Stickiness criterion (Pastewka & Robbins 2014, Eq. 10) for real materials.

    Give --modulus (E*) or --youngs-modulus with --poisson, and exactly one of --d-rep
    and --rms-curvature. Values take units (Pa, J/m^2, m, 1/m with prefixes); plain
    numbers are SI. The counter-surface is rigid unless --counter-modulus is given:
    1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2. Then the field's other criteria side by side
    (Persson & Tosatti, Fuller & Tabor, Dahlquist, Müser; JSON key "criteria"): Persson &
    Tosatti needs the spectrum (--hurst, --short-cutoff, --long-cutoff), Fuller & Tabor
    h_rms (from the spectrum or --rms-height); without them they say "no verdict".
    """
    from ..criterion import stickiness_criterion

    if modulus is not None and (youngs_modulus is not None or poisson is not None):
        raise ParameterError("--modulus (E*) excludes --youngs-modulus/--poisson")
    if modulus is None and youngs_modulus is None:
        raise ParameterError("give --modulus (E*) or --youngs-modulus with --poisson")
    if youngs_modulus is not None and poisson is None:
        raise ParameterError("--youngs-modulus needs --poisson")
    if youngs_modulus is None and poisson is not None:
        raise ParameterError("--poisson goes with --youngs-modulus")
    if (d_rep is None) == (rms_curvature is None):
        raise ParameterError("give exactly one of --d-rep and --rms-curvature")
    pair = None
    if counter_modulus is not None or counter_poisson is not None:
        from ..moduli import composite_modulus

        body = (modulus, None) if modulus is not None else (youngs_modulus, poisson)
        pair = composite_modulus(*body, counter_modulus, counter_poisson)
        modulus, youngs_modulus, poisson = pair.contact_modulus, None, None
    r = stickiness_criterion(
        contact_modulus=modulus,
        youngs_modulus=youngs_modulus,
        poisson=poisson,
        work_of_adhesion=work,
        rms_slope=rms_slope,
        interaction_range=range_,
        d_rep=d_rep,
        rms_curvature=rms_curvature,
        kappa_rep=kappa_rep,
        atomic_spacing=atomic_spacing,
    )
    table = _criteria_table(r, rms_height, hurst, short_cutoff, long_cutoff)
    if as_json:
        d = {**r.to_dict(), "criteria": table}
        if pair is not None:
            d["counter_modulus"], d["contact_modulus_formula"] = pair.counter, pair.text
        click.echo(json.dumps(d))
    else:
        from ..stickiness import format_table

        pair_line = "" if pair is None else f"\n{pair.text}"
        click.echo(
            _report(r)
            + pair_line
            + "\n\nThe field's criteria side by side:\n"
            + format_table(table)
        )


def _criteria_table(r, rms_height, hurst, short_cutoff, long_cutoff) -> dict:
    """:func:`roughcontact.stickiness.criteria_table` on the criterion's SI inputs."""
    from ..criterion import parse_quantity
    from ..stickiness import criteria_table, inputs_from_criterion

    def length(v, name):
        return None if v is None else parse_quantity(v, "length", name)

    inputs = inputs_from_criterion(
        r,
        rms_height=length(rms_height, "rms_height"),
        hurst=hurst,
        short_cutoff=length(short_cutoff, "short_cutoff"),
        long_cutoff=length(long_cutoff, "long_cutoff"),
    )
    return criteria_table(inputs)
