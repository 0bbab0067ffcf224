"""Write the validation gallery: docs/reference/<dataset>.md and its SVG figures.

Run from the repository root: ``python tools/build_reference_docs.py [OUT_DIR]``. Each
page renders what ``granudb.reference_show`` and ``granudb.reference_reproduce`` return
(``granudb.reporting.reference_gallery``); ``tests/reference/test_gallery.py`` rebuilds the
pages into a temporary folder and checks the committed ones are the same.
"""

from __future__ import annotations

import sys
from pathlib import Path

import granudb
from granudb.reporting import reference_gallery

ROOT = Path(__file__).resolve().parent.parent


def build(out: Path) -> list[str]:
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for entry in granudb.reference_list():
        name = entry["name"]
        text, figures = reference_gallery.page(
            granudb.reference_show(name), granudb.reference_reproduce(name)
        )
        (out / f"{name}.md").write_text(text, encoding="utf-8")
        written.append(f"{name}.md")
        for file, svg in figures.items():
            (out / file).write_text(svg, encoding="utf-8")
            written.append(file)
    return written


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "docs" / "reference"
    print("\n".join(build(target)))
