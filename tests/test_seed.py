"""The shipped seed data: loaded on first use, idempotent, every number cited."""

from __future__ import annotations

import csv
import shutil
from pathlib import Path

import pytest
from sqlalchemy import func, select
from support import dump_hash

from granudb.api.database import connect as open_database
from granudb.api.schema import load_seed
from granudb.db.models import Fluid, Material, PublishedValue, Source
from granudb.errors import ValidationError
from granudb.resources import shipped_dir

SEED = shipped_dir("seed_data")


def test_loading_twice_changes_nothing(db: str) -> None:
    before = dump_hash(db)
    database = open_database(db)
    with database.session(write=True) as session:
        report = load_seed(session)
    database.dispose()
    assert report[-1].startswith("seed: 0 added, 0 updated,")
    assert dump_hash(db) == before


def test_an_edited_value_updates_its_row_and_says_so(db: str, tmp_path: Path) -> None:
    folder = tmp_path / "seed"
    shutil.copytree(SEED, folder)
    materials = folder / "materials.csv"
    rows = list(csv.DictReader(materials.open(encoding="utf-8")))
    for row in rows:
        if row["name"] == "glass":
            row["youngs_modulus [GPa]"] = "63"
    with materials.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    database = open_database(db)
    with database.session(write=True) as session:
        report = load_seed(session, folder)
    with database.session() as session:
        glass = session.scalars(select(Material).filter_by(name_key="glass")).one()
        assert glass.youngs_modulus_pa == 6.3e10
    database.dispose()
    assert "updated material glass: youngs_modulus_pa 60000000000.0 → 63000000000.0" in report
    assert report[-1].startswith("seed: 0 added, 1 updated,")


def test_a_bad_seed_file_changes_nothing(db: str, tmp_path: Path) -> None:
    folder = tmp_path / "seed"
    shutil.copytree(SEED, folder)
    text = (folder / "materials.csv").read_text(encoding="utf-8")
    (folder / "materials.csv").write_text(text.replace(",0.27,", ",0.57,"), encoding="utf-8")
    (folder / "sources.toml").write_text(
        (folder / "sources.toml").read_text(encoding="utf-8").replace("year = 1985", "year = 1986"),
        encoding="utf-8",
    )
    before = dump_hash(db)
    database = open_database(db)
    with (
        pytest.raises(ValidationError, match=r"row 3: poisson_ratio: 0.57 must be"),
        database.session(write=True) as session,
    ):
        load_seed(session, folder)
    database.dispose()
    assert dump_hash(db) == before  # the source edit before the bad row rolled back too


def test_table_1_as_printed(db: str) -> None:
    database = open_database(db)
    with database.session() as session:
        rows = {m.name: m for m in session.scalars(select(Material))}
    database.dispose()
    expected = {  # Joseph & Hunt (2004) table 1: ρ, E, ν, σ_s, λ_p
        "glass": (2540, 60e9, 0.23, 0.1305e-6, 22.59e-6),
        "steel": (7780, 190e9, 0.27, 0.0236e-6, 48.04e-6),
        "Zerodur": (2540, 91e9, 0.24, 0.0155e-6, 1075e-6),
    }
    for name, (rho, e, nu, sigma, lam) in expected.items():
        m = rows[name]
        got = (
            m.density_kg_m3,
            m.youngs_modulus_pa,
            m.poisson_ratio,
            m.roughness_rms_m,
            m.correlation_length_m,
        )
        assert got == pytest.approx((rho, e, nu, sigma, lam), rel=1e-12)
        assert m.source.key == "joseph-hunt-2004" and m.source_locator == "table 1"


def test_fluids_of_the_paper(db: str) -> None:
    database = open_database(db)
    with database.session() as session:
        fluids = {f.name: f for f in session.scalars(select(Fluid))}
        printed = {
            "water": 1.0,
            "glycerol-33": 2.5,
            "glycerol-37": 3.0,
            "glycerol-45": 4.5,
            "glycerol-78": 48.0,
        }
        for name, cp in printed.items():
            fluid = fluids[name]
            assert fluid.reference_viscosity_pa_s == pytest.approx(cp * 1e-3, rel=1e-12)
            assert fluid.source.key == "joseph-hunt-2004"
            assert fluid.density_source.key == "volk-kahler-2018"
            assert 990 < fluid.reference_density_kg_m3 < 1260
            if name != "water":
                assert fluid.pressure_viscosity_pa_inv == 6e-9
                assert fluid.pressure_viscosity_source.key == "joseph-hunt-2004"
    database.dispose()


def test_every_published_number_carries_its_source_and_place(db: str) -> None:
    database = open_database(db)
    with database.session() as session:
        values = list(session.scalars(select(PublishedValue)))
        assert session.scalar(select(func.count()).select_from(PublishedValue)) >= 30
        for value in values:
            assert value.source is not None
            assert value.source_locator.strip()
            assert value.value_as_printed.strip()
        quantities = {(v.label, v.quantity): v for v in values}
    database.dispose()
    beta = quantities[("dry steel on Zerodur", "rotational_restitution")]
    assert (beta.value, beta.uncertainty) == (0.34, 0.07)
    glass = quantities[("dry glass on Zerodur", "rotational_restitution")]
    assert (glass.value, glass.uncertainty) == (0.39, 0.06)
    assert any("table 2" in v.source_locator for v in values)
    assert any("table 3" in v.source_locator for v in values)


def test_kharaz_alumina_on_soda_lime_glass_is_shipped_with_its_secondary_sources(
    db: str,
) -> None:
    """Kharaz, Gorham & Salman (2001) as two readable sources quote it (issue 23): each
    number names the source it was read in, and the paper is cited as not read."""
    database = open_database(db)
    with database.session() as session:
        values = {
            (v.label, v.quantity): (v.value, v.source.key, v.source_locator)
            for v in session.scalars(select(PublishedValue))
            if "Kharaz" in v.label
        }
        paper = session.scalars(select(Source).filter_by(key="kharaz-gorham-salman-2001")).one()
        assert paper.doi == "10.1016/S0032-5910(01)00283-2"
        assert "could not read the paper" in paper.notes
        # the two materials carry Kharaz's numbers, with the roughness no source states
        seeded = {
            m.name: m
            for m in session.scalars(select(Material))
            if m.name in ("alumina", "soda-lime glass (Kharaz anvil)")
        }
        stored = {
            name: (m.density_kg_m3, m.youngs_modulus_pa, m.poisson_ratio, m.roughness_rms_m)
            for name, m in seeded.items()
        }
        anvil_note = seeded["soda-lime glass (Kharaz anvil)"].description
    database.dispose()
    pair = "dry alumina on soda-lime glass (Kharaz et al. 2001)"
    alumina = "alumina sphere (Kharaz et al. 2001)"
    anvil = "soda-lime glass anvil (Kharaz et al. 2001)"
    assert values[(pair, "sliding_friction")][:2] == (0.092, "yade-chung-ooi-test4")
    assert values[(pair, "normal_restitution_mean")][:2] == (0.98, "yade-chung-ooi-test4")
    assert values[(alumina, "density_kg_m3")][:2] == (4000, "lethe-oblique-wall-impact")
    assert values[(alumina, "youngs_modulus_pa")][0] == 380e9
    assert values[(alumina, "poisson_ratio")][0] == 0.23
    assert values[(anvil, "youngs_modulus_pa")][0] == 70e9
    assert values[(anvil, "poisson_ratio")][0] == 0.25
    assert all(locator.strip() for _, _, locator in values.values())
    # the seeded materials are the published numbers, each read where it says
    assert stored["alumina"] == (
        values[(alumina, "density_kg_m3")][0],
        values[(alumina, "youngs_modulus_pa")][0],
        values[(alumina, "poisson_ratio")][0],
        None,
    )
    assert stored["soda-lime glass (Kharaz anvil)"][1:] == (
        values[(anvil, "youngs_modulus_pa")][0],
        values[(anvil, "poisson_ratio")][0],
        None,
    )
    # no source states the anvil's density: the borrowed value says so
    assert "BORROWED" in anvil_note and "roughness not stated" in anvil_note
