"""Writing a report to disk: one self-contained HTML file, or Markdown with SVG files
beside it (linked relatively, so the folder can be moved or committed as it is); a dataset
report whose run table shows only its first runs also gets ``<name>_runs.csv`` beside it,
with every run.

An existing file is never overwritten unless the caller says so (``force``): a report is
often handed in, and regenerating it by accident must not destroy the copy.
"""

from __future__ import annotations

import contextlib
import re
from pathlib import Path
from typing import Any

from granudb.errors import ValidationError
from granudb.output_files import clear_unfinished, land_with, write_bytes, write_text
from granudb.reporting.render import render
from granudb.reporting.tables import runs_csv


def default_name(report: dict[str, Any], fmt: str) -> str:
    slug = re.sub(r"[^a-z0-9]+", "-", report["title"].lower()).strip("-")[:80] or "report"
    return f"{slug}.{'html' if fmt == 'html' else 'md'}"


def check_output(path: Path | None, *, force: bool = False) -> None:
    """Refuse, before any work, an output in a missing folder, an existing file (unless
    ``force``) or a symbolic link. A folder is accepted: the file name is chosen later."""
    if path is None:
        return
    path = Path(path)
    if path.is_dir() and not path.is_symlink():
        return
    if not path.parent.is_dir():
        raise ValidationError("--output", str(path), "is in a folder that does not exist")
    if path.is_symlink():
        raise ValidationError("--output", str(path), "is a symbolic link (choose a new file)")
    if path.exists() and not force:
        raise ValidationError("--output", str(path), "exists (use --force to overwrite it)")


def _figures_folder(path: Path) -> Path:
    return path.with_name(path.stem + "_figures")


def _figure_files(report: dict[str, Any], path: Path, force: bool) -> dict[Path, str]:
    """The Markdown report's SVG files, each checked as the report is: a figures folder
    that is a symbolic link, or a figure file that exists (without ``force``), is refused
    before anything is written."""
    folder = _figures_folder(path)
    if not report["figures"]:
        return {}
    if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
        raise ValidationError("--output", str(folder), "is not a folder granudb may write into")
    files = {}
    for figure in report["figures"]:
        target = _beside(folder / f"{figure['id']}.svg", force)
        files[target] = '<?xml version="1.0" encoding="utf-8"?>\n' + figure["svg"]
        figure["file"] = f"{folder.name}/{figure['id']}.svg"
    return files


def _beside(target: Path, force: bool) -> Path:
    """A file written beside the report, refused as the report is: a symbolic link, or an
    existing file without ``force``."""
    if target.is_symlink():
        raise ValidationError("--output", str(target), "is a symbolic link")
    if target.exists() and not force:
        raise ValidationError("--output", str(target), "exists (use --force to overwrite it)")
    return target


def _runs_file(report: dict[str, Any], path: Path, force: bool) -> dict[Path, bytes]:
    """The CSV of every run beside a report whose run table shows only the first runs. An
    existing CSV with exactly these rows (the HTML and the Markdown report of the same
    runs share it) is kept as it is."""
    runs = report.get("runs")
    if not runs or runs["count"] <= runs["limit"]:
        return {}
    target = path.with_name(path.stem + "_runs.csv")
    payload = runs_csv(runs["frame"])
    runs["file"] = target.name
    unchanged = target.is_file() and not target.is_symlink() and target.read_bytes() == payload
    if unchanged and not force:
        return {}
    return {_beside(target, force): payload}


def write_report(
    report: dict[str, Any], fmt: str, output: Path | None, *, force: bool = False
) -> Path:
    """Write ``report`` as ``fmt`` ("html" or "md") to ``output`` (default: a name made
    from the title, in the current folder); returns the path written. Every file is
    written through ``granudb.output_files`` (exclusive temporary file, atomic rename,
    nothing left on failure)."""
    if fmt not in {"html", "md"}:
        raise ValidationError("--format", fmt, "must be html or md")
    path = Path(output) if output is not None else Path.cwd() / default_name(report, fmt)
    if path.is_dir() and not path.is_symlink():
        path = path / default_name(report, fmt)
    check_output(path, force=force)
    if fmt == "md":  # figures of an earlier write of this report that was killed mid-way
        clear_unfinished(_figures_folder(path), path)
    figures = _figure_files(report, path, force) if fmt == "md" else {}
    beside = _runs_file(report, path, force)
    text = render(report, fmt)
    folder = next(iter(figures)).parent if figures else None
    made_folder = folder is not None and not folder.exists()
    new_files = [target for target in (*figures, *beside) if not target.exists()]
    try:
        for target, payload in beside.items():
            write_bytes(target, payload, replace=force, field="--output")
        if made_folder and folder is not None:  # a new folder lands with the report
            svgs = {target.name: svg.encode("utf-8") for target, svg in figures.items()}
            return land_with(folder, svgs, path, text.encode("utf-8"), replace=force,
                             field="--output")  # fmt: skip
        for target, svg in figures.items():
            write_text(target, svg, replace=force, field="--output")
        return write_text(path, text, replace=force, field="--output")
    except BaseException:
        # all or nothing: a figure or run table written before the failure (disk full) goes
        for target in new_files:
            target.unlink(missing_ok=True)
        if made_folder and folder is not None:
            with contextlib.suppress(OSError):
                folder.rmdir()
        raise
