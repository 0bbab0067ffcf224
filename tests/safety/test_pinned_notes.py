"""What a release pins that today's catalogue has changed (issue 25): one line per value,
computed once (``granudb.db.catalog_differences``) and said alike by ``dataset
show|list|diff|export``, reports, DEM decks with ``--values dataset`` and run listings;
``dataset diff`` across catalogue revisions."""

from __future__ import annotations

import json
import logging
import re
from pathlib import Path

import pytest
from support import release_ptfe_runs

import granudb

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
DECK = {"diameter": "12.7 mm", "velocity": "0.3 m/s", "values": "dataset"}


def _release_then_edit(database) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=database)
    granudb.release_dataset("rel", db=database)
    granudb.update_material("steel", youngs_modulus="100 GPa", db=database)
    granudb.update_fluid("glycerol-37", reference_viscosity="10 mPa*s", db=database)
    granudb.add_fluid_point("glycerol-37", temperature="33 degC", viscosity="2 cP",
                            replace=True, db=database)  # fmt: skip


def _report_lines(report: str) -> list[str]:
    """The Markdown report's "Pinned values" list."""
    section = report.split("**Pinned values:**", 1)[1].split("\n\n", 2)[1]
    return [line[2:] for line in section.splitlines()]


def test_every_output_says_the_same_pinned_values(opened, db, cli, tmp_path, caplog) -> None:
    _release_then_edit(opened)
    shown = granudb.dataset("rel", db=opened)["pinned_changes"]
    assert len(shown) == 3, shown
    steel = next(line for line in shown if line.startswith("steel youngs_modulus_pa"))
    assert re.fullmatch(
        r"steel youngs_modulus_pa: release pins 190 GPa \(revision 1, kept \d{4}-\d\d-\d\d "
        r"\d\d:\d\d UTC\), catalogue now 100 GPa",
        steel,
    )
    assert "glycerol-37 viscosity_pa_s at 33 °C: release pins" in "\n".join(shown)
    listed = {(r["name"], r["version"]): r for r in granudb.datasets(db=opened, as_frame=False)}
    exported = granudb.export_dataset("rel", tmp_path / "rel.zip", db=opened)
    against_today = [d["fields"] for d in granudb.diff_datasets("rel", db=opened)]
    report = granudb.report(dataset="rel", format="md", db=opened)
    caplog.set_level(logging.INFO, logger="granudb")
    granudb.dem_export("liggghts", ["steel"], ["Zerodur"], fluid="glycerol-37",
                       dataset="rel", db=opened, **DECK)  # fmt: skip
    assert all(r.getMessage().startswith("rel@1.0.0 pins") for r in caplog.records)
    deck_notes = [r.getMessage().split(": ", 1)[1] for r in caplog.records]
    caplog.clear()
    granudb.collisions(dataset="rel", db=opened)
    listing_notes = [r.getMessage().split(": ", 1)[1] for r in caplog.records]
    cli_json = json.loads(cli("dataset", "show", "rel", "--format", "json", db=db).stdout)
    cli_list = json.loads(cli("dataset", "list", "--format", "json", db=db).stdout)
    table = cli("dataset", "show", "rel", db=db)
    assert listed[("rel", "1.0.0")]["pinned_changes"] == shown
    assert exported.pinned_changes == shown
    assert against_today == shown
    assert _report_lines(report) == shown
    assert deck_notes == shown and listing_notes == shown
    assert cli_json["pinned_changes"] == shown
    assert next(r for r in cli_list if r["name"] == "rel")["pinned_changes"] == shown
    assert all(line in " ".join(table.stderr.split()) for line in shown)


def test_a_draft_and_an_unchanged_release_pin_nothing(opened) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=opened)
    granudb.release_dataset("rel", db=opened)
    granudb.import_collisions(EXAMPLE, dataset="draft", db=opened)
    assert granudb.dataset("rel", db=opened)["pinned_changes"] == []
    granudb.update_material("steel", youngs_modulus="100 GPa", db=opened)
    assert granudb.dataset("draft", db=opened)["pinned_changes"] == []
    assert granudb.diff_datasets("draft", db=opened) == []
    report = granudb.report(dataset="draft", format="md", db=opened)
    assert "Pinned values" not in report


def test_a_pair_value_stored_after_the_release_is_said(opened, tmp_path) -> None:
    release_ptfe_runs(opened, tmp_path, EXAMPLE)
    granudb.add_pair_value("PTFE", "Zerodur", dry_restitution=0.5, notes="lab", db=opened)
    granudb.add_pair_value("PTFE", "steel", dry_restitution=0.6, notes="lab", db=opened)
    assert granudb.dataset("ptfe", db=opened)["pinned_changes"] == [
        "PTFE on Zerodur dry_restitution: release pins (none), catalogue now 0.5"
    ]


def test_diff_across_catalogue_revisions(opened) -> None:
    granudb.import_collisions(EXAMPLE, dataset="rel", db=opened)
    granudb.release_dataset("rel", db=opened)
    granudb.update_material("steel", youngs_modulus="100 GPa", db=opened)
    granudb.new_dataset_version("rel", "1.1.0", db=opened)
    granudb.release_dataset("rel@1.1.0", db=opened)
    granudb.update_material("steel", youngs_modulus="50 GPa", db=opened)
    granudb.update_fluid("glycerol-37", reference_viscosity="10 mPa*s", db=opened)
    granudb.new_dataset_version("rel@1.1.0", "1.2.0", db=opened)

    releases = granudb.diff_datasets("rel@1.0.0", "rel@1.1.0", db=opened)
    assert releases == [
        {"change": "catalogue", "run": None,
         "fields": "steel youngs_modulus_pa: 190 GPa → 100 GPa"},
    ]  # fmt: skip
    to_draft = [d["fields"] for d in granudb.diff_datasets("rel@1.1.0", "rel@1.2.0", db=opened)]
    assert to_draft == [
        "steel youngs_modulus_pa: 100 GPa → 50 GPa",
        "glycerol-37 reference_viscosity_pa_s: 3 mPa·s → 10 mPa·s",
    ]
    # the same values as the pinned note says of 1.1.0 against today's catalogue
    pinned = granudb.dataset("rel@1.1.0", db=opened)["pinned_changes"]
    assert [re.sub(r": release pins (.*) \(revision .*\), catalogue now ", r": \1 → ", line)
            for line in pinned] == to_draft  # fmt: skip
    assert granudb.diff_datasets("rel@1.2.0", "rel@1.2.0", db=opened) == []


def test_cli_diff_says_catalogue_differences(opened, db, cli) -> None:
    _release_then_edit(opened)
    granudb.new_dataset_version("rel", "1.1.0", db=opened)
    shown = cli("dataset", "diff", "rel@1.0.0", "rel@1.1.0", db=db)
    assert shown.exit_code == 0
    assert "0 added, 0 removed, 0 changed; 3 catalogue values differ" in shown.stdout
    today = cli("dataset", "diff", "rel@1.0.0", "--format", "json", db=db)
    assert [d["fields"] for d in json.loads(today.stdout)] == granudb.dataset(
        "rel@1.0.0", db=opened
    )["pinned_changes"]


@pytest.mark.parametrize("kind", ["material", "fluid"])
def test_history_and_pinned_revision_agree(opened, kind) -> None:
    _release_then_edit(opened)
    name = "steel" if kind == "material" else "glycerol-37"
    history = getattr(granudb, f"{kind}_history")(name, db=opened)
    kept = [r for r in history if r["revision"] == "1"][0]["kept_at"]
    line = next(x for x in granudb.dataset("rel", db=opened)["pinned_changes"]
                if x.startswith(name))  # fmt: skip
    assert f"(revision 1, kept {kept:%Y-%m-%d %H:%M} UTC)" in line
