"""Every physics docstring example runs and prints what it says."""

from __future__ import annotations

import doctest
import importlib

import pytest

MODULES = [
    "contact",
    "flow",
    "lubrication",
    "impact",
    "apparatus",
    "viscosity",
    "derive",
    "pair",
    "limits",
    "arguments",
    "reported",
]


@pytest.mark.parametrize("name", MODULES)
def test_docstring_examples(name: str) -> None:
    module = importlib.import_module(f"granudb.physics.{name}")
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0
    if name != "derive":
        assert result.attempted > 0
