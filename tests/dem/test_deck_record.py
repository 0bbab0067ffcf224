"""A deck's values are ``granudb pair``'s, labelled as ``pair`` labels them, and its low /
high sets take their interval from the stored ± or from ``pair``'s propagation (issue 33)."""

from __future__ import annotations

import math

import pytest

import granudb
from granudb.api.dem import dem_model
from granudb.dem import deck

SCENARIO = {"diameter": "12.7 mm", "velocity": "0.3 m/s"}


def _pair(particle: str, wall: str, fluid: str | None, db: str) -> dict:
    return granudb.pair(particle, wall, fluid=fluid, db=db, **SCENARIO)


@pytest.mark.parametrize("fluid", [None, "glycerol-37", "glycerol-78"])
def test_the_deck_writes_the_mu_and_e_pair_uses_with_its_words(fluid: str | None, db: str) -> None:
    model = dem_model(["steel", "glass"], ["Zerodur"], fluid=fluid, db=db, **SCENARIO)
    text = granudb.dem_export("lammps", ["steel", "glass"], ["Zerodur"], fluid=fluid, db=db,
                              **SCENARIO)  # fmt: skip
    flat = " ".join(line.removeprefix("#").strip() for line in text.splitlines())
    for particle in ("steel", "glass"):
        said = _pair(particle, "Zerodur", fluid, db)
        dry = said["dry_values"]
        pair = model.pair(particle, "Zerodur_wall")
        used = said["friction_coefficient_used"]
        assert pair.friction.value == used
        kind = "dry" if fluid is None else "immersed"
        source = dry["dry_friction_source" if fluid is None else "immersed_friction_source"]
        assert f"the {kind} friction {used:g} granudb pair uses, {source}" in flat
        assert f"mu_f = {deck.num(used)} (the {kind} friction" in flat
        if fluid is None:
            assert pair.restitution.value == said["restitution_ceiling"] == dry["dry_restitution"]
            assert dry["dry_restitution_source"] in pair.restitution.provenance
        else:
            assert pair.restitution.value == pytest.approx(said["predicted_restitution"], rel=1e-12)
    if fluid == "glycerol-37":  # the published 0.02 is named, with why neither uses it
        steel = model.pair("steel", "Zerodur_wall").friction
        assert steel.value == 0.11 and "not the published joseph-hunt-2004 §4, figure 11" in (
            steel.provenance
        )
        assert "granudb pair does not use it either" in steel.provenance


def _materials(db: str) -> None:
    granudb.add_material("rdball", density="2500 kg/m^3 ± 1 %", youngs_modulus="60 GPa",
                         poisson_ratio=0.23, roughness="0.1 um", dry_restitution="0.8 ± 0.01",
                         dry_friction="0.3 ± 0.02", dry_source="lab note 1", db=db)  # fmt: skip
    granudb.add_material("rdplate", density="2500 kg/m^3", youngs_modulus="70 GPa",
                         poisson_ratio=0.23, roughness="0.1 um", dry_restitution="0.9 ± 0.02",
                         dry_friction="0.2 ± 0.01", dry_source="lab note 2", db=db)  # fmt: skip


def _sets(db: str, **options: object) -> dict[str, object]:
    return {
        s: dem_model(
            ["rdball"],
            ["rdplate"],
            values="predicted",
            parameter_set=s,
            db=db,
            **SCENARIO,
            **options,
        ).pair("rdball", "rdplate_wall")  # fmt: skip
        for s in ("central", "low", "high")
    }


def test_low_and_high_bracket_stored_dry_values_by_2u(db: str) -> None:
    _materials(db)
    sets = _sets(db)
    e = [sets[s].restitution.value for s in ("low", "central", "high")]
    assert e == pytest.approx([0.8 - 0.02, 0.8, 0.8 + 0.02])  # the lower e, its own u
    mu = math.sqrt(0.3 * 0.2)
    u = mu / 2 * math.hypot(0.02 / 0.3, 0.01 / 0.2)  # GUM for the geometric mean
    friction = [sets[s].friction.value for s in ("low", "central", "high")]
    assert friction == pytest.approx([mu - 2 * u, mu, mu + 2 * u])
    assert "the stated u of rdball's dry restitution" in sets["low"].restitution.provenance
    assert "stated u of both materials' dry friction" in sets["high"].friction.provenance
    text = granudb.dem_export("yade", ["rdball"], ["rdplate"], values="predicted",
                              parameter_set="low", db=db, **SCENARIO)  # fmt: skip
    assert "no interval stated" not in text and "low end of the ± 2u" in text


def test_predicted_wet_e_takes_the_propagated_u(db: str) -> None:
    _materials(db)
    sets = _sets(db, fluid="glycerol-37")
    said = _pair("rdball", "rdplate", "glycerol-37", db)
    e = said["predicted_restitution"]
    u_flow = said["u_predicted_restitution"]
    assert u_flow > 0  # the particle's density carries ± 1 %
    u = math.hypot(e / 0.8 * 0.01, u_flow)
    central = sets["central"].restitution
    assert central.value == pytest.approx(e, rel=1e-12)
    assert (central.low, central.high) == pytest.approx((e - 2 * u, e + 2 * u))
    assert sets["low"].restitution.value == pytest.approx(e - 2 * u)
    assert sets["high"].restitution.value == pytest.approx(e + 2 * u)
    assert "from the inputs' stated u as granudb pair gives it" in central.interval
