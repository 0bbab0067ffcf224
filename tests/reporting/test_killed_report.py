"""A Markdown report killed mid-write leaves nothing that blocks its rerun (issue 35).

The figures folder lands with the report (``granudb.output_files.land_with``): staged
whole in a hidden sibling, renamed into place, then the report, then the folder's mark
goes. A real ``granudb report`` process is killed with SIGKILL at the two moments a kill
can leave something: just before the staged folder is renamed (a hidden staging folder is
left) and between the folder and the report (a marked folder is left). The same command
then succeeds, and its report and figures equal those of a run never killed.
"""

from __future__ import annotations

import json
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from granudb.output_files import LANDING_MARK, clear_unfinished, land_with, unfinished

#: Runs ``granudb report …`` in a process that kills itself (SIGKILL, no clean-up runs) the
#: moment it reaches the named step of the write.
KILLED_AT = """
import os, signal, sys
from granudb import output_files

moment = sys.argv[1]
real_rename, real_write = os.rename, output_files.write_bytes

def rename(source, target, *args, **kwargs):
    if moment == "before-folder" and str(target).endswith("_figures"):
        os.kill(os.getpid(), signal.SIGKILL)
    return real_rename(source, target, *args, **kwargs)

def write_bytes(path, payload, **kwargs):
    if moment == "before-report" and str(path).endswith(".md"):
        os.kill(os.getpid(), signal.SIGKILL)
    return real_write(path, payload, **kwargs)

os.rename, output_files.write_bytes = rename, write_bytes
sys.argv = ["granudb", *sys.argv[2:]]
from granudb.cli.main import main
main()
"""


def _report(folder: Path, db: str, *, killed_at: str | None = None) -> subprocess.CompletedProcess:
    argv = ["report", "--dataset", "paper", "--format", "md", "-o", "walton.md", "--db", db]
    if killed_at is None:
        command = [sys.executable, "-m", "granudb", *argv]
    else:
        command = [sys.executable, "-c", KILLED_AT, killed_at, *argv]
    return subprocess.run(command, cwd=folder, capture_output=True, text=True, timeout=300)


def _tree(folder: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()
    }


def _same_report(tree: dict[str, bytes]) -> dict[str, bytes]:
    """The report without its time of writing (the one line two runs may differ in)."""
    import re

    text = tree["walton.md"].decode("utf-8")
    return {**tree, "walton.md": re.sub(rb"\d{4}-\d\d-\d\dT[\d:]+\+00:00", b"T", text.encode())}


@pytest.mark.parametrize("moment", ["before-folder", "before-report"])
def test_a_report_killed_mid_write_does_not_block_its_rerun(
    paper_db: str, tmp_path: Path, moment: str
) -> None:
    clean = tmp_path / "clean"
    clean.mkdir()
    assert _report(clean, paper_db).returncode == 0
    expected = _tree(clean)
    assert any(name.startswith("walton_figures/fig-") for name in expected)
    assert not any(LANDING_MARK in name for name in expected)

    work = tmp_path / "work"
    work.mkdir()
    killed = _report(work, paper_db, killed_at=moment)
    assert killed.returncode == -signal.SIGKILL
    assert not (work / "walton.md").exists()  # no complete report was ever written
    left = sorted(p.name for p in work.iterdir())
    if moment == "before-report":
        assert left == ["walton_figures"]
        assert unfinished(work / "walton_figures", work / "walton.md")
    else:
        assert len(left) == 1 and left[0].startswith(".walton_figures.")  # hidden staging

    rerun = _report(work, paper_db)
    assert rerun.returncode == 0, rerun.stderr
    tree = {k: v for k, v in _tree(work).items() if not k.startswith(".walton_figures.")}
    assert _same_report(tree) == _same_report(expected)


def test_a_finished_report_still_refuses_to_be_overwritten(paper_db: str, tmp_path: Path) -> None:
    assert _report(tmp_path, paper_db).returncode == 0
    before = _tree(tmp_path)
    again = _report(tmp_path, paper_db)
    assert again.returncode == 1
    assert again.stderr.strip().endswith("exists (use --force to overwrite it)")
    assert _tree(tmp_path) == before


def test_only_a_folder_marked_for_this_report_is_taken_over(tmp_path: Path) -> None:
    """A user's own folder, a folder marked for another report, a mark listing a path
    outside the folder, and a report that exists are never cleared."""
    report = tmp_path / "walton.md"
    folder = tmp_path / "walton_figures"
    folder.mkdir()
    (folder / "fig-walton.svg").write_text("mine")
    assert not clear_unfinished(folder, report)
    (folder / LANDING_MARK).write_text(json.dumps({"file": "other.md", "files": []}))
    assert not clear_unfinished(folder, report)
    (folder / LANDING_MARK).write_text(json.dumps({"file": "walton.md", "files": ["../x"]}))
    assert not clear_unfinished(folder, report)
    (folder / LANDING_MARK).write_text(json.dumps({"file": "walton.md", "files": []}))
    report.write_text("done")
    assert not clear_unfinished(folder, report)
    assert (folder / "fig-walton.svg").read_text() == "mine"
    report.unlink()
    (folder / "notes.txt").write_text("the user's")  # added after the kill: kept
    (folder / LANDING_MARK).write_text(
        json.dumps({"file": "walton.md", "files": ["fig-walton.svg"]})
    )
    assert clear_unfinished(folder, report)
    assert sorted(p.name for p in folder.iterdir()) == ["notes.txt"]


def test_land_with_leaves_no_mark_when_it_finishes(tmp_path: Path) -> None:
    land_with(tmp_path / "r_figures", {"a.svg": b"<svg/>"}, tmp_path / "r.md", b"# r")
    assert _tree(tmp_path) == {"r.md": b"# r", "r_figures/a.svg": b"<svg/>"}
