"""Sharing datasets as Frictionless Data Packages: export, validate, import, catalogue."""

from __future__ import annotations

import hashlib
import json
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
from support import dump_hash

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"


@pytest.fixture
def exported(cli, db: str, tmp_path: Path) -> Path:
    assert (
        cli(
            "collisions",
            "import",
            str(EXAMPLE),
            "--dataset",
            "example",
            "--title",
            "Example runs",
            "--license",
            "CC-BY-4.0",
            db=db,
        ).exit_code
        == 0
    )
    out = tmp_path / "pkg"
    result = cli("dataset", "export", "example", "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    return out


def upstream_validates(folder: Path) -> str:
    """The upstream validator (frictionless) accepts the package in ``folder``; its
    report."""
    tool = shutil.which("frictionless") or str(Path(sys.executable).parent / "frictionless")
    check = subprocess.run(
        [tool, "validate", "datapackage.json"], cwd=folder, capture_output=True, text=True,
        timeout=300,
    )  # fmt: skip
    assert check.returncode == 0, check.stdout[-3000:]
    return check.stdout


def test_export_is_a_valid_data_package(exported: Path) -> None:
    descriptor = json.loads((exported / "datapackage.json").read_text("utf-8"))
    assert descriptor["name"] == "example" and descriptor["version"] == "1.0.0"
    assert descriptor["licenses"] == [{"name": "CC-BY-4.0"}]
    resources = {r["name"]: r for r in descriptor["resources"]}
    assert set(resources) == {"collisions", "materials", "fluids", "fluid_points", "sources"}
    fields = {f["name"]: f for f in resources["collisions"]["schema"]["fields"]}
    assert fields["v_n_in_m_s"]["unit"] == "m/s"
    assert fields["v_n_in_m_s"]["constraints"] == {"required": True, "minimum": 0.0}
    assert resources["collisions"]["schema"]["foreignKeys"][0]["reference"]["resource"] == (
        "materials"
    )
    assert resources["collisions"]["hash"].startswith("sha256:")
    assert (exported / "README.md").read_text("utf-8").startswith("# Example runs")
    assert 'cff-version: "1.2.0"' in (exported / "CITATION.cff").read_text("utf-8")
    # the upstream validator agrees
    assert "INVALID" not in upstream_validates(exported)


def test_round_trip_keeps_the_content_hash(
    cli, db: str, new_db: str, exported: Path, tmp_path: Path
) -> None:
    first = json.loads((exported / "datapackage.json").read_text("utf-8"))
    result = cli("dataset", "import", str(exported), db=new_db)
    assert result.exit_code == 0, result.stderr
    again = tmp_path / "again.zip"
    assert cli("dataset", "export", "example", "--output", str(again), db=new_db).exit_code == 0
    with zipfile.ZipFile(again) as archive:
        second = json.loads(archive.read("datapackage.json"))
        assert (
            archive.read("data/collisions.csv")
            == (exported / "data" / "collisions.csv").read_bytes()
        )
    assert second["granudb:content_hash"] == first["granudb:content_hash"]
    shown = json.loads(cli("dataset", "show", "example", "--format", "json", db=new_db).stdout)
    assert shown["content_hash"] == first["granudb:content_hash"] and shown["runs"] == 12


def test_conflicting_material_is_refused_field_by_field_then_renamed(
    cli, db: str, exported: Path
) -> None:
    assert cli("materials", "update", "glass", "--roughness", "0.2 um", db=db).exit_code == 0
    before = dump_hash(db)
    refused = cli("dataset", "import", str(exported), "--as", "copy", db=db)
    assert refused.exit_code == 1
    assert "material glass: roughness_rms_m: 2e-07 here, 1.305e-07 in the package" in (
        refused.stderr
    )
    assert dump_hash(db) == before
    renamed = cli("dataset", "import", str(exported), "--as", "copy", "--rename-conflicts", db=db)
    assert renamed.exit_code == 0, renamed.stderr
    assert "renamed material glass → glass (example)" in renamed.stdout
    names = [
        m["name"] for m in json.loads(cli("materials", "list", "--format", "json", db=db).stdout)
    ]
    assert "glass" in names and "glass (example)" in names


def test_same_name_and_version_is_refused(cli, db: str, exported: Path) -> None:
    before = dump_hash(db)
    result = cli("dataset", "import", str(exported), db=db)
    assert result.exit_code == 1 and "dataset example 1.0.0 already exists" in result.stderr
    assert dump_hash(db) == before


def _edit(package: Path, change) -> Path:
    path = package / "datapackage.json"
    descriptor = json.loads(path.read_text("utf-8"))
    change(descriptor)
    path.write_text(json.dumps(descriptor), encoding="utf-8")
    return package


def _resource(descriptor: dict, name: str) -> dict:
    return next(r for r in descriptor["resources"] if r["name"] == name)


BAD_PACKAGES = {
    "path traversal": (
        lambda d: _resource(d, "materials").update(path="../../etc/passwd"),
        "materials: path '../../etc/passwd' is not a relative path inside",
    ),
    "absolute path": (
        lambda d: _resource(d, "materials").update(path="/etc/passwd"),
        "is not a relative path inside the package",
    ),
    "url": (
        lambda d: _resource(d, "sources").update(path="https://example.org/x.csv"),
        "is not a relative path inside the package",
    ),
    "hash": (
        lambda d: _resource(d, "collisions").update(hash="sha256:" + "0" * 64),
        "collisions: sha256",
    ),
    "unknown field": (
        lambda d: _resource(d, "collisions")["schema"]["fields"].append(
            {"name": "colour", "type": "string"}
        ),
        "collisions.colour: is not a field granudb knows",
    ),
    "wrong unit": (
        lambda d: _resource(d, "collisions")["schema"]["fields"][8].update(unit="mm/s"),
        "unit 'mm/s' is not 'm/s'",
    ),
    "missing resource": (
        lambda d: d["resources"].remove(_resource(d, "fluids")),
        "fluids: resource is missing",
    ),
    "inline data": (lambda d: _resource(d, "sources").update(data=[]), "inline 'data'"),
    "content hash": (lambda d: d.update({"granudb:content_hash": "f" * 64}), "content hash"),
}


@pytest.mark.parametrize("case", sorted(BAD_PACKAGES))
def test_bad_packages_are_refused_and_change_nothing(
    cli, db: str, exported: Path, case: str
) -> None:
    change, expected = BAD_PACKAGES[case]
    package = _edit(exported, change)
    before = dump_hash(db)
    result = cli("dataset", "import", str(package), "--as", "other", db=db)
    assert result.exit_code == 1
    assert expected in result.stderr, result.stderr
    assert "Traceback" not in result.stderr
    assert result.stderr.strip().splitlines()[-1].startswith("Error: package: ")
    assert dump_hash(db) == before
    if case != "content hash":  # only import recomputes the hash
        assert cli("dataset", "validate", str(package)).exit_code == 1


def test_tampered_values_are_caught(cli, db: str, exported: Path) -> None:
    data = exported / "data" / "collisions.csv"
    data.write_text(data.read_text("utf-8").replace("0.3,", "-0.3,", 1), encoding="utf-8")
    result = cli("dataset", "validate", str(exported))
    assert result.exit_code == 1
    assert "collisions: sha256" in result.stderr
    assert "collisions.v_n_in_m_s: must be > 0" in result.stderr


@pytest.mark.parametrize(
    ("entry", "expected"),
    [
        ("../evil.txt", "would be written outside the package folder"),
        ("/abs/evil.txt", "would be written outside the package folder"),
    ],
)
def test_zip_entries_are_checked_before_extraction(
    cli, tmp_path: Path, entry: str, expected: str
) -> None:
    archive = tmp_path / "bad.zip"
    with zipfile.ZipFile(archive, "w") as handle:
        handle.writestr("datapackage.json", "{}")
        handle.writestr(entry, "x")
    result = cli("dataset", "validate", str(archive))
    assert result.exit_code == 1 and expected in result.stderr
    assert not (tmp_path.parent / "evil.txt").exists()


def test_zip_bomb_is_refused(cli, tmp_path: Path) -> None:
    archive = tmp_path / "bomb.zip"
    with zipfile.ZipFile(archive, "w", compression=zipfile.ZIP_DEFLATED) as handle:
        handle.writestr("datapackage.json", "{}")
        handle.writestr("data/collisions.csv", b"0" * 50_000_000)
    result = cli("dataset", "validate", str(archive))
    assert result.exit_code == 1 and "possible zip bomb" in result.stderr


def test_diff_between_versions(cli, db: str, tmp_path: Path) -> None:
    text = EXAMPLE.read_text("utf-8").splitlines()
    assert (
        cli(
            "collisions", "import", str(EXAMPLE), "--dataset", "d", "--version", "1", db=db
        ).exit_code
        == 0
    )
    changed = [
        text[0],
        *text[1:6],
        text[6].replace("519.62", "519.00"),
        "new-run" + text[7][text[7].index(",") :],
    ]
    path = tmp_path / "v2.csv"
    path.write_text("\n".join(changed) + "\n", encoding="utf-8")
    assert (
        cli("collisions", "import", str(path), "--dataset", "d", "--version", "2", db=db).exit_code
        == 0
    )
    out = json.loads(cli("dataset", "diff", "d@1", "d@2", "--format", "json", db=db).stdout)
    kinds = {(c["change"], c["run"]) for c in out}
    assert ("added", "new-run") in kinds
    assert ("changed", "steel-dry-6") in kinds
    assert sum(1 for c in out if c["change"] == "removed") == 6
    listed = json.loads(cli("dataset", "list", "--format", "json", db=db).stdout)
    assert {(d["name"], d["version"], d["runs"]) for d in listed} == {("d", "1", 12), ("d", "2", 7)}


def test_a_roughness_not_stated_travels_empty_and_older_schemas_still_import(
    cli, db: str, new_db: str, tmp_path: Path
) -> None:
    """Kharaz's seeded materials have no roughness (issue 23): the package's schema does
    not require one, the upstream validator accepts the empty cells, an import keeps them
    empty (never 0), and a package whose schema still requires the roughness (an older
    granudb's) imports the same."""
    # a name the other database does not seed, so the import itself stores the material
    renamed = cli("materials", "update", "alumina", "--rename", "alumina (lab)", db=db)
    assert renamed.exit_code == 0, renamed.stderr
    runs = tmp_path / "kharaz.csv"
    header = EXAMPLE.read_text("utf-8").splitlines()[0]
    runs.write_text(
        f"{header}\nk1,alumina (lab),soda-lime glass (Kharaz anvil),,5,0,3900,0,0,3800,0,0,,\n",
        "utf-8",
    )
    imported = cli("collisions", "import", str(runs), "--dataset", "kharaz", db=db)
    assert imported.exit_code == 0, imported.stderr
    out = tmp_path / "pkg"
    assert cli("dataset", "export", "kharaz", "--output", str(out), db=db).exit_code == 0
    descriptor = json.loads((out / "datapackage.json").read_text("utf-8"))
    materials = next(r for r in descriptor["resources"] if r["name"] == "materials")
    roughness = next(f for f in materials["schema"]["fields"] if f["name"] == "roughness_rms_m")
    assert not roughness.get("constraints", {}).get("required")
    density = next(f for f in materials["schema"]["fields"] if f["name"] == "density_kg_m3")
    assert density["constraints"]["required"] is True  # still required: the spec's rule
    upstream_validates(out)
    # an older granudb's schema: the roughness required
    roughness.setdefault("constraints", {})["required"] = True
    (out / "datapackage.json").write_text(json.dumps(descriptor), "utf-8")
    result = cli("dataset", "import", str(out), db=new_db)
    assert result.exit_code == 0, result.stderr
    shown = cli("materials", "show", "alumina (lab)", "--format", "json", db=new_db)
    assert shown.exit_code == 0, shown.stderr
    material = json.loads(shown.stdout)
    assert material["roughness_rms_m"] is None and material["density_kg_m3"] == 4000


#: Conditions with what a CSV must quote (comma, quotes) and what is not ASCII.
CONDITIONS = 'E by ultrasonic pulse-echo at 20 °C, "as received"; σ from SEM images'


def test_conditions_round_trip_through_a_package_byte_for_byte(
    cli, db: str, new_db: str, tmp_path: Path
) -> None:
    """A material's and a fluid's conditions travel in the package (an optional string
    column the upstream validator accepts), are imported exactly, and a second export
    writes the same bytes."""
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    for where in (db, new_db):  # the receiver's seeded entries must agree to merge
        for kind, name in (("materials", "steel"), ("fluids", "glycerol-37")):
            changed = cli(kind, "update", name, "--conditions", CONDITIONS, db=where)
            assert changed.exit_code == 0, changed.stderr
    first = tmp_path / "one"
    assert cli("dataset", "export", "example", "--output", str(first), db=db).exit_code == 0
    descriptor = json.loads((first / "datapackage.json").read_text("utf-8"))
    for resource in descriptor["resources"]:
        if resource["name"] in ("materials", "fluids"):
            field = next(f for f in resource["schema"]["fields"] if f["name"] == "conditions")
            assert field["type"] == "string"
            assert field["constraints"] == {"maxLength": 1000}  # optional, one line
    upstream_validates(first)
    imported = cli("dataset", "import", str(first), db=new_db)
    assert imported.exit_code == 0, imported.stderr
    shown = json.loads(cli("fluids", "show", "glycerol-37", "--format", "json", db=new_db).stdout)
    assert shown["conditions"] == CONDITIONS
    second = tmp_path / "two"
    assert cli("dataset", "export", "example", "--output", str(second), db=new_db).exit_code == 0
    for name in ("materials", "fluids"):
        written = (first / "data" / f"{name}.csv").read_bytes()
        assert CONDITIONS.replace('"', '""').encode("utf-8") in written
        assert written == (second / "data" / f"{name}.csv").read_bytes()


def test_a_line_break_in_conditions_refuses_the_package_in_one_line(
    cli, db: str, new_db: str, tmp_path: Path
) -> None:
    """Conditions are one line in a package as on the command line: a tab in one is
    refused, naming the table, the column and the rule, and nothing is imported."""
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db).exit_code == 0
    for where in (db, new_db):
        assert (
            cli("materials", "update", "steel", "--conditions", "at 20 °C", db=where).exit_code == 0
        )
    out = tmp_path / "pkg"
    assert cli("dataset", "export", "example", "--output", str(out), db=db).exit_code == 0
    descriptor = json.loads((out / "datapackage.json").read_text("utf-8"))
    resource = next(r for r in descriptor["resources"] if r["name"] == "materials")
    path = out / resource["path"]
    payload = path.read_bytes().replace("at 20 °C".encode(), "at\t20 °C".encode())
    path.write_bytes(payload)
    resource["bytes"] = len(payload)
    resource["hash"] = "sha256:" + hashlib.sha256(payload).hexdigest()
    (out / "datapackage.json").write_text(json.dumps(descriptor), "utf-8")
    before = dump_hash(new_db)
    refused = cli("dataset", "import", str(out), db=new_db)
    assert refused.exit_code != 0
    assert "materials.conditions" in refused.stderr and "U+0009" in refused.stderr
    assert "Traceback" not in refused.stderr
    assert dump_hash(new_db) == before
    assert len(refused.stderr.strip().splitlines()) == 1, refused.stderr
