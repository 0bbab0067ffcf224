"""What each writer produces, and what it refuses, without running a code."""

from __future__ import annotations

import dataclasses
import math

import pytest
from dem.dem_cases import E_DRY, GLASS, MU_GLASS, ZERODUR, dry_model, wet_model

from granudb.dem import lammps, liggghts, mercurydpm, yade
from granudb.dem.spec import DemModel, PairParameters, ParticleType, Value
from granudb.errors import ValidationError


def low_e_model() -> DemModel:
    """Glass in 78 % glycerol with e = 0.97 exp(-35/7.5) = 0.00912 (the law at St = 7.5,
    which the prediction itself calls "no rebound": a value given, not predicted)."""
    from dataclasses import replace

    from granudb.dem.spec import Value

    model = wet_model("glycerol78", speed=0.3)
    low = Value(0.97 * math.exp(-35 / 7.5), "given: e at St = 7.5")
    pairs = [replace(p, restitution=low) if "glass" in (p.type_i, p.type_j) else p
             for p in model.pairs]  # fmt: skip
    return DemModel(list(model.types), pairs, model.characteristic_velocity_m_s)


def test_liggghts_matrices_are_full_and_commented() -> None:
    text = liggghts.write(dry_model())
    assert "hard_particles yes" in text
    assert "coefficientRestitution peratomtypepair 3 &" in text
    assert "fix granudb_youngsModulus all property/global youngsModulus peratomtype" in text
    assert "2-3 steel/zerodur: coefficientFriction = 0.11 (Joseph & Hunt 2004" in text
    assert "coefficientRollingFriction" not in text


@pytest.mark.parametrize(
    ("writer", "rule"),
    [
        (liggghts, "LIGGGHTS refuses e <= 0.05"),
        (lammps, "LAMMPS damping tsuji reaches only 0.2628 <= e"),
        (yade, "Yade Hertz-Mindlin with viscous damping: e < 0.01"),
    ],
)
def test_unrepresentable_restitution_is_refused_in_one_line(writer: object, rule: str) -> None:
    with pytest.raises(ValidationError) as info:
        writer.write(low_e_model())  # type: ignore[attr-defined]
    message = str(info.value)
    assert "\n" not in message and rule in message and "--clamp" in message
    assert message.startswith("restitution glass/")


def test_liggghts_clamp_writes_the_floor_with_a_comment() -> None:
    text = liggghts.write(low_e_model(), clamp=True)
    # the floor target 0.2138, whose limitForce input is just above LIGGGHTS's 0.05
    assert "CLAMPED from 0.009121455675 to 0.2137" in text and "\n    0.05009" in text


def test_liggghts_soft_particles_below_its_floor() -> None:
    soft = ParticleType("rubber", 1e6, 0.45, 1100.0, 0.01)
    pairs = [
        PairParameters("rubber", "rubber", Value(0.8, "assumed"), Value(0.5, "assumed")),
        PairParameters("rubber", "zerodur", Value(0.8, "assumed"), Value(0.5, "assumed")),
    ]
    text = liggghts.write(DemModel([soft, ZERODUR], pairs, 1.0))
    assert "soft_particles yes" in text
    # μ_f 0.5 does not slide throughout at 60°: nothing to correct, and the deck says so
    assert text.replace("\n# ", " ").count("does not slide throughout with this mu_f") == 2


@pytest.mark.parametrize(
    ("writer", "written"),
    [
        (liggghts, "coefficientFriction peratomtypepair 3 &\n    0.106 "),
        (lammps, "0.0 0.106 damping"),
    ],
)
def test_dry_friction_is_written_as_measured(writer, written: str) -> None:
    """A dry pair (e 0.97) loses under 0.1 % of its friction at first touch: LIGGGHTS and
    LAMMPS get μ_f as measured; a wet pair in 78 % glycerol gets a larger input, with
    what it gives at 45° and 80° (Yade corrects every pair: its spring is incremental)."""
    dry = writer.write(dry_model())
    assert "mu_f input" not in dry
    assert " 0.106 " in dry or "0.106\n" in dry or " 0.106" in dry
    wet = writer.write(wet_model("glycerol78"))
    assert "mu_f input" in wet and "at 45 deg and" in wet


def test_rolling_friction_switches_models() -> None:
    model = dry_model()
    pairs = [dataclasses.replace(p, rolling_friction=Value(0.002, "assumed")) for p in model.pairs]
    model = DemModel(model.types, pairs, 0.3)
    assert "coefficientRollingFriction peratomtypepair 3" in liggghts.write(model)
    assert liggghts.pair_style(model).endswith("rolling_friction cdt")
    assert "rolling sds" in lammps.write(model)
    assert "setRollingFrictionCoefficient(0.002)" in mercurydpm.write(model)


def test_lammps_writes_every_pair_and_wall_explicitly() -> None:
    text = lammps.write(dry_model())
    for i, j in ((1, 1), (1, 2), (2, 2)):
        assert f"pair_coeff {i} {j} hertz " in text
    assert text.count("wall/gran granular hertz") == 2
    assert "${granudb_wall_zerodur}" in text and "damping tsuji" in text


def test_yade_uses_matchmakers_for_every_pair() -> None:
    text = yade.write(dry_model())
    assert text.count("math.atan(") == 5 and "betan=MatchMaker" in text
    compile(text, "fragment", "exec")


def test_mercurydpm_uses_documented_api_names() -> None:
    text = mercurydpm.write(dry_model())
    for name in mercurydpm.API_NAMES:
        if name != "setRollingFrictionCoefficient":
            assert name in text, name
    assert "LinearViscoelasticSlidingFrictionSpecies" in text
    assert "getMixedObject(glass, zerodur)" in text


def test_every_number_has_its_source() -> None:
    model = DemModel(
        [GLASS, ZERODUR],
        [
            PairParameters("glass", "glass", E_DRY, MU_GLASS),
            PairParameters("glass", "zerodur", E_DRY, MU_GLASS),
        ],
        0.3,
    )
    for writer in (liggghts, lammps, yade, mercurydpm):
        assert "Joseph & Hunt 2004 §3, glass on Zerodur" in writer.write(model)


def test_the_lammps_fragment_says_where_it_goes() -> None:
    """Groups by type hold the atoms that exist when made: the fragment says to include it
    after the atoms exist (granudb's own verify includes it there)."""
    text = lammps.write(dry_model())
    header = " ".join(line.lstrip("# ") for line in text.splitlines() if line.startswith("#"))
    assert "after the atoms exist" in header and "never straight after create_box" in header


def test_a_wet_deck_states_the_speeds_its_constant_e_holds_for() -> None:
    """glass in 37 % glycerol at 0.3 m/s: e(St) stays within 1 % of the constant between
    the two speeds the deck writes (St proportional to V)."""
    import re

    model = wet_model("glycerol37")
    pair = model.pair("glass", "zerodur")
    text = lammps.write(model)
    found = re.search(r"normal impact speeds ([0-9.]+) m/s to ([0-9.]+) m/s", " ".join(
        line.lstrip("# ") for line in text.splitlines()))  # fmt: skip
    assert found is not None
    st_per_speed = pair.wet.stokes_at(pair.restitution.value) / 0.3
    for speed, bound in zip(map(float, found.groups()), (0.99, 1.01), strict=True):
        ratio = pair.wet.restitution(st_per_speed * speed) / pair.restitution.value
        assert ratio == pytest.approx(bound, abs=2e-4)


def test_lammps_takes_a_measured_beta_liggghts_and_yade_say_they_cannot() -> None:
    text = lammps.write(dry_model())
    assert "rebounds with beta = 0.34" in text and "tangential mindlin 5.511919526e+10" in text
    for writer in (liggghts, yade):
        assert "beta NOT reproduced (glass/zerodur 0.39" in writer.write(dry_model())
    assert "beta NOT reproduced" not in liggghts.write(wet_model("glycerol78"))


def test_yade_refuses_a_friction_its_damped_contact_cannot_slide_with() -> None:
    """Glass in 78 % glycerol at 0.12 m/s (e ≈ 0.03): Yade's contact sticks so long at
    first touch that no μ_f input up to 1.3 times the target gives it at 60°; refused in
    one line, or written at that limit with --clamp and said so."""
    model = wet_model("glycerol78", speed=0.12)
    with pytest.raises(ValidationError, match="sticks so long at first touch.*--clamp"):
        yade.write(model)
    text = yade.write(model, clamp=True)
    assert "CLAMPED from 0.106 to" in text
