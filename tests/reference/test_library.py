"""The reference library: every package is what tools/build_reference.py writes from the
public digitisations, validates as a Data Package and a CITATION.cff, gives each value its
provenance and u, ships with an installed granudb, and says what its sources say."""

from __future__ import annotations

import csv
import fnmatch
import json
import math
import re
import runpy
import shutil
import statistics
import subprocess
import sys
import tomllib
from pathlib import Path

import frictionless
import pytest

ROOT = Path(__file__).resolve().parents[2]
LIBRARY = ROOT / "seed_data" / "reference"
NAMES = sorted(p.name for p in LIBRARY.iterdir() if (p / "datapackage.json").is_file())
PROVENANCE = ("source", "locator", "digitiser", "licence")


def _values(name: str) -> list[dict[str, str]]:
    with (LIBRARY / name / "data" / "values.csv").open(encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


def test_the_library_holds_the_five_datasets() -> None:
    assert NAMES == [
        "gondret-lance-petit-2002",
        "joseph-hunt-2004-tables",
        "joseph-hunt-2004-walberla",
        "kharaz-gorham-salman-2001",
        "vssuq-dry-collisions",
    ]


def test_committed_packages_are_what_the_builder_writes(tmp_path: Path) -> None:
    builder = runpy.run_path(str(ROOT / "tools" / "build_reference.py"))
    assert builder["build"](tmp_path) == list(builder["DATASETS"])
    written = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*") if p.is_file())
    for relative in written:
        committed = LIBRARY / relative
        assert committed.read_bytes() == (tmp_path / relative).read_bytes(), relative


@pytest.mark.parametrize("name", NAMES)
def test_each_package_validates(name: str) -> None:
    report = frictionless.validate(str(LIBRARY / name / "datapackage.json"))
    assert report.valid, report.flatten(["rowNumber", "fieldName", "type", "note"])
    tool = shutil.which("cffconvert") or str(Path(sys.executable).parent / "cffconvert")
    check = subprocess.run([tool, "--validate"], cwd=LIBRARY / name, capture_output=True, text=True)
    assert check.returncode == 0, check.stdout + check.stderr
    descriptor = json.loads((LIBRARY / name / "datapackage.json").read_text("utf-8"))
    cff = (LIBRARY / name / "CITATION.cff").read_text("utf-8")
    assert f'version: "{descriptor["version"]}"' in cff
    assert descriptor["granudb_reference"]["values"] == len(_values(name))


@pytest.mark.parametrize("name", NAMES)
def test_every_value_has_its_provenance_and_u(name: str) -> None:
    for row in _values(name):
        for column in PROVENANCE:
            assert row[column].strip(), (row["value_id"], column)
        u = float(row["u"])
        assert math.isfinite(u) and u > 0, row["value_id"]
        assert row["u_basis"], row["value_id"]
        assert row["role"] in ("measured", "derived", "condition")
        if row["role"] != "condition" and name != "joseph-hunt-2004-tables":
            # read from a public repository: which file and commit
            assert row["repository"].startswith("https://github.com/"), row["value_id"]
            assert row["file"] and len(row["commit"].split(" | ")[0]) == 40, row["value_id"]


def test_installed_granudb_ships_every_package_file() -> None:
    config = tomllib.loads((ROOT / "pyproject.toml").read_text("utf-8"))
    patterns = config["tool"]["setuptools"]["package-data"]["granudb.seed_data"]
    for path in LIBRARY.rglob("*"):
        relative = path.relative_to(ROOT / "seed_data").as_posix()
        if path.is_file() and not relative.startswith("reference/_raw/"):
            assert any(fnmatch.fnmatch(relative, p) for p in patterns), relative


def _digitisations() -> list[dict[str, str]]:
    path = LIBRARY / "kharaz-gorham-salman-2001" / "data" / "digitisations.csv"
    with path.open(encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


def test_kharaz_keeps_both_digitisations_and_their_spread_as_u() -> None:
    rows = _digitisations()
    assert {r["digitisation"] for r in rows} == {"lethe", "kratos"}
    values = {r["value_id"]: r for r in _values("kharaz-gorham-salman-2001")}
    # e_t at about 20°: Lethe reads (20.012, 0.59691), Kratos (20.218.., 0.59885..)
    lethe = next(
        r for r in rows
        if r["digitisation"] == "lethe" and r["series"] == "tangential_restitution"
        and r["incidence_angle_deg"] == "20.012"
    )  # fmt: skip
    kratos = next(
        r for r in rows
        if r["digitisation"] == "kratos" and r["series"] == "tangential_restitution"
        and r["incidence_angle_deg"].startswith("20.2")
    )  # fmt: skip
    a, b = float(lethe["value_as_written"]), float(kratos["value_as_written"])
    point = next(
        v for v in values.values()
        if v["quantity"] == "tangential_restitution" and "20.012" in v["locator"]
    )  # fmt: skip
    assert float(point["value"]) == pytest.approx((a + b) / 2, abs=1e-9)
    paired = [
        v for v in values.values()
        if v["quantity"] == "tangential_restitution" and "lethe:" in v["locator"]
        and "kratos:" in v["locator"]
    ]  # fmt: skip
    halves = []
    for v in paired:
        read = [float(y) for _, y in re.findall(r"\(([-\d.e]+), ([-\d.e]+)\)", v["locator"])]
        halves.append(abs(read[0] - read[1]) / 2)
    assert len(paired) == 7
    assert float(point["u"]) == pytest.approx(max(abs(a - b) / 2, statistics.median(halves)))
    assert "two digitisations" in point["u_basis"]


def test_kharaz_says_which_rebound_angle_is_which() -> None:
    values = _values("kharaz-gorham-salman-2001")
    centre = [v for v in values if v["quantity"] == "rebound_angle_centre_deg"]
    contact = [v for v in values if v["quantity"] == "rebound_angle_contact_deg"]
    assert centre and contact
    assert all("Lethe" in v["digitiser"] and "centre of mass" in v["notes"] for v in centre)
    assert all("Kratos" in v["digitiser"] and "contact point" in v["notes"] for v in contact)
    # the contact point recoils near 20° (negative angle); the centre of mass never does
    assert min(float(v["value"]) for v in contact) < 0 < min(float(v["value"]) for v in centre)


def test_vssuq_glass_glass_restitution_is_the_published_one() -> None:
    rows = [
        r for r in _values("vssuq-dry-collisions")
        if r["point"].startswith("epp_glass-glass-0") and r["quantity"] == "normal_restitution"
    ]  # fmt: skip
    values = [float(r["value"]) for r in rows]
    assert len(values) == 24
    assert round(statistics.mean(values), 4) == 0.9696
    assert round(statistics.stdev(values), 4) == 0.0150
    assert all(r["licence"].startswith("MIT") for r in rows)
    licence = (LIBRARY / "vssuq-dry-collisions" / "LICENSE-vssuq").read_text("utf-8")
    assert licence.startswith("MIT License")
    pairs = {(r["particle"], r["wall"]) for r in _values("vssuq-dry-collisions")}
    assert pairs == {("glass", "glass"), ("glass", "HDPE"), ("HDPE", "HDPE"), ("glass", "acrylic")}


def test_wet_cases_carry_their_conditions_and_reported_numbers() -> None:
    gondret = _values("gondret-lance-petit-2002")
    cases = {r["point"] for r in gondret}
    assert cases == {f"Case_St{n}" for n in (27, 100, 152, 192, 742)}
    for case in cases:
        quantities = {r["quantity"] for r in gondret if r["point"] == case}
        assert {"reynolds_number", "stokes_number", "dynamic_viscosity_pa_s"} <= quantities
    joseph = _values("joseph-hunt-2004-walberla")
    assert {r["fluid"] for r in joseph} == {
        "glycerol-78", "glycerol-45", "glycerol-33", "glycerol-37"
    }  # fmt: skip


def test_joseph_hunt_tables_are_the_seeded_values() -> None:
    with (ROOT / "seed_data" / "published_values.csv").open(encoding="utf-8") as f:
        seeded = [r for r in csv.DictReader(f) if r["source"] == "joseph-hunt-2004"]
    shipped = _values("joseph-hunt-2004-tables")
    assert [(r["quantity"], float(r["value"])) for r in seeded] == [
        (r["quantity"], float(r["value"])) for r in shipped
    ]
