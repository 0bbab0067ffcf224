"""``materials remove`` and ``fluids remove`` say what they delete and ask, or need
``--yes`` (issue 14: they deleted at once)."""

from __future__ import annotations

import pytest
from support import dump_hash

PTFE = [
    "materials", "add", "PTFE", "--density", "2.2 g/cm^3", "--youngs-modulus", "0.5 GPa",
    "--poisson-ratio", "0.46", "--roughness", "0.2 um",
]  # fmt: skip
OIL = [
    "fluids", "add", "oil", "--reference-viscosity", "9.6 cP", "--reference-density",
    "960 kg/m^3",
]  # fmt: skip


@pytest.mark.parametrize(
    ("add", "remove", "says", "gone"),
    [
        (PTFE, ["materials", "remove", "ptfe"], "material PTFE", ["materials", "show", "PTFE"]),
        (
            OIL,
            ["fluids", "remove", "oil"],
            "fluid oil with its 0 viscosity points",
            ["fluids", "show", "oil"],
        ),
    ],
)
def test_remove_needs_consent(cli, db: str, add, remove, says, gone) -> None:
    assert cli(*add, db=db).exit_code == 0
    before = dump_hash(db)
    refused = cli(*remove, db=db)
    assert refused.exit_code == 1
    lines = refused.stderr.strip().splitlines()
    assert len(lines) == 1 and says in lines[0] and "--yes" in lines[0], refused.stderr
    assert dump_hash(db) == before
    assert cli(*remove, "--yes", db=db).exit_code == 0
    assert cli(*gone, db=db).exit_code == 1


def test_remove_asks_on_a_terminal(db: str, monkeypatch) -> None:
    from typer.testing import CliRunner

    from granudb.cli import confirm
    from granudb.cli.main import app

    monkeypatch.setattr(confirm, "interactive", lambda: True)
    runner = CliRunner()
    assert runner.invoke(app, [*PTFE, "--db", db]).exit_code == 0
    before = dump_hash(db)
    no = runner.invoke(app, ["materials", "remove", "PTFE", "--db", db], input="\n")
    assert no.exit_code == 1 and "not confirmed" in no.stderr  # the default is no
    assert dump_hash(db) == before
    yes = runner.invoke(app, ["materials", "remove", "PTFE", "--db", db], input="y\n")
    assert yes.exit_code == 0 and "removed material PTFE" in yes.stdout


def test_a_material_in_use_is_refused_before_asking(cli, db: str) -> None:
    result = cli("materials", "remove", "glass", "--yes", db=db)
    assert result.exit_code == 1 and "is still used by" in result.stderr
