"""``NAME@VERSION`` splits one way: ``@`` is refused in new dataset names and versions
(from a file, a package and a new version alike), so ``lab@2024`` can only mean version
2024 of ``lab``."""

from __future__ import annotations

from pathlib import Path

import pytest

import granudb
from granudb.errors import ValidationError

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"


def test_a_new_name_or_version_with_at_is_refused(opened) -> None:
    with pytest.raises(ValidationError, match="must not contain '@'"):
        granudb.import_collisions(EXAMPLE, dataset="lab@2024", db=opened)
    with pytest.raises(ValidationError, match="must not contain '@'"):
        granudb.import_collisions(EXAMPLE, dataset="lab", version="20@24", db=opened)
    granudb.import_collisions(EXAMPLE, dataset="lab", version="2024", db=opened)
    with pytest.raises(ValidationError, match="must not contain '@'"):
        granudb.new_dataset_version("lab@2024", "2@5", db=opened)
    assert [d["name"] for d in granudb.datasets(db=opened, as_frame=False)] == ["lab"]


def test_name_at_version_means_that_version_everywhere(opened) -> None:
    granudb.import_collisions(EXAMPLE, dataset="lab", version="2024", db=opened)
    granudb.new_dataset_version("lab@2024", "2025", db=opened)
    assert granudb.dataset("lab@2024", db=opened)["version"] == "2024"
    assert granudb.diff_datasets("lab@2024", "lab@2025", db=opened) == []
    removed = granudb.remove_dataset("lab@2024", db=opened)
    assert removed and "lab@2024" in removed[0] and "12 runs" in removed[0]
    assert granudb.dataset("lab", db=opened)["version"] == "2025"


def test_a_package_cannot_bring_a_name_with_at(opened, tmp_path: Path) -> None:
    granudb.import_collisions(EXAMPLE, dataset="lab", db=opened)
    granudb.release_dataset("lab", db=opened)
    folder = tmp_path / "pkg"
    granudb.export_dataset("lab", folder, db=opened)
    with pytest.raises(ValidationError, match="must not contain '@'"):
        granudb.import_dataset(folder, as_name="other@1", db=opened)
