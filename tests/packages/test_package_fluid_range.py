"""A package's runs meet the CSV import's fluid-temperature rule (one rule, two doors):
a run at a temperature outside its fluid's viscosity data is refused in one line naming
the row, field, value and range, from the command line and Python alike, nothing
imported."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import pytest
from support import dump_hash

import granudb


def _temperature(package: Path, run: str, celsius: str) -> None:
    """Set one run's temperature in the package (fixing its declared size and hash, so the
    range rule is what refuses)."""
    path = package / "data" / "collisions.csv"
    lines = path.read_text("utf-8").splitlines(keepends=True)
    header = lines[0].rstrip("\n").split(",")
    column = header.index("temperature_c")
    for number, line in enumerate(lines):
        cells = line.rstrip("\n").split(",")
        if cells[0] == run:
            cells[column] = celsius
            lines[number] = ",".join(cells) + "\n"
    _write(package, "collisions", "".join(lines))


def _write(package: Path, resource: str, text: str) -> None:
    """Write a resource's file, its declared size and hash fixed."""
    data = text.encode()
    (package / "data" / f"{resource}.csv").write_bytes(data)
    descriptor = json.loads((package / "datapackage.json").read_text("utf-8"))
    descriptor.pop("granudb:content_hash", None)
    entry = next(r for r in descriptor["resources"] if r["name"] == resource)
    entry["bytes"], entry["hash"] = len(data), "sha256:" + hashlib.sha256(data).hexdigest()
    (package / "datapackage.json").write_text(json.dumps(descriptor), encoding="utf-8")


def _row(package: Path, run: str) -> int:
    lines = (package / "data" / "collisions.csv").read_text("utf-8").splitlines()
    return next(n for n, line in enumerate(lines, start=1) if line.startswith(f"{run},"))


def test_a_run_outside_its_fluids_range_is_refused(cli, db: str, package: Path) -> None:
    _temperature(package, "glass-g45-2", "95.0")
    row = _row(package, "glass-g45-2")
    before = dump_hash(db)
    result = cli("dataset", "import", str(package), "--as", "other", db=db)
    assert result.exit_code == 1, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert lines == [
        f"Error: collisions.csv: row {row}: temperature_c: 95 °C is outside fluid "
        "glycerol-45's viscosity data (10–60 °C), which granudb does not extrapolate; "
        "nothing was imported into dataset other"
    ]
    assert dump_hash(db) == before
    with pytest.raises(granudb.ValidationError) as raised:
        granudb.import_dataset(package, as_name="other", db=db)
    assert str(raised.value) == lines[0].removeprefix("Error: ")
    assert dump_hash(db) == before


def test_the_same_rule_as_the_csv_import(cli, db: str, package: Path, tmp_path: Path) -> None:
    """Two runs out of range (one below, one above): both named, in row order, with the
    words the CSV import uses for the same runs."""
    _temperature(package, "glass-g45-1", "5.0")
    _temperature(package, "steel-g37-1", "75.0")
    result = cli("dataset", "import", str(package), "--as", "other", db=db)
    assert result.exit_code == 1
    message = result.stderr.strip()
    assert message.startswith("Error: collisions.csv: 2 problems: row 2: temperature_c: 5 °C")
    assert "75 °C is outside fluid glycerol-37's viscosity data" in message
    csv = tmp_path / "hot.csv"
    csv.write_text(
        "run,particle,wall,fluid,diameter [mm],v_n_in [mm/s],v_t_in [mm/s],v_n_out [mm/s],"
        "v_t_out [mm/s],temperature [degC]\nhot,steel,Zerodur,glycerol-37,12.7,300,26,240,"
        "16,75\n",
        encoding="utf-8",
    )
    by_csv = cli("collisions", "import", str(csv), "--dataset", "hot", db=db)
    assert by_csv.exit_code == 1
    rule = by_csv.stderr.split("75 °C ", 1)[1].split("; nothing")[0]
    assert f"75 °C {rule}" in message


def test_a_run_inside_the_range_is_imported(cli, db: str, package: Path) -> None:
    _temperature(package, "glass-g45-2", "59.0")
    result = cli("dataset", "import", str(package), "--as", "other", db=db)
    assert result.exit_code == 0, result.stderr
    assert granudb.dataset("other", db=db)["runs"] == 12


def test_a_renamed_fluid_is_checked_against_its_own_points(cli, db: str, package: Path) -> None:
    """A package fluid that conflicts with the stored one comes in renamed, with the
    package's points: its runs are checked against those, under its new name."""
    fluids = (package / "data" / "fluids.csv").read_text("utf-8")
    _write(package, "fluids", fluids.replace("(glass sphere experiments", "(edited", 1))
    points = (package / "data" / "fluid_points.csv").read_text("utf-8").splitlines(True)
    kept = [p for p in points if not p.startswith("glycerol-45,") or float(p.split(",")[1]) < 45]
    assert len(kept) < len(points)
    _write(package, "fluid_points", "".join(kept))
    _temperature(package, "glass-g45-2", "50.0")  # inside the stored data, not the package's
    before = dump_hash(db)
    result = cli("dataset", "import", str(package), "--as", "other", "--rename-conflicts", db=db)
    assert result.exit_code == 1, result.stdout
    assert "50 °C is outside fluid glycerol-45 (" in result.stderr
    assert "'s viscosity data (10–40 °C)" in result.stderr
    assert dump_hash(db) == before
