"""Measured collisions: CSV import (all or nothing), listing with derived columns, fits."""

from __future__ import annotations

import json
import math
import random
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from support import COLLISION_HEADER, GOOD_ROW, dump_hash, write_csv

from granudb.api.database import connect as open_database
from granudb.errors import GranudbError

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"
HEADER = COLLISION_HEADER
GOOD = GOOD_ROW


write = write_csv


def walton_rows(
    n: int, particle: str, fluid: str, beta: float, mu: float, e: float, noise: float, seed: int
) -> list[list[str]]:
    rng = random.Random(seed)
    rows = []
    for i in range(n):
        angle = rng.uniform(2, 70)
        vn = rng.uniform(100, 380)
        psi_in = math.tan(math.radians(angle))
        psi_out = max(-beta * psi_in, psi_in - mu * (1 + e) * 3.5) + rng.gauss(0, noise)
        e_run = e + rng.gauss(0, 0.01)
        vt_out = (5 * psi_in * vn + 2 * psi_out * vn) / 7
        omega = (psi_out * vn - vt_out) / 6.35  # mm/s / mm
        rows.append(
            [
                f"{particle}-{fluid or 'dry'}-{i}",
                particle,
                "Zerodur",
                fluid,
                "12.7",
                f"{angle:.6f}",
                f"{vn:.6f}",
                f"{psi_in * vn:.6f}",
                "0",
                f"{e_run * vn:.6f}",
                f"{vt_out:.6f}",
                f"{omega:.6f}",
                "",
                "",
            ]
        )
    return rows


def test_example_file_imports_in_si(cli, db: str) -> None:
    result = cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db)
    assert result.exit_code == 0, result.stderr
    assert "imported 12 runs into dataset example 1.0.0" in result.stdout
    rows = json.loads(
        cli(
            "collisions", "list", "--dataset", "example", "--wide", "--format", "json", db=db
        ).stdout
    )
    assert len(rows) == 12
    first = next(r for r in rows if r["run"] == "steel-dry-1")
    assert first["v_n_in_m_s"] == 0.3 and first["diameter_m"] == 0.0127
    assert first["nominal_angle_rad"] == pytest.approx(math.radians(5), rel=1e-12)
    assert first["fluid"] is None and first["normal_stokes_number"] is None
    assert first["normal_restitution"] == pytest.approx(0.97)
    assert first["rotational_restitution"] == pytest.approx(0.34, abs=2e-3)
    for key in (
        "normal_restitution",
        "rotational_restitution",
        "effective_incidence",
        "effective_rebound",
        "sliding_friction",
        "normal_stokes_number",
        "reynolds_number",
        "roughness_exceeds_gap",
        "rebound_expected",
        "tangential_regime",
    ):
        assert key in first
    immersed = next(r for r in rows if r["run"] == "glass-g45-1")
    assert immersed["roughness_exceeds_gap"] is True
    assert immersed["normal_stokes_number"] > 10


def test_decimals_round_trip_and_names_match_case_insensitively(
    cli, db: str, tmp_path: Path
) -> None:
    row = [
        "a",
        "STEEL",
        "zerodur",
        "Glycerol-37",
        "12.7",
        "0.1",
        "0.1",
        "0",
        "0",
        "0.1",
        "0",
        "0",
        "21.5",
        "note",
    ]
    path = write(tmp_path / "one.csv", [row])
    assert cli("collisions", "import", str(path), "--dataset", "d", db=db).exit_code == 0
    data = json.loads(cli("collisions", "list", "--format", "json", db=db).stdout)[0]
    assert data["v_n_in_m_s"] == 0.0001  # 0.1 mm/s exactly, no float dust
    assert data["particle"] == "steel" and data["fluid"] == "glycerol-37"


def test_reimport_is_refused_and_changes_nothing(cli, db: str) -> None:
    assert cli("collisions", "import", str(EXAMPLE), "--dataset", "x", db=db).exit_code == 0
    before = dump_hash(db)
    again = cli("collisions", "import", str(EXAMPLE), "--dataset", "x", db=db)
    assert again.exit_code == 1
    assert "was already imported into dataset x 1.0.0" in again.stderr
    assert dump_hash(db) == before


def _with(**cells: str) -> list[str]:
    row = list(GOOD)
    for header, value in cells.items():
        row[[h.split(" ")[0] for h in HEADER].index(header)] = value
    return row


BAD = [
    ([_with(v_n_in="-3")], "row 2: v_n_in [mm/s]: -3 must be > 0"),
    ([_with(v_n_in="0")], "row 2: v_n_in [mm/s]: 0 must be > 0"),
    ([_with(incidence_angle="90")], "row 2: incidence_angle [deg]: 90 must be ≥ 0 and < 1.5708"),
    ([_with(incidence_angle="-1")], "row 2: incidence_angle [deg]: -1 must be ≥ 0"),
    ([_with(v_n_out="400")], "row 2: v_n_out / v_n_in: 1.333 must be ≤ 1.05"),
    (
        [_with(particle="brass")],
        "row 2: particle: 'brass' is not in the database; did you mean 'glass'?",
    ),
    (
        [_with(particle="unobtainium")],
        "row 2: particle: 'unobtainium' is not in the database (known: alumina, Delrin",
    ),
    ([_with(fluid="mercury")], "row 2: fluid: 'mercury' is not in the database"),
    ([_with(v_t_in="nan")], "row 2: v_t_in [mm/s]: 'nan' is not a number"),
    ([_with(v_t_in="inf")], "row 2: v_t_in [mm/s]: 'inf' must be a finite number"),
    ([_with(v_t_in="fast")], "row 2: v_t_in [mm/s]: 'fast' is not a number"),
    ([_with(v_t_out="")], "row 2: v_t_out [mm/s]: (empty) is required"),
    ([GOOD, GOOD], "row 3: run: 'r1' appears twice"),
    ([_with(run="x" * 201)], "row 2: run: 'xxxxxxxxxxxxxxxxxxxx…' must be at most 200"),
    ([_with(run="a\x01b")], "row 2: run: 'a\\x01b' must not contain U+0001 (control"),
    ([_with(temperature="-300")], "row 2: temperature [degC]: -300 must be > -273.15"),
    ([_with(diameter="0")], "row 2: diameter [mm]: 0 must be > 0"),
]


@pytest.mark.parametrize(("rows", "expected"), BAD, ids=[e[:40] for _, e in BAD])
def test_bad_rows_refuse_the_whole_file(cli, db: str, tmp_path: Path, rows, expected) -> None:
    path = write(tmp_path / "bad.csv", rows)
    before = dump_hash(db)
    result = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert result.exit_code == 1
    assert result.stderr.count("\n") == 1, result.stderr
    assert expected in result.stderr, result.stderr
    assert dump_hash(db) == before


@pytest.mark.parametrize(
    ("content", "expected"),
    [
        (b"run,particle\n\xff\xfe,steel\n", "is not UTF-8 text"),
        (
            (",".join(HEADER) + "\n" + ",".join(GOOD) + ",extra,cells\n").encode(),
            "row 2: cells: 16 where the header has 14",
        ),
        (
            (",".join(HEADER) + "\n" + ",".join(GOOD[:6]) + "\n").encode(),
            "row 2: cells: 6 where the header has 14 (truncated?)",
        ),
        (b"", "is empty"),
        (
            (",".join(HEADER[:3]) + "\nr,steel,Zerodur\n").encode(),
            "are required columns but missing",
        ),
        (
            (
                ",".join(["run", "particle", "wall", "fluid", "diameter", *HEADER[5:]]) + "\n"
            ).encode(),
            "'diameter' needs a unit in brackets",
        ),
        (
            (
                ",".join(["run", "particle", "wall", "fluid", "diameter [kg]", *HEADER[5:]]) + "\n"
            ).encode(),
            "is not a length",
        ),
        ((",".join(HEADER) + "\n").encode(), "holds no rows"),
    ],
)
def test_bad_files(cli, db: str, tmp_path: Path, content: bytes, expected: str) -> None:
    path = tmp_path / "file.csv"
    path.write_bytes(content)
    before = dump_hash(db)
    result = cli("collisions", "import", str(path), "--dataset", "d", db=db)
    assert result.exit_code == 1
    assert result.stderr.count("\n") == 1 and expected in result.stderr, result.stderr
    assert dump_hash(db) == before


def test_a_bad_last_row_after_ten_thousand_good_ones_writes_nothing(
    db: str, tmp_path: Path
) -> None:
    from granudb.io.collision_import import import_collisions

    rows = walton_rows(10_000, "steel", "", 0.34, 0.11, 0.97, 0.0, seed=1)
    rows.append(_with(run="last", v_n_in="-1"))
    path = write(tmp_path / "big.csv", rows)
    before = dump_hash(db)
    database = open_database(db)
    with pytest.raises(GranudbError, match="row 10002: v_n_in"):
        import_collisions(database, path, dataset="big", chunk_rows=3000)
    database.dispose()
    assert dump_hash(db) == before


def test_content_hash_does_not_depend_on_row_order(db: str, tmp_path: Path) -> None:
    from granudb.db import datasets
    from granudb.db.content_hash import content_hash
    from granudb.io.collision_import import import_collisions

    rows = walton_rows(200, "glass", "glycerol-45", 0.39, 0.15, 0.7, 0.01, seed=2)
    shuffled = list(rows)
    random.Random(3).shuffle(shuffled)
    database = open_database(db)
    import_collisions(database, write(tmp_path / "a.csv", rows), dataset="a")
    import_collisions(database, write(tmp_path / "b.csv", shuffled), dataset="b")
    with database.session() as session:
        first = datasets.get_dataset(session, "a")
        second = datasets.get_dataset(session, "b")
        assert first.content_hash == second.content_hash == content_hash(session, first)
    database.dispose()


@settings(
    max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(
    cells=st.lists(
        st.one_of(st.text(max_size=12), st.floats(allow_nan=True).map(str)), min_size=8, max_size=8
    )
)
def test_fuzzed_numeric_cells_import_cleanly_or_refuse_cleanly(
    db: str, tmp_path: Path, cells: list[str]
) -> None:
    from granudb.io.collision_import import import_collisions

    row = GOOD[:4] + cells + ["", ""]
    path = write(tmp_path / "fuzz.csv", [row])
    before = dump_hash(db)
    database = open_database(db)
    try:
        import_collisions(database, path, dataset=f"fuzz-{abs(hash(tuple(cells)))}")
    except GranudbError as exc:
        assert "\n" not in str(exc)
        assert dump_hash(db) == before
    finally:
        database.dispose()


def test_list_filters(cli, db: str) -> None:
    cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db)

    def runs(*args: str) -> set[str]:
        out = cli("collisions", "list", *args, "--format", "json", db=db)
        assert out.exit_code == 0, out.stderr
        return {r["run"] for r in json.loads(out.stdout)}

    assert runs("--fluid", "dry") == {f"steel-dry-{i}" for i in range(1, 7)}
    assert runs("--particle", "glass") == {"glass-g45-1", "glass-g45-2"}
    assert runs("--angle-range", "20..45 deg", "--fluid", "dry") == {"steel-dry-4", "steel-dry-5"}
    assert runs("--regime", "gross_slip", "--fluid", "dry") == {"steel-dry-5", "steel-dry-6"}
    assert runs("--roughness-exceeds-gap") == {"glass-g45-1", "glass-g45-2"}
    assert runs("--min-normal-stokes", "500") == {f"steel-g37-{i}" for i in range(1, 5)}
    csv_out = cli("collisions", "list", "--format", "csv", db=db).stdout
    assert csv_out.splitlines()[0].startswith("run,particle,wall,fluid")
    wide = cli("collisions", "list", "--wide", "--format", "csv", db=db).stdout
    assert wide.splitlines()[0].startswith("dataset,version,run,particle")


def test_python_api_returns_a_dataframe(cli, db: str) -> None:
    import granudb

    cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db)
    frame = granudb.collisions(db=db, particle="steel", fluid="glycerol-37")
    assert len(frame) == 4
    assert frame["normal_restitution"].to_numpy() == pytest.approx(0.8)


def test_walton_fit_recovers_the_published_dry_values(db: str, tmp_path: Path) -> None:
    # Synthetic runs scattered around the paper's dry fits (β = 0.34, μ_f = 0.11 for steel;
    # β = 0.39, μ_f = 0.106 for glass; ē = 0.97): the fit must give them back within error.
    from granudb.analysis import fits
    from granudb.io.collision_import import import_collisions
    from granudb.scenario.collision_query import CollisionQuery
    from granudb.scenario.collisions import select_collisions

    rows = walton_rows(120, "steel", "", 0.34, 0.11, 0.97, 0.01, seed=4) + walton_rows(
        120, "glass", "", 0.39, 0.106, 0.97, 0.01, seed=5
    )
    database = open_database(db)
    import_collisions(database, write(tmp_path / "dry.csv", rows), dataset="dry")
    with database.session() as session:
        results = {
            r["particle"]: r for r in fits.walton(select_collisions(session, CollisionQuery()))
        }
    database.dispose()
    for particle, beta, mu in (("steel", 0.34, 0.11), ("glass", 0.39, 0.106)):
        fit = results[particle]
        assert fit["rotational_restitution"] == pytest.approx(beta, abs=0.02)
        assert fit["sliding_friction"] == pytest.approx(mu, abs=0.005)
        assert fit["normal_restitution_mean"] == pytest.approx(0.97, abs=0.005)
        assert fit["n_sliding"] + fit["n_sticking"] == 120
        assert fit["sliding_friction_stderr"] < 0.005


def test_fit_commands(cli, db: str) -> None:
    cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db)
    walton = json.loads(cli("fit", "walton", "--fluid", "dry", "--format", "json", db=db).stdout)
    assert walton[0]["rotational_restitution"] == pytest.approx(0.34, abs=1e-3)
    # two sliding runs decide the split but give no μ_f (fewer than 3 runs on the line)
    assert walton[0]["sliding_friction"] is None
    assert "2 sliding runs" in walton[0]["reason"]
    assert walton[0]["n_sliding"] == 2 and walton[0]["n_sticking"] == 4
    for model in ("threshold", "exponential"):
        out = cli("fit", "restitution", "--model", model, "--format", "json", db=db)
        assert out.exit_code == 0, out.stderr
        assert {r["model"] for r in json.loads(out.stdout)} == {model}
    bad = cli("fit", "restitution", "--model", "magic", db=db)
    assert bad.exit_code == 1 and "--model: magic must be one of" in bad.stderr
    gap = cli("fit", "gap-viscosity", "--format", "json", db=db)
    assert gap.exit_code == 0, gap.stderr


def test_restitution_models_recover_their_parameters() -> None:
    import pandas as pd

    from granudb.analysis import fits

    st_n = np.geomspace(5, 2000, 60)
    for model, parameter in (("threshold", 10.0), ("exponential", 35.0)):
        e = fits.restitution_curve(model, st_n, 0.97, parameter)
        frame = pd.DataFrame(
            {
                "dataset": "d",
                "particle": "steel",
                "wall": "Zerodur",
                "normal_stokes_number": st_n,
                "normal_restitution": e,
            }
        )
        [result] = fits.restitution(frame, model)
        assert result["e_dry"] == pytest.approx(0.97, rel=1e-3)
        assert result["parameter"] == pytest.approx(parameter, rel=1e-3)
