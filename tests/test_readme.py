"""Every example in README.md runs.

The README is split into fenced code blocks, each with its language and the ``##`` section
(and ``###`` subsection) it sits under, and every example becomes one test, in README order:

* ``python`` blocks are executed in ONE namespace per ``##`` section (later blocks use the
  names of earlier ones), with the working directory a fresh per-section temporary
  directory holding a copy of the repository's ``studies/``.  The code is compiled under
  the README's own file name and line numbers, so a traceback points at the README line.
* ``bash`` blocks: every non-empty, non-comment line is one command (``\\`` continues a
  line), run with ``bash`` in the same per-section directory, the virtualenv's ``bin``
  first on ``PATH``; the exit code must be 0.  ``pip install ...`` segments of a
  ``a && b`` command are dropped (the package is installed already) and so are ``pytest``
  segments (the suite does not run itself; ``test_setup_commands`` checks that line).
* ``toml`` blocks are parsed; one with a ``[study]`` table is validated as a study.

State is kept per section and examples are run lazily in order, so running one test alone
(``-k L123``) first runs the examples of its section that precede it.

Skipping is explicit and reported (``-ra``):

* an example that needs a GPU (``device="cuda"``, ``cupy``, ``--device cuda``) is skipped
  only where CuPy with a CUDA device, or JAX's CUDA backend, is unavailable;
* a command with a ``tcp://HOST`` placeholder (a Dask scheduler address to fill in);
* a block whose first line is ``# not run by the tests: <reason>`` (the reason is
  required, and at most ``MAX_OPT_OUTS`` blocks may opt out).
"""

from __future__ import annotations

import functools
import importlib.util
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import tomllib
import traceback
from dataclasses import dataclass, field
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
CI_RUN = ROOT / ".ci" / "run"

COMMAND_TIMEOUT = 600  # seconds per README command
MAX_OPT_OUTS = 3  # blocks that may say "# not run by the tests: <reason>"
INSTALL_AND_RUN = "pip install . && roughcontact demo"
TEST_COMMAND = 'pip install -e ".[test]" && pytest'

LANGUAGES = {
    "python": "python",
    "py": "python",
    "python3": "python",
    "bash": "bash",
    "sh": "bash",
    "shell": "bash",
    "toml": "toml",
}
NOT_RUN_LANGUAGES = {"text", "json", "output", "console-output"}

OPT_OUT = re.compile(r"^\s*#\s*not\s+run\s+by\s+the\s+tests\b\s*:?\s*(?P<reason>.*?)\s*$", re.I)
NEEDS_GPU = re.compile(
    r"""device\s*=\s*["']cuda|--device[ =]+["']?cuda|\bcupy\b|to_device\([^)]*["']cuda""",
)
HOST_PLACEHOLDER = "tcp://HOST"


# --------------------------------------------------------------------------- parsing


@dataclass
class Block:
    lang: str  # normalised: python, bash, toml, or the raw info string
    info: str  # the fence's info string as written
    line: int  # README line of the opening fence (1-based)
    lines: list[str]  # the block's lines (without the fences)
    section: str  # the ## heading ("" before the first one)
    subsection: str  # the ### heading under it ("" if none)

    @property
    def first_code_line(self) -> int:
        return self.line + 1

    @property
    def text(self) -> str:
        return "\n".join(self.lines) + "\n"

    @property
    def where(self) -> str:
        out = f"## {self.section}" if self.section else "(before the first ## heading)"
        return out + (f" > ### {self.subsection}" if self.subsection else "")

    def opt_out(self) -> str | None:
        """The reason of a ``# not run by the tests: <reason>`` first line ('' if none given)."""
        for text in self.lines:
            if text.strip():
                match = OPT_OUT.match(text)
                return match.group("reason") if match else None
        return None


@dataclass
class Example:
    kind: str  # python | bash | toml
    line: int  # README line of the example (python/toml: the fence; bash: the command)
    block: Block
    source: str  # python/toml: the block; bash: the command with its comment stripped

    @property
    def section(self) -> str:
        return self.block.section

    @property
    def id(self) -> str:
        return f"L{self.line}-{self.kind}-{slug(self.section) or 'top'}"


def slug(heading: str) -> str:
    """'Set-up (Python >= 3.11 ...)' -> 'Set-up'; 'Python tour' -> 'Python-tour'."""
    heading = re.sub(r"\(.*?\)", "", heading)
    return re.sub(r"[^0-9A-Za-z.]+", "-", heading).strip("-")


FENCE = re.compile(r"^(?P<indent> {0,3})(?P<fence>`{3,}|~{3,})\s*(?P<info>[^`]*?)\s*$")
HEADING = re.compile(r"^ {0,3}(?P<level>#{1,6})\s+(?P<title>.*?)\s*#*\s*$")


def parse_blocks(text: str) -> list[Block]:
    """Fenced code blocks of a Markdown text with their language and headings."""
    blocks, section, subsection = [], "", ""
    open_fence = None  # (fence string, info, line, lines)
    for number, raw in enumerate(text.splitlines(), start=1):
        if open_fence is not None:
            fence, info, start, lines = open_fence
            match = FENCE.match(raw)
            if (
                match
                and not match.group("info")
                and match.group("fence")[0] == fence[0]
                and len(match.group("fence")) >= len(fence)
            ):
                lang = info.split()[0].lower() if info else ""
                blocks.append(
                    Block(LANGUAGES.get(lang, lang), info, start, lines, section, subsection)
                )
                open_fence = None
            else:
                lines.append(raw)
            continue
        match = FENCE.match(raw)
        if match:
            open_fence = (match.group("fence"), match.group("info"), number, [])
            continue
        heading = HEADING.match(raw)
        if heading:
            level = len(heading.group("level"))
            if level == 2:
                section, subsection = heading.group("title"), ""
            elif level == 3:
                subsection = heading.group("title")
    if open_fence is not None:
        raise ValueError(f"README.md:{open_fence[2]}: code fence {open_fence[0]!r} never closed")
    return blocks


def _unquoted(text: str):
    """Indices of the characters of ``text`` outside shell quotes and backslash escapes."""
    quote, escaped = None, False
    for i, char in enumerate(text):
        if escaped:
            escaped = False
        elif char == "\\" and quote != "'":
            escaped = True
        elif quote:
            if char == quote:
                quote = None
        elif char in "'\"":
            quote = char
        else:
            yield i


def strip_comment(line: str) -> str:
    """Drop a trailing shell comment: '#' at the start or after whitespace, outside quotes."""
    for i in _unquoted(line):
        if line[i] == "#" and (i == 0 or line[i - 1].isspace()):
            return line[:i].rstrip()
    return line.rstrip()


def split_and(command: str) -> list[str]:
    """Split a command at '&&' outside quotes."""
    parts, start = [], 0
    for i in _unquoted(command):
        if i >= start and command.startswith("&&", i):
            parts.append(command[start:i].strip())
            start = i + 2
    parts.append(command[start:].strip())
    return parts


def bash_commands(block: Block) -> list[tuple[int, str]]:
    """(README line, command) for every non-empty, non-comment line; '\\' continues."""
    out, pending, pending_line = [], "", 0
    for offset, raw in enumerate(block.lines):
        number = block.first_code_line + offset
        command = strip_comment(raw)
        if not command.strip():
            if pending:
                out.append((pending_line, pending.strip()))
                pending = ""
            continue
        if not pending:
            pending_line = number
        if command.endswith("\\") and not command.endswith("\\\\"):
            pending += command[:-1] + " "
            continue
        out.append((pending_line, (pending + command).strip()))
        pending = ""
    if pending:
        out.append((pending_line, pending.strip()))
    return out


def examples_of(blocks: list[Block]) -> list[Example]:
    out = []
    for block in blocks:
        if block.lang in ("python", "toml"):
            out.append(Example(block.lang, block.line, block, block.text))
        elif block.lang == "bash":
            commands = bash_commands(block)
            if not commands:  # only comments: keep the block visible (and its opt-out)
                out.append(Example("bash", block.line, block, ""))
            out.extend(Example("bash", line, block, command) for line, command in commands)
    return out


BLOCKS = parse_blocks(README.read_text(encoding="utf-8"))
EXAMPLES = examples_of(BLOCKS)


def _is_demo(example: Example) -> bool:
    return example.kind == "bash" and any(
        part.split()[:2] == ["roughcontact", "demo"] for part in split_and(example.source)
    )


SLOW_SECTIONS = {example.section for example in EXAMPLES if _is_demo(example)}


# --------------------------------------------------------------------------- environment


@functools.cache
def gpu_available() -> bool:
    """CuPy is importable and sees at least one CUDA device, and JAX has a CUDA backend
    (``device="cuda"`` runs the compiled JAX loops there)."""
    if importlib.util.find_spec("cupy") is None or importlib.util.find_spec("jax") is None:
        return False
    try:
        import cupy
        import jax

        return cupy.cuda.runtime.getDeviceCount() > 0 and bool(jax.devices("gpu"))
    except Exception:  # no driver, no device, no CUDA backend in JAX, broken install
        return False


def command_env() -> dict[str, str]:
    env = dict(os.environ)
    bin_dir = str(Path(sys.executable).parent)  # the venv's bin (not resolved: a symlink)
    env["PATH"] = os.pathsep.join([bin_dir, env.get("PATH", "")])
    env.setdefault("MPLBACKEND", "Agg")
    return env


def tail(text: str, lines: int = 40, chars: int = 4000) -> str:
    text = "\n".join((text or "").rstrip().splitlines()[-lines:])
    return text[-chars:] if len(text) > chars else text


# --------------------------------------------------------------------------- running


@dataclass
class Outcome:
    status: str  # passed | failed | skipped
    message: str = ""
    seconds: float = 0.0


@dataclass
class SectionRun:
    """The examples of one ## section, run in order in one directory and one namespace."""

    section: str
    examples: list[Example]
    directory: Path
    namespace: dict = field(default_factory=lambda: {"__name__": "__main__"})
    outcomes: list[Outcome] = field(default_factory=list)

    def outcome(self, example: Example) -> Outcome:
        index = self.examples.index(example)
        while len(self.outcomes) <= index:
            current = self.examples[len(self.outcomes)]
            start = time.perf_counter()
            result = self._run(current)
            result.seconds = time.perf_counter() - start
            self.outcomes.append(result)
        result = self.outcomes[index]
        earlier = [  # failed, or skipped and of the same kind (names, files it would make)
            f"L{e.line} ({o.status})"
            for e, o in zip(self.examples[:index], self.outcomes[:index], strict=True)
            if o.status == "failed" or (o.status == "skipped" and e.kind == example.kind)
        ]
        if result.status == "failed" and earlier:
            result = Outcome(
                "failed",
                result.message + "\n(earlier examples of this section did not pass: "
                f"{', '.join(earlier)}; this failure may follow from them)",
                result.seconds,
            )
        return result

    # -- skipping

    def _skip_reason(self, example: Example) -> str | None:
        reason = example.block.opt_out()
        if reason is not None:
            if not reason:
                return "FAIL"
            return f"README.md:{example.block.line}: not run by the tests: {reason}"
        if NEEDS_GPU.search(example.source) and not gpu_available():
            return (
                f"README.md:{example.line}: needs CuPy, JAX with CUDA and a CUDA GPU "
                "(device='cuda' / cupy / --device cuda), not available here"
            )
        if HOST_PLACEHOLDER in example.source:
            return (
                f"README.md:{example.line}: needs a running Dask scheduler "
                f"({HOST_PLACEHOLDER} is a placeholder address)"
            )
        return None

    def _run(self, example: Example) -> Outcome:
        reason = self._skip_reason(example)
        if reason == "FAIL":
            return Outcome(
                "failed",
                f"README.md:{example.block.line} ({example.block.lang} block in "
                f"{example.block.where}) opts out with '# not run by the tests:' but gives "
                "no reason: write '# not run by the tests: <reason>'",
            )
        if reason is not None:
            return Outcome("skipped", reason)
        return getattr(self, f"_run_{example.kind}")(example)

    # -- the three kinds

    def _run_python(self, example: Example) -> Outcome:
        block = example.block
        # Pad so that line numbers in the code object are README line numbers.
        source = "\n" * (block.first_code_line - 1) + block.text
        try:
            code = compile(source, str(README), "exec")
            exec(code, self.namespace)
        except (Exception, SystemExit) as err:
            frames = traceback.extract_tb(err.__traceback__)
            frames = [f for f in frames if f.filename == str(README)]
            line = frames[-1].lineno if frames else getattr(err, "lineno", None) or block.line
            text = README.read_text(encoding="utf-8").splitlines()
            code_line = text[line - 1].strip() if 0 < line <= len(text) else ""
            formatted = "".join(traceback.format_exception(err))
            return Outcome(
                "failed",
                f"README.md:{line}: python block at L{block.line} ({block.where}) failed\n"
                f"    {code_line}\n{type(err).__name__}: {err}\n\n{tail(formatted, 30)}",
            )
        return Outcome("passed")

    def _run_bash(self, example: Example) -> Outcome:
        if not example.source:
            return Outcome("skipped", f"README.md:{example.line}: bash block with no command")
        kept, dropped = [], []
        for part in split_and(example.source):
            words = part.split()
            if words[:2] == ["pip", "install"] or words[:3] == ["python", "-m", "pip"]:
                dropped.append(f"{part!r} (the package is installed in the test environment)")
            elif words[:1] == ["pytest"] or words[:3] == ["python", "-m", "pytest"]:
                dropped.append(f"{part!r} (the suite does not run itself; see test_setup_commands)")
            else:
                kept.append(part)
        if not kept:
            return Outcome(
                "skipped", f"README.md:{example.line}: nothing to run: {'; '.join(dropped)}"
            )
        command = " && ".join(kept)
        bash = shutil.which("bash")
        process = subprocess.Popen(
            ("set -o pipefail\n" if bash else "") + command,
            shell=True,
            executable=bash,
            cwd=self.directory,
            env=command_env(),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,  # so that a timeout ends the whole process group
        )
        start = time.perf_counter()
        try:
            stdout, stderr = process.communicate(timeout=COMMAND_TIMEOUT)
            code = process.returncode
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            stdout, stderr = process.communicate()
            code = f"timeout after {COMMAND_TIMEOUT} s"
        seconds = time.perf_counter() - start
        if code == 0:
            return Outcome("passed")
        ran = f"\n    ran: {command}" if command != example.source else ""
        return Outcome(
            "failed",
            f"README.md:{example.line} ({example.block.where}): command failed with exit code "
            f"{code} after {seconds:.1f} s\n    $ {example.source}{ran}\n"
            f"(in {self.directory})\n--- stdout (tail) ---\n{tail(stdout)}\n"
            f"--- stderr (tail) ---\n{tail(stderr)}",
        )

    def _run_toml(self, example: Example) -> Outcome:
        where = f"README.md:{example.line}: toml block ({example.block.where})"
        try:
            data = tomllib.loads(example.source)
        except tomllib.TOMLDecodeError as err:
            return Outcome("failed", f"{where} is not valid TOML: {err}")
        if "study" in data:
            from roughcontact.studies import study_from_dict

            try:
                spec = study_from_dict(data, source="README")
            except Exception as err:
                return Outcome("failed", f"{where} is not a valid study: {err}")
            if not spec.tasks:
                return Outcome("failed", f"{where}: the study has no tasks")
        return Outcome("passed")


@pytest.fixture(scope="module")
def section_runs(tmp_path_factory):
    """One SectionRun per ## section (created on first use)."""
    runs: dict[str, SectionRun] = {}

    def get(section: str) -> SectionRun:
        if section not in runs:
            directory = tmp_path_factory.mktemp(f"readme-{slug(section)[:30] or 'top'}")
            if (ROOT / "studies").is_dir():  # the README's relative paths to study files
                shutil.copytree(ROOT / "studies", directory / "studies")
            for part in ("reproduction/reproduction.toml", "reproduction/data"):
                source = ROOT / part  # the committed reproduction (its report is rebuilt)
                if source.is_dir():
                    shutil.copytree(source, directory / part)
                elif source.is_file():
                    (directory / part).parent.mkdir(parents=True, exist_ok=True)
                    shutil.copy(source, directory / part)
            examples = [e for e in EXAMPLES if e.section == section]
            runs[section] = SectionRun(section, examples, directory)
        return runs[section]

    yield get
    durations = {}
    for run in runs.values():
        durations[run.section] = sum(o.seconds for o in run.outcomes)
    if durations:
        print("\nREADME examples, seconds per section:")
        for section, seconds in durations.items():
            print(f"  {seconds:8.1f}  ## {section}")


PARAMS = [
    pytest.param(
        example,
        id=example.id,
        marks=[pytest.mark.slow] if example.section in SLOW_SECTIONS else [],
    )
    for example in EXAMPLES
]


@pytest.mark.parametrize("example", PARAMS)
def test_readme_example(example, section_runs, monkeypatch):
    run = section_runs(example.section)
    monkeypatch.chdir(run.directory)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    result = run.outcome(example)
    if result.status == "skipped":
        pytest.skip(result.message)
    if result.status == "failed":
        pytest.fail(result.message, pytrace=False)


# --------------------------------------------------------------------------- README checks


def test_readme_has_examples():
    kinds = {example.kind for example in EXAMPLES}
    assert {"python", "bash", "toml"} <= kinds, f"README examples found: {sorted(kinds)}"


def test_every_block_has_a_known_language():
    unknown = [
        f"README.md:{b.line}: ```{b.info}"
        for b in BLOCKS
        if b.lang not in ("python", "bash", "toml") and b.lang not in NOT_RUN_LANGUAGES
    ]
    assert not unknown, (
        "code blocks the tests neither run nor know (tag them python, bash, toml or text):\n"
        + "\n".join(unknown)
    )


def test_opt_outs_are_few_and_give_a_reason():
    opted = [(b.line, b.opt_out()) for b in BLOCKS if b.opt_out() is not None]
    missing = [f"README.md:{line}" for line, reason in opted if not reason]
    assert not missing, f"'# not run by the tests:' without a reason at {', '.join(missing)}"
    assert len(opted) <= MAX_OPT_OUTS, (
        f"{len(opted)} README blocks opt out of the tests (at most {MAX_OPT_OUTS}): "
        + "; ".join(f"L{line}: {reason}" for line, reason in opted)
    )


def _commands(blocks) -> list[str]:
    return [command for b in blocks if b.lang == "bash" for _, command in bash_commands(b)]


def test_setup_commands():
    """The Set-up section installs and runs the main job, and installs and runs the tests;
    CI runs that same test command."""
    setup = [b for b in BLOCKS if b.section.lower().startswith("set-up")]
    assert setup, "README has no '## Set-up' section with code blocks"
    commands = _commands(setup)
    for expected in (INSTALL_AND_RUN, TEST_COMMAND):
        assert expected in commands, (
            f"the README's Set-up section lacks the command line {expected!r}; it has {commands}"
        )
    ci_lines = [strip_comment(line).strip() for line in CI_RUN.read_text().splitlines()]
    assert TEST_COMMAND in ci_lines, f"{CI_RUN} does not run the README's {TEST_COMMAND!r}"


# --------------------------------------------------------------------------- the harness itself


@pytest.mark.parametrize(
    ("line", "expected"),
    [
        ("roughcontact demo", "roughcontact demo"),
        ("a --json          # mean pressure", "a --json"),
        ('c --work-of-adhesion "50 mJ/m^2" --json', 'c --work-of-adhesion "50 mJ/m^2" --json'),
        ("echo '# not a comment' # a comment", "echo '# not a comment'"),
        ("echo a#b", "echo a#b"),
        ('echo "x \\" # y" # z', 'echo "x \\" # y"'),
        ("# only a comment", ""),
    ],
)
def test_strip_comment(line, expected):
    assert strip_comment(line) == expected


def test_split_and_and_headings():
    assert split_and('pip install -e ".[test]" && pytest') == ['pip install -e ".[test]"', "pytest"]
    assert split_and("echo '&&' && true") == ["echo '&&'", "true"]
    text = "# T\n## A (x)\n```python\nx = 1\n# y\n```\n### B\n```bash\na \\\n  b # c\n\nd\n```\n"
    blocks = parse_blocks(text)
    assert [(b.lang, b.line, b.section, b.subsection) for b in blocks] == [
        ("python", 3, "A (x)", ""),
        ("bash", 8, "A (x)", "B"),
    ]
    assert bash_commands(blocks[1]) == [(9, "a    b"), (12, "d")]
    assert examples_of(blocks)[0].id == "L3-python-A"
