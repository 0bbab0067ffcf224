"""What the particle hits is a choice stated everywhere: a flat wall, a fixed sphere or a
free sphere at rest (docs/physics.md §9), with m*, St and the Walton factor of that case."""

from __future__ import annotations

import csv
import io
import json

import pytest

import granudb
from granudb.errors import ValidationError

SCENARIO = {"diameter": "12.7 mm", "velocity": "0.3 m/s", "fluid": "water"}


def test_two_equal_free_spheres_halve_the_mass_and_double_st(opened) -> None:
    wall = granudb.pair("steel", "steel", **SCENARIO, db=opened)
    free = granudb.pair("steel", "steel", wall_diameter="12.7 mm", **SCENARIO, db=opened)
    fixed = granudb.pair(
        "steel", "steel", wall_diameter="12.7 mm", target="fixed", **SCENARIO, db=opened
    )
    assert (wall["inputs"]["target"], free["inputs"]["target"]) == ("wall", "free")
    assert fixed["inputs"]["target"] == "fixed"
    m1 = wall["effective_mass_kg"]
    assert free["effective_mass_kg"] == pytest.approx(m1 / 2, rel=1e-12)
    assert fixed["effective_mass_kg"] == pytest.approx(m1, rel=1e-12)
    st_wall = wall["normal_stokes_number"]
    assert free["normal_stokes_number"] == pytest.approx(2 * st_wall, rel=1e-12)
    assert fixed["normal_stokes_number"] == pytest.approx(4 * st_wall, rel=1e-12)
    assert free["walton_factor"] == pytest.approx(3.5, rel=1e-12)  # two equal spheres
    assert free["effective_radius_m"] == pytest.approx(12.7e-3 / 4, rel=1e-12)


@pytest.mark.parametrize(
    ("target", "wall_diameter", "words"),
    [
        ("free", None, "give its wall_diameter"),
        ("fixed", None, "give its wall_diameter"),
        ("wall", "12.7 mm", "no wall_diameter"),
        ("loose", "12.7 mm", "must be one of wall, fixed, free"),
    ],
)
def test_an_impossible_target_is_refused(opened, target, wall_diameter, words) -> None:
    with pytest.raises(ValidationError, match=words):
        granudb.pair(
            "steel", "steel", wall_diameter=wall_diameter, target=target, **SCENARIO, db=opened
        )


def test_every_format_says_what_the_particle_hits(cli, db: str, tmp_path) -> None:
    args = ["pair", "steel", "steel", "--wall-diameter", "12.7 mm", "--diameter", "12.7 mm",
            "--velocity", "0.3 m/s", "--target", "fixed"]  # fmt: skip
    table = cli(*args, db=db)
    assert table.exit_code == 0, table.stderr
    assert "fixed sphere, d = 12.7 mm" in table.stdout
    document = json.loads(cli(*args, "--format", "json", db=db).stdout)
    assert document["inputs"]["target"] == "fixed"
    assert document["inputs"]["wall_diameter_m"] == pytest.approx(0.0127)
    (row,) = csv.DictReader(io.StringIO(cli(*args, "--format", "csv", db=db).stdout))
    assert row["target"] == "fixed"
    out = tmp_path / "r.md"
    report = cli("report", "--pair", "steel", "steel", "--wall-diameter", "12.7 mm", "--format",
                 "md", "--output", str(out), db=db)  # fmt: skip
    assert report.exit_code == 0, report.stderr
    assert "free sphere at rest" in out.read_text("utf-8")
