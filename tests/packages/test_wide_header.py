"""A package whose header is a million columns wide (issue 35) is refused in one line
with a bounded cost: its header line is read with the bound of a CSV file's header
(16 KiB, 200 columns) before pandas parses anything. Memory is measured in a subprocess
(its peak resident size, ``VmHWM``: ``ru_maxrss`` would carry the pytest parent's
peak across fork and exec), beside the same validation of the unchanged
package in the same run, never wall time in a unit test."""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path

import pytest

#: Validates the package argv[1] and prints its problems and its peak resident size (MB).
MEASURE = """
import json, re, sys
from pathlib import Path
from granudb.io.package_import import validate_package
problems = validate_package(Path(sys.argv[1]), keep_collisions=False).problems
status = Path("/proc/self/status").read_text()
peak = int(re.search(r"VmHWM:\\s*(\\d+) kB", status).group(1)) / 1024
print(json.dumps({"problems": problems, "peak_mb": peak}))
"""


def _measured(package: Path) -> dict:
    done = subprocess.run(
        [sys.executable, "-c", MEASURE, str(package)], capture_output=True, text=True, timeout=600
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def _widen(package: Path, columns: int) -> int:
    """The collisions header made ``columns`` wider (size and hash fixed)."""
    path = package / "data" / "collisions.csv"
    header, rest = path.read_bytes().split(b"\n", 1)
    data = header + b"," + b",".join(b"c%d" % i for i in range(columns)) + b"\n" + rest
    path.write_bytes(data)
    descriptor = json.loads((package / "datapackage.json").read_text("utf-8"))
    descriptor.pop("granudb:content_hash", None)
    entry = next(r for r in descriptor["resources"] if r["name"] == "collisions")
    entry["bytes"], entry["hash"] = len(data), "sha256:" + hashlib.sha256(data).hexdigest()
    (package / "datapackage.json").write_text(json.dumps(descriptor), encoding="utf-8")
    return len(data)


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs Linux /proc")
def test_a_million_column_header_is_refused_within_200_mb(package: Path) -> None:
    plain = _measured(package)
    assert plain["problems"] == []
    assert _widen(package, 1_000_000) > 7_000_000
    wide = _measured(package)
    assert wide["problems"] == [
        "collisions: collisions.csv has a header line longer than 16,384 bytes "
        "(a header has at most 200 columns)"
    ]
    assert wide["peak_mb"] < 200, (wide, plain)
    # less than validating the unchanged package: refused before pandas is imported
    assert wide["peak_mb"] < plain["peak_mb"], (wide, plain)
