"""Data that travels: odd-but-legal text round-trips byte for byte; a bare CR is quoted on
export and refused by name on import; CITATION.cff passes cffconvert."""

from __future__ import annotations

import csv
import io
import json
import shutil
import subprocess
import sys
from pathlib import Path

from support import dump_hash, execute

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
ODD = ["=SUM(A1:A9)", "-1+2", "@cmd ümlaut 材料", 'a "quoted", comma', "line\nbreak", " padded "]


def _export(cli, db: str, out: Path) -> Path:
    assert cli("dataset", "export", "example", "--output", str(out), db=db).exit_code == 0
    return out


def test_odd_notes_round_trip_byte_for_byte(cli, db: str, new_db: str, tmp_path: Path) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    for i, text in enumerate(ODD, start=1):
        execute(
            db,
            "UPDATE collisions SET notes = :n WHERE run = :r",
            {"n": text, "r": f"steel-dry-{i}"},
        )
    first = _export(cli, db, tmp_path / "one")
    result = cli("dataset", "import", str(first), db=new_db)
    assert result.exit_code == 0, result.stderr
    second = _export(cli, new_db, tmp_path / "two")
    for name in ("collisions", "materials", "fluids", "sources"):
        assert (first / "data" / f"{name}.csv").read_bytes() == (
            second / "data" / f"{name}.csv"
        ).read_bytes()
    rows = list(
        csv.DictReader(
            io.StringIO((second / "data" / "collisions.csv").read_text("utf-8"), newline="")
        )
    )
    assert {r["notes"] for r in rows} >= set(ODD)


def test_bare_cr_is_quoted_and_refused_by_name(cli, db: str, tmp_path: Path) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    execute(db, "UPDATE collisions SET notes = 'a\rb' WHERE run = 'steel-dry-1'")
    out = _export(cli, db, tmp_path / "pkg")
    text = (out / "data" / "collisions.csv").read_bytes().decode("utf-8")
    rows = list(csv.reader(io.StringIO(text, newline="")))
    assert len(rows) == 13 and "a\rb" in [r[-1] for r in rows]
    before = dump_hash(db)
    result = cli("dataset", "import", str(out), "--as", "other", db=db)
    assert result.exit_code == 1
    lines = [
        line for line in result.stderr.splitlines() if not line.startswith("created ")
    ]  # one line: the database existed already
    assert len(lines) == 1 and "collisions.notes" in lines[0] and "U+000D" in lines[0]
    assert dump_hash(db) == before


def test_exports_pass_cffconvert_and_carry_metadata(cli, db: str, tmp_path: Path) -> None:
    imported = cli(
        "collisions", "import", str(EXAMPLE), "--dataset", "example",
        "--source", "joseph-hunt-2004", "--license", "CC-BY-4.0", db=db,
    )  # fmt: skip
    assert imported.exit_code == 0, imported.stderr
    out = _export(cli, db, tmp_path / "pkg")
    tool = shutil.which("cffconvert") or str(Path(sys.executable).parent / "cffconvert")
    check = subprocess.run([tool, "--validate"], cwd=out, capture_output=True, text=True)
    assert check.returncode == 0, check.stdout + check.stderr
    cff = (out / "CITATION.cff").read_text("utf-8")
    assert 'family-names: "Joseph"' in cff and "references:" in cff
    assert "doi:" not in cff.split("references:")[0]  # the paper's DOI is not the dataset's
    descriptor = json.loads((out / "datapackage.json").read_text("utf-8"))
    assert descriptor["contributors"][0]["familyName"] == "Joseph"
    assert "created" in descriptor and descriptor["licenses"] == [{"name": "CC-BY-4.0"}]
    zenodo = json.loads((out / ".zenodo.json").read_text("utf-8"))
    assert zenodo["upload_type"] == "dataset" and zenodo["license"] == "cc-by-4.0"
    assert zenodo["related_identifiers"][0]["identifier"] == "10.1017/S002211200400919X"
    assert "byte for byte" in (out / "README.md").read_text("utf-8")
