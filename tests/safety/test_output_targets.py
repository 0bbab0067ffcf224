"""Nothing is written outside the target a user named (issue 25): a symbolic link planted
as the output, as a temporary name or as the figures folder is never written through, an
existing figure is not overwritten without --force, and no temporary file is left."""

from __future__ import annotations

from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"


@pytest.fixture
def setup(cli, db, tmp_path):
    result = cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", db=db)
    assert result.exit_code == 0, result.stderr
    work, outside = tmp_path / "work", tmp_path / "outside"
    work.mkdir()
    outside.mkdir()
    return work, outside


def _listing(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


def test_a_dangling_symlink_as_output_is_refused(cli, db, setup) -> None:
    work, outside = setup
    commands = {
        "r.html": ["report", "--dataset", "ex"],
        "deck.in": ["dem", "export", "--code", "lammps", "--particle", "steel", "--wall",
                    "Zerodur", "--diameter", "12.7 mm", "--velocity", "0.3 m/s"],
        "e.zip": ["dataset", "export", "ex"],
    }  # fmt: skip
    for name, command in commands.items():
        (work / name).symlink_to(outside / name)
        result = cli(*command, "--output", str(work / name), db=db)
        assert result.exit_code != 0, name
        assert result.stderr.count("\n") == 1 and "Traceback" not in result.stderr
        assert _listing(outside) == [], name


def test_planted_temporary_names_are_not_written_through(cli, db, setup) -> None:
    work, outside = setup
    for name in ("r.html.part", "e.zip.part", ".r.html.part"):
        (work / name).symlink_to(outside / name)
    assert cli("report", "--dataset", "ex", "--output", str(work / "r.html"), db=db).exit_code == 0
    assert cli("dataset", "export", "ex", "--output", str(work / "e.zip"), db=db).exit_code == 0
    assert _listing(outside) == []
    assert {"r.html", "e.zip"} <= set(_listing(work))
    assert not [n for n in _listing(work) if n.endswith(".part") and not (work / n).is_symlink()]


def test_a_symlinked_figures_folder_is_refused(cli, db, setup) -> None:
    work, outside = setup
    (work / "r_figures").symlink_to(outside, target_is_directory=True)
    result = cli("report", "--dataset", "ex", "--format", "md", "--output", str(work / "r.md"),
                 db=db)  # fmt: skip
    assert result.exit_code == 1 and "r_figures" in result.stderr
    assert _listing(outside) == [] and not (work / "r.md").exists()


def test_figures_follow_the_report_overwrite_rule(cli, db, setup) -> None:
    work, _ = setup
    args = ["report", "--dataset", "ex", "--format", "md", "--output", str(work / "r.md")]
    assert cli(*args, db=db).exit_code == 0
    figures = sorted((work / "r_figures").iterdir())
    assert figures
    figures[0].write_text("mine", encoding="utf-8")
    (work / "r.md").unlink()
    refused = cli(*args, db=db)
    assert refused.exit_code == 1 and "--force" in refused.stderr
    assert figures[0].read_text("utf-8") == "mine" and not (work / "r.md").exists()
    assert cli(*args, "--force", db=db).exit_code == 0
    assert figures[0].read_text("utf-8") != "mine"


def test_a_folder_export_leaves_no_staging_folder(cli, db, setup) -> None:
    work, _ = setup
    assert cli("dataset", "export", "ex", "--output", str(work / "pkg"), db=db).exit_code == 0
    assert [p.name for p in work.iterdir()] == ["pkg"]
    assert (work / "pkg" / "datapackage.json").is_file()
