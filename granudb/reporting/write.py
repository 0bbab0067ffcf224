"""Writing a report to disk: one self-contained HTML file, or Markdown with SVG files
beside it (linked relatively, so the folder can be moved or committed as it is).

An existing file is never overwritten unless the caller says so (``force``): a report is
often handed in, and regenerating it by accident must not destroy the copy.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from granudb.errors import ValidationError
from granudb.reporting.render import render


def default_name(report: dict[str, Any], fmt: str) -> str:
    slug = re.sub(r"[^a-z0-9]+", "-", report["title"].lower()).strip("-")[:80] or "report"
    return f"{slug}.{'html' if fmt == 'html' else 'md'}"


def check_output(path: Path | None, *, force: bool = False) -> None:
    """Refuse, before any work, an output in a missing folder or an existing file
    (unless ``force``). A folder is accepted: the file name is chosen later."""
    if path is None or Path(path).is_dir():
        return
    path = Path(path)
    if not path.parent.is_dir():
        raise ValidationError("--output", str(path), "is in a folder that does not exist")
    if path.exists() and not force:
        raise ValidationError("--output", str(path), "exists (use --force to overwrite it)")


def write_report(
    report: dict[str, Any], fmt: str, output: Path | None, *, force: bool = False
) -> Path:
    """Write ``report`` as ``fmt`` ("html" or "md") to ``output`` (default: a name made
    from the title, in the current folder); returns the path written."""
    if fmt not in {"html", "md"}:
        raise ValidationError("--format", fmt, "must be html or md")
    path = Path(output) if output is not None else Path.cwd() / default_name(report, fmt)
    if path.is_dir():
        path = path / default_name(report, fmt)
    check_output(path, force=force)
    if fmt == "md":
        folder = path.with_name(path.stem + "_figures")
        if report["figures"]:
            folder.mkdir(exist_ok=True)
        for figure in report["figures"]:
            (folder / f"{figure['id']}.svg").write_text(
                '<?xml version="1.0" encoding="utf-8"?>\n' + figure["svg"], encoding="utf-8"
            )
            figure["file"] = f"{folder.name}/{figure['id']}.svg"
    text = render(report, fmt)
    temporary = path.with_name(path.name + ".part")
    temporary.write_text(text, encoding="utf-8")
    temporary.replace(path)
    return path
