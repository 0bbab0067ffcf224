"""Opening a Data Package safely: its folder or zip, and its ``datapackage.json``.

Nothing from a package is trusted. Zip entries are checked before anything is extracted
(paths stay inside the package, no links, no encryption, no entry twice, bounded sizes and
compression ratios); the descriptor is bounded in size and nesting, and a key written
twice in one JSON object is refused, because other tools keep the first value where
Python's ``json`` keeps the last, and the two would then read different packages. Every
problem is a ``PackageError`` naming the path or field: one line, never a traceback.
"""

from __future__ import annotations

import hashlib
import json
import shutil
import stat
import tempfile
import zipfile
import zlib
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path, PurePosixPath
from typing import Any

from granudb.errors import PackageError

MAX_DESCRIPTOR_BYTES = 1_000_000
MAX_DESCRIPTOR_DEPTH = 32
MAX_RESOURCE_BYTES = 2_000_000_000
MAX_PACKAGE_BYTES = 4_000_000_000
MAX_ZIP_ENTRIES = 100
MAX_COMPRESSION_RATIO = 200  # a zip bomb expands thousands of times


def safe_relative(path: object) -> PurePosixPath | None:
    """A resource path as a safe relative path, or None when it may escape the package."""
    if not isinstance(path, str) or not path or len(path) > 500:
        return None
    if "://" in path or path.startswith(("/", "\\", "~")) or "\\" in path or ":" in path:
        return None
    pure = PurePosixPath(path)
    if any(part in {"..", ""} for part in pure.parts) or "\x00" in path:
        return None
    return pure


def _check_entry(entry: zipfile.ZipInfo, seen: set[str]) -> None:
    name = entry.filename
    if safe_relative(name.rstrip("/")) is None:
        raise PackageError([f"zip: entry {name!r} would be written outside the package folder"])
    if entry.flag_bits & 0x1:
        raise PackageError([f"zip: entry {name!r} is encrypted; granudb reads open packages"])
    if stat.S_ISLNK(entry.external_attr >> 16):
        raise PackageError([f"zip: entry {name!r} is a symbolic link"])
    folded = name.rstrip("/").casefold()
    if folded in seen:
        raise PackageError(
            [f"zip: entry {name!r} appears twice (tools disagree about which one counts)"]
        )
    seen.add(folded)
    if entry.file_size > MAX_RESOURCE_BYTES:
        raise PackageError(
            [f"zip: entry {name!r} is {entry.file_size} bytes, more than {MAX_RESOURCE_BYTES}"]
        )
    if entry.compress_size and entry.file_size / entry.compress_size > MAX_COMPRESSION_RATIO:
        raise PackageError(
            [
                f"zip: entry {name!r} expands {entry.file_size // entry.compress_size}×: "
                "refused as a possible zip bomb"
            ]
        )


def _check_zip(archive: zipfile.ZipFile) -> None:
    entries = archive.infolist()
    if len(entries) > MAX_ZIP_ENTRIES:
        raise PackageError([f"zip: {len(entries)} entries, more than {MAX_ZIP_ENTRIES}"])
    seen: set[str] = set()
    for entry in entries:
        _check_entry(entry, seen)
    total = sum(entry.file_size for entry in entries)
    if total > MAX_PACKAGE_BYTES:
        raise PackageError([f"zip: expands to {total} bytes, more than {MAX_PACKAGE_BYTES}"])


def _extract(archive: zipfile.ZipFile, folder: Path) -> None:
    """Extract checked entries, refusing any that is larger than its header says."""
    for entry in archive.infolist():
        target = folder / entry.filename
        if entry.is_dir():
            target.mkdir(parents=True, exist_ok=True)
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        written = 0
        with archive.open(entry) as source, target.open("wb") as sink:
            while chunk := source.read(1 << 20):
                written += len(chunk)
                if written > entry.file_size:
                    raise PackageError(
                        [f"zip: entry {entry.filename!r} is larger than its header says"]
                    )
                sink.write(chunk)


@contextmanager
def package_root(path: Path) -> Iterator[Path]:
    """The folder holding ``datapackage.json``: the folder itself, or a checked zip
    extracted into a temporary folder (removed afterwards)."""
    path = Path(path)
    if path.is_dir():
        yield path
        return
    if path.name == "datapackage.json" and path.is_file():
        yield path.parent
        return
    if not path.exists():
        raise PackageError([f"{path} does not exist"])
    if not path.is_file():  # a pipe or device would block or never end
        raise PackageError([f"{path} is not a folder, a datapackage.json or a zip file"])
    try:
        with path.open("rb"):
            pass
        is_zip = zipfile.is_zipfile(path)
    except OSError as exc:
        raise PackageError([f"{path}: cannot be read ({exc.strerror or exc})"]) from None
    if not is_zip:
        raise PackageError([f"{path} is not a folder, a datapackage.json or a zip file"])
    folder = Path(tempfile.mkdtemp(prefix="granudb-package-"))
    try:
        try:
            with zipfile.ZipFile(path) as archive:
                _check_zip(archive)
                _extract(archive, folder)
        except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError) as exc:
            raise PackageError([f"zip: {path} is damaged or unsupported ({exc})"]) from None
        except RuntimeError as exc:  # zipfile's "encrypted, password required"
            raise PackageError([f"zip: {path} cannot be opened ({exc})"]) from None
        except OSError as exc:
            raise PackageError([f"zip: {path} cannot be read ({exc.strerror or exc})"]) from None
        yield folder
    finally:
        shutil.rmtree(folder, ignore_errors=True)


def sha256(path: Path) -> tuple[int, str]:
    """(size, hex sha256) of a file, read in chunks."""
    digest = hashlib.sha256()
    size = 0
    with path.open("rb") as handle:
        while chunk := handle.read(1 << 20):
            size += len(chunk)
            digest.update(chunk)
    return size, digest.hexdigest()


def _no_duplicates(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    seen: dict[str, Any] = {}
    for key, value in pairs:
        if key in seen:
            raise PackageError(
                [
                    f"datapackage.json: key {key!r} appears twice in one object (tools "
                    "disagree about which value counts)"
                ]
            )
        seen[key] = value
    return seen


def _refuse_constant(name: str) -> Any:
    raise PackageError([f"datapackage.json: {name} is not valid JSON"])


def _depth(value: Any, limit: int) -> int:
    """Nesting depth of parsed JSON, stopping as soon as it exceeds ``limit``."""
    stack = [(value, 1)]
    deepest = 0
    while stack:
        item, level = stack.pop()
        deepest = max(deepest, level)
        if deepest > limit:
            return deepest
        children = (
            item.values() if isinstance(item, dict) else item if isinstance(item, list) else ()
        )
        stack.extend((child, level + 1) for child in children)
    return deepest


def read_descriptor(root: Path) -> dict[str, Any]:
    """The parsed ``datapackage.json`` of an unpacked package, or ``PackageError``."""
    path = root / "datapackage.json"
    if not path.is_file():
        raise PackageError(["datapackage.json: not found at the top of the package"])
    try:
        if path.stat().st_size > MAX_DESCRIPTOR_BYTES:
            raise PackageError([f"datapackage.json: larger than {MAX_DESCRIPTOR_BYTES} bytes"])
        text = path.read_bytes().decode("utf-8")
        descriptor = json.loads(
            text, object_pairs_hook=_no_duplicates, parse_constant=_refuse_constant
        )
    except PackageError:
        raise
    except OSError as exc:
        raise PackageError([f"{path}: cannot be read ({exc.strerror or exc})"]) from None
    except UnicodeDecodeError:
        raise PackageError(["datapackage.json: is not UTF-8 text"]) from None
    except json.JSONDecodeError as exc:
        raise PackageError(
            [f"datapackage.json: is not valid JSON ({exc.msg} at line {exc.lineno})"]
        ) from None
    except RecursionError:
        raise PackageError(["datapackage.json: nested too deeply"]) from None
    except ValueError as exc:  # e.g. an integer beyond Python's digit limit
        raise PackageError([f"datapackage.json: {str(exc).splitlines()[0]}"]) from None
    if _depth(descriptor, MAX_DESCRIPTOR_DEPTH) > MAX_DESCRIPTOR_DEPTH:
        raise PackageError([f"datapackage.json: nested more than {MAX_DESCRIPTOR_DEPTH} deep"])
    if not isinstance(descriptor, dict) or not isinstance(descriptor.get("resources"), list):
        raise PackageError(["datapackage.json: needs a 'resources' list"])
    return descriptor
