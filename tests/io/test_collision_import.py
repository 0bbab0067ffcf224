"""Collision CSV import, as real lab files and hostile files meet it (issue 14).

Each test names the behaviour it pins; each failed on the code before this change (a
header unit like ``m**(9**9**9)/s`` hung inside the write transaction, a 1,000,000-column
header took 102 s and 3.2 GB, a run at 80 °C in water imported and then broke every read,
and so on).
"""

from __future__ import annotations

import csv
import json
import math
import resource
from pathlib import Path

import pytest
from support import COLLISION_HEADER, GOOD_ROW, CostBound, dump_hash, engine_for, write_csv

from granudb.api.database import connect as open_database
from granudb.errors import ValidationError

HEADER = COLLISION_HEADER
GOOD = GOOD_ROW


write = write_csv


def row(**cells: str) -> list[str]:
    out = list(GOOD)
    for name, value in cells.items():
        out[[h.split(" ")[0] for h in HEADER].index(name)] = value
    return out


def header(**replaced: str) -> list[str]:
    out = list(HEADER)
    for name, value in replaced.items():
        out[[h.split(" ")[0] for h in HEADER].index(name)] = value
    return out


def refused(cli, db: str, path: Path, *options: str) -> str:
    before = dump_hash(db)
    result = cli("collisions", "import", str(path), "--dataset", "d", *options, db=db)
    assert result.exit_code == 1, result.stdout
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: "), result.stderr
    assert "internal error" not in result.stderr and "Traceback" not in result.stderr
    assert dump_hash(db) == before
    return lines[0]


def stored(db: str, column: str) -> list:
    from sqlalchemy import text

    engine = engine_for(db)
    try:
        with engine.connect() as connection:
            return [r[0] for r in connection.execute(text(f"SELECT {column} FROM collisions"))]
    finally:
        engine.dispose()


def imported(cli, db: str, path: Path, *options: str) -> list[dict]:
    result = cli("collisions", "import", str(path), "--dataset", "d", *options, db=db)
    assert result.exit_code == 0, result.stderr
    listed = cli("collisions", "list", "--dataset", "d", "--wide", "--format", "json", db=db)
    assert listed.exit_code == 0, listed.stderr
    return json.loads(listed.stdout)


# 3. Bounded cost, before any lock -------------------------------------------------------


@pytest.mark.parametrize(
    "bad_header",
    [
        header(v_n_in="v_n_in [m**(9**9**9)/s]"),
        header(incidence_angle="incidence_angle [%]"),
        header(diameter="diameter"),
        [*HEADER, "colour"],
    ],
    ids=["exponent bomb", "percent angle", "no unit", "unknown"],
)
def test_header_is_refused_before_the_write_transaction_opens(
    db: str, tmp_path: Path, monkeypatch, bad_header: list[str]
) -> None:
    import granudb.db.collision_store as store
    from granudb.io.collision_import import import_collisions

    def no_transaction(*args, **kwargs):
        raise AssertionError("store_collisions (the write transaction) was reached")

    monkeypatch.setattr(store, "store_collisions", no_transaction)
    path = write(tmp_path / "bad.csv", [GOOD + [""] * (len(bad_header) - len(GOOD))], bad_header)
    database = open_database(db)
    with CostBound():
        try:
            with pytest.raises(ValidationError):
                import_collisions(database, path, dataset="d")
        finally:
            database.dispose()


def test_a_million_column_header_is_refused_quickly(cli, db: str, tmp_path: Path) -> None:
    path = tmp_path / "wide.csv"
    path.write_text(",".join(f"c{i}" for i in range(1_000_000)) + "\n1\n", encoding="utf-8")
    before_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    with CostBound():  # before: 102 s and 3.2 GB
        line = refused(cli, db, path)
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024 - before_mb < 200
    assert "has a header line longer than 16,384 bytes" in line


def test_many_short_headers_are_refused_by_count(cli, db: str, tmp_path: Path) -> None:
    path = tmp_path / "many.csv"
    path.write_text(",".join(f"c{i}" for i in range(1000)) + "\n", encoding="utf-8")
    assert "1,000 columns is more than 200" in refused(cli, db, path)


def test_package_schema_units_have_bounded_cost_too() -> None:
    from granudb.io.package_schema import _same_unit

    with CostBound():
        assert _same_unit("m**(9**9**9)/s", "m/s") is False
        assert _same_unit("m/s", "m/s") is True


# 2. Angles and angular velocities in headers ---------------------------------------------


@pytest.mark.parametrize("name", ["incidence_angle", "nominal_angle"])
def test_a_percent_angle_header_is_refused(cli, db: str, tmp_path: Path, name: str) -> None:
    # Before: 5 % was stored as 0.05 rad.
    path = write(tmp_path / "a.csv", [GOOD], header(incidence_angle=f"{name} [%]"))
    assert f"'{name} [%]': [%] is not an angle" in refused(cli, db, path)


def test_hz_spin_is_converted_with_two_pi(cli, db: str, tmp_path: Path) -> None:
    # Before: omega_in [Hz] stored 10 Hz as 10 rad/s.
    path = write(
        tmp_path / "hz.csv",
        [row(omega_in="10", omega_out="-1")],
        header(omega_in="omega_in [Hz]", omega_out="omega_out [rpm]"),
    )
    imported(cli, db, path)
    assert stored(db, "omega_in_rad_s") == [pytest.approx(20 * math.pi, rel=1e-12)]
    assert stored(db, "omega_out_rad_s") == [pytest.approx(-2 * math.pi / 60, rel=1e-12)]


def test_a_bare_inverse_second_spin_is_refused(cli, db: str, tmp_path: Path) -> None:
    path = write(tmp_path / "s.csv", [GOOD], header(omega_in="omega_in [1/s]"))
    assert "[1/s] is not an angular velocity" in refused(cli, db, path)


# 4. Missing values stay missing ----------------------------------------------------------


def test_empty_spin_is_stored_as_null_and_the_angle_column_is_optional(
    cli, db: str, tmp_path: Path
) -> None:
    without_angle = [h for h in HEADER if not h.startswith("incidence_angle")]
    cells = [
        c
        for h, c in zip(HEADER, row(omega_in="", omega_out=""), strict=True)
        if not h.startswith("incidence_angle")
    ]
    rows = imported(cli, db, write(tmp_path / "n.csv", [cells], without_angle))
    assert stored(db, "omega_in_rad_s") == [None] and stored(db, "omega_out_rad_s") == [None]
    assert stored(db, "nominal_angle_rad") == [None]
    assert rows[0]["incidence_angle_rad"] == pytest.approx(math.atan(109.2 / 300), rel=1e-6)


# 5. The stated angle agrees with the velocities -----------------------------------------


def test_an_angle_that_disagrees_with_the_velocities_is_refused(
    cli, db: str, tmp_path: Path
) -> None:
    path = write(tmp_path / "a.csv", [GOOD, row(run="r2", incidence_angle="45")])
    line = refused(cli, db, path)
    assert line.startswith("Error: a.csv: row 3: incidence_angle [deg]: 45 disagrees with atan(")
    assert "= 20.00° by more than 3°" in line


def test_an_angle_within_the_tolerance_is_kept_as_stated(cli, db: str, tmp_path: Path) -> None:
    imported(cli, db, write(tmp_path / "a.csv", [row(incidence_angle="22.5")]))
    assert stored(db, "nominal_angle_rad") == [pytest.approx(math.radians(22.5))]


# 6. Friendlier lab files -----------------------------------------------------------------


def test_every_header_problem_is_reported_in_one_line(cli, db: str, tmp_path: Path) -> None:
    bad = header(diameter="diameter", v_n_in="v_n_in [kg]", notes="remarks")
    line = refused(cli, db, write(tmp_path / "h.csv", [GOOD], bad))
    assert line.startswith("Error: h.csv header: 3 problems: (1) 'diameter' needs a")
    assert "(2) 'v_n_in [kg]': [kg] is not a velocity" in line
    assert "(3) 'remarks' is not a known column" in line


def test_headers_are_case_insensitive_and_take_units_in_parentheses(
    cli, db: str, tmp_path: Path
) -> None:
    lab = [
        "Run",
        "PARTICLE",
        "Wall",
        "Fluid",
        "Diameter (mm)",
        "Incidence Angle (deg)",
        "V_N_IN (m s-1)",
        "v_t_in (mm/s)",
        "Omega_In [rad/s]",
        "v_n_out [mm/s]",
        "v_t_out [mm/s]",
        "omega_out [rad/s]",
        "Temperature (degC)",
        "Notes",
    ]
    rows = imported(cli, db, write(tmp_path / "lab.csv", [row(v_n_in="0.3")], lab))
    assert rows[0]["v_n_in_m_s"] == 0.3 and rows[0]["diameter_m"] == 0.0127


def test_semicolon_files_are_detected_and_decimal_commas_never_guessed(
    cli, db: str, tmp_path: Path
) -> None:
    plain = write(tmp_path / "plain.csv", [row(run="s1")], delimiter=";")
    assert imported(cli, db, plain)[0]["diameter_m"] == 0.0127  # detected: no comma at all
    european = [row(run="s2", diameter="12,7", v_t_in="109,2")]
    path = write(tmp_path / "eu.csv", european, delimiter=";")
    line = refused(cli, db, path)  # "12,7" could be 12.7 or 127: said, not guessed
    assert line.startswith("Error: eu.csv: 2 problems: row 2: diameter [mm]: '12,7' has a")
    assert "decimal comma: use a decimal point, or import with --decimal ','" in line
    line = refused(cli, db, path, "--delimiter", ",")
    assert "looks semicolon-delimited" in line and "--delimiter ';'" in line
    assert "--decimal ','" in line
    rows = imported(cli, db, path, "--decimal", ",")
    assert rows[-1]["diameter_m"] == 0.0127 and rows[-1]["v_t_in_m_s"] == 0.1092


def test_a_point_in_a_decimal_comma_file_is_refused_not_guessed(
    cli, db: str, tmp_path: Path
) -> None:
    path = write(
        tmp_path / "eu.csv", [row(diameter="12,7", v_t_in="109,2", v_n_in="1.300,5")], delimiter=";"
    )
    line = refused(cli, db, path, "--delimiter", ";", "--decimal", ",")
    assert "v_n_in [mm/s]: '1.300,5' has a '.' but the file's decimal separator is ','" in line


def test_comma_as_both_delimiter_and_decimal_is_refused(cli, db: str, tmp_path: Path) -> None:
    path = write(tmp_path / "a.csv", [GOOD])
    assert "--decimal: ','" in refused(cli, db, path, "--decimal", ",")


# 7. Imports cannot poison reads ----------------------------------------------------------


def test_a_run_outside_the_fluids_data_is_refused_and_reads_keep_working(
    cli, db: str, tmp_path: Path
) -> None:
    assert (
        cli(
            "collisions",
            "import",
            str(write(tmp_path / "ok.csv", [GOOD])),
            "--dataset",
            "ok",
            db=db,
        ).exit_code
        == 0
    )
    hot = write(tmp_path / "hot.csv", [row(run="hot", fluid="water", temperature="80")])
    line = refused(cli, db, hot)
    assert line.startswith(
        "Error: hot.csv: row 2: temperature [degC]: 80 °C is outside fluid water's viscosity "
        "data (10–60 °C)"
    )
    assert "dataset d" in line
    listed = cli("collisions", "list", "--format", "json", db=db)
    assert listed.exit_code == 0 and len(json.loads(listed.stdout)) == 1


def test_a_run_inside_the_fluids_data_imports(cli, db: str, tmp_path: Path) -> None:
    rows = imported(cli, db, write(tmp_path / "w.csv", [row(fluid="water", temperature="55")]))
    assert rows[0]["temperature_c"] == 55.0


def test_what_an_import_accepts_every_read_derives(cli, db: str, tmp_path: Path) -> None:
    """The import's temperature rule and the reads' fluid state agree at the edges."""
    temps = ["10", "20", "20.3", "59.9", "60"]
    lines = [row(run=f"w{i}", fluid="water", temperature=t) for i, t in enumerate(temps)]
    rows = imported(cli, db, write(tmp_path / "edges.csv", lines))
    assert len(rows) == len(temps)
    import granudb

    frame = granudb.collisions(db=db, fluid="water", wide=True)
    assert frame["derivation_note"].isna().all()
    assert frame["normal_stokes_number"].notna().all()


# 8. Names and text -----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("cells", "expected"),
    [
        ({"run": "r\u202e1"}, "row 2: run: 'r\\u202e1' must not contain U+202E"),
        ({"particle": "steel "}, "row 2: particle: 'steel ' must not begin or end with spaces"),
        ({"wall": "Zero\u200bdur"}, "must not contain U+200B"),
        ({"notes": "\x1b[2Jgone"}, "row 2: notes: '\\x1b[2Jgone' must not contain U+001B"),
    ],
)
def test_names_and_notes_follow_the_vocabulary_rules(
    cli, db: str, tmp_path: Path, cells: dict, expected: str
) -> None:
    path = write(tmp_path / "t.csv", [row(**cells)], quoting=csv.QUOTE_ALL)
    assert expected in refused(cli, db, path)


@pytest.mark.parametrize(
    ("option", "value", "expected"),
    [
        ("--dataset", "bad\x1b[31m", "--dataset: 'bad\\x1b[31m' must not contain U+001B"),
        ("--dataset", " padded", "--dataset: ' padded' must not begin or end with spaces"),
        ("--version", "1.0\u202e", "--version: '1.0\\u202e' must not contain U+202E"),
        ("--dataset", "x" * 201, "must be at most 200 characters"),
    ],
)
def test_dataset_and_version_options_follow_the_name_rules(
    cli, db: str, tmp_path: Path, option: str, value: str, expected: str
) -> None:
    path = write(tmp_path / "ok.csv", [GOOD])
    before = dump_hash(db)
    args = ["--dataset", "d", "--version", "1.0.0"]
    args[args.index(option) + 1] = value
    result = cli("collisions", "import", str(path), *args, db=db)
    assert result.exit_code == 1 and expected in result.stderr, result.stderr
    assert dump_hash(db) == before


# 1 and 2 at the command line -------------------------------------------------------------


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (
            ["--density", "2,5 g/cm^3"],
            "--density: 2,5 g/cm^3 has a decimal comma: use a decimal point: 2.5 g/cm^3",
        ),
        (["--poisson-ratio", "0,2"], "--poisson-ratio: 0,2 has a decimal comma"),
        (["--roughness", "23,6 nm"], "--roughness: 23,6 nm has a decimal comma"),
        (["--youngs-modulus", "1 GPa**(9**9**9)"], "has an exponent that is not a small number"),
    ],
)
def test_materials_add_refuses_decimal_commas(cli, db: str, args: list[str], expected: str):
    good = {
        "--density": "2.2 g/cm^3",
        "--youngs-modulus": "0.5 GPa",
        "--poisson-ratio": "0.46",
        "--roughness": "0.2 um",
    }
    good.update(dict([args]))
    before = dump_hash(db)
    argv = [a for pair in good.items() for a in pair]
    result = cli("materials", "add", "PTFE", *argv, db=db)
    assert result.exit_code == 1 and expected in result.stderr, result.stderr
    assert dump_hash(db) == before


def test_pair_refuses_a_percent_angle(cli, db: str) -> None:
    # Before: --angle "30 %" meant 17.2°.
    result = cli(
        "pair",
        "steel",
        "Zerodur",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.3 m/s",
        "--angle",
        "30 %",
        db=db,
    )
    assert result.exit_code == 1
    assert "--angle: 30 % is not an angle: an angle needs deg or rad" in result.stderr
