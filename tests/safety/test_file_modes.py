"""Files for colleagues (issue 33): everything granudb writes honours the umask — 0644
files and 0755 folders under umask 022, 0600/0700 under 077 — atomic writes included
(``mkstemp`` alone would leave them 0600)."""

from __future__ import annotations

import os
import stat
import zipfile
from collections.abc import Iterator
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
DECK = ["--particle", "steel", "--wall", "Zerodur", "--diameter", "12.7 mm",
        "--velocity", "0.3 m/s"]  # fmt: skip


@pytest.fixture
def umask() -> Iterator:
    """Set the process's umask for the test; the one found is put back after."""
    found = os.umask(0o022)
    yield lambda mask: os.umask(mask)
    os.umask(found)


def _modes(folder: Path) -> dict[str, int]:
    return {str(p.relative_to(folder)): stat.S_IMODE(p.stat().st_mode) for p in folder.rglob("*")}


@pytest.mark.parametrize("mask", [0o022, 0o077])
def test_every_file_written_honours_the_umask(cli, db, tmp_path, umask, mask) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db).exit_code == 0
    umask(mask)
    out = tmp_path / "out"
    out.mkdir()
    commands = [
        ["report", "--dataset", "ex", "--output", str(out / "r.html")],
        ["report", "--dataset", "ex", "--format", "md", "--output", str(out / "r.md")],
        ["dataset", "export", "ex", "--output", str(out / "ex.zip")],
        ["dataset", "export", "ex", "--output", str(out / "pkg")],
        ["fit", "walton", "--method", "bayes", "--draws", str(out / "draws.csv")],
    ]
    for code in ("lammps", "liggghts", "yade", "mercurydpm"):
        commands.append(["dem", "export", "--code", code, *DECK, "--output", str(out / code)])
    for command in commands:
        done = cli(*command, db=db)
        assert done.exit_code == 0, (command, done.stderr)
    modes = _modes(out)
    files = {n for n, m in modes.items() if (out / n).is_file()}
    assert {"r.html", "r.md", "ex.zip", "draws.csv", "lammps", "yade"} <= files
    assert "pkg/datapackage.json" in files and any(n.startswith("r_figures/") for n in files)
    wrong = {n: oct(m) for n, m in modes.items() if m != (0o666 if n in files else 0o777) & ~mask}
    assert wrong == {}
    # the zip's entries are regular files readable by all, whatever the umask (same bytes)
    with zipfile.ZipFile(out / "ex.zip") as archive:
        entry_modes = {i.external_attr >> 16 for i in archive.infolist()}
    assert entry_modes == {0o100644}
