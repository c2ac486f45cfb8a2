"""The criteria side by side: a table (dict) and its text, and where they disagree."""

from __future__ import annotations

from .result import NO_VERDICT

__all__ = ["agreement", "criteria_table", "format_table"]


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
    return "\n".join(lines)
