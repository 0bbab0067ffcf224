"""A released dataset never changes (issue 25): after a release, every catalogue value it
uses is edited — materials, the fluid, its points, a rename, a re-seed — and the release's
package bytes, content hash, report numbers and DEM deck are the same, while a draft that
uses the same materials follows the edits."""

from __future__ import annotations

import hashlib
import io
import zipfile
from pathlib import Path

import pytest
from support import release_ptfe_runs

import granudb
from granudb.errors import ConflictError

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
DECK = {"diameter": "12.7 mm", "velocity": "0.3 m/s", "values": "dataset"}


def _package(database, name: str, tmp_path: Path, tag: str) -> dict[str, bytes]:
    exported = granudb.export_dataset(name, tmp_path / f"{tag}.zip", db=database)
    with zipfile.ZipFile(io.BytesIO(Path(exported.path).read_bytes())) as archive:
        return {n: archive.read(n) for n in archive.namelist()}


def _state(database, name: str, tmp_path: Path, tag: str) -> dict[str, object]:
    package = _package(database, name, tmp_path, tag)
    runs = granudb.collisions(dataset=name, db=database, as_frame=False, wide=True)
    deck = granudb.dem_export(
        "liggghts", ["steel"], ["Zerodur"], fluid="glycerol-37", dataset=name, db=database,
        **DECK,
    )  # fmt: skip
    report = granudb.report(dataset=name, format="md", db=database)
    # the note on what the release pins that the catalogue has changed since is
    # tests/safety/test_pinned_notes.py's; every other line stays the same
    pinned = {f"- {line}" for line in granudb.dataset(name, db=database)["pinned_changes"]}
    kept = [
        line for line in report.splitlines()
        if line.strip() and "Generated" not in line and line not in pinned
        and "**Pinned values:**" not in line
    ]  # fmt: skip
    return {
        "report": kept,
        "package": {k: hashlib.sha256(v).hexdigest() for k, v in package.items()},
        "hash": granudb.dataset(name, db=database)["content_hash"],
        "derived": [
            (r["run"], r["reduced_modulus_pa"], repr(r["normal_stokes_number"])) for r in runs
        ],
        "deck": deck.split("\n", 3)[-1],  # after the header's date-free lines
    }


def test_a_release_keeps_the_values_it_used(opened, tmp_path: Path) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=opened)
    granudb.release_dataset("rel", db=opened)
    granudb.import_collisions(EXAMPLE, dataset="draft", db=opened)
    before = _state(opened, "rel", tmp_path, "before")
    draft_before = granudb.collisions(dataset="draft", db=opened, as_frame=False, wide=True)

    granudb.update_material("steel", youngs_modulus="100 GPa", roughness="50 nm", db=opened)
    granudb.update_material("Zerodur", density="2600 kg/m^3", db=opened)
    granudb.update_material("glass", youngs_modulus="70 GPa", db=opened)
    for fluid in ("glycerol-37", "water"):
        granudb.update_fluid(fluid, reference_viscosity="10 mPa*s", db=opened)
    granudb.add_fluid_point("glycerol-37", temperature="33 degC", viscosity="2 cP",
                            replace=True, db=opened)  # fmt: skip
    granudb.update_material("steel", rename="steel-AISI-52100", db=opened)
    granudb.update_material("steel-AISI-52100", rename="steel", db=opened)

    after = _state(opened, "rel", tmp_path, "after")
    assert after == before
    draft_after = granudb.collisions(dataset="draft", db=opened, as_frame=False, wide=True)
    assert [r["reduced_modulus_pa"] for r in draft_after] != [
        r["reduced_modulus_pa"] for r in draft_before
    ]
    listed = granudb.materials(db=opened, as_frame=False)
    assert [m["name"] for m in listed].count("steel") == 1
    steel = granudb.material("steel", db=opened)
    assert steel["youngs_modulus_pa"] == pytest.approx(100e9)


def test_a_new_version_of_a_release_follows_the_live_catalogue(opened, tmp_path) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=opened)
    granudb.release_dataset("rel", db=opened)
    granudb.update_material("steel", youngs_modulus="100 GPa", db=opened)
    granudb.new_dataset_version("rel", "1.1.0", db=opened)
    old = granudb.collisions(dataset="rel", version="1.0.0", particle="steel", db=opened, wide=True,
                             as_frame=False)  # fmt: skip
    new = granudb.collisions(dataset="rel", version="1.1.0", particle="steel", db=opened, wide=True,
                             as_frame=False)  # fmt: skip
    assert old and new and len(old) == len(new)
    assert old[0]["reduced_modulus_pa"] != new[0]["reduced_modulus_pa"]


def test_a_material_a_release_keeps_cannot_be_removed(opened, tmp_path) -> None:
    release_ptfe_runs(opened, tmp_path, EXAMPLE)
    granudb.update_material("PTFE", roughness="0.3 um", db=opened)
    with pytest.raises(ConflictError, match="a release never changes"):
        granudb.remove_material("PTFE", db=opened)


def test_history_shows_what_a_release_keeps(opened, cli, db) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=opened)
    granudb.release_dataset("rel", db=opened)
    granudb.update_material("steel", youngs_modulus="200 GPa", db=opened)
    history = granudb.material_history("steel", db=opened)
    assert [r["revision"] for r in history] == ["current", "1"]
    assert history[0]["youngs_modulus_pa"] == pytest.approx(200e9) and history[0]["used_by"] == ""
    assert history[1]["youngs_modulus_pa"] == pytest.approx(190e9)
    assert history[1]["used_by"].startswith("rel@1.0.0 (") and history[1]["kept_at"]
    table = cli("materials", "history", "steel", db=db)
    assert table.exit_code == 0 and "current" in table.stdout and "rel@1.0.0" in table.stdout
