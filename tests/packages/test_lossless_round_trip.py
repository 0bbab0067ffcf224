"""A package round trip is lossless (issue 33): a dataset with two authors (ORCID,
affiliation), keywords, its own source, a licence and a DOI exports, imports into a fresh
database and exports again byte for byte, as a draft and as a release; a release comes
back a release with its version and content hash, a draft's placeholder title and
description stay placeholders; and after ``sources update`` of a source a release cites,
every file of the release's export is what it was (CITATION.cff and .zenodo.json too)."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import granudb

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
SOURCE = "joseph-hunt-2004"
AUTHORS = [
    "Doe, Jane; orcid=0000-0002-1825-0097; affiliation=Lab A",
    "Roe, Rick; orcid=0000-0001-5109-3700; affiliation=Lab B, Dept. 2",
]


def _files(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def _export(cli, db: str, folder: Path) -> dict[str, bytes]:
    done = cli("dataset", "export", "ex", "--output", str(folder), db=db)
    assert done.exit_code == 0, done.stderr
    return _files(folder)


def _tools_accept(folder: Path) -> None:
    """cffconvert and the upstream Data Package validator accept the export."""
    for name, args in (("cffconvert", ["--validate"]),
                       ("frictionless", ["validate", "datapackage.json"])):  # fmt: skip
        tool = shutil.which(name) or str(Path(sys.executable).parent / name)
        check = subprocess.run([tool, *args], cwd=folder, capture_output=True, text=True,
                               timeout=300)  # fmt: skip
        assert check.returncode == 0, (name, check.stdout[-2000:], check.stderr[-2000:])


def _dataset(cli, db: str) -> None:
    done = cli("collisions", "import", str(EXAMPLE), "--dataset", "ex", "--source", SOURCE,
               "--license", "CC-BY-4.0", db=db)  # fmt: skip
    assert done.exit_code == 0, done.stderr
    edit = ["dataset", "edit", "ex", "--keyword", "glass", "--keyword", "lubrication",
            "--doi", "10.5281/zenodo.1234567"]  # fmt: skip
    for author in AUTHORS:
        edit += ["--author", author]
    done = cli(*edit, db=db)
    assert done.exit_code == 0, done.stderr


@pytest.mark.parametrize("released", [False, True], ids=["draft", "release"])
def test_export_import_export_is_byte_identical(
    cli, db: str, new_db: str, tmp_path: Path, released: bool
) -> None:
    _dataset(cli, db)
    if released:
        assert cli("dataset", "release", "ex", db=db).exit_code == 0
    first = _export(cli, db, tmp_path / "one")
    _tools_accept(tmp_path / "one")
    done = cli("dataset", "import", str(tmp_path / "one"), db=new_db)
    assert done.exit_code == 0, done.stderr
    second = _export(cli, new_db, tmp_path / "two")
    assert sorted(first) == sorted(second)
    assert {n: b for n, b in second.items() if first[n] != b} == {}

    here, there = (granudb.dataset("ex", db=d) for d in (db, new_db))
    for field in ("version", "state", "content_hash", "license", "doi", "source", "title",
                  "description"):  # fmt: skip
        assert there[field] == here[field], field
    assert there["state"] == ("released" if released else "draft")
    assert there["title"] is None and there["description"] is None  # placeholders stay so
    descriptor = json.loads(second["datapackage.json"])
    assert descriptor["title"] == "ex"  # the placeholder a reader needs
    assert descriptor["granudb:status"] == there["state"]
    assert [a["orcid"] for a in descriptor["granudb:authors"]] == [
        "0000-0002-1825-0097", "0000-0001-5109-3700"]  # fmt: skip
    cff = second["CITATION.cff"].decode("utf-8")
    for said in ('family-names: "Roe"', 'orcid: "https://orcid.org/0000-0001-5109-3700"',
                 'affiliation: "Lab B, Dept. 2"', '"lubrication"', 'doi: "10.5281/zenodo.1234567"',
                 "references:"):  # fmt: skip
        assert said in cff, said
    # the imported release is a release: it takes no edit but a DOI
    if released:
        refused = cli("dataset", "edit", "ex", "--title", "changed", db=new_db)
        assert refused.exit_code != 0


def test_a_release_export_is_pinned_after_its_source_changes(cli, db: str, tmp_path: Path) -> None:
    _dataset(cli, db)
    assert cli("dataset", "release", "ex", db=db).exit_code == 0
    before = _export(cli, db, tmp_path / "before")
    zenodo = json.loads(before[".zenodo.json"])
    assert zenodo["related_identifiers"][0]["identifier"] == "10.1017/S002211200400919X"
    done = cli("sources", "update", SOURCE, "--doi", "10.9999/moved", "--url",
               "https://example.org/moved", "--year", "2005", db=db)  # fmt: skip
    assert done.exit_code == 0, done.stderr
    after = _export(cli, db, tmp_path / "after")
    assert {n: b for n, b in after.items() if before[n] != b} == {}
    _tools_accept(tmp_path / "after")
    # a draft of the same runs cites today's source in every file
    assert cli("dataset", "new-version", "ex", "--version", "2.0.0", db=db).exit_code == 0
    draft = _export(cli, db, tmp_path / "draft")
    for name in ("CITATION.cff", ".zenodo.json", "datapackage.json", "data/sources.csv",
                 "README.md"):  # fmt: skip
        assert b"10.9999/moved" in draft[name], name
        assert b"10.9999/moved" not in after[name], name


def test_a_bad_dataset_record_is_refused_by_name(cli, db: str, new_db: str, tmp_path) -> None:
    _dataset(cli, db)
    folder = tmp_path / "pkg"
    _export(cli, db, folder)
    path = folder / "datapackage.json"
    descriptor = json.loads(path.read_text("utf-8"))
    descriptor["granudb:authors"][1]["orcid"] = "0000-0001-5109-3701"
    descriptor["granudb:status"] = "published"
    descriptor["granudb:source"] = "nobody-1999"
    path.write_text(json.dumps(descriptor), "utf-8")
    done = cli("dataset", "validate", str(folder))
    assert done.exit_code != 0
    said = done.stdout + done.stderr
    for part in ("granudb:authors 2 orcid", "granudb:status", "granudb:source"):
        assert part in said, (part, said)
    assert cli("dataset", "import", str(folder), db=new_db).exit_code != 0
    assert "ex" not in {d["name"] for d in granudb.datasets(db=new_db, as_frame=False)}


def test_an_older_package_reads_as_before_with_placeholders_kept(
    cli, db: str, new_db: str, tmp_path: Path
) -> None:
    """A package without the dataset record (an older granudb's) imports as a draft; its
    descriptor's placeholder title and description (the name) are not taken as metadata."""
    _dataset(cli, db)
    folder = tmp_path / "pkg"
    _export(cli, db, folder)
    path = folder / "datapackage.json"
    descriptor = json.loads(path.read_text("utf-8"))
    older = {k: v for k, v in descriptor.items() if k.removeprefix("granudb:") not in
             {"status", "title", "description", "authors", "keywords", "source"}}  # fmt: skip
    older["description"] = "granudb dataset ex"  # what an older export wrote
    path.write_text(json.dumps(older, indent=2), "utf-8")
    done = cli("dataset", "import", str(folder), db=new_db)
    assert done.exit_code == 0, done.stderr
    record = granudb.dataset("ex", db=new_db)
    assert record["state"] == "draft" and record["title"] is None
    assert record["description"] is None and record["license"] == "CC-BY-4.0"
