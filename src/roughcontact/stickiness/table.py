"""The criteria side by side: a table (dict) and its text, and where they disagree."""

from __future__ import annotations

from .result import NO_VERDICT

__all__ = ["agreement", "criteria_table", "criteria_table_for_heights", "format_table"]

#: Said below every table: a criterion of the field that is deliberately missing.
NOT_EVALUATED = (
    "the bearing-area (BAM) criteria of Ciavarella (2018) and Violano et al. (2019), whose "
    "equations could not be checked against the papers (docs: Stickiness criteria)"
)


def agreement(results, simulated: str | None = None) -> dict:
    """Which criteria say sticky, which not, which give no verdict; do they disagree?

    ``simulated``: the simulation's verdict ("sticky"/"not sticky"/other), if one ran.
    """
    sticky = [r.key for r in results if r.sticky is True]
    not_sticky = [r.key for r in results if r.sticky is False]
    none = [r.key for r in results if r.sticky is None]
    out = {
        "sticky": sticky,
        "not_sticky": not_sticky,
        "no_verdict": none,
        "disagree": bool(sticky and not_sticky),
    }
    if simulated in ("sticky", "not sticky"):
        out["simulation"] = simulated
        out["agree_with_simulation"] = [
            r.key for r in results if r.sticky is not None and r.sticky == (simulated == "sticky")
        ]
    return out


def criteria_table(inputs, *, simulated: str | None = None) -> dict:
    """Every criterion on ``inputs`` as one JSON-ready dict.

    Parameters
    ----------
    inputs : CriterionInputs
        Material, interaction and surface statistics (consistent units).
    simulated : str, optional
        The simulation's verdict on the same surface (``--simulate``), shown beside.

    Returns
    -------
    dict
        ``{"inputs": ..., "criteria": [CriterionResult.to_dict(), ...],
        "agreement": agreement(...)}``.
    """
    from . import evaluate_all

    results = evaluate_all(inputs)
    return {
        "inputs": inputs.to_dict(),
        "criteria": [r.to_dict() for r in results],
        "agreement": agreement(results, simulated),
    }


def _num(v) -> str:
    return "—" if v is None else f"{v:.4g}"


def format_table(table: dict) -> str:
    """The text of :func:`criteria_table`: one row per criterion, then the disagreements."""
    rows = [("criterion", "parameter", "value", "threshold", "verdict")]
    for c in table["criteria"]:
        sign = "<" if c["sticky_below"] else ">"
        rows.append(
            (c["name"], c["parameter_symbol"], _num(c["parameter"]),
             f"{sign} {_num(c['threshold'])}", c["verdict"])
        )  # fmt: skip
    widths = [max(len(r[i]) for r in rows) for i in range(4)]
    lines = ["  ".join(r[i].ljust(widths[i]) for i in range(4)) + "  " + r[4] for r in rows]
    ag = table["agreement"]
    names = {c["key"]: c["name"] for c in table["criteria"]}

    def say(keys):
        return ", ".join(names[k] for k in keys) or "none"

    if ag["disagree"]:
        lines.append(
            f"The criteria disagree: sticky by {say(ag['sticky'])}; not sticky by "
            f"{say(ag['not_sticky'])}."
        )
    else:
        lines.append("The criteria with a verdict agree.")
    if ag["no_verdict"]:
        lines.append(f"No verdict from {say(ag['no_verdict'])} ({NO_VERDICT}: see the row).")
    if "simulation" in ag:
        lines.append(
            f"Simulation: {ag['simulation']}; agreeing: {say(ag['agree_with_simulation'])}."
        )
    lines.append("Validated against simulation or experiment:")
    for c in table["criteria"]:
        lines.append(f"  {c['name']}: {c['validated']}")
    lines.append(f"Not evaluated: {NOT_EVALUATED}.")
    noted = [c for c in table["criteria"] if c.get("notes")]
    if noted:
        lines.append("Model choices and caveats:")
        lines += [f"  {c['name']}: " + "; ".join(c["notes"]) for c in noted]
    return "\n".join(lines)


def criteria_table_for_heights(
    heights,
    *,
    pixel_size,
    contact_modulus,
    work_of_adhesion,
    interaction_range=float("nan"),
    youngs_modulus=float("nan"),
    units="SI",
    periodic=False,
    simulated: str | None = None,
) -> dict:
    """:func:`criteria_table` of a height map (a scan: ``periodic=False``, SI by default).

    ``heights`` and ``pixel_size`` [m], ``contact_modulus``/``youngs_modulus`` [Pa],
    ``work_of_adhesion`` [J/m^2], ``interaction_range`` [m] (or all in lattice units with
    ``units="lattice"``); the moments come from
    :func:`~roughcontact.stickiness.inputs.inputs_from_heights`. ``simulated``: the
    simulation's verdict on the same surface, shown beside. For ``roughcontact stick``.
    """
    from .inputs import inputs_from_heights

    inputs = inputs_from_heights(
        heights,
        contact_modulus=contact_modulus,
        work_of_adhesion=work_of_adhesion,
        interaction_range=interaction_range,
        pixel_size=pixel_size,
        youngs_modulus=youngs_modulus,
        units=units,
        periodic=periodic,
    )
    return criteria_table(inputs, simulated=simulated)
