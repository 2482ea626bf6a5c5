"""The README and docs/*.md cannot go stale: every fenced ``sh``/``bash``/``console``,
``python`` and ``rust`` snippet is run by this test, or says why it is not; and every number
a page quotes from an output is checked against that output.

How a snippet is run:

- ``sh``/``bash``: the block as one shell script (``set -eu``), in a temporary directory,
  with the ``stickslip`` built here first on the ``PATH``; it must exit with status 0.
- ``console``: each ``$ command`` line is run as above, and the lines after it, up to the
  next ``$`` line, are what it must print on standard output, token by token, each number to
  the last digit shown (a line ``...`` stands for any lines).
- ``python``: the block in this Python (the installed package), in a temporary directory;
  the blocks of one page run in order, each in a namespace of its own.
- ``rust``: an excerpt of an example program (``excerpt of:`` below), which cargo compiles
  (``cargo test``, ``cargo clippy --all-targets``): every line of the snippet must be in the
  example, in order (whitespace aside).

What may stand in an HTML comment right before the fence (blank lines between are fine):

- ``<!-- not run: REASON -->``: not run, and why (an install, a server that runs until it is
  stopped, a run of minutes that a test runs in another form).
- ``<!-- tested by: PATH -->``: run by another test, which must exist and name the page.
- ``<!-- excerpt of: PATH -->``: a ``rust`` snippet from that example program.
- ``<!-- files: NAME=PATH NAME=PATH -->``: files of the repository copied into the
  temporary directory under those names before the snippet runs.
- ``<!-- lab: http://127.0.0.1:8080 -->``: the snippet asks the lab's server at that address:
  the test starts ``stickslip lab --port 0`` and runs the snippet against it.
- ``<!-- quick: OLD => NEW; OLD => NEW -->``: the test runs the snippet with these
  replacements (a long run made short); each OLD must be in the snippet, and the page says
  in words that the test runs it so.

Numbers quoted in the text are checked by a comment placed after them:

    <!-- check `stickslip lyapunov --zeta 0 --mu-s 3 --w 0.33 --beta 9 --json`:
    lambda1 == 0.014504
    periods == 620 -->

Each line ``EXPRESSION == QUOTED`` (or ``assert CONDITION``, for a fact that is not a
number) evaluates the Python expression over the output and
compares it with QUOTED, which must be written, character for character, in the page's
text since the previous check or heading (so the check and the prose cannot part): a number
must round to it at the digits shown (a typographic minus, thin spaces between digit groups
and ``·10⁻³`` are read as numbers), anything else must equal it as text. The source is:

- a command in backticks: ``stickslip ...`` (run as a snippet line, in a directory where
  ``examples/`` is the repository's; the names are ``out``,
  ``err``, ``status``, ``json`` when the output is JSON, and its top-level keys;
  ``rows(FILE)``, ``col(FILE, COLUMN, where)`` and ``read_json(FILE)`` read the files it wrote),
  or ``cargo run --release -p
  CRATE --example NAME [-- ARGS]`` (the example built by ``cargo test``);
- none (``<!-- check: ... -->``): the namespace of the page's last ``python`` snippet (or
  a fresh one with ``stickslip``, ``Experiment`` and ``np``), with ``printed`` (what the
  snippet printed) and ``error(function)`` (the message of the exception it raises).

A new snippet with neither a way to run nor a reason fails this test, and so does a check
whose quoted text is not on the page.
"""

from __future__ import annotations

import contextlib
import csv as csv_module
import io
import json as json_module
import math
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Tuple

import numpy as np
import pytest

import stickslip
from conftest import CLI, ROOT, TARGET

PAGES = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))
#: The fences that must be run or say why not.
RUN_KINDS = {"sh", "bash", "console", "python", "rust"}
#: The longest a snippet may take (a snippet that takes longer is a long run: make it quick).
TIMEOUT = 300
#: The keys of a comment before a fence.
BLOCK_KEYS = ("not run", "tested by", "excerpt of", "files", "quick", "lab")


@dataclass
class Block:
    """A fenced snippet, with the comments right before it."""

    page: pathlib.Path
    line: int
    kind: str
    text: str
    notes: Dict[str, str] = field(default_factory=dict)

    @property
    def where(self) -> str:
        return f"{shown(self.page)}:{self.line}"


@dataclass
class Check:
    """A check comment: its source (a command, or None for the page's Python), its
    assertions and the page's text it vouches for."""

    page: pathlib.Path
    line: int
    source: Optional[str]
    assertions: List[Tuple[int, str, str]]
    scope: str
    after: int  # index of the last snippet before it on the page (-1: none)

    @property
    def where(self) -> str:
        return f"{shown(self.page)}:{self.line}"


COMMENT = re.compile(r"<!--(.*?)-->", re.S)


def shown(page: pathlib.Path) -> str:
    """A page's path as messages give it (from the repository's root)."""
    try:
        return str(page.relative_to(ROOT))
    except ValueError:
        return str(page)


def squeezed(text: str) -> str:
    """Text with every run of white space one space: a quote may wrap across lines."""
    return " ".join(text.split())


def parse(page: pathlib.Path) -> Tuple[List[Block], List[Check]]:
    """The page's snippets and checks, in order."""
    lines = page.read_text().splitlines()
    blocks: List[Block] = []
    checks: List[Check] = []
    pending: Dict[str, str] = {}
    scope: List[str] = []
    # After a check, the next text starts a new scope; checks in a row share one.
    fresh = False
    k = 0
    while k < len(lines):
        line = lines[k]
        fence = re.match(r"^\s*(```+|~~~+)\s*([\w+-]*)", line)
        if fence:
            marker, kind = fence.group(1), fence.group(2).lower()
            end = k + 1
            while end < len(lines) and not lines[end].strip().startswith(marker):
                end += 1
            text = "\n".join(lines[k + 1:end]) + "\n"
            blocks.append(Block(page, k + 1, kind, text, pending))
            pending = {}
            if fresh:
                scope, fresh = [], False
            scope.extend(lines[k:end + 1])
            k = end + 1
            continue
        if line.lstrip().startswith("<!--"):
            start = k
            text = line
            while "-->" not in text and k + 1 < len(lines):
                k += 1
                text += "\n" + lines[k]
            body = COMMENT.search(text)
            assert body, f"{shown(page)}:{start + 1}: an unclosed comment"
            content = body.group(1).strip()
            check = re.match(r"^check\s*(`([^`]*)`)?\s*:?\s*(.*)$", content, re.S)
            if check:
                assertions = []
                for offset, raw in enumerate(check.group(3).split("\n")):
                    raw = raw.strip()
                    if not raw:
                        continue
                    if raw.startswith("assert "):
                        assertions.append((start + 1 + offset, raw[len("assert "):], ""))
                        continue
                    assert " == " in raw, (
                        f"{shown(page)}:{start + 1}: a check line is "
                        f"'EXPRESSION == QUOTED', got {raw!r}")
                    expression, quoted = raw.rsplit(" == ", 1)
                    assertions.append((start + 1 + offset, expression.strip(), quoted.strip()))
                checks.append(Check(page, start + 1, check.group(2), assertions,
                                    "\n".join(scope), len(blocks) - 1))
                fresh = True
            else:
                key, _, value = content.partition(":")
                if key.strip() in BLOCK_KEYS:
                    pending[key.strip()] = value.strip()
            k += 1
            continue
        if line.startswith("#"):
            scope, fresh = [], False
        elif line.strip() and fresh:
            scope, fresh = [], False
        if line.strip() and pending and not line.lstrip().startswith("<!--"):
            raise AssertionError(f"{shown(page)}:{k + 1}: the comment "
                                 f"{pending} is not right before a fenced snippet")
        scope.append(COMMENT.sub("", line))
        k += 1
    return blocks, checks


# ---------------------------------------------------------------------------------------
# Numbers as the pages write them.

SUPERSCRIPTS = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺", "0123456789-+")


def as_number(text: str) -> Optional[Tuple[float, float]]:
    """A quoted number and one unit of its last digit ('1.45e-4' → (1.45e-4, 1e-6)); None
    for text that is not a number."""
    t = text.replace("−", "-").replace("\u2009", "").replace("\u202f", "").replace(" ", "")
    t = re.sub(r"[·×]10([⁰¹²³⁴⁵⁶⁷⁸⁹⁻⁺]+)$", lambda m: "e" + m.group(1).translate(SUPERSCRIPTS), t)
    match = re.fullmatch(r"([+-]?)(\d+)(?:\.(\d*))?(?:[eE]([+-]?\d+))?", t)
    if not match:
        return None
    sign, whole, decimals, exponent = match.groups()
    value = float(t.lstrip("+"))
    unit = 10.0 ** (int(exponent or 0) - len(decimals or ""))
    return value, unit


def agrees(value: Any, quoted: str) -> bool:
    """Whether ``value`` is what the page quotes: a number that rounds to it at the digits
    shown, or the same text."""
    number = as_number(quoted)
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value.item()
    if number is not None and isinstance(value, (int, float, np.integer, np.floating)) \
            and not isinstance(value, bool):
        shown, unit = number
        v = float(value)
        return math.isfinite(v) and abs(v - shown) <= 0.5 * unit * (1 + 1e-9) + 1e-12 * abs(v)
    return str(value).strip() == quoted


def same_token(want: str, got: str) -> bool:
    """A token of a console block against the printed one: the same text, or the same
    punctuation around a number that the printed one rounds to."""
    if want == got:
        return True
    pattern = re.compile(r"^(.*?)([+-]?\d[\d.]*(?:[eE][+-]?\d+)?)(.*?)$")
    w, g = pattern.match(want), pattern.match(got)
    if not w or not g or w.group(1) != g.group(1) or w.group(3) != g.group(3):
        return False
    return agrees(float(g.group(2)), w.group(2))


# ---------------------------------------------------------------------------------------
# Running.

def bin_dir(tmp: pathlib.Path) -> pathlib.Path:
    """A directory holding ``stickslip`` (the binary built here), first on the PATH."""
    if not CLI.is_file():
        pytest.fail(f"the stickslip binary is missing at {CLI}: build it with "
                    "`cargo build --release -p stickslip-cli` (scripts/test does)")
    target = tmp / "bin"
    target.mkdir(exist_ok=True)
    link = target / "stickslip"
    if not link.exists():
        link.symlink_to(CLI)
    return target


def shell(command: str, cwd: pathlib.Path) -> subprocess.CompletedProcess:
    environment = dict(os.environ)
    environment["PATH"] = f"{bin_dir(cwd.parent)}{os.pathsep}{environment['PATH']}"
    environment.pop("RUST_BACKTRACE", None)
    return subprocess.run(["bash", "-c", "set -eu -o pipefail\n" + command], cwd=cwd,
                          capture_output=True, text=True, env=environment, timeout=TIMEOUT)


def quick(block: Block) -> str:
    """The snippet as the test runs it (its ``quick:`` replacements made)."""
    text = block.text
    for rule in filter(None, (r.strip() for r in block.notes.get("quick", "").split(";"))):
        old, _, new = rule.partition("=>")
        old, new = old.strip(), new.strip()
        assert old in text, f"{block.where}: quick: {old!r} is not in the snippet"
        text = text.replace(old, new)
    return text


def prepare(block: Block, directory: pathlib.Path) -> None:
    """The snippet's ``files:`` in its directory."""
    for item in block.notes.get("files", "").split():
        name, _, source = item.partition("=")
        path = ROOT / source
        assert path.is_file(), f"{block.where}: files: {source} does not exist"
        shutil.copy(path, directory / name)


@contextlib.contextmanager
def lab_server(block: Block, directory: pathlib.Path):
    """The snippet as the test runs it; with ``lab:``, against a lab server of its own."""
    text = quick(block)
    address = block.notes.get("lab")
    if not address:
        yield text
        return
    assert address in text, f"{block.where}: lab: {address} is not in the snippet"
    server = subprocess.Popen([str(bin_dir(directory.parent) / "stickslip"), "lab", "--port",
                               "0"], cwd=directory, stdout=subprocess.PIPE,
                              stderr=subprocess.DEVNULL, text=True)
    try:
        assert server.stdout is not None
        found = re.search(r"(http://127\.0\.0\.1:\d+)", server.stdout.readline())
        assert found, f"{block.where}: the lab did not say its address"
        yield text.replace(address, found.group(1))
    finally:
        server.terminate()
        server.wait(timeout=30)
        if server.stdout is not None:
            server.stdout.close()


def run_console(block: Block, directory: pathlib.Path) -> List[str]:
    """Each ``$`` line of a console block run, and its output compared with the block's."""
    problems = []
    steps: List[Tuple[str, List[str]]] = []
    for line in quick(block).splitlines():
        if line.startswith("$ "):
            steps.append((line[2:], []))
        elif steps:
            steps[-1][1].append(line)
    for command, want in steps:
        done = shell(command, directory)
        if done.returncode != 0:
            problems.append(f"{block.where}: `{command}` failed ({done.returncode}): {done.stderr}")
            continue
        got = done.stdout.splitlines()
        if want and want[0] == "...":
            want = want[1:]
            got = got[len(got) - len(want):] if len(got) >= len(want) else got
        if len(want) != len(got) or not all(
                len(w.split()) == len(g.split()) and
                all(same_token(a, b) for a, b in zip(w.split(), g.split()))
                for w, g in zip(want, got)):
            problems.append(f"{block.where}: `{command}` prints\n" + "\n".join(got) +
                            "\n  the page shows\n" + "\n".join(want))
    return problems


def excerpt(block: Block) -> List[str]:
    """A rust snippet is in its example, line by line in order (whitespace aside)."""
    source = block.notes.get("excerpt of", "")
    path = ROOT / source
    if not source or not path.is_file():
        return [f"{block.where}: excerpt of: {source!r} is not a file of the repository"]
    if "/examples/" not in source or not source.endswith(".rs"):
        return [f"{block.where}: excerpt of: {source} is not an example program (cargo "
                "compiles crates/*/examples/*.rs)"]
    whole = re.sub(r"\s+", "", path.read_text())
    at = 0
    for line in block.text.splitlines():
        squeezed = re.sub(r"\s+", "", line)
        if not squeezed:
            continue
        found = whole.find(squeezed, at)
        if found < 0:
            return [f"{block.where}: the line {line.strip()!r} is not in {source} (after the "
                    "lines before it)"]
        at = found + len(squeezed)
    return []


def example_binary(command: str) -> Optional[List[str]]:
    """``cargo run --release -p CRATE --example NAME [-- ARGS]`` as the example's binary (built
    by ``cargo test --release``) and its arguments; None for another command."""
    words = command.split()
    if words[:2] != ["cargo", "run"] or "--example" not in words:
        return None
    name = words[words.index("--example") + 1]
    args = words[words.index("--") + 1:] if "--" in words else []
    binary = TARGET / "release" / "examples" / name
    if not binary.is_file():
        pytest.fail(f"the example {name} is missing at {binary}: `cargo test --release "
                    f"--workspace` builds it (scripts/test does)")
    return [str(binary), *args]


def value(text: str) -> Any:
    """A CSV cell: an int, a float, None (empty) or the text."""
    if text == "":
        return None
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def grab(pattern: str, text: str) -> float:
    """The number of the first group of ``pattern`` in ``text``."""
    found = re.search(pattern, text)
    assert found, f"{pattern!r} is not in the output"
    return float(found.group(1))


def rust_version() -> str:
    """The workspace's minimum Rust version (Cargo.toml's ``rust-version``)."""
    found = re.search(r'^rust-version\s*=\s*"([^"]+)"', (ROOT / "Cargo.toml").read_text(), re.M)
    assert found, "Cargo.toml has no rust-version"
    return found.group(1)


def extras() -> Dict[str, List[str]]:
    """The Python package's extras (crates/stickslip-py/pyproject.toml)."""
    text = (ROOT / "crates" / "stickslip-py" / "pyproject.toml").read_text()
    section = text.split("[project.optional-dependencies]", 1)[1].split("\n[", 1)[0]
    found: Dict[str, List[str]] = {}
    for name, body in re.findall(r"^(\w+)\s*=\s*\[(.*?)\]\s*$", section, re.M | re.S):
        found[name] = re.findall(r'"([^"]+)"', body)
    return found


#: What every check may use.
HELPERS: Dict[str, Any] = {"np": np, "re": re, "math": math, "grab": grab,
                           "rust_version": rust_version, "extras": extras,
                           "stickslip": stickslip, "Experiment": stickslip.Experiment}


class Outputs:
    """Commands of checks, each run once in the session, in a directory of its own."""

    def __init__(self, tmp: pathlib.Path) -> None:
        self.tmp = tmp
        self.done: Dict[str, Dict[str, Any]] = {}

    def __call__(self, command: str) -> Dict[str, Any]:
        if command not in self.done:
            directory = self.tmp / f"check{len(self.done)}"
            directory.mkdir()
            # The repository's examples (scope records, TOML files) by their paths.
            (directory / "examples").symlink_to(ROOT / "examples")
            started = time.perf_counter()
            binary = example_binary(command)
            if binary is not None:
                done = subprocess.run(binary, cwd=directory, capture_output=True, text=True,
                                      timeout=TIMEOUT)
            elif command.startswith("stickslip "):
                done = shell(command, directory)
            else:
                raise AssertionError(f"a check runs `stickslip ...` or `cargo run ... "
                                     f"--example NAME`, not `{command}`")
            names: Dict[str, Any] = {"out": done.stdout, "err": done.stderr,
                                     "status": done.returncode, "json": None,
                                     "seconds": time.perf_counter() - started}
            try:
                parsed = json_module.loads(done.stdout)
                names["json"] = parsed
                if isinstance(parsed, dict):
                    names.update({k: v for k, v in parsed.items() if k.isidentifier()})
            except ValueError:
                pass

            def rows(name: str) -> List[Dict[str, Any]]:
                """The rows of a CSV file the command wrote, numbers as numbers and empty
                cells as None."""
                with open(directory / name, newline="") as f:
                    return [{k: value(v) for k, v in row.items()}
                            for row in csv_module.DictReader(f)]

            def col(name: str, column: str,
                    where: Callable[[Dict[str, Any]], bool] = lambda r: True) -> List[Any]:
                """One column of ``rows(name)``, of the rows ``where`` keeps."""
                return [r[column] for r in rows(name) if where(r)]

            def read_json(name: str) -> Any:
                return json_module.loads((directory / name).read_text())

            names.update(rows=rows, col=col, read_json=read_json)
            self.done[command] = names
        return self.done[command]


def error(function: Callable[[], Any]) -> str:
    """The message of the exception ``function`` raises."""
    try:
        function()
    except Exception as e:  # noqa: BLE001 - any exception: its message is quoted
        return str(e)
    raise AssertionError("no exception was raised")


def fresh_namespace() -> Dict[str, Any]:
    return {"error": error, "__name__": "__doc_snippet__", **HELPERS}


def run_python(block: Block, directory: pathlib.Path) -> Tuple[Dict[str, Any], List[str]]:
    namespace = fresh_namespace()
    printed = io.StringIO()
    previous = os.getcwd()
    os.chdir(directory)
    try:
        with contextlib.redirect_stdout(printed):
            exec(compile(quick(block), block.where, "exec"), namespace)
    except Exception as e:  # noqa: BLE001 - reported with the snippet's place
        return namespace, [f"{block.where}: the snippet raised {type(e).__name__}: {e}"]
    finally:
        os.chdir(previous)
    namespace["printed"] = printed.getvalue()
    return namespace, []


# ---------------------------------------------------------------------------------------
# The test.

def every_block_is_run_or_says_why(blocks: List[Block]) -> List[str]:
    problems = []
    for b in blocks:
        if b.kind not in RUN_KINDS:
            continue
        notes = b.notes
        if "not run" in notes:
            if len(notes["not run"]) < 8:
                problems.append(f"{b.where}: 'not run:' needs a reason")
        elif "tested by" in notes:
            path = ROOT / notes["tested by"]
            name = str(shown(b.page))
            if not path.is_file() or name not in path.read_text():
                problems.append(f"{b.where}: tested by: {notes['tested by']} is not a file "
                                f"of the repository that names {name}")
        elif b.kind == "rust" and "excerpt of" not in notes:
            problems.append(f"{b.where}: a rust snippet is an excerpt of an example program "
                            "(<!-- excerpt of: crates/.../examples/NAME.rs -->), or says why "
                            "it is not run (<!-- not run: ... -->)")
    return problems


@pytest.fixture(scope="session")
def outputs(tmp_path_factory):
    return Outputs(tmp_path_factory.mktemp("checks"))


@pytest.mark.parametrize("page", PAGES, ids=[str(p.relative_to(ROOT)) for p in PAGES])
def test_every_snippet_runs_and_every_quoted_number_is_the_output(page, tmp_path, outputs):
    blocks, checks = parse(page)
    problems = every_block_is_run_or_says_why(blocks)
    namespaces: Dict[int, Dict[str, Any]] = {}
    last_python: Optional[int] = None
    python_before: Dict[int, Optional[int]] = {}
    for index, block in enumerate(blocks):
        if block.kind not in RUN_KINDS or {"not run", "tested by"} & set(block.notes):
            python_before[index] = last_python
            continue
        directory = tmp_path / f"snippet{index}"
        directory.mkdir()
        prepare(block, directory)
        if block.kind in ("sh", "bash"):
            with lab_server(block, directory) as text:
                done = shell(text, directory)
            if done.returncode != 0:
                problems.append(f"{block.where}: the snippet failed ({done.returncode}):\n"
                                f"{done.stderr[-2000:]}")
        elif block.kind == "console":
            problems.extend(run_console(block, directory))
        elif block.kind == "python":
            namespaces[index], found = run_python(block, directory)
            problems.extend(found)
            last_python = index
        elif block.kind == "rust":
            problems.extend(excerpt(block))
        python_before[index] = last_python
    for check in checks:
        if check.source is None:
            owner = python_before.get(check.after) if check.after >= 0 else None
            names = namespaces.get(owner, fresh_namespace()) if owner is not None \
                else fresh_namespace()
        else:
            names = dict(outputs(check.source))
        for name, helper in {**HELPERS, "error": error}.items():
            names.setdefault(name, helper)
        for line, expression, quoted in check.assertions:
            where = f"{shown(page)}:{line}"
            if not quoted:
                try:
                    holds = bool(eval(expression, names))  # noqa: S307 - the page's own check
                except Exception as e:  # noqa: BLE001 - reported with its place
                    problems.append(f"{where}: {expression}: {type(e).__name__}: {e}")
                    continue
                if not holds:
                    problems.append(f"{where}: the page's claim {expression} does not hold")
                continue
            if squeezed(quoted) not in squeezed(check.scope):
                problems.append(f"{where}: the check quotes {quoted!r}, which the page does not "
                                "write since the previous check or heading")
                continue
            try:
                value = eval(expression, names)  # noqa: S307 - the page's own check
            except Exception as e:  # noqa: BLE001 - reported with its place
                problems.append(f"{where}: {expression}: {type(e).__name__}: {e}")
                continue
            if not agrees(value, quoted):
                problems.append(f"{where}: the page says {quoted}, but {expression} is {value!r}"
                                + (f" (from `{check.source}`)" if check.source else ""))
    assert not problems, "\n".join(problems)


def test_the_harness_reads_numbers_as_the_pages_write_them():
    assert as_number("0.014504") == (0.014504, pytest.approx(1e-6))
    assert as_number("1.45e-4")[1] == pytest.approx(1e-6)
    assert as_number("−2.958e−5")[0] == pytest.approx(-2.958e-5)
    assert as_number("10 816") == (10816.0, 1.0)
    assert as_number("2.3·10⁻³")[0] == pytest.approx(2.3e-3)
    assert as_number("periodic-stick") is None
    assert agrees(0.0145044, "0.014504") and not agrees(0.0145046, "0.014504")
    assert agrees(620, "620") and not agrees(621, "620")
    assert agrees("chaotic", "chaotic") and not agrees(float("nan"), "0.1")
    assert same_token("8.281676e1", "8.2816758e1") and not same_token("(95", "95")


def test_a_snippet_without_a_way_to_run_fails(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("# A page\n\n```sh\npip install something\n```\n\n"
                    "<!-- not run: an install command -->\n```sh\npip install x\n```\n\n"
                    "```rust\nlet x = 1;\n```\n")
    blocks, _ = parse(page)
    problems = every_block_is_run_or_says_why(blocks)
    # The sh block without a reason is run (and would fail); the rust one is refused.
    assert [b.notes for b in blocks] == [{}, {"not run": "an install command"}, {}]
    assert len(problems) == 1 and "rust snippet" in problems[0]


def test_a_check_must_quote_the_page(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("# A page\n\nThe answer is 42, said the machine.\n"
                    "<!-- check: 6 * 7 == 42 -->\n<!-- check: 2 * 21 == 42 -->\n\n"
                    "Another paragraph.\n<!-- check: 6 * 7 == 42 -->\n")
    _, checks = parse(page)
    assert [c.assertions[0][1:] for c in checks] == [("6 * 7", "42"), ("2 * 21", "42"),
                                                     ("6 * 7", "42")]
    # Checks in a row vouch for the same text; after new text, only for it.
    assert "42" in checks[0].scope and "42" in checks[1].scope and "42" not in checks[2].scope


def test_the_extras_the_pages_name_exist():
    """``pip install "...[a,b]"`` on any page names extras of the package."""
    known = extras()
    for page in PAGES:
        for line_number, line in enumerate(page.read_text().splitlines(), 1):
            if "pip install" not in line:
                continue
            for group in re.findall(r"(?:stickslip|\.whl|stickslip-py)\[([\w,\s-]+)\]", line):
                for name in (n.strip() for n in group.split(",")):
                    assert name in known, (f"{shown(page)}:{line_number}: the "
                                           f"extra {name!r} is not one of {sorted(known)}")
