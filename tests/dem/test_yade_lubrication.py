"""Yade's lubrication law against granudb's e(St): the figures a wet Yade fragment states
(``yade.LUBRICATION_MEASURED``) are the ones tools/yade_lubrication.py measures, against
the curve ``pair`` and the reports use."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest
from dem.dem_cases import dry_model, require, wet_model

from granudb.dem import yade

_SPEC = importlib.util.spec_from_file_location(
    "yade_lubrication", Path(__file__).resolve().parents[2] / "tools" / "yade_lubrication.py"
)
assert _SPEC is not None and _SPEC.loader is not None
lubrication = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(lubrication)


def test_the_stated_curve_is_granudbs() -> None:
    """Each St_am's e(St) in the stated table is the prediction's, for every material and
    fluid measured; and the stated gap is beyond the tolerance at every St."""
    for case in lubrication.cases():
        stated = yade.LUBRICATION_MEASURED[int(case["St"])][2]
        assert case["law"] == pytest.approx(stated, abs=5e-4), case
    for wall, sphere, law in yade.LUBRICATION_MEASURED.values():
        assert min(abs(e - law) for e in (*wall, *sphere)) > 0.03


def test_a_wet_fragment_says_why_it_holds_e_constant() -> None:
    wet, dry = yade.write(wet_model("glycerol78")), yade.write(dry_model())
    assert "lubrication law" in wet and "NOT exported" in wet
    assert "St_am 2000: 0.990-0.991 (wall), 0.995 (sphere) for e(St) 0.953" in " ".join(
        line.removeprefix("# ") for line in wet.splitlines()
    )
    assert "lubrication" not in dry


@pytest.mark.dem_run
def test_yade_gives_the_stated_figures() -> None:
    """Glass in 78 % glycerol at St_am = 200 (2.2 m/s), against a wall and a sphere: Yade's
    e is the stated one (the full table takes minutes: python tools/yade_lubrication.py)."""
    require("yade")
    todo = [
        c
        for c in lubrication.cases()
        if (c["material"], c["fluid"], c["St"]) == ("glass", "glycerol-78", 200.0)
    ]
    assert len(todo) == 2
    for case, e in zip(todo, lubrication.measure(todo), strict=True):
        wall, sphere, _ = yade.LUBRICATION_MEASURED[200]
        low, high = wall if case["wall"] else sphere
        assert low - 0.002 <= e <= high + 0.002, (case["wall"], e)
