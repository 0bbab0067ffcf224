"""Start-up stays light: the lazy command table matches the modules, and the cheap
"is the schema current?" check agrees with Alembic."""

from __future__ import annotations

import subprocess
import sys

import typer

from granudb.cli.main import COMMANDS, load_command


def test_lazy_command_help_matches_each_module() -> None:
    for name, (_, _, help_text) in COMMANDS.items():
        command = load_command(name)
        assert command.help is not None
        assert " ".join(command.help.split("\n\n")[0].split()) == help_text, name
        assert isinstance(command, typer.core.TyperCommand | typer.core.TyperGroup)


def test_shipped_head_agrees_with_alembic() -> None:
    from granudb.db.migration import head_revision, shipped_head

    assert shipped_head() == head_revision()


def test_materials_list_json_imports_no_heavy_libraries(tmp_path) -> None:
    """Not even SQLAlchemy's ORM: the list reads through Core (``db/catalog_rows.py``), and
    Typer is pinned below the release that validates every option with pydantic."""
    db = tmp_path / "g.sqlite"
    code = (
        "import sys\nfrom granudb.cli.main import app\n"
        f"args = ['materials', 'list', '--format', 'json', '--db', {str(db)!r}]\n"
        "try:\n    app(args)\nexcept SystemExit:\n    pass\n"
        "heavy = [m for m in ('pandas', 'numpy', 'pint', 'alembic', 'scipy', 'matplotlib',"
        " 'pydantic', 'sqlalchemy.orm', 'granudb.db.models') if m in sys.modules]\n"
        "print('HEAVY=' + ','.join(heavy))"
    )
    first = [sys.executable, "-c", code]
    subprocess.run(first, capture_output=True, text=True, check=True)  # creates and seeds
    out = subprocess.run(first, capture_output=True, text=True, check=True)
    assert out.stdout.strip().splitlines()[-1] == "HEAVY="


def test_a_dataset_report_imports_no_plotting_fitting_or_orm_library(tmp_path) -> None:
    """Figures are written by ``granudb.reporting.svg``, the fits are numpy, and the runs and
    catalogue are read through Core (``lookup_rows``, ``catalog_rows``): the report path
    is spared matplotlib, scipy, the ORM and the models (issue 17)."""
    from pathlib import Path

    example = Path(__file__).resolve().parents[1] / "examples" / "collisions_example.csv"
    db, out = tmp_path / "g.sqlite", tmp_path / "r.html"

    def run(args: list[str]) -> str:
        code = (
            "import sys\nfrom granudb.cli.main import app\n"
            f"try:\n    app({args!r})\nexcept SystemExit as stop:\n"
            "    assert not stop.code, stop.code\n"
            "heavy = ('matplotlib', 'scipy', 'sqlalchemy.orm', 'granudb.db.models', 'pint')\n"
            "print('HEAVY=' + ','.join(m for m in heavy if m in sys.modules))"
        )
        done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        assert done.returncode == 0, done.stderr[-2000:]
        return done.stdout.strip().splitlines()[-1]

    run(["collisions", "import", str(example), "--dataset", "ex", "--db", str(db)])
    assert run(["report", "--dataset", "ex", "--output", str(out), "--db", str(db)]) == "HEAVY="
    assert out.read_text("utf-8").count("<svg id=") >= 5
