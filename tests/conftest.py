"""Shared test helpers: a tiny study (32² or 64² grids, short paths)."""

import textwrap

import pytest

TINY = """
[study]
name = "tiny"

[surface]
size = {size}
hurst = [0.5, 0.8]
rms_slope = 0.1
short_cutoff = 4.0
seeds = [1, 2]

[interaction]
adhesion_length = [0.005, 0.05]

[path]
unit = "rms_height"
start = 0.5
stop = -2.0
num = {num}
retract = true

[solver]
tol = 1e-6
{extra}
"""


def tiny_study(directory, *, size=32, num=6, extra="", name="tiny.toml"):
    """Write a 2 x 2 x 2-seed study (8 tasks) and return its path."""
    path = directory / name
    path.write_text(textwrap.dedent(TINY.format(size=size, num=num, extra=extra)))
    return path


@pytest.fixture()
def make_study(tmp_path):
    """``make_study(size=32, num=6, extra="")``: write a tiny study into ``tmp_path``."""
    return lambda **kwargs: tiny_study(tmp_path, **kwargs)


# --------------------------------------------------------------------------- peer count
# The cross-checks against the peer libraries (tamaas, ContactMechanics, Adhesion) carry
# the marker ``peers`` and skip when a peer is not installed. So that they cannot vanish
# silently, the run ends with their count and skip reasons, and with
# ROUGHCONTACT_PEER_REPORT=FILE set it writes them as JSON (what .ci/run checks). Works
# under pytest-xdist: the reports reach the controller with their keywords.
PEER_REPORT = "ROUGHCONTACT_PEER_REPORT"
PEER_LIBRARIES = ("tamaas", "ContactMechanics", "Adhesion")
_PEERS: dict[str, dict] = {}


def _reason(report) -> str:
    longrepr = report.longrepr
    return longrepr[2] if isinstance(longrepr, tuple) else str(longrepr)


def pytest_collectreport(report):
    # a peer module that skips as a whole (importorskip at import) has no test items and
    # no markers yet: it counts as one skipped cross-check, named by its module
    if report.skipped and any(name in _reason(report) for name in PEER_LIBRARIES):
        _PEERS[report.nodeid] = {"outcome": "skipped", "reason": _reason(report)}


def pytest_runtest_logreport(report):
    if "peers" not in report.keywords:
        return
    entry = _PEERS.setdefault(report.nodeid, {"outcome": "passed", "reason": ""})
    if report.failed:
        entry["outcome"] = "failed"
    elif report.skipped and entry["outcome"] != "failed":
        entry["outcome"] = "skipped"
        entry["reason"] = _reason(report)


def peer_counts() -> dict:
    """``{"ran", "passed", "failed", "skipped", "skip_reasons": {reason: count}}``.

    A peer module skipped as a whole at collection counts as one skipped cross-check.
    """
    outcomes = [e["outcome"] for e in _PEERS.values()]
    reasons: dict[str, int] = {}
    for e in _PEERS.values():
        if e["outcome"] == "skipped":
            reasons[e["reason"]] = reasons.get(e["reason"], 0) + 1
    return {
        "ran": outcomes.count("passed") + outcomes.count("failed"),
        "passed": outcomes.count("passed"),
        "failed": outcomes.count("failed"),
        "skipped": outcomes.count("skipped"),
        "skip_reasons": reasons,
    }


def pytest_terminal_summary(terminalreporter, config):
    import json
    import os

    if hasattr(config, "workerinput"):  # an xdist worker: the controller reports
        return
    counts = peer_counts()
    line = (
        f"peer cross-checks (marker 'peers'): {counts['ran']} ran ({counts['passed']} passed, "
        f"{counts['failed']} failed), {counts['skipped']} skipped"
    )
    terminalreporter.write_sep("-", line)
    for reason, n in sorted(counts["skip_reasons"].items()):
        terminalreporter.write_line(f"  skipped {n}: {reason}")
    target = os.environ.get(PEER_REPORT)
    if target:
        with open(target, "w", encoding="utf-8") as f:
            json.dump(counts, f, indent=1)
