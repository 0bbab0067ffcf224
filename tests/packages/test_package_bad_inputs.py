"""Bad packages are refused in one line (exit 1, no "internal error"), the database as it
was: descriptors, CSV cells, zip files, names and ``--as``."""

from __future__ import annotations

import hashlib
import json
import os
import zipfile
from collections.abc import Callable
from pathlib import Path

import pytest
from support import dump_hash


def _descriptor(package: Path, text: str) -> None:
    (package / "datapackage.json").write_text(text, encoding="utf-8")


def _edit(package: Path, change: Callable[[dict], None]) -> None:
    path = package / "datapackage.json"
    descriptor = json.loads(path.read_text("utf-8"))
    change(descriptor)
    path.write_text(json.dumps(descriptor), encoding="utf-8")


def _cell(package: Path, resource: str, old: str, new: str) -> None:
    """Change a CSV file and fix its size and hash, so the cell rule is what refuses."""
    path = package / "data" / f"{resource}.csv"
    data = path.read_bytes().replace(old.encode(), new.encode(), 1)
    assert data != path.read_bytes()
    path.write_bytes(data)

    def fix(descriptor: dict) -> None:
        descriptor.pop("granudb:content_hash", None)
        entry = next(r for r in descriptor["resources"] if r["name"] == resource)
        entry["bytes"] = len(data)
        entry["hash"] = "sha256:" + hashlib.sha256(data).hexdigest()

    _edit(package, fix)


def _meta(key: str, value: object) -> Callable[[Path], None]:
    return lambda p: _edit(p, lambda d: d.update({key: value}))


def _run_label(label: str) -> Callable[[Path], None]:
    return lambda p: _cell(p, "collisions", "steel-dry-1,", f"{label},")


CASES: dict[str, tuple[Callable[[Path], None], str]] = {
    "duplicate key": (
        lambda p: _descriptor(
            p, (p / "datapackage.json").read_text("utf-8").replace("{", '{"name": "x", ', 1)
        ),
        "appears twice in one object",
    ),
    "deep nesting": (lambda p: _descriptor(p, "[" * 100_000 + "]" * 100_000), "datapackage.json"),
    "nesting past limit": (
        lambda p: _descriptor(p, '{"resources": [], "x": ' + "[" * 40 + "]" * 40 + "}"),
        "nested more than",
    ),
    "huge integer": (
        lambda p: _descriptor(p, '{"resources": [], "bytes": ' + "9" * 5000 + "}"),
        "datapackage.json",
    ),
    "NaN constant": (lambda p: _descriptor(p, '{"resources": [], "x": NaN}'), "NaN"),
    "not JSON": (lambda p: _descriptor(p, "{"), "is not valid JSON"),
    "not UTF-8": (
        lambda p: (p / "datapackage.json").write_bytes(b'{"name": "\xff"}'),
        "is not UTF-8",
    ),
    "no resources": (lambda p: _descriptor(p, "{}"), "needs a 'resources' list"),
    "descriptor is a list": (lambda p: _descriptor(p, "[]"), "needs a 'resources' list"),
    "dataset name newline": (_meta("granudb:dataset", "a\nb"), "U+000A"),
    "dataset name 5000": (_meta("granudb:dataset", "x" * 5000), "at most 200"),
    "dataset name padded": (_meta("granudb:dataset", " example "), "spaces"),
    "dataset name escape": (_meta("granudb:dataset", "ex\x1b[31mample"), "U+001B"),
    "dataset name bidi": (_meta("granudb:dataset", "ex\u202eelpma"), "U+202E"),
    "dataset name zero-width": (_meta("granudb:dataset", "exa\u200bmple"), "U+200B"),
    "dataset name number": (_meta("granudb:dataset", 12), "must be a string"),
    "version newline": (_meta("version", "1\n2"), "U+000A"),
    "title CR": (_meta("title", "a\rb"), "U+000D"),
    "run escape": (_run_label("run\x1b]0;pwned\x07"), "collisions.run"),
    "run bidi": (_run_label("run\u202e1"), "U+202E"),
    "run zero-width": (_run_label("ru\u200bn"), "U+200B"),
    "run padded": (_run_label('" steel-dry-1"'), "spaces"),
    "run 5000": (_run_label("r" * 5000), "at most 200"),
    "run newline": (_run_label('"a\nb"'), "U+000A"),
    "material name newline": (
        lambda p: _cell(p, "materials", "\nglass,", '\n"gl\nass",'),
        "materials.name",
    ),
    "notes NUL": (lambda p: _cell(p, "sources", "Joseph", "Jo\x00seph"), "U+0000"),
    # a package's sources follow the rules of `granudb sources add`
    "source DOI as a link": (
        lambda p: _cell(p, "sources", ",10.1017/", ",https://doi.org/10.1017/"),
        "sources.doi: 'https://doi.org/10.1017/",
    ),
    "source URL script": (
        lambda p: _cell(p, "sources", ",https://", ",javascript://"),
        "sources.url: 'javascript://",
    ),
    "field of 50 MB": (
        lambda p: _cell(p, "sources", "Joseph", "J" * 50_000_000),
        "at most 10000 characters",
    ),
    "unknown resource name 5000": (
        lambda p: _edit(p, lambda d: d["resources"].append({"name": "z" * 5000})),
        "is not a resource granudb knows",
    ),
    "unit with huge exponent": (
        lambda p: _edit(
            p,
            lambda d: d["resources"][0]["schema"]["fields"][7].update(unit="m**(9**9**9)/s"),
        ),
        "is not 'm/s'",
    ),
    "bytes not a number": (
        lambda p: _edit(p, lambda d: d["resources"][0].update(bytes="many")),
        "bytes must be a whole number (Table Schema), not str 'many'",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_bad_package(cli, db: str, package: Path, case: str) -> None:
    change, expected = CASES[case]
    change(package)
    before = dump_hash(db)
    result = cli("dataset", "import", str(package), "--as", "other", db=db)
    _refused(result, expected)
    assert dump_hash(db) == before


def _refused(result, expected: str) -> None:
    assert result.exit_code == 1, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("Error: ") and expected in lines[0], lines[0]
    assert "internal error" not in lines[0] and "Traceback" not in result.stderr


@pytest.mark.parametrize(
    ("as_name", "expected"),
    [
        ("a\nb", "U+000A"),
        (" padded", "spaces"),
        ("x" * 5000, "at most 200"),
        ("esc\x1b[2J", "U+001B"),
        ("bidi\u202e", "U+202E"),
        ("", "must not be empty"),
    ],
)
def test_bad_as_name(cli, db: str, package: Path, as_name: str, expected: str) -> None:
    before = dump_hash(db)
    _refused(cli("dataset", "import", str(package), "--as", as_name, db=db), expected)
    assert dump_hash(db) == before


def _zip(package: Path, target: Path, tweak: Callable[[zipfile.ZipInfo], None] | None) -> Path:
    with zipfile.ZipFile(target, "w", compression=zipfile.ZIP_DEFLATED) as archive:
        for file in sorted(package.rglob("*")):
            if file.is_file():
                info = zipfile.ZipInfo(str(file.relative_to(package)))
                info.compress_type = zipfile.ZIP_DEFLATED
                if tweak is not None:
                    tweak(info)
                archive.writestr(info, file.read_bytes())
    return target


def test_encrypted_zip(cli, db: str, package: Path, tmp_path: Path) -> None:
    archive = _zip(package, tmp_path / "locked.zip", None)
    data = bytearray(archive.read_bytes())
    start = data.find(b"PK\x01\x02")  # set "encrypted" in the central directory's flags
    while start != -1:
        data[start + 8] |= 0x1
        start = data.find(b"PK\x01\x02", start + 4)
    archive.write_bytes(bytes(data))
    before = dump_hash(db)
    _refused(cli("dataset", "import", str(archive), db=db), "is encrypted")
    assert dump_hash(db) == before


def test_corrupt_zip(cli, db: str, package: Path, tmp_path: Path) -> None:
    archive = _zip(package, tmp_path / "broken.zip", None)
    data = bytearray(archive.read_bytes())
    for i in range(200, 400):
        data[i] ^= 0x5A
    archive.write_bytes(bytes(data))
    before = dump_hash(db)
    _refused(cli("dataset", "import", str(archive), db=db), "zip")
    assert dump_hash(db) == before


def test_truncated_zip(cli, db: str, package: Path, tmp_path: Path) -> None:
    archive = _zip(package, tmp_path / "cut.zip", None)
    archive.write_bytes(archive.read_bytes()[:300])
    _refused(cli("dataset", "import", str(archive), db=db), "cut.zip")


def test_duplicate_zip_entries(cli, db: str, package: Path, tmp_path: Path) -> None:
    archive = _zip(package, tmp_path / "twice.zip", None)
    with pytest.warns(UserWarning), zipfile.ZipFile(archive, "a") as handle:
        handle.writestr("datapackage.json", "{}")
    _refused(cli("dataset", "import", str(archive), db=db), "appears twice")


def test_fifo_is_refused_without_hanging(cli, db: str, tmp_path: Path) -> None:
    fifo = tmp_path / "pipe.zip"
    os.mkfifo(fifo)
    _refused(cli("dataset", "import", str(fifo), db=db), "pipe.zip")


def test_missing_package(cli, db: str, tmp_path: Path) -> None:
    _refused(cli("dataset", "import", str(tmp_path / "nope.zip"), db=db), "does not exist")


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads every file")
def test_unreadable_zip(cli, db: str, package: Path, tmp_path: Path) -> None:
    archive = _zip(package, tmp_path / "secret.zip", None)
    archive.chmod(0)
    _refused(cli("dataset", "import", str(archive), db=db), "cannot be read")


@pytest.mark.parametrize("kind", ["zip exists", "file exists", "no folder", "not empty"])
def test_export_never_overwrites(cli, db: str, package: Path, tmp_path: Path, kind: str) -> None:
    target = {
        "zip exists": tmp_path / "out.zip",
        "file exists": tmp_path / "out.txt",
        "no folder": tmp_path / "missing" / "out.zip",
        "not empty": package,
    }[kind]
    if kind in {"zip exists", "file exists"}:
        target.write_text("keep me", encoding="utf-8")
    result = cli("dataset", "export", "example", "--output", str(target), db=db)
    _refused(result, "--output")
    if target.is_file():
        assert target.read_text("utf-8") == "keep me"
