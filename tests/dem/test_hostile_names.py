"""Decks no name can break (issue 26): materials named with spaces, hyphens, accents, a
leading digit or a C++ keyword, and a dataset name with LAMMPS's line-joining sequences,
give decks the real codes run to the same e as a plain name; every generated identifier
is one each code accepts, and the material's own name stays in the comments."""

from __future__ import annotations

import re

import pytest
from support import require_binary

import granudb
from granudb.dem.spec import IDENTIFIER, RESERVED

HOSTILE = ["stainless steel", "PTFE-1", "Glasä", "316L", "new"]
SCENARIO = {"diameter": "12.7 mm", "velocity": "0.3 m/s"}


@pytest.fixture
def opened(db: str):
    database = granudb.connect(db)
    steel = granudb.material("steel", db=database)
    for name in HOSTILE:
        granudb.add_material(
            name, density=steel["density_kg_m3"], youngs_modulus=steel["youngs_modulus_pa"],
            poisson_ratio=steel["poisson_ratio"], roughness=steel["roughness_rms_m"],
            db=database,
        )  # fmt: skip
    yield database
    database.dispose()


@pytest.mark.parametrize("code", ["liggghts", "lammps", "yade", "mercurydpm"])
def test_every_identifier_is_one_the_code_accepts(opened, code: str) -> None:
    text = granudb.dem_export(code, HOSTILE, ["Zerodur"], db=opened, **SCENARIO)
    model = granudb.api.dem.dem_model(HOSTILE, ["Zerodur"], db=opened, **SCENARIO)
    names = [t.name for t in model.types]
    assert len(set(names)) == len(names)
    assert all(IDENTIFIER.fullmatch(n) and n not in RESERVED for n in names), names
    assert {t.material for t in model.types} == {*HOSTILE, "Zerodur"}
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith(("#", "//")):
            assert not stripped.endswith(("&", "\\")) and '"""' not in stripped, line
    if code == "lammps":
        ids = re.findall(r"^(?:fix|group) (\S+)", text, re.MULTILINE)
        assert ids and all(re.fullmatch(r"[A-Za-z0-9_]+", i) for i in ids), ids


@pytest.mark.dem_run
@pytest.mark.parametrize(("code", "binary"), [("liggghts", "liggghts"), ("lammps", "lmp"),
                                              ("yade", "yade")])  # fmt: skip
def test_hostile_names_run_to_the_plain_result(opened, code: str, binary: str) -> None:
    require_binary(binary)
    plain = granudb.dem_verify(["steel"], ["Zerodur"], codes=(code,), db=opened, **SCENARIO)
    hostile = granudb.dem_verify(HOSTILE[:3], ["Zerodur"], codes=(code,), db=opened, **SCENARIO)
    normal = {r.speed_m_s: r.achieved_e for r in plain if r.kind == "normal"}
    checked = [r for r in hostile if r.kind == "normal"]
    assert checked and all(r.verdict == "pass" for r in hostile if r.status == "checked")
    for r in checked:
        assert r.achieved_e == pytest.approx(normal[r.speed_m_s], rel=1e-6)


def test_a_dataset_name_cannot_join_deck_lines(opened, tmp_path) -> None:
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
    hostile = 'lab """ & \\ data'
    granudb.import_collisions(example, dataset=hostile, db=opened)
    text = granudb.dem_export("lammps", ["steel"], ["Zerodur"], values="dataset",
                              dataset=hostile, db=opened, **SCENARIO)  # fmt: skip
    assert '"""' not in text and "fix granudb_Zerodur_wall_steel" in text
    for line in text.splitlines():
        assert not line.rstrip().endswith("\\")
        if line.lstrip().startswith("#"):
            assert not line.rstrip().endswith("&")
