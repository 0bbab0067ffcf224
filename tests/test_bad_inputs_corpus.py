"""The corpus in tests/bad_inputs/: every entry point refuses bad input in one line, with
a non-zero exit, no traceback, the database exactly as it was (a full dump compared), and
nothing created or changed in the working folder, where symlinks are planted as the names
an output would take (a listing compared)."""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

import pytest
from support import dump_hash

CORPUS = Path(__file__).resolve().parent / "bad_inputs"
CLI_CASES = json.loads((CORPUS / "cli_cases.json").read_text(encoding="utf-8"))
CSV_CASES = json.loads((CORPUS / "csv" / "expected.json").read_text(encoding="utf-8"))
PACKAGE_CASES = json.loads((CORPUS / "package_cases.json").read_text(encoding="utf-8"))
#: The corpus before issue 25 (CLI and CSV cases); it asks for at least 60 more.
BEFORE_ISSUE_25 = 84 + 74
#: Names an output could take, planted as dangling symlinks into a folder that must stay
#: absent: a refusal follows none of them and creates nothing.
PLANTED = ("out", "out.csv", "deck.in", "r.html", "r.html.part", "e.zip.part", "r_figures")


def _plant(folder: Path) -> Path:
    outside = folder.parent / f"{folder.name}-outside"
    for name in PLANTED:
        if not (folder / name).is_symlink():
            (folder / name).symlink_to(outside / name)
    return outside


def _listing(folder: Path) -> list[tuple]:
    """Every entry below ``folder`` (the test's database folder aside): its path, kind,
    link target, size and a hash of its bytes."""
    entries = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if Path(root, d) != folder / "db")
        for name in sorted(dirs + files):
            path = Path(root, name)
            link = os.readlink(path) if path.is_symlink() else None
            data = path.read_bytes() if path.is_file() and not link else b""
            kind = "link" if link else "dir" if path.is_dir() else "file"
            entries.append((str(path.relative_to(folder)), kind, link, len(data),
                            hashlib.sha256(data).hexdigest()))  # fmt: skip
    return entries


def _untouched(folder: Path, run) -> object:
    """``run()`` with symlinks planted in ``folder``: nothing there (or outside) changes."""
    outside = _plant(folder)
    before = _listing(folder)
    result = run()
    assert _listing(folder) == before
    assert not outside.exists()
    return result


EXAMPLES = CORPUS.parent.parent / "examples"


def _refused(result, expected: str, exit_code: int = 1) -> None:
    """One line on stderr, the exit code (1 for a refusal, 2 for a usage error), never an
    internal error or a traceback."""
    assert result.exit_code == exit_code, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("Error: ") and expected in lines[0], lines[0]
    assert "internal error" not in lines[0]
    assert "Traceback" not in result.stdout + result.stderr


def _argv(args: list[str]) -> list[str]:
    places = {"{examples}": str(EXAMPLES), "{corpus}": str(CORPUS)}
    out = []
    for arg in args:
        for key, value in places.items():
            arg = arg.replace(key, value)
        out.append(arg)
    return out


@pytest.mark.parametrize(
    "case", CLI_CASES, ids=[f"{i}-{' '.join(c['argv'][:3])}" for i, c in enumerate(CLI_CASES)]
)
def test_cli_values(cli, db: str, tmp_path: Path, monkeypatch, case: dict) -> None:
    monkeypatch.chdir(tmp_path)
    for step in case.get("setup", []):  # state the case needs (a dataset, a released one)
        done = cli(*_argv(step), db=db)
        assert done.exit_code == 0, (step, done.stderr)
    before = dump_hash(db)
    result = _untouched(tmp_path, lambda: cli(*_argv(case["argv"]), db=db))
    _refused(result, case["expect"], case.get("exit", 1))
    assert dump_hash(db) == before


@pytest.mark.parametrize("name", sorted(CSV_CASES))
def test_csv_files(cli, db: str, tmp_path: Path, monkeypatch, name: str) -> None:
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    before = dump_hash(db)
    file = str(CORPUS / "csv" / name)
    result = _untouched(work, lambda: cli("collisions", "import", file, "--dataset", "bad", db=db))
    _refused(result, CSV_CASES[name])
    assert dump_hash(db) == before


def _package(cli, db: str, folder: Path) -> Path:
    """The example dataset exported as a package folder, removed from the database again
    (so an import under its own name is not a conflict)."""
    imported = cli("collisions", "import", str(EXAMPLES / "collisions_example.csv"),
                   "--dataset", "example", db=db)  # fmt: skip
    assert imported.exit_code == 0, imported.stderr
    out = folder / "pkg"
    exported = cli("dataset", "export", "example", "--output", str(out), db=db)
    assert exported.exit_code == 0, exported.stderr
    return out


def _change_package(package: Path, case: dict) -> None:
    """A package case's change: a CSV resource's text replaced (its size and hash then
    fixed, so the cell rule is what refuses) and/or descriptor keys set."""
    descriptor_path = package / "datapackage.json"
    descriptor = json.loads(descriptor_path.read_text("utf-8"))
    for resource, old, new in case.get("replace", []):
        path = package / "data" / f"{resource}.csv"
        data = path.read_bytes()
        assert old.encode() in data, (resource, old)
        data = data.replace(old.encode(), new.encode(), 1)
        path.write_bytes(data)
        descriptor.pop("granudb:content_hash", None)
        entry = next(r for r in descriptor["resources"] if r["name"] == resource)
        entry["bytes"] = len(data)
        entry["hash"] = "sha256:" + hashlib.sha256(data).hexdigest()
    for resource, key, value in case.get("resource_keys", []):
        entry = next(r for r in descriptor["resources"] if r["name"] == resource)
        entry[key] = value
    descriptor.update(case.get("descriptor", {}))
    descriptor_path.write_text(json.dumps(descriptor), encoding="utf-8")


@pytest.mark.parametrize("name", sorted(PACKAGE_CASES))
def test_package_cases(cli, db: str, tmp_path: Path, monkeypatch, name: str) -> None:
    case = PACKAGE_CASES[name]
    package = _package(cli, db, tmp_path)
    _change_package(package, case)
    work = tmp_path / "work"
    work.mkdir()
    monkeypatch.chdir(work)
    before = dump_hash(db)
    argv = ["dataset", "import", str(package), *case.get("options", ["--as", "other"])]
    result = _untouched(work, lambda: cli(*argv, db=db))
    _refused(result, case["expect"])
    assert dump_hash(db) == before


def test_the_corpus_is_large_enough() -> None:
    assert len(CLI_CASES) + len(CSV_CASES) >= 40
    # issue 14: at least 40 more command-line cases (usage, files, consent, lifecycle)
    assert len(CLI_CASES) >= 30 + 40
    assert sum(c.get("exit") == 2 for c in CLI_CASES) >= 15
    # issue 25: at least 60 more cases across CSV files, packages and options
    assert len(CLI_CASES) + len(CSV_CASES) + len(PACKAGE_CASES) >= BEFORE_ISSUE_25 + 60


@pytest.mark.parametrize(
    "name",
    [
        "'; DROP TABLE materials; --",
        "<img src=x onerror=alert(1)>",
        "**bold** _x_ `code` | a",
        "Robert'); DELETE FROM collisions;--",
        "ümlaut ß 材料",
    ],
)
def test_hostile_strings_are_stored_and_shown_verbatim(cli, db: str, name: str) -> None:
    added = cli(
        "materials",
        "add",
        name,
        "--density",
        "1 g/cm^3",
        "--youngs-modulus",
        "1 GPa",
        "--poisson-ratio",
        "0.3",
        "--roughness",
        "1 nm",
        "--description",
        name,
        db=db,
    )
    assert added.exit_code == 0, added.stderr
    shown = json.loads(cli("materials", "show", name, "--format", "json", db=db).stdout)
    assert shown["name"] == name and shown["description"] == name
    assert {"glass", "steel", "Zerodur"} <= {
        m["name"] for m in json.loads(cli("materials", "list", "--format", "json", db=db).stdout)
    }
