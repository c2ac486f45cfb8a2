"""Study definitions: a TOML file, validated on load and expanded into tasks.

A study is a grid (cartesian product of every list-valued parameter) and/or an explicit
list of ``[[cases]]`` over the surface, substrate and interaction parameters, times the
seeds. Every task is one surface realisation × one parameter set × its whole path. The
schema is in :data:`SCHEMA`; an example is ``studies/smoke.toml``. Lengths in units of
the pixel size a0 (lattice units), moduli and pressures in the units of E*.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

from .._validate import (
    MAX_PATH_STEPS,
    MAX_TOL_FLOAT32,
    ParameterError,
    layer_thickness,
    step_indices,
)
from ..interactions.registry import law_parameters
from ..solvers.inputs import DEFAULT_TOL
from .schema import KINDS, LAW_KEYS, SCHEMA, SWEEP_KEYS, UNITS, find, make_interaction

#: the most tasks a study may have (seeds x parameter sets): checked before they are built
MAX_TASKS = 100_000
#: the largest study file read (a study lists parameters, not data)
MAX_STUDY_BYTES = 16 * 2**20
#: the deepest nesting of arrays and inline tables a study file may hold
MAX_NESTING = 32

__all__ = [
    "StudySpec",
    "Task",
    "approach_steps",
    "load_study",
    "make_interaction",
    "path_steps",
    "study_from_dict",
]


@dataclass(frozen=True)
class Task:
    """One unit of work: a resolved parameter set (incl. the seed) and the shared settings.

    ``params`` holds every surface, substrate and interaction parameter with the
    interaction's derived values filled in (None where a parameter does not apply);
    ``key`` is the SHA-256 of ``params`` and ``settings``, checked on resume.
    """

    id: str
    params: dict
    settings: dict = field(repr=False)
    key: str = ""
    device: str | None = None  # where to compute; not part of the key (same results)


@dataclass(frozen=True)
class StudySpec:
    """A validated study: its tasks in a deterministic order and where it came from."""

    name: str
    description: str
    tasks: tuple
    settings: dict
    source: str
    text: str
    sha256: str
    axes: dict = field(default_factory=dict)


def load_study(path) -> StudySpec:
    """Read, validate and expand a study TOML file (nothing is computed).

    Raises
    ------
    ParameterError
        Naming the key, the value and the accepted range of the first problem found.
    """
    from .._files import read_input_bytes

    path = Path(path)
    try:  # a FIFO or device is refused before it is opened (it could block forever)
        raw = read_input_bytes(path, "cannot read study file", "a TOML file", MAX_STUDY_BYTES + 1)
    except OSError as err:
        raise ParameterError(f"cannot read study file {str(path)!r}: {err.strerror}") from None
    if len(raw) > MAX_STUDY_BYTES:
        raise ParameterError(
            f"study file {path.name}: larger than {MAX_STUDY_BYTES // 2**20} MiB; expected a "
            "TOML study file (lists of parameters, not data)"
        )
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise ParameterError(
            f"study file {path.name}: not a text file (byte {err.start} is not UTF-8); "
            "expected a TOML study file"
        ) from None
    # a UTF-8 byte order mark (some Windows editors write one) is not TOML: dropped
    text = text.removeprefix("\ufeff")
    data = _parse_toml(path, text)
    return study_from_dict(data, source=str(path), text=text, default_name=path.stem)


def _parse_toml(path, text) -> dict:
    """The parsed TOML, or one ParameterError line (also for values nested too deep)."""
    depth = _nesting(text)
    if depth > MAX_NESTING:
        raise ParameterError(
            f"study file {path.name}: values or keys nested {depth} deep; accepted at most "
            f"{MAX_NESTING} levels of arrays, inline tables and dotted keys"
        )
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(f"study file {path.name}: not valid TOML: {err}") from None
    except RecursionError:  # pragma: no cover - refused by _nesting first
        raise ParameterError(f"study file {path.name}: values nested too deep") from None


#: TOML strings and comments (their brackets and dots are text, not structure)
_STRINGS = re.compile(
    r'"""[\s\S]*?"""' r"|'''[\s\S]*?'''" r'|"(?:\\.|[^"\\\n])*"' r"|'[^'\n]*'|#[^\n]*"
)
#: a dot of a dotted key (a.b.c), not one inside a number (1.5, a time's 00.999)
_KEY_DOT = re.compile(r"(?<![0-9])\.|\.(?![0-9])")


def _nesting(text: str) -> int:
    """An upper bound of the nesting a TOML text asks for: of arrays and inline tables
    (the running count of brackets and braces) and of dotted keys (the dots of one line),
    outside strings and comments. tomllib recurses on each level of the former (a deep
    one ends in a RecursionError and thousands of lines) and takes quadratic time in the
    latter (a key of 50,000 parts: minutes)."""
    bare = _STRINGS.sub('""', text)
    depth = deepest = 0
    for match in re.finditer(r"[\[\]{}]", bare):
        depth = depth + 1 if match.group() in "[{" else max(depth - 1, 0)
        deepest = max(deepest, depth)
    dots = max((len(_KEY_DOT.findall(line)) for line in bare.splitlines()), default=0)
    return max(deepest, dots)


def _fail(message):
    message = str(message)
    if len(message) > 1000:  # a value of 10^5 entries: its head and the accepted range
        message = f"{message[:500]} ... {message[-400:]}"
    raise ParameterError(f"study: {message}")


def _inner(err) -> str:
    """A nested error's text without its own ``study:`` prefix (said once, by _fail)."""
    return str(err).removeprefix("study: ")


def _value(where, key, spec, value):
    """Check one scalar against its type and range; return it (ints become floats)."""
    bad_type = isinstance(value, bool) and spec.kind is not bool
    if spec.kind is float and isinstance(value, int) and not bad_type:
        value = float(value)
    if bad_type or not isinstance(value, spec.kind):
        expected = KINDS[spec.kind] + (f" ({spec.accepted})" if spec.accepted else "")
        _fail(f"{where} {key} = {value!r} has the wrong type: expected {expected}")
    if isinstance(value, str) and any(ord(ch) < 32 and ch not in "\t\n\r" for ch in value):
        _fail(
            f"{where} {key} = {value!r} holds a control character (NUL, ...): accepted "
            "printable text"
        )
    if spec.test is not None and not spec.test(value):
        _fail(f"{where} {key} = {value!r} is out of range: accepted {spec.accepted}")
    return value


def _section(data, name, where=None):
    """Validated values of one section (lists stay lists) with unknown keys rejected."""
    where = where or f"[{name}]"
    raw = data.get(name, {})
    if not isinstance(raw, dict):
        _fail(f"{where} must be a table, got {raw!r}")
    allowed = SCHEMA[name] if name != "cases" else {k: find(k) for k in SWEEP_KEYS}
    out = {}
    for key, value in raw.items():
        if key not in allowed:
            _fail(f"unknown key {key!r} in {where}; accepted: {', '.join(allowed)}")
        spec = allowed[key]
        if isinstance(value, list) and (spec.is_list or (spec.sweep and name != "cases")):
            if not value and key not in ("fields_at", "fields_at_area", "lead_in"):
                _fail(f"{where} {key} = [] is empty: give at least one value")
            out[key] = [_value(where, key, spec, v) for v in value]
        elif spec.is_list:
            _fail(f"{where} {key} = {value!r} has the wrong type: expected a list")
        else:
            out[key] = _value(where, key, spec, value)
    return out


def study_from_dict(data, *, source="<dict>", text=None, default_name="study") -> StudySpec:
    """Validate and expand a study given as a dict (the parsed TOML)."""
    if not isinstance(data, dict):
        _fail(f"a study is a table of sections, got {type(data).__name__}")
    for name in data:
        if name not in SCHEMA and name != "cases":
            _fail(f"unknown section [{name}]; accepted: {', '.join(SCHEMA)}, [[cases]]")
    sections = {name: _section(data, name) for name in SCHEMA}
    cases = data.get("cases", [{}])
    if not isinstance(cases, list) or not cases:
        _fail(f"[[cases]] must be a non-empty array of tables, got {cases!r}")
    cases = [_section({"cases": c}, "cases", f"[[cases]] #{i + 1}") for i, c in enumerate(cases)]
    seeds = sections["surface"].pop("seeds", None)
    if seeds is None:
        _fail("[surface] seeds is missing: give a list of integers >= 0, e.g. seeds = [1, 2]")
    if len(set(seeds)) != len(seeds):
        _fail(f"[surface] seeds = {seeds!r} has repeated values: accepted {find('seeds').accepted}")
    settings = _settings(sections)
    base = {k: v for s in ("surface", "substrate", "interaction") for k, v in sections[s].items()}
    axes = {k: v for k, v in base.items() if isinstance(v, list)}
    for i, case in enumerate(cases):
        clash = sorted(set(case) & set(axes))
        if clash:
            _fail(
                f"[[cases]] #{i + 1} sets {clash[0]!r}, which is already a grid axis "
                f"({clash[0]} = {axes[clash[0]]!r}); give it in one place only"
            )
    count = len(cases) * len(seeds) * math.prod(len(v) for v in axes.values())
    if count > MAX_TASKS:
        sizes = " x ".join(f"{len(v)} {k}" for k, v in {**axes, "seeds": seeds}.items())
        _fail(
            f"{count} tasks ({sizes}, {len(cases)} [[cases]]) are too many: accepted at "
            f"most {MAX_TASKS}; split the study"
        )
    combos = []
    for case in cases:
        for values in itertools.product(*axes.values()):
            varying = {**dict(zip(axes, values, strict=True)), **case}
            combos.append(({**base, **varying}, varying))
    tasks, width = [], max(5, len(str(len(combos) * len(seeds))))
    for combo, varying in combos:
        resolved = _resolve(combo, varying)
        _tensile_loads(settings["path"], resolved, varying)
        for seed in seeds:
            params = {**resolved, "seed": seed}
            key = _digest({"params": _keyed(params), "settings": settings})
            tasks.append(Task(f"{len(tasks):0{width}d}", params, settings, key))
    text = json.dumps(data, sort_keys=True) if text is None else text
    return StudySpec(
        name=sections["study"].get("name", default_name),
        description=sections["study"].get("description", ""),
        tasks=tuple(tasks),
        settings=settings,
        source=source,
        text=text,
        sha256=hashlib.sha256(text.encode("utf-8")).hexdigest(),
        axes={**axes, "seed": seeds},
    )


def _digest(obj) -> str:
    return hashlib.sha256(json.dumps(obj, sort_keys=True).encode()).hexdigest()


def _keyed(params) -> dict:
    """The parameters a task key hashes: a later key left at its default is dropped, so a
    study that does not use it keeps the keys it had (its directories still --resume)."""
    return {k: v for k, v in params.items() if not (k == "periodic" and v is True)}


def _settings(sections) -> dict:
    """Path, solver, analysis and output settings (shared by every task), with defaults."""
    out = {}
    for name in ("path", "solver", "analysis", "output"):
        given = sections[name]
        out[name] = {k: given.get(k, d.default) for k, d in SCHEMA[name].items()}
    path = out["path"]
    ranged = [k for k in ("start", "stop") if path[k] is not None]
    if (path["values"] is not None) == (len(ranged) == 2):
        _fail("[path] needs either values = [...] or start and stop (with step or num)")
    if path["values"] is None and (path["step"] is None) == (path["num"] is None):
        _fail("[path] with start/stop needs exactly one of step or num")
    if path["values"] is not None and any(path[k] is not None for k in ("start", "step", "num")):
        _fail("[path] give either values or start/stop/step, not both")
    if path["spacing"] == "geometric" and (
        path["num"] is None or path["start"] * path["stop"] <= 0
    ):
        _fail(
            f"[path] spacing = 'geometric' needs num and start, stop of the same sign "
            f"(start = {path['start']!r}, stop = {path['stop']!r})"
        )
    units = UNITS[path["control"]]
    path["unit"] = units[0] if path["unit"] is None else path["unit"]
    if path["unit"] not in units:
        _fail(
            f"[path] unit = {path['unit']!r} is out of range for control = "
            f"{path['control']!r}: accepted {', '.join(map(repr, units))}"
        )
    path["lead_in"] = list(path["lead_in"])
    if path["lead_in"] and path["control"] != "offset":
        _fail(f"[path] lead_in = {path['lead_in']!r} applies to control = 'offset' only")
    if path["unit"] == "bearing_area":
        given = path["values"] or [path["start"], path["stop"]]
        if not all(0 <= v <= 1 for v in given):
            _fail(
                f"[path] values {given!r} are out of range for unit = 'bearing_area': "
                "accepted fractions in [0, 1]"
            )
    out["output"]["fields"] = list(out["output"]["fields"])
    out["output"]["fields_at"] = list(out["output"]["fields_at"])
    steps = path_steps(path)  # its own message ([path]): outside the try below
    try:  # the range approach_retract checks, known here: before any work
        step_indices("fields_at", out["output"]["fields_at"], steps)
    except ParameterError as err:
        _fail(f"[output] {_inner(err)}")
    # settings enter every task's key: a study that does not use this later key keeps
    # the keys it had, so its directories written before it existed still --resume
    areas = list(out["output"].pop("fields_at_area"))
    if areas:
        out["output"]["fields_at_area"] = areas
    for key, default in (("allow_unconverged", False), ("hard_wall_reference", True)):
        if out["analysis"][key] is default:  # the default: keys as before (see above)
            del out["analysis"][key]
    solver = out["solver"]
    if solver["dtype"] == "float32" and solver["tol"] < DEFAULT_TOL["float32"]:
        _fail(
            f"[solver] tol = {solver['tol']!r} is out of range for dtype = 'float32': "
            f"accepted >= {DEFAULT_TOL['float32']:g} (its rounding floor)"
        )
    if solver["dtype"] == "float32" and solver["tol"] > MAX_TOL_FLOAT32:
        _fail(
            f"[solver] tol = {solver['tol']!r} is out of range for dtype = 'float32': "
            f"accepted <= {MAX_TOL_FLOAT32:g} (a looser single-precision solve means nothing)"
        )
    if solver["dtype"] == "float64":
        del solver["dtype"]  # the default: keys as before the key existed (see above)
    return out


def approach_steps(path: dict) -> int:
    """Steps of the approach of validated ``[path]`` settings (lead-in included)."""
    if path["values"] is not None:
        n = len(path["values"])
    elif path["num"] is not None:
        n = path["num"]
    else:  # as task.path_values counts them
        span = abs(path["stop"] - path["start"]) / abs(path["step"])
        if not span < MAX_PATH_STEPS:
            _fail(
                f"[path] start = {path['start']!r}, stop = {path['stop']!r}, step = "
                f"{path['step']!r} gives more than {MAX_PATH_STEPS} steps: accepted at most "
                f"{MAX_PATH_STEPS}; use a larger step"
            )
        n = int(math.floor(span + 1e-9)) + 1
    lead = len(path["lead_in"]) if path["control"] == "offset" else 0
    if n + lead > MAX_PATH_STEPS:
        given = f"{n} values" + (f" and {lead} lead_in steps" if lead else "")
        _fail(
            f"[path] {given} give {n + lead} steps: accepted at most {MAX_PATH_STEPS} "
            "(approach, lead-in included)"
        )
    return n + lead


def path_steps(path: dict) -> int:
    """Steps of the whole path of validated ``[path]`` settings (retraction included)."""
    n = approach_steps(path)
    return n + (n - 1 if path["retract"] and n > 1 else 0)


def _tensile_loads(path: dict, params: dict, varying: dict) -> None:
    """A non-adhesive law carries no tensile (negative) load: fail before any work."""
    if path["control"] != "load" or make_interaction(params).adhesive:
        return
    given = path["values"] if path["values"] is not None else [path["start"], path["stop"]]
    if min(given) < 0:
        where = ", ".join(f"{k}={v!r}" for k, v in varying.items()) or "every task"
        _fail(
            f"[path] loads down to {min(given)!r} are out of range for law = "
            f"{params['law']!r} ({where}): a non-adhesive law cannot carry a tensile "
            "load; accepted loads >= 0, or an adhesive law"
        )


def _resolve(combo, varying) -> dict:
    """Fill defaults, check the cross-parameter ranges, derive the interaction's values."""
    p = {k: combo.get(k, find(k).default) for k in SWEEP_KEYS}
    where = "in the parameter set " + ", ".join(f"{k}={v!r}" for k, v in varying.items())
    where = where if varying else "for every task"
    for key in ("size", "hurst", "short_cutoff"):
        if p[key] is None:
            _fail(f"[surface] {key} is missing: accepted {find(key).accepted}")
    if (p["rms_slope"] is None) == (p["rms_height"] is None):
        _fail(f"[surface] give exactly one of rms_slope, rms_height ({where})")
    a0, size = p["pixel_size"], p["size"] * p["pixel_size"]
    if p["rms_height"] is not None and not 1e-8 <= p["rms_height"] / a0 <= 1e8:
        _fail(
            f"[surface] rms_height = {p['rms_height']!r} is out of range: accepted in "
            f"[1e-8, 1e8] * pixel_size = [{1e-8 * a0:g}, {1e8 * a0:g}] ({where})"
        )
    if p["thickness"] is not None:  # relative to a0: the range Substrate checks
        try:
            layer_thickness("thickness", p["thickness"], a0)
        except ParameterError as err:
            _fail(f"[substrate] {_inner(err)} ({where})")
        if p["periodic"] is False:
            _fail(f"[substrate] periodic = false needs a half-space (no thickness) ({where})")
    if p["short_cutoff"] < 2 * a0:
        _fail(
            f"[surface] short_cutoff = {p['short_cutoff']!r} is out of range: accepted >= "
            f"2 * pixel_size = {2 * a0} ({where})"
        )
    default = p["long_cutoff"] is None
    if default:
        p["long_cutoff"] = size / 2
    if not p["short_cutoff"] < p["long_cutoff"] <= size:
        _fail(
            f"[surface] long_cutoff = {p['long_cutoff']!r}"
            + (" (the default size * pixel_size / 2)" if default else "")
            + f" is out of range: accepted in (short_cutoff, size * pixel_size] = "
            f"({p['short_cutoff']}, {size}] ({where})"
        )
    p["law_inputs"] = {k: p[k] for k in LAW_KEYS if p[k] is not None}
    try:
        law = make_interaction(p)
    except ParameterError as err:
        _fail(f"[interaction] {_inner(err)} ({where})")
    values = law_parameters(law)
    for key in ("work_of_adhesion", "range", "stiffness"):
        p[key] = values.get(key, p[key])
    if p["work_of_adhesion"] is not None:
        p["adhesion_length"] = p["work_of_adhesion"] / p["contact_modulus"]
    return p
