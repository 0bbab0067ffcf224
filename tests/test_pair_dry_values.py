"""A pair's dry restitution and friction come from one rule, with their source in every
output (docs/physics.md §18): the pair table, else the two materials' own values, else
Joseph & Hunt's steel on Zerodur, labelled borrowed. Brittleness is stored, not guessed;
past yield the prediction is Thornton's elastic–plastic e; Hertz's small strain is
checked (§15, §16)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pandas as pd
import pytest
from sqlalchemy import select

import granudb
from granudb.db.models import PublishedValue
from granudb.errors import ConflictError, ValidationError
from granudb.physics.limits import HERTZ_STRAIN_LIMIT, thornton_restitution
from granudb.reporting.sections import dataset_flag

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "collisions_example.csv"
SPHERE = {"diameter": "12.7 mm", "velocity": "0.3 m/s"}
PLAIN = {"density": 2000, "youngs_modulus": "1 GPa", "poisson_ratio": 0.3, "roughness": 0}


def _verdict(document: dict, key: str) -> dict:
    return next(v for v in document["verdicts"] if v["key"] == key)


def test_predicted_restitution_follows_the_materials_dry_restitution(opened) -> None:
    granudb.add_material("soft", **PLAIN, dry_restitution=0.6, dry_source="lab A", db=opened)
    granudb.add_material("hard", **PLAIN, dry_restitution=0.9, dry_source="lab B", db=opened)
    granudb.add_material("block", **PLAIN, db=opened)
    soft = granudb.pair("soft", "block", **SPHERE, db=opened)
    hard = granudb.pair("hard", "block", **SPHERE, db=opened)
    assert soft["predicted_restitution"] == 0.6 and hard["predicted_restitution"] == 0.9
    for document, lab in ((soft, "lab A"), (hard, "lab B")):
        assert document["dry_values"]["dry_restitution_basis"] == "materials"
        assert lab in document["dry_values"]["dry_restitution_source"]
        assert lab in _verdict(document, "predicted_restitution")["text"]
    # wet: the same e_dry scales the Stokes-number form
    wet = [
        granudb.pair(m, "block", fluid="water", **SPHERE, db=opened)["predicted_restitution"]
        for m in ("soft", "hard")
    ]
    assert wet[0] / wet[1] == pytest.approx(0.6 / 0.9)


def test_two_materials_combine_by_the_stated_rule(opened) -> None:
    granudb.add_material("a", **PLAIN, dry_restitution=0.8, dry_friction=0.4, db=opened)
    granudb.add_material("b", **PLAIN, dry_restitution=0.95, dry_friction=0.1, db=opened)
    values = granudb.dry_values("a", "b", db=opened)
    assert values["dry_restitution"] == 0.8  # the lower
    assert values["dry_friction"] == pytest.approx(math.sqrt(0.4 * 0.1))  # √(μ₁μ₂)
    assert "granudb's rule" in values["dry_friction_source"]
    reverse = granudb.dry_values("b", "a", db=opened)
    assert (reverse["dry_restitution"], reverse["dry_friction"]) == (0.8, values["dry_friction"])


def test_without_values_the_borrowed_ones_say_so_everywhere(opened, cli, db: str) -> None:
    granudb.add_material("x", **PLAIN, db=opened)
    document = granudb.pair("x", "x", **SPHERE, db=opened)
    borrowed = "borrowed: steel on Zerodur, Joseph & Hunt 2004 §3"
    assert document["dry_values"]["dry_restitution_source"] == borrowed
    assert document["dry_values"]["dry_friction_basis"] == "borrowed"
    assert borrowed in _verdict(document, "predicted_restitution")["text"]
    assert borrowed in _verdict(document, "lubricated_friction_state")["text"]
    shown = cli("pair", "x", "x", "--diameter", "12.7 mm", "--velocity", "0.3 m/s", db=db)
    assert "borrowed: steel on Zerodur" in shown.stdout
    as_json = cli(
        "pair", "x", "x", "--diameter", "1 cm", "--velocity", "1 m/s", "--format", "json", db=db
    )
    assert json.loads(as_json.stdout)["dry_values"]["dry_restitution_basis"] == "borrowed"


def test_the_pair_table_comes_first_either_way_round(opened) -> None:
    for first, second in (("steel", "Zerodur"), ("Zerodur", "steel")):
        values = granudb.dry_values(first, second, db=opened)
        assert (values["dry_restitution"], values["dry_friction"]) == (0.97, 0.11)
        assert values["dry_friction_basis"] == "pair"
        assert "joseph-hunt-2004, §3, figure 4" in values["dry_friction_source"]
    assert granudb.dry_values("glass", "Zerodur", db=opened)["dry_friction"] == 0.106
    # the materials' own values (Nijssen et al.'s glass: 0.4) do not override the pair's
    assert granudb.material("glass", db=opened)["dry_friction"] == 0.4


def test_adding_pair_values_once_and_refusing_bad_ones(opened) -> None:
    added = granudb.add_pair_value(
        "Delrin", "glass", dry_restitution="0.9", notes="a test", db=opened
    )
    assert added["dry_restitution"] == 0.9 and added["dry_restitution_basis"] == "pair"
    assert added["dry_friction_basis"] == "materials"  # the pair has no friction of its own
    with pytest.raises(ConflictError, match="already has dry values"):
        granudb.add_pair_value("glass", "Delrin", dry_friction=0.3, notes="a test",
                               db=opened)  # fmt: skip
    with pytest.raises(ValidationError, match="dry_restitution"):
        granudb.add_pair_value("steel", "Delrin", dry_restitution=1.5, notes="a test",
                               db=opened)  # fmt: skip
    with pytest.raises(ValidationError, match="or dry_friction or immersed_friction is needed"):
        granudb.add_pair_value("steel", "Delrin", notes="a test", db=opened)
    with pytest.raises(ValidationError, match="source: .* is required unless notes say"):
        granudb.add_pair_value("steel", "Delrin", dry_friction=0.2, db=opened)
    with pytest.raises(ValidationError, match="brittleness"):
        granudb.update_material("Delrin", brittleness="soft", db=opened)
    rows = granudb.pair_values(db=opened, as_frame=False)
    assert ("Delrin", "glass", "a test") in {(r["particle"], r["wall"], r["notes"])
                                             for r in rows}  # fmt: skip


def test_the_command_line_sets_and_shows_them(cli, db: str) -> None:
    added = cli(
        "materials", "add", "PTFE", "--density", "2.2 g/cm^3", "--youngs-modulus", "0.5 GPa",
        "--poisson-ratio", "0.46", "--roughness", "0.2 um", "--dry-restitution", "0.5",
        "--dry-friction", "0.05", "--dry-source", "a lab note", "--brittleness", "ductile", db=db,
    )  # fmt: skip
    assert added.exit_code == 0, added.stderr
    shown = json.loads(cli("pairs", "show", "PTFE", "steel", "--format", "json", db=db).stdout)
    assert shown["dry_restitution"] == 0.5 and "a lab note" in shown["dry_restitution_source"]
    bad = cli("materials", "update", "PTFE", "--dry-restitution", "0", db=db)
    assert bad.exit_code == 1 and "--dry-restitution: 0 must be > 0" in bad.stderr
    pair = cli("pairs", "add", "PTFE", "glass", "--dry-friction", "0.2", "--source", "x", db=db)
    assert pair.exit_code == 1 and "source" in pair.stderr
    listed = cli("pairs", "list", "--format", "csv", db=db).stdout
    assert listed.splitlines()[0].startswith("particle,wall,dry_restitution,dry_friction")


def test_brittleness_is_read_not_guessed(opened) -> None:
    """PTFE on glass used to print "Brittle bodies do not yield" because PTFE had no
    yield stress; now only a material stored as brittle gets the note."""
    granudb.add_material("PTFE", density="2.2 g/cm^3", youngs_modulus="0.5 GPa",
                         poisson_ratio=0.46, roughness="0.2 um", db=opened)  # fmt: skip
    on_glass = _verdict(granudb.pair("PTFE", "glass", **SPHERE, db=opened), "elastic_state")
    assert "glass is stored as brittle" in on_glass["text"]
    assert "PTFE" not in on_glass["text"].split("stored as brittle")[0].split(".")[-1]
    on_steel = _verdict(granudb.pair("PTFE", "steel", **SPHERE, db=opened), "elastic_state")
    assert "brittle" not in on_steel["text"]
    assert granudb.material("Zerodur", db=opened)["brittleness"] == "brittle"


def test_past_yield_the_prediction_is_elastic_plastic_with_its_source(opened) -> None:
    """Hard steel on aluminium at 0.3 m/s is well past yield: Thornton's e, not 0.97."""
    hard = {"youngs_modulus": "210 GPa", "poisson_ratio": 0.3, "yield_stress": "2 GPa"}
    soft = {"youngs_modulus": "70 GPa", "poisson_ratio": 0.33, "yield_stress": "300 MPa"}
    granudb.add_material("hard steel", density=7800, roughness=0, **hard, db=opened)
    granudb.add_material("aluminium", density=2700, roughness=0, **soft, db=opened)
    document = granudb.pair("hard steel", "aluminium", **SPHERE, db=opened)
    assert document["elastic_state"] == "yield_exceeded"
    assert document["restitution_model"] == "elastic_plastic"
    ratio = document["yield_speed_m_s"] / document["normal_speed_m_s"]
    assert 1 / 15 < ratio < 1 / 8  # about 11 × V_y, as the issue says
    expected = float(thornton_restitution(document["yield_speed_m_s"], 0.3))
    assert document["predicted_restitution"] == pytest.approx(expected, rel=1e-12)
    assert 0.55 < document["predicted_restitution"] < 0.7 < 0.97
    said = _verdict(document, "predicted_restitution")
    assert said["raised"] and "Thornton (1997)" in said["text"]
    assert "Thornton (1997)" in _verdict(document, "elastic_state")["text"]
    slow = granudb.pair("hard steel", "aluminium", diameter="12.7 mm", velocity="1 mm/s",
                        db=opened)  # fmt: skip
    assert slow["restitution_model"] == "elastic"
    assert slow["predicted_restitution"] == document["dry_values"]["dry_restitution"]


def test_rubber_at_five_metres_per_second_is_outside_hertz(opened) -> None:
    granudb.add_material("rubber", density=1100, youngs_modulus="5 MPa", poisson_ratio=0.49,
                         roughness=0, db=opened)  # fmt: skip
    document = granudb.pair("rubber", "steel", diameter="12.7 mm", velocity="5 m/s", db=opened)
    assert document["contact_radius_ratio"] == pytest.approx(0.44, abs=0.005)
    assert document["approach_ratio"] == pytest.approx(0.19, abs=0.005)
    assert document["hertz_strain_valid"] is False
    said = _verdict(document, "hertz_strain_valid")
    assert said["raised"] and said["text"].startswith("Hertz not valid")
    assert f"a/R* ≤ {HERTZ_STRAIN_LIMIT:g}" in said["text"]
    steel = granudb.pair("steel", "Zerodur", **SPHERE, db=opened)
    assert steel["hertz_strain_valid"] is True
    assert _verdict(steel, "hertz_strain_valid")["text"].startswith("valid")


def test_a_release_keeps_the_dry_values_it_was_released_with(opened) -> None:
    granudb.import_collisions(EXAMPLE, dataset="lab", db=opened)
    granudb.release_dataset("lab", db=opened)
    before = granudb.dry_values("steel", "glass", dataset="lab", db=opened)
    granudb.update_material("steel", dry_restitution=0.5, db=opened)
    granudb.add_pair_value("steel", "glass", dry_friction=0.3, notes="a test", db=opened)
    live = granudb.dry_values("steel", "glass", db=opened)
    assert (live["dry_restitution"], live["dry_friction"]) == (0.5, 0.3)
    assert granudb.dry_values("steel", "glass", dataset="lab", db=opened) == before
    assert before["dry_restitution"] == 0.97 and before["dry_friction_basis"] == "materials"


def test_stored_runs_use_the_same_rule(opened) -> None:
    """The listing's predicted e of a dry run is the pair's resolved e_dry."""
    granudb.import_collisions(EXAMPLE, dataset="lab", db=opened)
    granudb.update_material("Zerodur", dry_restitution=0.8, db=opened)  # the pair's 0.97 wins
    runs = granudb.collisions(dataset="lab", fluid="dry", wide=True, db=opened)
    pairs = {(p, w) for p, w in zip(runs["particle"], runs["wall"], strict=True)}
    for particle, wall in pairs:
        e = granudb.dry_values(particle, wall, db=opened)["dry_restitution"]
        chosen = runs[(runs["particle"] == particle) & (runs["wall"] == wall)]
        assert (chosen["predicted_restitution"] == e).all()


def test_immersed_glass_uses_the_friction_measured_in_a_liquid(opened) -> None:
    """Where asperities touch in a liquid, the pair's immersed value (glass on Zerodur:
    0.15, Joseph & Hunt §4) is used, not the dry 0.106; without one, the dry value, said
    so."""
    wet = granudb.pair("glass", "Zerodur", fluid="glycerol-45", angle="30 deg",
                       diameter="12.7 mm", velocity="0.1 m/s", db=opened)  # fmt: skip
    assert wet["roughness_regime"] == "asperity_contact"
    assert wet["friction_coefficient_used"] == wet["dry_values"]["immersed_friction"] == 0.15
    assert "in a liquid (joseph-hunt-2004" in _verdict(wet, "lubricated_friction_state")["text"]
    steel = granudb.dry_values("steel", "Zerodur", db=opened)
    assert steel["immersed_friction"] == steel["dry_friction"] == 0.11
    assert steel["immersed_friction_source"].startswith("the dry value (no immersed value")


ANVIL = "soda-lime glass (Kharaz anvil)"
KHARAZ = {"diameter": "5 mm", "velocity": "3.9 m/s"}


def test_alumina_on_soda_lime_glass_uses_kharaz_values_from_the_pair_table(
    opened, cli, db: str
) -> None:
    """Kharaz et al. (2001) as seeded (issue 23): the pair's dry μ and e are the published
    values read in the secondary source, taken from the pair table, in Python and the CLI."""
    with opened.session() as session:
        shipped = {
            v.quantity: (v.value, v.source.key)
            for v in session.scalars(select(PublishedValue))
            if v.label.startswith("dry alumina on soda-lime glass")
        }
    document = granudb.pair("alumina", ANVIL, **KHARAZ, db=opened)
    values = document["dry_values"]
    assert values["dry_friction"] == shipped["sliding_friction"][0] == 0.092
    assert values["dry_restitution"] == shipped["normal_restitution_mean"][0] == 0.98
    assert values["dry_friction_basis"] == values["dry_restitution_basis"] == "pair"
    assert shipped["sliding_friction"][1] in values["dry_friction_source"]
    assert "not read" in values["dry_friction_source"]
    assert document["predicted_restitution"] == 0.98  # dry, below yield: e_dry
    assert document["friction_coefficient_used"] == 0.092
    # dry: σ is not needed, and the roughness verdict is the dry one
    assert "dry contact" in _verdict(document, "roughness_regime")["text"]
    shown = cli("pair", "alumina", ANVIL, "--diameter", "5 mm", "--velocity", "3.9 m/s", db=db)
    assert shown.exit_code == 0, shown.stderr
    assert "e_dry = 0.98" in shown.stdout and "μ_dry = 0.092" in shown.stdout


def test_a_roughness_not_stated_leaves_the_wet_roughness_verdict_undetermined(
    opened, cli, db: str
) -> None:
    """In a liquid, σ-dependent quantities are NaN and the verdict names the materials
    whose roughness is not stated; with a stated roughness the same pair gets a verdict."""
    wet = granudb.pair("alumina", ANVIL, fluid="water", **KHARAZ, db=opened)
    for column in ("composite_roughness_m", "film_parameter"):
        assert wet[column] is None or math.isnan(wet[column])
    assert wet["roughness_regime"] == "not_stated"
    verdict = _verdict(wet, "roughness_regime")
    assert verdict["text"].startswith(
        f"not determined: roughness of alumina and {ANVIL} not stated"
    )
    assert verdict["raised"]
    # not a film: Maw's regime takes the friction where asperities touch (the dry μ here)
    assert wet["friction_coefficient_used"] == 0.092
    # a fluid with a pressure coefficient: (5.8) is not used either, and the text says why
    glycerol = granudb.pair("alumina", ANVIL, fluid="glycerol-45", **KHARAZ, db=opened)
    assert glycerol["friction_coefficient_used"] == 0.092
    friction = _verdict(glycerol, "lubricated_friction_state")["text"]
    assert "the roughness is not stated (no film is assumed), so μ = 0.092" in friction
    # with uncertainties, P(σ > h_m) is not a number either
    uncertain = granudb.pair(
        "alumina", ANVIL, fluid="water", diameter="5 mm", velocity="3.9 m/s ± 3 %", db=opened
    )
    assert uncertain["u_normal_stokes_number"] > 0  # the uncertainty was propagated
    probability = uncertain["probability_asperity_contact"]
    assert probability is None or math.isnan(probability)
    assert "P(σ > h_m)" not in _verdict(uncertain, "roughness_regime")["text"]
    shown = cli(
        "pair", "alumina", ANVIL, "--fluid", "water", "--diameter", "5 mm",
        "--velocity", "3.9 m/s", db=db,
    )  # fmt: skip
    assert shown.exit_code == 0, shown.stderr
    assert "not determined: roughness of alumina" in " ".join(shown.stdout.split())
    assert "│ RMS roughness   │ not stated" in shown.stdout  # the materials table, too
    # one material with a roughness: the verdict names only the other
    granudb.add_material(
        "polished alumina", density="4000 kg/m^3", youngs_modulus="380 GPa",
        poisson_ratio=0.23, roughness="10 nm", db=opened,
    )  # fmt: skip
    one = granudb.pair("polished alumina", ANVIL, fluid="water", **KHARAZ, db=opened)
    assert _verdict(one, "roughness_regime")["text"].startswith(
        f"not determined: roughness of {ANVIL} not stated"
    )
    granudb.add_material(
        "polished glass", density="2500 kg/m^3", youngs_modulus="70 GPa",
        poisson_ratio=0.25, roughness="10 nm", db=opened,
    )  # fmt: skip
    stated = granudb.pair("polished alumina", "polished glass", fluid="water", **KHARAZ, db=opened)
    assert stated["roughness_regime"] in ("film", "uncertain", "asperity_contact")
    assert not _verdict(stated, "roughness_regime")["text"].startswith("not determined")


def test_a_dataset_flag_counts_runs_whose_roughness_is_not_stated_apart() -> None:
    """A set of runs: one whose roughness is not stated is neither film nor contact."""
    frame = pd.DataFrame(
        {
            "fluid": ["water", "water", None],
            "roughness_regime": ["not_stated", "film", "dry"],
            "composite_roughness_m": [math.nan, 20e-9, math.nan],
            "film_parameter": [math.nan, 5.0, math.nan],
        }
    )
    flag = dataset_flag(frame)
    assert flag["raised"]
    assert flag["headline"] == "Roughness not stated in 1 immersed runs: regime not determined"
    assert "1 in film" in flag["detail"] and "1 not determined" in flag["detail"]
    assert "σ from 20 nm to 20 nm" in flag["detail"]


@pytest.mark.parametrize("code", ["liggghts", "lammps", "yade", "mercurydpm"])
def test_the_dem_export_of_kharaz_needs_no_roughness(opened, code: str) -> None:
    """The DEM fragment takes E, ν, e and μ (no σ): Kharaz's pair exports with 0.092."""
    text = granudb.dem_export(code, ["alumina"], [ANVIL], **KHARAZ, db=opened)
    assert "0.092" in text and "yade-chung-ooi-test4" in text


def test_per_run_resolves_each_run_as_its_own_pair() -> None:
    """``dry_values.per_run`` resolves each distinct (names, own values) once and hands it
    to every run that has it: the same numbers as resolving every run by itself, with
    missing names, NaN values and case-different names mixed in."""
    from types import SimpleNamespace

    import numpy as np

    from granudb.scenario import dry_values

    rng = np.random.default_rng(7)
    n = 400
    names = np.array(["steel", "Steel", "glass", None, "alumina"], dtype=object)
    walls = np.array(["Zerodur", "zerodur", "glass", "PTFE"], dtype=object)
    particle = names[rng.integers(0, len(names), n)]
    wall = walls[rng.integers(0, len(walls), n)]
    pick = np.array([np.nan, 0.9, 0.95])
    own = {c: pick[rng.integers(0, 3, n)] for c in dry_values._OWN}
    measured = [
        SimpleNamespace(particle="steel", wall="Zerodur", dry_restitution=0.97,
                        dry_friction=0.11, immersed_friction=0.02, source_locator=None,
                        notes=None, source=SimpleNamespace(key="k", citation="c")),
    ]  # fmt: skip
    e, mu, wet = dry_values.per_run(particle, wall, own, measured)
    for i in range(n):
        values = [None if v != v else float(v) for v in (own[c][i] for c in dry_values._OWN)]
        if particle[i] is None:
            one = dry_values.BORROWED_VALUES
        else:
            first = SimpleNamespace(name=particle[i], dry_restitution=values[0],
                                    dry_friction=values[2], dry_provenance=None)  # fmt: skip
            second = SimpleNamespace(name=wall[i], dry_restitution=values[1],
                                     dry_friction=values[3], dry_provenance=None)  # fmt: skip
            pair = [m for m in measured
                    if {m.particle.casefold(), m.wall.casefold()}
                    == {particle[i].casefold(), wall[i].casefold()}]  # fmt: skip
            one = dry_values.resolve(first, second, pair)
        assert e[i] == one.restitution and mu[i] == one.friction, i
        expected_wet = one.immersed_friction if one.immersed_friction_basis == "pair" else None
        assert (math.isnan(wet[i]) and expected_wet is None) or wet[i] == expected_wet, i
