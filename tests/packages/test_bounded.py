"""Bounded everything (issue 25): problem lists capped with a count, names granudb builds
within its own rules (and its exports importable again), deep JSON and unit bombs refused
in one line at bounded cost, a full file size limit during any output one line naming the
path with nothing left behind, and a killed package import leaving the database as it was.
"""

from __future__ import annotations

import hashlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from support import dump_hash


def _one_line(result, *expected: str) -> str:
    assert result.exit_code == 1, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr[:2000]
    assert lines[0].startswith("Error: ") and "internal error" not in lines[0]
    for text in expected:
        assert text in lines[0], lines[0]
    return lines[0]


def _descriptor(package: Path) -> dict:
    return json.loads((package / "datapackage.json").read_text("utf-8"))


def _save(package: Path, descriptor: dict) -> None:
    text = json.dumps(descriptor, separators=(",", ":"))
    (package / "datapackage.json").write_text(text, encoding="utf-8")


def _rewrite(package: Path, resource_name: str, change) -> None:
    """Change a resource's CSV text and fix its size and hash (and drop the content hash),
    so that what the test changed is what is judged."""
    path = package / "data" / f"{resource_name}.csv"
    data = change(path.read_text("utf-8")).encode("utf-8")
    path.write_bytes(data)
    descriptor = _descriptor(package)
    descriptor.pop("granudb:content_hash", None)
    entry = next(r for r in descriptor["resources"] if r["name"] == resource_name)
    entry["bytes"] = len(data)
    entry["hash"] = "sha256:" + hashlib.sha256(data).hexdigest()
    _save(package, descriptor)


def test_fifty_thousand_junk_resources_print_twenty_lines_and_a_count(
    cli, db: str, package: Path
) -> None:
    descriptor = _descriptor(package)
    descriptor["resources"] += [{"name": f"j{i}"} for i in range(50_000)]
    _save(package, descriptor)
    result = cli("dataset", "validate", str(package))
    assert result.exit_code == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) <= 22, len(lines)
    assert "… and 49980 more problems" in lines[-2], lines[-2:]
    assert "(and 49999 more)" in lines[-1]
    before = dump_hash(db)
    _one_line(cli("dataset", "import", str(package), db=db), "and 49999 more")
    assert dump_hash(db) == before


def test_many_bad_rows_are_counted_once_per_problem(cli, package: Path) -> None:
    """A problem in rows of many blocks is one problem naming its first rows and count."""
    from granudb.io import package_import

    lines = (package / "data" / "collisions.csv").read_text("utf-8").splitlines()
    header, row = lines[0], lines[1]
    after_particle = row.split(",", 2)[2]
    rows = package_import.CHUNK_ROWS * 2 + 7
    body = "".join(f"x{i},nosuch,{after_particle}\n" for i in range(rows))
    _rewrite(package, "collisions", lambda _: header + "\n" + body)
    import granudb

    result = granudb.validate_dataset(package)
    assert result.counts["collisions"] == rows
    dangling = [p for p in result.problems if "'nosuch'" in p]
    assert len(dangling) == 1, result.problems
    assert f"rows 2, 3, 4, 5, 6 and {rows - 5} more" in dangling[0]


def test_duplicate_runs_across_blocks_are_found(package: Path) -> None:
    import granudb
    from granudb.io import package_import

    lines = (package / "data" / "collisions.csv").read_text("utf-8").splitlines()
    header, row = lines[0], lines[1]
    rest = row.split(",", 1)[1]
    rows = package_import.CHUNK_ROWS + 10
    body = [f"r{i},{rest}" for i in range(rows)]
    body[-1] = body[3]  # the same run label in the second block as in the first
    _rewrite(package, "collisions", lambda _: "\n".join([header, *body]) + "\n")
    result = granudb.validate_dataset(package)
    assert result.problems == [f"collisions: duplicate run in row {rows + 1}"]


def _long_names(package: Path, material: str, package_name: str) -> None:
    _rewrite(package, "materials", lambda t: t.replace("\nglass,", f"\n{material},"))
    _rewrite(package, "collisions", lambda t: t.replace(",glass,", f",{material},"))
    descriptor = _descriptor(package)
    descriptor["name"] = package_name
    _save(package, descriptor)


def test_rename_conflicts_builds_names_within_the_rule_and_its_export_imports(
    cli, db: str, new_db: str, package: Path, tmp_path: Path
) -> None:
    long_material, long_package = "g" * 200, "p" * 200
    _long_names(package, long_material, long_package)
    assert cli("dataset", "import", str(package), "--as", "first", db=db).exit_code == 0
    changed = cli("materials", "update", long_material, "--roughness", "0.2 um", db=db)
    assert changed.exit_code == 0, changed.stderr
    for name in ("second", "third"):  # the second rename needs a number too
        done = cli("dataset", "import", str(package), "--as", name, "--rename-conflicts", db=db)
        assert done.exit_code == 0, done.stderr
    names = [m["name"] for m in json.loads(cli("materials", "list", "--format", "json",
                                              db=db).stdout)]  # fmt: skip
    renamed = [n for n in names if n.startswith("g" * 50) and n != long_material]
    assert len(renamed) == 2 and all(len(n) <= 200 for n in renamed), [len(n) for n in renamed]
    assert len(set(renamed)) == 2
    out = tmp_path / "again"
    assert cli("dataset", "export", "third", "--output", str(out), db=db).exit_code == 0
    assert cli("dataset", "validate", str(out)).exit_code == 0
    again = cli("dataset", "import", str(out), db=new_db)
    assert again.exit_code == 0, again.stderr


def test_authors_json_nested_five_thousand_deep_is_one_line(cli, db: str, package: Path) -> None:
    before = dump_hash(db)
    deep = "[" * 5000 + "]" * 5000
    _one_line(cli("dataset", "edit", "example", "--authors-json", deep, db=db), "authors")
    deep_objects = '{"a":' * 5000 + "1" + "}" * 5000
    _one_line(cli("dataset", "edit", "example", "--authors-json", deep_objects, db=db), "authors")
    assert dump_hash(db) == before


UNIT_BOMBS = [
    "m**(9**9**9)",
    "m^999999999999",
    "((((m^99)^99)^99)^99)^99",
    "m**1e308",
    "m^-1e999",
    "10**9**9**9 m",
    "m" + "*m" * 5000,
    "(" * 3000 + "m" + ")" * 3000,
    "m**(" * 500 + "2" + ")" * 500,
]


@pytest.mark.parametrize("unit", UNIT_BOMBS, ids=range(len(UNIT_BOMBS)))
def test_unit_bombs_in_a_schema_are_refused_at_bounded_cost(
    cli, db: str, package: Path, unit: str
) -> None:
    descriptor = _descriptor(package)
    collisions = next(r for r in descriptor["resources"] if r["name"] == "collisions")
    field = next(f for f in collisions["schema"]["fields"] if f["name"] == "diameter_m")
    field["unit"] = unit
    _save(package, descriptor)
    before = dump_hash(db)
    started = time.process_time()
    line = _one_line(cli("dataset", "import", str(package), db=db), "collisions.diameter_m")
    assert "unit" in line
    # bounded: the whole import refusal costs about what a valid package does (a power
    # bomb evaluated would take tens of seconds or never end)
    assert time.process_time() - started < 10
    assert dump_hash(db) == before


# --- every failure a refusal: a file size limit (RLIMIT_FSIZE) during any output ---------

LIMITED = """
import resource, signal, sys
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG
limit, folder = int(sys.argv[1]), sys.argv[2]

def limit_output(event, args):
    # the limit starts when the first file in the output folder is opened: the database
    # (and Python's start-up) are read without it, as on a disk that filled meanwhile
    if event == "open" and str(args[0]).startswith(folder):
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

sys.addaudithook(limit_output)
from granudb.cli.main import main
sys.argv = ["granudb", *sys.argv[3:]]
main()
"""


def _limited(limit: int, out: Path, *argv: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", LIMITED, str(limit), str(out), *argv],
        capture_output=True,
        text=True,
        timeout=300,
    )


def _listing(folder: Path) -> list[str]:
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*"))


@pytest.mark.sqlite_only
@pytest.mark.parametrize(
    "argv",
    [
        ["report", "--dataset", "example", "--format", "html", "--output", "{out}/r.html"],
        ["report", "--dataset", "example", "--format", "md", "--output", "{out}/r.md"],
        ["dataset", "export", "example", "--output", "{out}/e.zip"],
        ["dataset", "export", "example", "--output", "{out}/folder"],
        ["dem", "export", "--code", "liggghts", "--particle", "steel", "--particle", "glass",
         "--wall", "Zerodur", "--diameter", "12.7 mm", "--velocity", "0.3 m/s",
         "--output", "{out}/deck.in"],
    ],
    ids=["report-html", "report-md", "export-zip", "export-folder", "dem-deck"],
)  # fmt: skip
def test_a_file_size_limit_during_output_is_one_line_and_leaves_nothing(
    cli, db: str, package: Path, tmp_path: Path, argv: list[str]
) -> None:
    out = tmp_path / "out"
    out.mkdir()
    args = [a.replace("{out}", str(out)) for a in argv] + ["--db", db]
    full = _limited(10**9, out, *args)  # the same command without the limit writes its output
    assert full.returncode == 0, full.stderr
    written = max(p.stat().st_size for p in out.rglob("*") if p.is_file())
    for p in sorted(out.rglob("*"), reverse=True):
        p.unlink() if p.is_file() else p.rmdir()
    before, listing = dump_hash(db), _listing(out)
    limited = _limited(written // 2, out, *args)
    assert limited.returncode == 1, (limited.stdout, limited.stderr)
    lines = limited.stderr.strip().splitlines()
    assert len(lines) == 1 and "internal error" not in lines[0], limited.stderr
    assert "File too large" in lines[0] and str(out) in lines[0], lines[0]
    assert _listing(out) == listing == []
    assert dump_hash(db) == before


# --- SIGKILL during a package import ------------------------------------------------------


@pytest.mark.sqlite_only
def test_sigkill_during_a_package_import_leaves_the_database_as_before(
    db: str, package: Path
) -> None:
    import sqlite3

    lines = (package / "data" / "collisions.csv").read_text("utf-8").splitlines()
    header, rest = lines[0], [line.split(",", 1)[1] for line in lines[1:]]
    rows = 300_000
    body = "".join(f"k{i},{rest[i % len(rest)]}\n" for i in range(rows))
    _rewrite(package, "collisions", lambda _: header + "\n" + body)
    before = dump_hash(db)
    command = [sys.executable, "-m", "granudb", "dataset", "import", str(package)]
    command += ["--as", "big", "--db", db]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    wal = Path(db + "-wal")
    deadline = time.time() + 240
    while time.time() < deadline and process.poll() is None:
        if wal.exists() and wal.stat().st_size > 2_000_000:
            break
        time.sleep(0.02)
    assert process.poll() is None, process.communicate()
    os.kill(process.pid, signal.SIGKILL)
    process.wait(timeout=30)
    with sqlite3.connect(db) as connection:
        assert connection.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    assert dump_hash(db) == before
    again = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert again.returncode == 0, again.stderr
    with sqlite3.connect(db) as connection:
        assert connection.execute("SELECT count(*) FROM collisions").fetchone()[0] == rows + 12
