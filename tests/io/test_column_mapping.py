"""A lab's own headers, mapped to granudb's columns (issue 24): ``--columns`` on the
command line, ``columns=`` in Python, or a small mapping file; the header's unit is kept."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from support import COLLISION_HEADER, GOOD_ROW, dump_hash, write_csv

import granudb
from granudb.errors import ValidationError

#: The same runs as ``GOOD_ROW``'s file, under one lab's own headers.
LAB_HEADER = [
    "Shot",
    "particle",
    "wall",
    "fluid",
    "Ball diameter (mm)",
    "incidence_angle [deg]",
    "Approach speed [mm/s]",
    "v_t_in [mm/s]",
    "omega_in [rad/s]",
    "Rebound speed [cm/s]",
    "v_t_out [mm/s]",
    "omega_out [rad/s]",
    "temperature [degC]",
    "Remarks",
]
MAPPING = {
    "Shot": "run",
    "Ball diameter (mm)": "diameter",
    "approach speed [mm/s]": "v_n_in",  # case and spaces around a header do not matter
    "Rebound speed [cm/s]": "v_n_out",
    "Remarks": "notes",
}
LAB_ROW = [*GOOD_ROW[:9], "29.1", *GOOD_ROW[10:]]  # 291 mm/s written as 29.1 cm/s


def listing(cli, db: str, dataset: str) -> list[dict]:
    shown = cli("collisions", "list", "--dataset", dataset, "--wide", "--format", "json", db=db)
    assert shown.exit_code == 0, shown.stderr
    return json.loads(shown.stdout)


def test_mapped_headers_import_what_the_plain_file_imports(cli, db: str, tmp_path: Path) -> None:
    plain = write_csv(tmp_path / "plain.csv", [GOOD_ROW])
    lab = write_csv(tmp_path / "lab.csv", [LAB_ROW], LAB_HEADER)
    assert cli("collisions", "import", str(plain), "--dataset", "plain", db=db).exit_code == 0
    text = ",".join(f"{k}={v}" for k, v in MAPPING.items())
    done = cli("collisions", "import", str(lab), "--dataset", "cli", "--columns", text, db=db)
    assert done.exit_code == 0, done.stderr
    granudb.import_collisions(lab, dataset="python", columns=MAPPING, db=db)
    mapping_file = tmp_path / "lab-columns.txt"
    mapping_file.write_text(
        "# our sheet → granudb\n" + "\n".join(f"{k}={v}" for k, v in MAPPING.items()) + "\n",
        encoding="utf-8",
    )
    assert (
        cli(
            "collisions", "import", str(lab), "--dataset", "file", "--columns", str(mapping_file),
            db=db,
        ).exit_code
        == 0
    )  # fmt: skip
    expected = listing(cli, db, "plain")
    for dataset in ("cli", "python", "file"):
        got = listing(cli, db, dataset)
        assert [{k: v for k, v in r.items() if k != "dataset"} for r in got] == [
            {k: v for k, v in r.items() if k != "dataset"} for r in expected
        ]
    assert expected[0]["v_n_out_m_s"] == pytest.approx(0.291)


def test_the_target_may_carry_the_unit(db: str, tmp_path: Path) -> None:
    header = [*COLLISION_HEADER[:6], "speed", *COLLISION_HEADER[7:]]
    path = write_csv(tmp_path / "speed.csv", [GOOD_ROW], header)
    result = granudb.import_collisions(path, dataset="d", columns="speed=v_n_in [mm/s]", db=db)
    assert result.rows == 1


@pytest.mark.parametrize(
    ("columns", "expected"),
    [
        ("Shot=runn", "--columns: 'runn' is not a granudb column; did you mean run?"),
        ("Approach speed [mm/s]=v_n_inn", "did you mean v_n_in?"),
        ("Sh0t=run", "--columns: 'Sh0t' is not a header of lab.csv (its headers: 'Shot'"),
        ("Shot", "--columns: Shot is neither 'header=column' pairs nor a mapping file"),
        ("Shot=run,Shot=run", "--columns: 'Shot' is mapped twice"),
        ("Shot=", "--columns: 'Shot=' must be 'your header=granudb column'"),
        ("Shot=run,Approach speed [mm/s]=v_n_in,Rebound speed [cm/s]=v_n_in", "a second time"),
        ("Shot=run,Approach speed [mm/s]=v_n_in [kg]", "'Approach speed [mm/s]'"),
    ],
)
def test_a_bad_mapping_is_refused_in_one_line(
    cli, db: str, tmp_path: Path, columns: str, expected: str
) -> None:
    lab = write_csv(tmp_path / "lab.csv", [LAB_ROW], LAB_HEADER)
    before = dump_hash(db)
    result = cli("collisions", "import", str(lab), "--dataset", "d", "--columns", columns, db=db)
    assert result.exit_code == 1, result.stdout
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and expected in lines[0], result.stderr
    assert dump_hash(db) == before


def test_python_refuses_a_mapping_that_is_not_text(db: str, tmp_path: Path) -> None:
    lab = write_csv(tmp_path / "lab.csv", [LAB_ROW], LAB_HEADER)
    with pytest.raises(ValidationError, match="columns: 3 must be a dict"):
        granudb.import_collisions(lab, dataset="d", columns=3, db=db)
    with pytest.raises(ValidationError, match="columns: 'Shot' must map text to text"):
        granudb.import_collisions(lab, dataset="d", columns={"Shot": 1}, db=db)
