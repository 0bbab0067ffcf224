"""Runs as papers report them: a run stated as e alone and a run stated as e_t(θ) import,
list and fit; nothing shows a velocity; a velocity column, a bad cell or an unknown name
is refused in one line with the database unchanged; the downgrade names the loss."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from support import dump_hash

import granudb

VELOCITY = ("v_n_in", "v_t_in", "v_n_out", "v_t_out", "velocity", "speed")


def _write(path: Path, text: str) -> Path:
    path.write_text(text, encoding="utf-8")
    return path


def _synthetic_e_t(tmp_path: Path) -> tuple[Path, float, float]:
    """e_t(θ) of a known Walton model (μ_f = 0.1, β = 0.35, e = 0.95) for steel on
    Zerodur, no spin in, with scatter 0.002: the textbook laws, not granudb's relations."""
    mu, beta, e = 0.1, 0.35, 0.95
    theta = np.linspace(4.0, 80.0, 24)
    rad = np.radians(theta)
    rng = np.random.default_rng(3)
    e_t = np.maximum(1 - mu * (1 + e) / np.tan(rad), (5 - 2 * beta) / 7)
    e_t = e_t + rng.normal(0, 0.002, theta.size)
    lines = ["run,particle,wall,incidence_angle [deg],e,e_t,u(e_t)"]
    lines += [
        f"t{i:02d},steel,Zerodur,{a:.3f},{e},{v:.5f},0.002"
        for i, (a, v) in enumerate(zip(theta, e_t, strict=True))
    ]
    return _write(tmp_path / "et.csv", "\n".join(lines) + "\n"), mu, beta


def test_e_alone_and_e_t_of_theta_import_list_and_fit(cli, db: str, tmp_path: Path) -> None:
    e_file = _write(
        tmp_path / "e.csv",
        "run,particle,wall,fluid,e,u(e),notes\n"
        "a1,glass,glass,,0.97,0.01,drop test\na2,glass,glass,,0.95,0.01,\n"
        "a3,glass,glass,,0.96,,\n",
    )
    assert cli("reported", "import", str(e_file), "--collection", "e-only", db=db).exit_code == 0
    et_file, mu, beta = _synthetic_e_t(tmp_path)
    done = cli("reported", "import", str(et_file), "--collection", "et", "--no-spin-in", db=db)
    assert done.exit_code == 0, done.stderr
    assert "stored 24 runs" in done.stdout

    listed = json.loads(cli("reported", "list", "--format", "json", db=db).stdout)
    assert len(listed) == 27
    for run in listed:  # what was stated, and no velocity anywhere
        assert not any(k.startswith(VELOCITY) for k in run), run
    e_only = [r for r in listed if r["collection"] == "e-only"]
    assert {r["stated"] for r in e_only} == {"normal_restitution"}
    assert all(r["effective_incidence"] is None or math.isnan(r["effective_incidence"])
               for r in e_only)  # fmt: skip
    et = [r for r in listed if r["collection"] == "et"]
    assert all("3.5 e_t − 2.5" in r["derived_by"] for r in et)
    first = min(et, key=lambda r: r["incidence_angle_rad"])
    assert first["effective_incidence"] == pytest.approx(math.tan(first["incidence_angle_rad"]))
    assert first["effective_rebound"] == pytest.approx(
        first["effective_incidence"] * (3.5 * first["tangential_restitution"] - 2.5)
    )
    table = cli("reported", "list", db=db).stdout.lower()
    assert "v_n" not in table and "velocity" not in table

    restitution = granudb.fit_reported("e-only", model="restitution", db=db)
    assert restitution[0]["n_runs"] == 3
    assert restitution[0]["normal_restitution_mean"] == pytest.approx(0.96)
    assert (
        restitution[0]["normal_restitution_low"] < 0.96 < restitution[0]["normal_restitution_high"]
    )
    walton = granudb.fit_reported("et", model="walton", db=db)
    assert len(walton) == 1 and walton[0]["model"] == "split"
    assert walton[0]["sliding_friction"] == pytest.approx(mu, abs=0.005)
    assert walton[0]["rotational_restitution"] == pytest.approx(beta, abs=0.03)
    assert "exact for a rigid sphere arriving without spin" in walton[0]["relation"]
    shown = json.loads(
        cli("reported", "fit", "--collection", "et", "--format", "json", db=db).stdout
    )
    assert shown[0]["sliding_friction"] == walton[0]["sliding_friction"]
    # e_t runs without "no spin in" give no Ψ and no Walton fit: the relation would not hold
    assert cli("reported", "import", str(et_file), "--collection", "spin?", db=db).exit_code == 0
    assert granudb.fit_reported("spin?", model="walton", db=db) == []
    spin = granudb.reported_runs("spin?", db=db)[0]
    assert "does not state that the sphere arrives without spin" in spin["derived_by"]


@pytest.mark.parametrize(
    ("text", "words"),
    [
        ("run,particle,wall,v_n_in [m/s],e\nr,steel,Zerodur,0.3,0.9\n", "is a velocity"),
        ("run,particle,wall,e\nr,steel,Zerodur,abc\n", "row 2"),
        ("run,particle,wall,e\nr,stel,Zerodur,0.9\n", "known"),
        ("run,particle,wall,incidence_angle [deg]\nr,steel,Zerodur,20\n", "states e or e_t"),
        ("run,particle,wall,e,e\nr,steel,Zerodur,0.9,0.9\n", "twice"),
        ("run,particle,wall,incidence_angle [deg],e\nr,steel,Zerodur,95,0.9\n", "row 2"),
        ("run,particle,wal,e\nr,steel,Zerodur,0.9\n", "did you mean wall?"),
    ],
)
def test_bad_files_are_one_line_and_change_nothing(
    cli, db: str, tmp_path: Path, text: str, words: str
) -> None:
    before = dump_hash(db)
    path = _write(tmp_path / "bad.csv", text)
    result = cli("reported", "import", str(path), "--collection", "bad", db=db)
    assert result.exit_code == 1
    lines = [line for line in result.stderr.splitlines() if not line.startswith("created ")]
    assert len(lines) == 1 and words in lines[0], result.stderr
    assert dump_hash(db) == before


def test_a_run_label_is_not_stored_twice(cli, db: str, tmp_path: Path) -> None:
    path = _write(tmp_path / "e.csv", "run,particle,wall,e\nr,steel,Zerodur,0.9\n")
    assert cli("reported", "import", str(path), "--collection", "c", db=db).exit_code == 0
    again = cli("reported", "import", str(path), "--collection", "c", db=db)
    assert again.exit_code == 1 and "already in collection" in again.stderr


def test_the_downgrade_names_the_reported_runs_it_drops(cli, db: str, tmp_path: Path) -> None:
    path = _write(tmp_path / "e.csv", "run,particle,wall,e\nr,steel,Zerodur,0.9\n")
    assert cli("reported", "import", str(path), "--collection", "c", db=db).exit_code == 0
    refused = cli("db", "downgrade", "0011", db=db)
    assert refused.exit_code != 0
    assert "reported_runs.run: 1 values dropped" in refused.stdout + refused.stderr


def test_a_material_its_reported_runs_use_is_not_removed(cli, db: str, tmp_path: Path) -> None:
    added = cli("materials", "add", "bead", "--density", "2500 kg/m^3", "--youngs-modulus",
                "60 GPa", "--poisson-ratio", "0.23", db=db)  # fmt: skip
    assert added.exit_code == 0, added.stderr
    path = _write(tmp_path / "e.csv", "run,particle,wall,e\nr,bead,Zerodur,0.9\n")
    assert cli("reported", "import", str(path), "--collection", "c", db=db).exit_code == 0
    before = dump_hash(db)
    refused = cli("materials", "remove", "bead", "--yes", db=db)
    assert refused.exit_code == 1
    assert "1 runs as reported" in refused.stderr and refused.stderr.count("\n") == 1
    assert dump_hash(db) == before
