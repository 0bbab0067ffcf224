"""Every example in the public API's docstrings runs and prints what it says, against a
fresh seeded database (``db``) in a temporary folder (``tmp``)."""

from __future__ import annotations

import doctest
import importlib
from pathlib import Path

import pytest

from granudb import api

#: Every module of ``granudb.api`` that defines a public function.
MODULES = sorted({module for module in api.NAMES.values() if module != "errors"})
EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "collisions_example.csv"


@pytest.mark.parametrize("name", MODULES)
def test_api_docstring_examples(name: str, db: str, tmp_path: Path) -> None:
    import granudb

    module = importlib.import_module(f"granudb.api.{name}")
    opened = granudb.connect(db)
    try:
        result = doctest.testmod(
            module,
            extraglobs={"db": opened, "tmp": tmp_path, "example_csv": EXAMPLE},
            optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE,
        )
    finally:
        opened.dispose()
    assert result.attempted > 0 and result.failed == 0


def test_every_public_function_has_an_example() -> None:
    import granudb

    for name in granudb.__all__:
        value = getattr(granudb, name)
        if name == "__version__" or isinstance(value, type):  # the version, the errors
            continue
        assert ">>>" in (value.__doc__ or ""), name
