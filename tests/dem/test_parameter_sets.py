"""Low / central / high parameter sets for sensitivity runs (issue 27): every exported value
carries its interval in its comment, and ``--set low|high`` writes each value at that end
of it — the ends being the fit's own interval or ± 2u from a stated u, never invented."""

from __future__ import annotations

import math
import re

import pytest
from dem.dem_cases import require
from paper_runs import paper_rows, write_csv

import granudb
from granudb.api.dem import dem_model
from granudb.dem import liggghts
from granudb.dem.spec import Value
from granudb.errors import ValidationError

STEEL = {"diameter": "12.7 mm", "velocity": "0.3 m/s"}


def friction_matrix(deck: str) -> list[float]:
    """The numbers of LIGGGHTS's coefficientFriction matrix (particle, wall)."""
    block = deck.split("coefficientFriction peratomtypepair 2", 1)[1].split("fix", 1)[0]
    return [float(x) for x in re.findall(r"^\s+([0-9.eE+-]+)", block, flags=re.M)]


def test_a_value_at_each_end_of_its_interval_and_without_one() -> None:
    v = Value.uncertain(0.11, "paper", 0.003, "(the paper's ±)", (0.0, math.inf))
    assert (v.at("low").value, v.at("central").value, v.at("high").value) == pytest.approx(
        (0.104, 0.11, 0.116)
    )
    assert "low end of the ± 2u" in v.at("low").provenance
    bare = Value(0.5, "assumed")
    assert bare.at("high").value == 0.5 and "no interval stated" in bare.at("high").provenance
    cut = Value.uncertain(0.97, "paper", 0.02, "(±)", (0.0, 1.0))
    assert cut.high == 1.0 and "cut to [0, 1]" in cut.interval
    with pytest.raises(ValidationError, match="must hold the value"):
        Value(0.5, "x", 0.6, 0.7, "95 % interval")
    with pytest.raises(ValidationError, match="parameter_set"):
        bare.at("medium")


def test_published_values_give_the_ends_of_their_stated_uncertainty(db: str) -> None:
    decks = {
        which: granudb.dem_export(
            "liggghts", ["steel"], ["Zerodur"], parameter_set=which, db=db, **STEEL
        )
        for which in ("low", "central", "high")
    }
    # Joseph & Hunt: μ_f = 0.11 ± 0.003 → 0.104 / 0.11 / 0.116 in the code's own matrix
    assert friction_matrix(decks["central"])[0] == pytest.approx(0.11)
    assert friction_matrix(decks["low"])[0] == pytest.approx(0.104)
    assert friction_matrix(decks["high"])[0] == pytest.approx(0.116)
    comments = " ".join(decks["central"].replace("\n#", " ").split())
    assert (
        "± 2u (k = 2, about 95 %), u = 0.003 (the source's ±: joseph-hunt-2004 §3, figure 4: "
        "μ_f = 0.11 ± 0.003): 0.104–0.116" in comments
    )
    assert "Parameter set" not in decks["central"]
    assert "Parameter set: HIGH" in decks["high"]


def test_dataset_sets_are_the_walton_fits_interval(cli, db: str, tmp_path) -> None:
    source = write_csv(tmp_path / "runs.csv", paper_rows(runs_per_group=24))
    assert cli("collisions", "import", str(source), "--dataset", "sens", db=db).exit_code == 0
    [fit] = [
        f for f in granudb.fit_walton(db=db, dataset="sens", as_frame=False)
        if (f["particle"], f["fluid"]) == ("steel", "dry")
    ]  # fmt: skip
    assert fit["sliding_friction_low"] < fit["sliding_friction"] < fit["sliding_friction_high"]
    got = {
        which: friction_matrix(
            granudb.dem_export(
                "liggghts", ["steel"], ["Zerodur"], values="dataset", dataset="sens",
                parameter_set=which, db=db, **STEEL,
            )
        )[0]
        for which in ("low", "central", "high")
    }  # fmt: skip
    # one answer: the deck's ends are the fit's interval, as `fit walton` prints it
    assert got["low"] == pytest.approx(fit["sliding_friction_low"], rel=1e-9)
    assert got["central"] == pytest.approx(fit["sliding_friction"], rel=1e-9)
    assert got["high"] == pytest.approx(fit["sliding_friction_high"], rel=1e-9)
    # the deck says which of granudb pair's values the dataset's fit replaces (issue 33)
    model = dem_model(["steel"], ["Zerodur"], values="dataset", dataset="sens", db=db, **STEEL)
    friction = model.pair("steel", "Zerodur_wall").friction
    assert friction.provenance.startswith("dataset sens: Walton fit")
    assert "--values dataset: instead of the 0.11 granudb pair uses" in friction.provenance


def test_a_wet_restitution_follows_the_dry_e_of_its_set(db: str) -> None:
    def e_of(which: str) -> float:
        model = dem_model(
            ["glass"], ["Zerodur"], fluid="glycerol-45", parameter_set=which, db=db, **STEEL
        )
        return model.pairs[0].restitution.value

    low, central, high = e_of("low"), e_of("central"), e_of("high")
    assert low < central <= high
    model = dem_model(["glass"], ["Zerodur"], fluid="glycerol-45", db=db, **STEEL)
    wet = model.pairs[0].restitution
    assert wet.low == pytest.approx(low) and wet.high == pytest.approx(high)


def test_an_unknown_set_is_refused_in_one_line(cli, db: str) -> None:
    with pytest.raises(ValidationError) as info:
        granudb.dem_export("liggghts", ["steel"], ["Zerodur"], parameter_set="max", db=db, **STEEL)
    assert "parameter_set" in str(info.value) and "\n" not in str(info.value)
    result = cli(
        "dem", "export", "--code", "liggghts", "--particle", "steel", "--wall", "Zerodur",
        "--diameter", "12.7 mm", "--velocity", "0.3 m/s", "--set", "max", db=db,
    )  # fmt: skip
    assert result.exit_code != 0 and "Traceback" not in result.stderr
    assert "must be one of central, low, high" in result.stderr


@pytest.mark.dem_run
def test_the_low_and_high_decks_run_to_their_own_values(db: str) -> None:
    require("liggghts")
    for which in ("low", "high"):
        records = granudb.dem_verify(
            ["steel"], ["Zerodur"], codes=("liggghts",), parameter_set=which, db=db, **STEEL
        )
        assert granudb.api.verify_passed(records), granudb.api.verify_table(records)
    text = liggghts.write(dem_model(["steel"], ["Zerodur"], parameter_set="low", db=db, **STEEL))
    assert friction_matrix(text)[0] == pytest.approx(0.104)
