"""The documentation is the project's own and covers the whole API: docs/api.md documents
every public function, the physics page has every section the code cites, and nothing in
the product points to a document outside the repository."""

from __future__ import annotations

import re
from pathlib import Path

from granudb import api

REPO = Path(__file__).resolve().parent.parent
DOCS = REPO / "docs"


def test_the_api_page_documents_every_public_name() -> None:
    page = (DOCS / "api.md").read_text(encoding="utf-8")
    documented = set(re.findall(r"^::: granudb\.api\.(\w+)\.(\w+)$", page, re.MULTILINE))
    expected = {(module, name) for name, module in api.NAMES.items() if name != "__version__"}
    assert documented == expected


def test_every_section_the_code_cites_is_on_the_physics_page() -> None:
    headings = set(
        re.findall(r"^## (\d+)\. ", (DOCS / "physics.md").read_text("utf-8"), re.MULTILINE)
    )
    cited = set()
    for path in (REPO / "granudb").rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        for match in re.finditer(r"physics\.md (?:§|section )([\d§, –\-]+)", text):
            cited |= set(re.findall(r"\d+", match.group(1)))
    assert cited and cited <= headings, sorted(cited - headings)


def test_nothing_in_the_product_points_outside_the_repository() -> None:
    offences = []
    for folder in ("granudb", "docs"):
        for path in (REPO / folder).rglob("*"):
            if path.suffix not in {".py", ".md", ".j2", ".toml", ".yml", ".json", ".csv"}:
                continue
            text = path.read_text(encoding="utf-8")
            if "PHYSICS.md" in text or "../shared" in text:
                offences.append(str(path.relative_to(REPO)))
    assert offences == []
