"""Run every example of README.md and the manual, and compare what it prints.

Docs that cannot drift, after sqlite-utils' cog habit. In README.md, docs/*.md and
docs/guide/*.md:

- a ```` ```console ```` block is a terminal session: each line starting with ``$ `` is a
  command, the lines after it (up to the next ``$``) are what it prints. The command runs
  and its output must equal the lines shown, after normalising what changes from run to run
  (times, temporary paths, trailing spaces);
- a ```` ```sh ```` block is a list of commands: each line starting with ``granudb `` runs
  and must exit 0 (install and system commands — ``pip``, ``apt-get``, ``python3 -m venv``,
  ``datasette``, ``initdb`` … — are run by ``.ci/run`` or need a server, and are not run here);
- a ```` ```python ```` block runs as a script and must not raise.

``<!-- examples: skip -->`` on the line before a block leaves it out (say why beside it).

The fixture: every page starts in a fresh temporary folder holding a copy of ``examples/``
and a freshly created and seeded SQLite database (what the first ``granudb`` command of a
new install makes), with ``GRANUDB_DATABASE_URL`` pointing at it, ``COLUMNS=100`` and
``HOME`` in the folder. Blocks
of a page run in order and share that folder and database.

    python -m tools.docs_examples            # check: lists every difference, exit 1 if any
    python -m tools.docs_examples --update   # rewrite the shown outputs from what runs print
    python -m tools.docs_examples --update docs/guide/import.md   # one page

``--update`` also regenerates the command-line reference (docs/cli.md, tools/cli_reference.py).
"""

from __future__ import annotations

import atexit
import contextlib
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SKIP_MARK = "<!-- examples: skip"
#: commands a ``sh`` block may hold that the docs test does not run (installs, servers).
NOT_RUN = ("pip ", "python3 -m venv", "python -m venv", "apt-get", "sudo ", "mkdocs ", "pytest")

TIME = re.compile(r"\d{4}-\d\d-\d\d[T ]\d\d:\d\d(:\d\d(\.\d+)?)?([+-]\d\d:?\d\d|Z| UTC)?")
FENCE = re.compile(r"^```(\w*)[^\n]*\n(.*?)^```[ \t]*$", re.S | re.M)


def pages() -> list[Path]:
    """Every page whose examples run: README.md, docs/*.md and docs/guide/*.md."""
    found = [REPO / "README.md"]
    found += sorted((REPO / "docs").glob("*.md"))
    found += sorted((REPO / "docs" / "guide").glob("*.md"))
    return [page for page in found if page.name != "cli.md"]  # generated, not examples


@dataclass
class Block:
    kind: str  # console | sh | python
    start: int  # offset of the block's body in the page's text
    end: int
    body: str
    line: int  # line number of the opening fence


@dataclass
class Difference:
    page: Path
    line: int
    command: str
    shown: str
    printed: str


@dataclass
class Result:
    page: Path
    blocks: int = 0
    commands: int = 0
    differences: list[Difference] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    updated_text: str | None = None


def blocks(text: str) -> list[Block]:
    found = []
    for match in FENCE.finditer(text):
        kind = match.group(1)
        if kind not in {"console", "sh", "python"}:
            continue
        before = text[: match.start()].rstrip("\n").rsplit("\n", 1)[-1]
        if before.startswith(SKIP_MARK):
            continue
        found.append(
            Block(
                kind,
                match.start(2),
                match.end(2),
                match.group(2),
                text.count("\n", 0, match.start()) + 1,
            )
        )
    return found


def normalise(output: str, folder: Path) -> str:
    """What may differ between two runs of the same example, made the same."""
    text = output.replace(str(folder.resolve()), ".").replace(str(folder), ".")
    text = TIME.sub("<time>", text)
    text = re.sub(r"(?m)[ \t]+$", "", text)
    return text.strip("\n")


_TEMPLATE: list[Path] = []


def seeded_database() -> Path:
    """A freshly created and seeded SQLite file (made once per process, then copied)."""
    if not _TEMPLATE:
        import sqlite3

        from granudb.api.database import connect

        folder = Path(tempfile.mkdtemp(prefix="granudb-docs-template-"))
        atexit.register(shutil.rmtree, folder, ignore_errors=True)  # gone with the process
        path = folder / "granudb.sqlite"
        connect(str(path)).dispose()
        with sqlite3.connect(path) as connection:  # fold the WAL into the one file
            connection.execute("PRAGMA wal_checkpoint(TRUNCATE)")
            connection.execute("PRAGMA journal_mode=DELETE")
        _TEMPLATE.append(path)
    return _TEMPLATE[0]


class Session:
    """One page's fixture: a folder with examples/, a database, and the granudb app."""

    def __init__(self, folder: Path) -> None:
        self.folder = folder
        shutil.copytree(REPO / "examples", folder / "examples")
        (folder / "home").mkdir()
        shutil.copy(seeded_database(), folder / "granudb.sqlite")
        self.env = {
            "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}",
            "GRANUDB_DATABASE_URL": str(folder / "granudb.sqlite"),
            "COLUMNS": "100",
            "HOME": str(folder / "home"),
            "XDG_DATA_HOME": str(folder / "home" / "data"),
            "NO_COLOR": "1",
        }

    @contextlib.contextmanager
    def inside(self):
        saved_env = {key: os.environ.get(key) for key in self.env}
        saved_cwd = os.getcwd()
        os.environ.update(self.env)
        os.chdir(self.folder)
        try:
            yield
        finally:
            os.chdir(saved_cwd)
            for key, value in saved_env.items():
                if value is None:
                    os.environ.pop(key, None)
                else:
                    os.environ[key] = value

    def run(self, command: str) -> tuple[int, str]:
        """Run one shell-like command: granudb in-process, anything else in a shell."""
        words = shlex.split(command, comments=True)
        lexer = shlex.shlex(command, posix=True, punctuation_chars=True)
        piped = any(token in {"|", ">", ">>", "<", "&&", ";", "||"} for token in lexer)
        if words and words[0] == "granudb" and not piped:
            from typer.testing import CliRunner

            from granudb.cli.main import app

            with self.inside():
                result = CliRunner().invoke(app, words[1:], catch_exceptions=True, env=self.env)
            output = result.output
            if result.exception is not None and not isinstance(result.exception, SystemExit):
                output += f"\n{type(result.exception).__name__}: {result.exception}"
            return result.exit_code, output
        completed = subprocess.run(
            command,
            shell=True,
            cwd=self.folder,
            env={**os.environ, **self.env},
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,  # interleaved, as a terminal shows them
            text=True,
            timeout=120,
        )
        return completed.returncode, completed.stdout

    def run_python(self, source: str) -> str | None:
        """Run a Python block as a script; the error, if it raised."""
        buffer = io.StringIO()
        with self.inside(), contextlib.redirect_stdout(buffer):
            try:
                exec(compile(source, "<docs example>", "exec"), {"__name__": "__docs__"})
            except Exception as error:  # reported, with the page and line
                return f"{type(error).__name__}: {error}"
        return None


def console_commands(body: str) -> list[tuple[str, list[str]]]:
    """``$ command`` lines and the lines shown after each."""
    commands: list[tuple[str, list[str]]] = []
    for line in body.rstrip("\n").split("\n"):
        if line.startswith("$ "):
            commands.append((line[2:], []))
        elif commands:
            if commands[-1][0].endswith("\\") and not commands[-1][1]:
                commands[-1] = (commands[-1][0][:-1] + line.strip(), [])
            else:
                commands[-1][1].append(line)
    return commands


def shell_lines(body: str) -> list[str]:
    """The commands of an ``sh`` block (backslash continuations joined)."""
    joined = body.replace("\\\n", " ")
    return [line.strip() for line in joined.split("\n") if line.strip()]


def check_page(page: Path, update: bool = False) -> Result:
    text = page.read_text(encoding="utf-8")
    result = Result(page)
    replacements: list[tuple[int, int, str]] = []
    with tempfile.TemporaryDirectory(prefix="granudb-docs-") as name:
        session = Session(Path(name))
        for block in blocks(text):
            result.blocks += 1
            if block.kind == "python":
                error = session.run_python(block.body)
                if error:
                    result.errors.append(f"{page.name}:{block.line}: python block: {error}")
                continue
            if block.kind == "sh":
                for line in shell_lines(block.body):
                    if line.startswith("#") or line.startswith(NOT_RUN):
                        continue
                    if not line.startswith("granudb "):
                        continue
                    if line.startswith("granudb dem verify") and not shutil.which("liggghts"):
                        continue  # needs the DEM codes; their own tests say when one is missing
                    result.commands += 1
                    code, output = session.run(line)
                    if code != 0:
                        result.errors.append(
                            f"{page.name}:{block.line}: `{line}` exited {code}:\n{output}"
                        )
                continue
            new_body = []
            for command, shown in console_commands(block.body):
                result.commands += 1
                code, output = session.run(command)
                printed = normalise(output, session.folder)
                if code != 0:
                    printed += f"\n[exit code {code}]"
                if "Traceback (most recent call last)" in output:
                    result.errors.append(f"{page.name}:{block.line}: `{command}` raised:\n{output}")
                shown_text = normalise("\n".join(shown), session.folder)
                if printed != shown_text:
                    result.differences.append(
                        Difference(page, block.line, command, shown_text, printed)
                    )
                new_body.append(f"$ {command}")
                if printed:
                    new_body.append(printed)
            replacements.append((block.start, block.end, "\n".join(new_body) + "\n"))
    if update and result.differences:
        for start, end, body in reversed(replacements):
            text = text[:start] + body + text[end:]
        result.updated_text = text
    return result


def report(results: list[Result]) -> str:
    lines = []
    for result in results:
        for difference in result.differences:
            lines.append(
                f"{difference.page.relative_to(REPO)}:{difference.line}: "
                f"$ {difference.command}\n--- shown\n{difference.shown}\n+++ printed\n"
                f"{difference.printed}\n"
            )
        lines.extend(result.errors)
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    update = "--update" in argv
    chosen = [REPO / arg for arg in argv if not arg.startswith("--")]
    results = []
    for page in chosen or pages():
        result = check_page(page, update=update)
        results.append(result)
        if result.updated_text is not None:
            page.write_text(result.updated_text, encoding="utf-8")
            print(f"updated {page.relative_to(REPO)}")
    if update:
        from tools.cli_reference import write

        print(write())
    text = report(results)
    if text:
        print(text)
    failed = any(r.errors for r in results) or (not update and any(r.differences for r in results))
    commands = sum(r.commands for r in results)
    print(f"{len(results)} pages, {commands} commands: {'FAIL' if failed else 'ok'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
