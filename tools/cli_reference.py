"""The command-line reference (docs/cli.md), generated from the Typer app so it cannot drift.

Walks ``granudb``'s Click tree (loading the lazy sub-commands) and writes every command
with its help, usage, arguments and options: type, default, environment variable.
``tests/test_docs_examples.py`` compares docs/cli.md with what this writes.

    python -m tools.cli_reference            # print the page
    python -m tools.docs_examples --update   # rewrite docs/cli.md (with the examples)
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

REPO = Path(__file__).resolve().parent.parent
PAGE = REPO / "docs" / "cli.md"

HEADER = """# Command-line reference

Every command of `granudb`, with every argument and option, its default and the
environment variable that sets it. This page is generated from the command line itself
(`python -m tools.docs_examples --update` rewrites it; a test fails when it differs from
the code). `granudb COMMAND --help` prints the same in a terminal.

`--db` and `--format` may come before the command or after it:
`granudb --db lab.sqlite dataset list` is `granudb dataset list --db lab.sqlite`.
"""


def _root() -> Any:
    from typer.main import get_command

    from granudb.cli.main import app

    return get_command(app)


def walk() -> list[tuple[list[str], Any]]:
    """Every leaf command as (words after ``granudb``, its Click command), in help order."""
    from granudb.cli.main import click

    found: list[tuple[list[str], Any]] = []

    def visit(command: Any, path: list[str]) -> None:
        if hasattr(command, "list_commands"):
            context = click.Context(command)
            for name in command.list_commands(context):
                sub = command.get_command(context, name)
                if sub is None or sub.hidden:
                    continue
                visit(sub, [*path, name])
        else:
            found.append((path, command))

    visit(_root(), [])
    return found


def _clean(text: str | None) -> str:
    return " ".join((text or "").split())


def _metavar(param: Any) -> str:
    if getattr(param, "is_flag", False):
        return ""
    name = getattr(param.type, "name", "") or "value"
    if hasattr(param.type, "choices"):
        return "|".join(str(choice) for choice in param.type.choices)
    return {"text": "TEXT", "path": "PATH", "integer": "INTEGER", "float": "FLOAT"}.get(
        name, name.upper()
    )


def _default(param: Any) -> str:
    default = param.default
    if default is None or getattr(param, "show_default", True) is False:
        return ""
    if callable(default):
        return ""
    if isinstance(default, (list, tuple)):
        if not default:
            return ""
        default = ", ".join(str(item) for item in default)
    if getattr(param, "is_flag", False) and default is False:
        return ""
    if hasattr(default, "value"):  # an Enum
        default = default.value
    return str(default)


def _param_line(param: Any) -> str:
    if param.param_type_name == "argument":
        words = f"`{param.name.upper()}`"
        help_text = _clean(getattr(param, "help", ""))
    else:
        names = " / ".join(param.opts + list(param.secondary_opts))
        metavar = _metavar(param)
        words = f"`{names}{' ' + metavar if metavar else ''}`"
        help_text = _clean(param.help)
    parts = [words]
    if param.required:
        parts.append("(required)")
    line = " ".join(parts) + (f" — {help_text}" if help_text else "")
    extras = []
    default = _default(param)
    if default:
        extras.append(f"default: `{default}`")
    envvar = getattr(param, "envvar", None)
    if envvar:
        envvars = [envvar] if isinstance(envvar, str) else list(envvar)
        extras.append("environment: " + ", ".join(f"`{name}`" for name in envvars))
    if extras:
        line += " (" + "; ".join(extras) + ")"
    return "- " + line


def _usage(path: list[str], command: Any) -> str:
    pieces = ["granudb", *path, "[OPTIONS]"]
    for param in command.params:
        if param.param_type_name == "argument":
            name = param.name.upper()
            if getattr(param, "nargs", 1) == -1:
                name += "..."
            pieces.append(name if param.required else f"[{name}]")
    return " ".join(pieces)


def render() -> str:
    commands = walk()
    lines = [HEADER]
    lines.append("## Commands\n")
    for path, command in commands:
        name = " ".join(path)
        anchor = "-".join(path)
        lines.append(f"- [`granudb {name}`](#{anchor}) — {_clean(command.get_short_help_str(200))}")
    lines.append("")
    for path, command in commands:
        name = " ".join(path)
        anchor = "-".join(path)
        lines.append(f"## granudb {name} {{#{anchor}}}\n")
        help_text = (command.help or "").strip()
        if help_text:
            paragraphs = [_clean(p) for p in help_text.split("\n\n") if p.strip()]
            lines.append("\n\n".join(paragraphs) + "\n")
        lines.append(f"```text\n{_usage(path, command)}\n```\n")
        params = [p for p in command.params if p.name != "help"]
        arguments = [p for p in params if p.param_type_name == "argument"]
        options = [p for p in params if p.param_type_name != "argument"]
        if arguments:
            lines.append("Arguments:\n")
            lines.extend(_param_line(p) for p in arguments)
            lines.append("")
        if options:
            lines.append("Options:\n")
            lines.extend(_param_line(p) for p in options)
            lines.append("")
    return "\n".join(lines).rstrip("\n") + "\n"


def write() -> str:
    text = render()
    if PAGE.exists() and PAGE.read_text(encoding="utf-8") == text:
        return f"{PAGE.relative_to(REPO)} is current"
    PAGE.write_text(text, encoding="utf-8")
    return f"wrote {PAGE.relative_to(REPO)}"


if __name__ == "__main__":
    sys.stdout.write(render())
