"""DEM reproduction of Kharaz et al.'s e_t(θ) in LIGGGHTS, LAMMPS and Yade: each code's
e_t per angle against the experiment, within the data's u. Three points keep it short
(about 4 s for the three codes); `granudb reference dem kharaz-gorham-salman-2001` runs
all eleven."""

from __future__ import annotations

import json
import math
import shutil

import pytest

import granudb

KHARAZ = "kharaz-gorham-salman-2001"
POINTS = ["et-03", "et-05", "et-09"]
BINARIES = {"liggghts": "liggghts", "lammps": "lmp", "yade": "yade"}


def test_each_code_against_the_experiment_per_angle(cli) -> None:
    result = granudb.reference_dem(KHARAZ, points=POINTS)
    rows = result["rows"]
    assert {(r["code"], r["point"]) for r in rows} == {(c, p) for c in BINARIES for p in POINTS}
    assert result["inputs"]["sliding_friction"] == 0.092
    experiment = {
        c["point"]: c["reported"]
        for c in granudb.reference_reproduce(KHARAZ)["checks"]
        if c["quantity"] == "tangential_restitution"
    }
    for row in rows:
        assert row["reported"] == experiment[row["point"]]  # the experiment, not a target
        if shutil.which(BINARIES[row["code"]]) is None:
            assert row["status"] == "not checked" and row["verdict"] == "not checked"
            continue
        assert row["status"] == "checked", row
        assert math.isfinite(row["computed"]) and 0.0 < row["computed"] < 1.1
        assert row["verdict"] == ("agrees" if abs(row["residual"]) <= 2 * row["u_combined"]
                                  else "differs")  # fmt: skip
        if row["point"] == "et-05":  # 30°, on the sliding branch: μ_f = 0.092 holds
            assert abs(row["residual"]) < 0.01, row
    shown = cli("reference", "dem", KHARAZ, "--code", "lammps", "--point", "et-05",
                "--format", "json")  # fmt: skip
    assert shown.exit_code == 0, shown.stderr
    printed = json.loads(shown.stdout)["rows"]
    direct = [r for r in rows if r["code"] == "lammps" and r["point"] == "et-05"]
    assert [r["verdict"] for r in printed] == [r["verdict"] for r in direct]


def test_a_wet_dataset_says_why_it_has_no_dem_run(cli) -> None:
    result = cli("reference", "dem", "gondret-lance-petit-2002")
    assert result.exit_code == 1
    assert "has no DEM reproduction" in result.stderr and "e(St)" in result.stderr
    with pytest.raises(granudb.ValidationError, match="is not one of"):
        granudb.reference_dem(KHARAZ, codes=["mercury"])
    with pytest.raises(granudb.ValidationError, match="is not one of"):
        granudb.reference_dem(KHARAZ, points=["et-99"])
