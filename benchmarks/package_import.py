r"""How much memory does ``granudb dataset import`` need for a large package?

Builds the same package as ``package_validate.py`` (the example dataset with its
collisions replaced by N rows, default 2,000,000; the content hash recomputed so the
import checks it), then imports it into a new SQLite database in a separate process and
prints seconds and peak RSS. The import validates in blocks keeping no collision, then
reads the collisions again block by block (50,000 rows) and inserts each, and checks the
declared content hash on the stored rows: peak memory does not grow with the row count.
Run with ``--rows`` at two sizes to see it (the script prints both when given two).

    python benchmarks/package_import.py [--rows 2000000 [200000]] [--no-hash]
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from package_validate import build, measure  # noqa: E402

BOUND_MB = 400

IMPORT = """
import granudb, sys
db = granudb.connect(sys.argv[2])
print(granudb.import_dataset(sys.argv[1], as_name="big", db=db).rows)
"""
HASH = """
import granudb, sys
db = granudb.connect(sys.argv[1])
print(granudb.dataset("big", db=db)["content_hash"])
"""


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--rows", type=int, nargs="+", default=[2_000_000])
    parser.add_argument(
        "--no-hash", action="store_true", help="declare no content hash (one import, not two)"
    )
    args = parser.parse_args()
    for rows in args.rows:
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp) / "package"
            build(folder, rows)
            target = Path(tmp) / "target.sqlite"
            if not args.no_hash:  # declare the hash the rows give: the import checks it
                measure([sys.executable, "-c", IMPORT, str(folder), str(target)])
                _, _, digest = measure([sys.executable, "-c", HASH, str(target)])
                target.unlink()
                path = folder / "datapackage.json"
                descriptor = json.loads(path.read_text(encoding="utf-8"))
                descriptor["granudb:content_hash"] = digest.strip()
                path.write_text(json.dumps(descriptor), encoding="utf-8")
            seconds, peak, out = measure([sys.executable, "-c", IMPORT, str(folder), str(target)])
            assert int(out.strip()) == rows, out
            size = (folder / "data" / "collisions.csv").stat().st_size / 1e6
            verdict = "pass" if peak < BOUND_MB else "FAIL"
            checked = "no hash declared" if args.no_hash else "hash checked"
            print(
                f"import of {rows:,} collisions ({size:.0f} MB CSV, {checked}): "
                f"{seconds:.1f} s, {peak:.0f} MB peak; bound {BOUND_MB} MB: {verdict}"
            )
    print(f"load average: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
