"""The schema: SQLAlchemy 2 typed models.

Every column holds an SI value and its name says the unit (``density_kg_m3``,
``youngs_modulus_pa``); the same names are granudb's public vocabulary in JSON, CSV, data
packages and reports. CHECK constraints refuse unphysical rows even when something bypasses
the validation layer, and every published number points to a ``Source`` plus the table or
figure it was printed in (``source_locator``).

Alembic's first revision (``migrations/versions/0001_initial.py``) creates exactly these
tables; ``tests/db/test_migrations.py`` proves the two agree.
"""

from __future__ import annotations

from collections.abc import Iterable
from datetime import datetime

from sqlalchemy import (
    Boolean,
    CheckConstraint,
    DateTime,
    Float,
    ForeignKey,
    Index,
    Integer,
    String,
    Text,
    UniqueConstraint,
    func,
)
from sqlalchemy.orm import Mapped, mapped_column, relationship

from granudb.db.base import Base, Timestamped, add_finite_checks, name_key, utcnow
from granudb.vocabulary import COLLISION_UNCERTAINTIES
from granudb.vocabulary.catalogue import FLUIDS, MATERIALS


def _positive_if_given(column: str, name: str) -> CheckConstraint:
    """The rule of an optional positive value: ``column`` NULL (not given) or > 0."""
    return CheckConstraint(f"{column} IS NULL OR {column} > 0", name=name)


def _non_negative_if_given(columns: Iterable[str]) -> list[CheckConstraint]:
    """The rule of optional standard uncertainties: each column NULL (not stated) or ≥ 0."""
    return [CheckConstraint(f"{c} IS NULL OR {c} >= 0", name=f"{c}_non_negative") for c in columns]


__all__ = [
    "Base",
    "Collision",
    "CollisionImport",
    "Dataset",
    "Fluid",
    "FluidPoint",
    "Material",
    "PairValue",
    "PublishedValue",
    "ReportedRun",
    "SeedRecord",
    "Source",
    "SourceRevision",
    "name_key",
    "utcnow",
]


#: The dry values' ranges, on materials and on pairs alike (migration 0006).
DRY_VALUE_RULES = {
    "dry_restitution_range": "dry_restitution IS NULL OR "
    "(dry_restitution > 0 AND dry_restitution <= 1)",
    "dry_friction_non_negative": "dry_friction IS NULL OR dry_friction >= 0",
}
DRY_VALUE_CHECKS = tuple(CheckConstraint(rule, name=n) for n, rule in DRY_VALUE_RULES.items())


# Stable constraint names, so migrations can refer to them on every dialect.
class Source(Base):
    """A publication, correlation or measurement campaign that numbers come from.

    Where in it a number was printed (``table 1``, ``figure 4``, ``§3``) is stored beside the
    number, as ``source_locator`` on the row that cites the source.
    """

    __tablename__ = "sources"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    key: Mapped[str] = mapped_column(String(100), unique=True)
    citation: Mapped[str] = mapped_column(Text)
    doi: Mapped[str | None] = mapped_column(String(200))
    url: Mapped[str | None] = mapped_column(String(500))
    year: Mapped[int | None] = mapped_column(Integer)
    kind: Mapped[str] = mapped_column(String(40), default="publication")
    notes: Mapped[str | None] = mapped_column(Text)

    __table_args__ = (
        CheckConstraint("length(key) > 0", name="key_not_empty"),
        CheckConstraint("year IS NULL OR (year >= 1600 AND year <= 3000)", name="year_range"),
    )


class SourceRevision(Base):
    """A source's values before one change (a re-seed that changed its citation, DOI, …),
    with when and why it changed. A released dataset reads each source as it was when the
    dataset was released: the first revision kept after that, or the live row when none
    (``granudb.db.catalog_revisions.sources_as_of``)."""

    __tablename__ = "source_revisions"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    source_id: Mapped[int] = mapped_column(ForeignKey("sources.id", ondelete="CASCADE"))
    key: Mapped[str] = mapped_column(String(100))
    citation: Mapped[str] = mapped_column(Text)
    doi: Mapped[str | None] = mapped_column(String(200))
    url: Mapped[str | None] = mapped_column(String(500))
    year: Mapped[int | None] = mapped_column(Integer)
    kind: Mapped[str] = mapped_column(String(40))
    notes: Mapped[str | None] = mapped_column(Text)
    kept_at: Mapped[datetime] = mapped_column(DateTime(timezone=True), default=utcnow)
    reason: Mapped[str] = mapped_column(Text)


class Material(Timestamped, Base):
    """A solid a particle or a wall is made of (Joseph & Hunt 2004, table 1)."""

    __tablename__ = "materials"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    name_key: Mapped[str] = mapped_column(String(200), unique=True)
    description: Mapped[str | None] = mapped_column(Text)
    density_kg_m3: Mapped[float] = mapped_column(Float)
    youngs_modulus_pa: Mapped[float] = mapped_column(Float)
    poisson_ratio: Mapped[float] = mapped_column(Float)
    #: RMS surface roughness σ; empty: no source states it (σ-dependent outputs say so).
    roughness_rms_m: Mapped[float | None] = mapped_column(Float)
    correlation_length_m: Mapped[float | None] = mapped_column(Float)
    shear_modulus_pa: Mapped[float | None] = mapped_column(Float)
    #: Yield stress Y in tension (Johnson 1985 §11.4: yield starts at p_max = 1.6 Y);
    #: empty where not known or for brittle solids, which crack instead.
    yield_stress_pa: Mapped[float | None] = mapped_column(Float)
    #: Standard uncertainty of each property (same unit; NULL: not given), ``u_<property>``.
    u_density_kg_m3: Mapped[float | None] = mapped_column(Float)
    u_youngs_modulus_pa: Mapped[float | None] = mapped_column(Float)
    u_poisson_ratio: Mapped[float | None] = mapped_column(Float)
    u_roughness_rms_m: Mapped[float | None] = mapped_column(Float)
    u_correlation_length_m: Mapped[float | None] = mapped_column(Float)
    u_shear_modulus_pa: Mapped[float | None] = mapped_column(Float)
    u_yield_stress_pa: Mapped[float | None] = mapped_column(Float)
    #: The material's own dry restitution and friction, and where they come from
    #: (docs/physics.md §18); empty where not known. Brittleness: "brittle" or "ductile".
    dry_restitution: Mapped[float | None] = mapped_column(Float)
    dry_friction: Mapped[float | None] = mapped_column(Float)
    dry_provenance: Mapped[str | None] = mapped_column(Text)
    brittleness: Mapped[str | None] = mapped_column(String(20))
    #: The conditions of the values where the source gives them (temperature, method).
    conditions: Mapped[str | None] = mapped_column(Text)
    u_dry_restitution: Mapped[float | None] = mapped_column(Float)
    u_dry_friction: Mapped[float | None] = mapped_column(Float)
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))
    #: Set on a revision: the values this material had when a released dataset used it,
    #: kept when the live row (this id) changed (``granudb.db.catalog_revisions``).
    revision_of: Mapped[int | None] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))

    source: Mapped[Source | None] = relationship(lazy="joined")

    __table_args__ = (
        CheckConstraint("length(name) > 0", name="name_not_empty"),
        CheckConstraint("density_kg_m3 > 0", name="density_positive"),
        CheckConstraint("youngs_modulus_pa > 0", name="youngs_modulus_positive"),
        CheckConstraint("poisson_ratio > -1 AND poisson_ratio < 0.5", name="poisson_ratio_range"),
        CheckConstraint("roughness_rms_m >= 0", name="roughness_non_negative"),  # NULL passes
        _positive_if_given("correlation_length_m", "correlation_length_positive"),
        _positive_if_given("shear_modulus_pa", "shear_modulus_positive"),
        _positive_if_given("yield_stress_pa", "yield_stress_positive"),
        *_non_negative_if_given(MATERIALS.uncertainties.values()),
        *DRY_VALUE_CHECKS,
        CheckConstraint(
            "brittleness IS NULL OR brittleness IN ('brittle', 'ductile')",
            name="brittleness_word",
        ),
    )


class Fluid(Timestamped, Base):
    """A liquid the collisions happen in (absent for a dry collision).

    ``reference_viscosity_pa_s`` and ``reference_density_kg_m3`` are the fluid at
    ``reference_temperature_c`` as the source printed them (``source``); density and the
    Barus pressure–viscosity coefficient C may come from other sources, cited separately;
    ``points`` hold measured or correlated viscosity (and density) against temperature so
    viscosity can be evaluated anywhere inside their range.
    """

    __tablename__ = "fluids"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    name_key: Mapped[str] = mapped_column(String(200), unique=True)
    description: Mapped[str | None] = mapped_column(Text)
    glycerol_mass_fraction: Mapped[float | None] = mapped_column(Float)
    reference_density_kg_m3: Mapped[float] = mapped_column(Float)
    reference_viscosity_pa_s: Mapped[float] = mapped_column(Float)
    reference_temperature_c: Mapped[float] = mapped_column(Float, default=20.0)
    pressure_viscosity_pa_inv: Mapped[float | None] = mapped_column(Float)
    #: Standard uncertainty of each property (same unit; NULL: not given), ``u_<property>``.
    u_glycerol_mass_fraction: Mapped[float | None] = mapped_column(Float)
    u_reference_density_kg_m3: Mapped[float | None] = mapped_column(Float)
    u_reference_viscosity_pa_s: Mapped[float | None] = mapped_column(Float)
    u_reference_temperature_c: Mapped[float | None] = mapped_column(Float)
    u_pressure_viscosity_pa_inv: Mapped[float | None] = mapped_column(Float)
    #: The conditions of the values where the source gives them (temperature, method).
    conditions: Mapped[str | None] = mapped_column(Text)
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))
    density_source_id: Mapped[int | None] = mapped_column(
        ForeignKey("sources.id", ondelete="RESTRICT")
    )
    density_locator: Mapped[str | None] = mapped_column(String(200))
    pressure_viscosity_source_id: Mapped[int | None] = mapped_column(
        ForeignKey("sources.id", ondelete="RESTRICT")
    )
    pressure_viscosity_locator: Mapped[str | None] = mapped_column(String(200))
    #: Set on a revision: this fluid (with its points) as a released dataset used it.
    revision_of: Mapped[int | None] = mapped_column(ForeignKey("fluids.id", ondelete="RESTRICT"))

    source: Mapped[Source | None] = relationship(foreign_keys=[source_id], lazy="joined")
    density_source: Mapped[Source | None] = relationship(
        foreign_keys=[density_source_id], lazy="joined"
    )
    pressure_viscosity_source: Mapped[Source | None] = relationship(
        foreign_keys=[pressure_viscosity_source_id], lazy="joined"
    )
    points: Mapped[list[FluidPoint]] = relationship(
        back_populates="fluid",
        cascade="all, delete-orphan",
        order_by="FluidPoint.temperature_c",
        lazy="selectin",
    )

    __table_args__ = (
        CheckConstraint("length(name) > 0", name="name_not_empty"),
        CheckConstraint("reference_density_kg_m3 > 0", name="density_positive"),
        CheckConstraint("reference_viscosity_pa_s > 0", name="viscosity_positive"),
        CheckConstraint(
            "glycerol_mass_fraction IS NULL OR "
            "(glycerol_mass_fraction >= 0 AND glycerol_mass_fraction <= 1)",
            name="glycerol_mass_fraction_range",
        ),
        CheckConstraint(
            "reference_temperature_c > -273.15", name="reference_temperature_above_zero_k"
        ),
        _positive_if_given("pressure_viscosity_pa_inv", "pressure_viscosity_positive"),
        *_non_negative_if_given(FLUIDS.uncertainties.values()),
    )


class FluidPoint(Base):
    """One viscosity (and optionally density) of a fluid at one temperature."""

    __tablename__ = "fluid_points"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    fluid_id: Mapped[int] = mapped_column(ForeignKey("fluids.id", ondelete="CASCADE"))
    temperature_c: Mapped[float] = mapped_column(Float)
    viscosity_pa_s: Mapped[float] = mapped_column(Float)
    density_kg_m3: Mapped[float | None] = mapped_column(Float)
    #: Standard uncertainties of the point's viscosity and density (NULL: not given).
    u_viscosity_pa_s: Mapped[float | None] = mapped_column(Float)
    u_density_kg_m3: Mapped[float | None] = mapped_column(Float)
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))

    fluid: Mapped[Fluid] = relationship(back_populates="points")
    source: Mapped[Source | None] = relationship(lazy="joined")

    __table_args__ = (
        UniqueConstraint("fluid_id", "temperature_c"),
        CheckConstraint("temperature_c > -273.15", name="temperature_above_zero_k"),
        CheckConstraint("viscosity_pa_s > 0", name="viscosity_positive"),
        _positive_if_given("density_kg_m3", "density_positive"),
        *_non_negative_if_given(["u_viscosity_pa_s", "u_density_kg_m3"]),
    )


class Dataset(Timestamped, Base):
    """A named, versioned, curated collection of collisions.

    ``content_hash`` is a sha256 over the dataset's collisions in a canonical form (see
    ``granudb.db.datasets``); two copies with the same hash hold the same measurements.
    """

    __tablename__ = "datasets"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    version: Mapped[str] = mapped_column(String(50), default="1.0.0")
    title: Mapped[str | None] = mapped_column(Text)
    description: Mapped[str | None] = mapped_column(Text)
    license: Mapped[str | None] = mapped_column(String(200))
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    content_hash: Mapped[str | None] = mapped_column(String(80))
    #: The dataset's own DOI (e.g. a Zenodo version DOI), once it has been published.
    doi: Mapped[str | None] = mapped_column(String(200))
    #: JSON list of people: {"given_names", "family_names", "orcid", "affiliation"}.
    authors: Mapped[str | None] = mapped_column(Text)
    #: JSON list of keywords.
    keywords: Mapped[str | None] = mapped_column(Text)
    #: draft (editable) → released (immutable) → superseded (a newer version was released).
    state: Mapped[str] = mapped_column(String(20), default="draft", server_default="draft")
    released_at: Mapped[datetime | None] = mapped_column(DateTime(timezone=True))

    source: Mapped[Source | None] = relationship(lazy="joined")

    __table_args__ = (
        UniqueConstraint("name", "version"),
        CheckConstraint("length(name) > 0", name="name_not_empty"),
        CheckConstraint("state IN ('draft', 'released', 'superseded')", name="state_known"),
    )


class SeedRecord(Base):
    """The values ``db seed`` last wrote to one row (JSON), so a re-seed can tell a value
    the user changed (it differs from this record) from one the seed changed, and leave the
    user's edit alone. ``seed_key`` is the row's natural key in the seed files."""

    __tablename__ = "seed_records"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    table_name: Mapped[str] = mapped_column(String(40))
    seed_key: Mapped[str] = mapped_column(String(500))
    seeded_values: Mapped[str] = mapped_column(Text)

    __table_args__ = (UniqueConstraint("table_name", "seed_key"),)


class Collision(Base):
    """One measured impact of a particle on a wall (or a second particle).

    Sign convention (Joseph & Hunt 2004 §2, docs/physics.md §5), for the particle's centre of
    mass in the wall's frame at the instants just before (``_in``) and after (``_out``)
    contact:

    * ``v_n_in_m_s`` and ``v_n_out_m_s`` are normal *speeds*, both positive: towards the
      wall before impact, away from it after. So e = v_n_out / v_n_in, which is the paper's
      e = −v_N,out / v_N,in with signed components.
    * the tangential axis points along the incoming tangential motion, so
      ``v_t_in_m_s`` ≥ 0; ``v_t_out_m_s`` is negative when the particle recoils backwards.
    * spin ``omega_*_rad_s`` is positive where it adds to the contact point's tangential
      velocity: the contact point moves at v_T = v_t + ω R (R = diameter / 2).
    * ``nominal_angle_rad`` is the set-up's nominal incidence angle, if the lab records
      one (NULL otherwise); the incidence angle ζ_in of the contact point's path is
      derived from the velocities (``incidence_angle_rad`` in listings), and an import
      checks that the two agree.
    * ``omega_*_rad_s`` NULL means the spin was not measured (not zero).

    ``wall_diameter_m`` is NULL for a flat wall and the second sphere's diameter for a
    particle–particle collision; ``wall_v_*``/``wall_omega_*`` are that sphere's velocities
    and spins on the same axes (NULL for a flat wall or a fixed sphere). ``fluid_id`` NULL
    means dry.
    """

    __tablename__ = "collisions"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    dataset_id: Mapped[int] = mapped_column(ForeignKey("datasets.id", ondelete="CASCADE"))
    run: Mapped[str] = mapped_column(String(200))
    particle_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    wall_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    fluid_id: Mapped[int | None] = mapped_column(ForeignKey("fluids.id", ondelete="RESTRICT"))
    diameter_m: Mapped[float] = mapped_column(Float)
    wall_diameter_m: Mapped[float | None] = mapped_column(Float)
    nominal_angle_rad: Mapped[float | None] = mapped_column(Float)
    v_n_in_m_s: Mapped[float] = mapped_column(Float)
    v_t_in_m_s: Mapped[float] = mapped_column(Float)
    omega_in_rad_s: Mapped[float | None] = mapped_column(Float)
    v_n_out_m_s: Mapped[float] = mapped_column(Float)
    v_t_out_m_s: Mapped[float] = mapped_column(Float)
    omega_out_rad_s: Mapped[float | None] = mapped_column(Float)
    wall_v_n_in_m_s: Mapped[float | None] = mapped_column(Float)
    wall_v_t_in_m_s: Mapped[float | None] = mapped_column(Float)
    wall_omega_in_rad_s: Mapped[float | None] = mapped_column(Float)
    wall_v_n_out_m_s: Mapped[float | None] = mapped_column(Float)
    wall_v_t_out_m_s: Mapped[float | None] = mapped_column(Float)
    wall_omega_out_rad_s: Mapped[float | None] = mapped_column(Float)
    temperature_c: Mapped[float | None] = mapped_column(Float)
    notes: Mapped[str | None] = mapped_column(Text)
    #: The stated standard uncertainty of each measured value (same unit; NULL: not
    #: stated), ``u_<column>`` (``granudb.vocabulary.terms.COLLISION_UNCERTAINTIES``).
    u_diameter_m: Mapped[float | None] = mapped_column(Float)
    u_v_n_in_m_s: Mapped[float | None] = mapped_column(Float)
    u_v_t_in_m_s: Mapped[float | None] = mapped_column(Float)
    u_omega_in_rad_s: Mapped[float | None] = mapped_column(Float)
    u_v_n_out_m_s: Mapped[float | None] = mapped_column(Float)
    u_v_t_out_m_s: Mapped[float | None] = mapped_column(Float)
    u_omega_out_rad_s: Mapped[float | None] = mapped_column(Float)
    u_temperature_c: Mapped[float | None] = mapped_column(Float)

    dataset: Mapped[Dataset] = relationship()
    particle: Mapped[Material] = relationship(foreign_keys=[particle_id])
    wall: Mapped[Material] = relationship(foreign_keys=[wall_id])
    fluid: Mapped[Fluid | None] = relationship()

    __table_args__ = (
        UniqueConstraint("dataset_id", "run"),
        Index("ix_collisions_pair_fluid", "particle_id", "wall_id", "fluid_id"),
        Index("ix_collisions_fluid_id", "fluid_id"),
        CheckConstraint("length(run) > 0", name="run_not_empty"),
        CheckConstraint("diameter_m > 0", name="diameter_positive"),
        _positive_if_given("wall_diameter_m", "wall_diameter_positive"),
        CheckConstraint(
            "nominal_angle_rad IS NULL OR "
            "(nominal_angle_rad >= 0 AND nominal_angle_rad < 1.5707963267948966)",
            name="nominal_angle_range",
        ),
        # With a free target (its wall_v_n_in given) the rules are on relative velocities:
        # the particle may start at rest or move on forward (checked on import).
        CheckConstraint(
            "v_n_in_m_s > 0 OR wall_v_n_in_m_s IS NOT NULL", name="v_n_in_positive_or_free"
        ),
        CheckConstraint("v_t_in_m_s >= 0", name="v_t_in_non_negative"),
        CheckConstraint(
            "v_n_out_m_s >= 0 OR wall_v_n_in_m_s IS NOT NULL",
            name="v_n_out_non_negative_or_free",
        ),
        CheckConstraint(
            "temperature_c IS NULL OR temperature_c > -273.15", name="temperature_above_zero_k"
        ),
        *_non_negative_if_given(COLLISION_UNCERTAINTIES),
    )


class CollisionImport(Base):
    """One file imported into a dataset, remembered by its sha256 so it is never imported
    twice."""

    __tablename__ = "collision_imports"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    dataset_id: Mapped[int] = mapped_column(ForeignKey("datasets.id", ondelete="CASCADE"))
    file_sha256: Mapped[str] = mapped_column(String(64))
    file_name: Mapped[str | None] = mapped_column(String(500))
    rows: Mapped[int] = mapped_column(Integer)
    imported_at: Mapped[datetime] = mapped_column(
        DateTime(timezone=True), default=utcnow, server_default=func.current_timestamp()
    )

    __table_args__ = (
        UniqueConstraint("dataset_id", "file_sha256"),
        CheckConstraint("rows >= 0", name="rows_non_negative"),
    )


class PublishedValue(Base):
    """A number as a source printed it: a fitted coefficient, a table cell.

    ``value_as_printed`` keeps the printed text exactly (``"0.34 ± 0.07"``); ``value`` and
    ``uncertainty`` are the same in the SI unit named by ``quantity``'s suffix. The
    database records what was published even where it disagrees with the paper's own
    formula; the computation layer computes from the formula and reports may show both.
    ``label`` groups the cells of one table row (``"table 2: 37 %"``).
    """

    __tablename__ = "published_values"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    source_id: Mapped[int] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str] = mapped_column(String(200))
    label: Mapped[str] = mapped_column(String(200))
    quantity: Mapped[str] = mapped_column(String(100))
    value: Mapped[float] = mapped_column(Float)
    uncertainty: Mapped[float | None] = mapped_column(Float)
    value_as_printed: Mapped[str] = mapped_column(String(200))
    particle_id: Mapped[int | None] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    wall_id: Mapped[int | None] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    fluid_id: Mapped[int | None] = mapped_column(ForeignKey("fluids.id", ondelete="RESTRICT"))
    condition: Mapped[str | None] = mapped_column(String(200))
    notes: Mapped[str | None] = mapped_column(Text)

    source: Mapped[Source] = relationship(lazy="joined")
    particle: Mapped[Material | None] = relationship(foreign_keys=[particle_id], lazy="joined")
    wall: Mapped[Material | None] = relationship(foreign_keys=[wall_id], lazy="joined")
    fluid: Mapped[Fluid | None] = relationship(lazy="joined")

    __table_args__ = (
        UniqueConstraint("source_id", "label", "quantity"),
        CheckConstraint("uncertainty IS NULL OR uncertainty >= 0", name="uncertainty_non_negative"),
    )


class PairValue(Timestamped, Base):
    """Dry values a source measured for one pair of materials (either way round: steel
    on Zerodur is Zerodur hit by steel), docs/physics.md §18. They come before the two
    materials' own values; ``created_at`` lets a release read only the pair values that
    existed when it was released."""

    __tablename__ = "pair_values"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    particle_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    wall_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    dry_restitution: Mapped[float | None] = mapped_column(Float)
    dry_friction: Mapped[float | None] = mapped_column(Float)
    #: Friction of the pair where asperities touch in a liquid (Joseph & Hunt §4: glass on
    #: Zerodur, 0.15); empty: the dry value is used there.
    immersed_friction: Mapped[float | None] = mapped_column(Float)
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))
    notes: Mapped[str | None] = mapped_column(Text)

    __table_args__ = (
        UniqueConstraint("particle_id", "wall_id"),
        CheckConstraint(
            "dry_restitution IS NOT NULL OR dry_friction IS NOT NULL "
            "OR immersed_friction IS NOT NULL",
            name="has_a_value",
        ),
        CheckConstraint(
            "immersed_friction IS NULL OR immersed_friction >= 0",
            name="immersed_friction_non_negative",
        ),
        *(CheckConstraint(rule, name=n) for n, rule in DRY_VALUE_RULES.items()),
    )


#: A reported run's quantities and their standard uncertainties (migration 0012).
REPORTED_QUANTITIES = (
    "incidence_angle_rad",
    "normal_restitution",
    "tangential_restitution",
    "omega_out_rad_s",
)


class ReportedRun(Base):
    """One run as a paper reports it: the quantities it states (e, e_t, ω_out, an
    incidence angle), never velocities it did not measure (docs/reference/index.md).

    ``collection`` names the runs a person imported together (a paper, a figure). Each
    quantity is NULL when the paper does not state it; ``u_<quantity>`` its standard
    uncertainty (NULL: not stated). ``no_spin_in`` is true when the paper states the
    sphere arrives without spin: only then do e_t and θ give Walton's Ψ by the exact
    relations of ``granudb.physics.reported``.
    """

    __tablename__ = "reported_runs"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    collection: Mapped[str] = mapped_column(String(200))
    run: Mapped[str] = mapped_column(String(200))
    particle_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    wall_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    fluid_id: Mapped[int | None] = mapped_column(ForeignKey("fluids.id", ondelete="RESTRICT"))
    diameter_m: Mapped[float | None] = mapped_column(Float)
    incidence_angle_rad: Mapped[float | None] = mapped_column(Float)
    normal_restitution: Mapped[float | None] = mapped_column(Float)
    tangential_restitution: Mapped[float | None] = mapped_column(Float)
    omega_out_rad_s: Mapped[float | None] = mapped_column(Float)
    u_incidence_angle_rad: Mapped[float | None] = mapped_column(Float)
    u_normal_restitution: Mapped[float | None] = mapped_column(Float)
    u_tangential_restitution: Mapped[float | None] = mapped_column(Float)
    u_omega_out_rad_s: Mapped[float | None] = mapped_column(Float)
    no_spin_in: Mapped[bool] = mapped_column(Boolean, default=False)
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))
    notes: Mapped[str | None] = mapped_column(Text)
    #: Who read the values from the figure or file, its licence, and the shipped
    #: reference dataset ("NAME VERSION") the run came from (migration 0013).
    digitiser: Mapped[str | None] = mapped_column(Text)
    licence: Mapped[str | None] = mapped_column(Text)
    reference_package: Mapped[str | None] = mapped_column(String(200))

    __table_args__ = (
        UniqueConstraint("collection", "run"),
        CheckConstraint("length(collection) > 0", name="collection_not_empty"),
        CheckConstraint("length(run) > 0", name="run_not_empty"),
        _positive_if_given("diameter_m", "diameter_positive"),
        CheckConstraint(
            "normal_restitution IS NOT NULL OR tangential_restitution IS NOT NULL",
            name="states_a_restitution",
        ),
        CheckConstraint(
            "incidence_angle_rad IS NULL OR "
            "(incidence_angle_rad >= 0 AND incidence_angle_rad < 1.5707963267948966)",
            name="incidence_angle_range",
        ),
        CheckConstraint(
            "normal_restitution IS NULL OR normal_restitution >= 0",
            name="normal_restitution_non_negative",
        ),
        *_non_negative_if_given(f"u_{q}" for q in REPORTED_QUANTITIES),
    )


add_finite_checks(Base)
