"""The schema: SQLAlchemy 2 typed models.

Every column holds an SI value and its name says the unit (``density_kg_m3``,
``youngs_modulus_pa``); the same names are granudb's public vocabulary in JSON, CSV, data
packages and reports. The stored values of materials, fluids, fluid points, collisions,
pair values and reported runs, with their CHECKs, are generated from their declarations
(``granudb.vocabulary.terms.STORED``, mixed in by ``declared``); the classes here add keys,
names, links and relationships. CHECK constraints refuse unphysical rows even when
something bypasses the validation layer, and every published number points to a
``Source`` plus the table or figure it was printed in (``source_locator``).

Alembic's first revision (``migrations/versions/0001_initial.py``) creates exactly these
tables; ``tests/db/test_migrations.py`` proves the two agree.
"""

from __future__ import annotations

from datetime import datetime
from typing import TYPE_CHECKING, Any

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
from granudb.vocabulary.terms import TABLE_CHECKS, Stored, keyed, stored

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


_SQL_TYPES: dict[str, Any] = {
    "float": Float,
    "integer": Integer,
    "text": Text,
    "string": String,
    "boolean": Boolean,
    "datetime": DateTime(timezone=True),
}


def _mapped(declaration: Stored, kept: bool) -> Any:
    kind = _SQL_TYPES[declaration.sql]
    sql_type = kind(declaration.length) if declaration.length else kind
    extra: dict[str, Any] = {}
    if declaration.server_default is not None and not kept:
        extra["server_default"] = declaration.server_default
    if declaration.default is not None and not kept:
        extra["default"] = declaration.default
    if declaration.unique and not kept:
        extra["unique"] = True
    return mapped_column(sql_type, nullable=declaration.nullable, **extra)


def declared(table: str, *, kept: bool = False) -> type:
    """A mixin holding ``table``'s declared columns (``granudb.vocabulary.terms.STORED``),
    each with its ``u_`` column where it has one: a model gets its stored values from its
    declarations, never by spelling them again. ``kept``: the columns of a kept copy (a
    source's revision), without uniqueness or defaults. Type checkers see them as
    ``Any``."""
    columns = {s.column: _mapped(s, kept) for s in stored(table, uncertainties=True)}
    return type(f"Declared_{table}{'_kept' if kept else ''}", (), columns)


def declared_checks(table: str) -> list[CheckConstraint]:
    """The CHECKs of ``table``'s declared columns (and those across them), by the names
    the migrations gave them."""
    declarations = stored(table, uncertainties=True)
    checks = [
        CheckConstraint(s.constraint, name=s.check)
        for s in declarations
        if s.check is not None and s.constraint is not None
    ]
    return checks + [CheckConstraint(sql, name=n) for n, sql in TABLE_CHECKS.get(table, {}).items()]


class _Declared:
    """What a type checker sees of a model's declared columns: any attribute, ``Any``
    (they are generated from ``granudb.vocabulary.terms.STORED`` at import)."""

    if TYPE_CHECKING:

        def __getattr__(self, name: str) -> Any: ...


if TYPE_CHECKING:
    _Sources = _Declared
    _SourcesKept = _Declared
    _Materials = _Declared
    _Fluids = _Declared
    _FluidPoints = _Declared
    _Datasets = _Declared
    _Collisions = _Declared
    _PairValues = _Declared
    _ReportedRuns = _Declared
else:
    _Sources = declared("sources")
    _SourcesKept = declared("sources", kept=True)
    _Materials = declared("materials")
    _Fluids = declared("fluids")
    _FluidPoints = declared("fluid_points")
    _Datasets = declared("datasets")
    _Collisions = declared("collisions")
    _PairValues = declared("pair_values")
    _ReportedRuns = declared("reported_runs")


#: The column that orders a fluid's points and keys them within the fluid.
(_POINT_KEY,) = keyed("fluid_points")


# Stable constraint names, so migrations can refer to them on every dialect.
class Source(_Sources, Base):
    """A publication, correlation or measurement campaign that numbers come from.

    Where in it a number was printed (``table 1``, ``figure 4``, ``§3``) is stored beside the
    number, as ``source_locator`` on the row that cites the source.
    """

    __tablename__ = "sources"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin;
    # what queries name at class level, for type checkers:
    if TYPE_CHECKING:
        key: Mapped[str]

    __table_args__ = tuple(declared_checks("sources"))


class SourceRevision(_SourcesKept, Base):
    """A source's values before one change (a re-seed that changed its citation, DOI, …),
    with when and why it changed. A released dataset reads each source as it was when the
    dataset was released: the first revision kept after that, or the live row when none
    (``granudb.db.catalog_revisions.sources_as_of``)."""

    __tablename__ = "source_revisions"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    source_id: Mapped[int] = mapped_column(ForeignKey("sources.id", ondelete="CASCADE"))
    # the source's declared columns, as they were (``granudb.vocabulary.terms.STORED``)
    kept_at: Mapped[datetime] = mapped_column(DateTime(timezone=True), default=utcnow)
    reason: Mapped[str] = mapped_column(Text)


class Material(Timestamped, _Materials, Base):
    """A solid a particle or a wall is made of (Joseph & Hunt 2004, table 1)."""

    __tablename__ = "materials"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    name_key: Mapped[str] = mapped_column(String(200), unique=True)
    description: Mapped[str | None] = mapped_column(Text)
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))
    #: Set on a revision: the values this material had when a released dataset used it,
    #: kept when the live row (this id) changed (``granudb.db.catalog_revisions``).
    revision_of: Mapped[int | None] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))

    source: Mapped[Source | None] = relationship(lazy="joined")

    __table_args__ = (
        CheckConstraint("length(name) > 0", name="name_not_empty"),
        *declared_checks("materials"),
    )


class Fluid(Timestamped, _Fluids, Base):
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
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin
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
        order_by=f"FluidPoint.{_POINT_KEY}",
        lazy="selectin",
    )

    __table_args__ = (
        CheckConstraint("length(name) > 0", name="name_not_empty"),
        *declared_checks("fluids"),
    )


class FluidPoint(_FluidPoints, Base):
    """One viscosity (and optionally density) of a fluid at one temperature."""

    __tablename__ = "fluid_points"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    fluid_id: Mapped[int] = mapped_column(ForeignKey("fluids.id", ondelete="CASCADE"))
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))

    fluid: Mapped[Fluid] = relationship(back_populates="points")
    source: Mapped[Source | None] = relationship(lazy="joined")

    __table_args__ = (
        UniqueConstraint("fluid_id", _POINT_KEY),
        *declared_checks("fluid_points"),
    )


class Dataset(Timestamped, _Datasets, Base):
    """A named, versioned, curated collection of collisions.

    ``content_hash`` is a sha256 over the dataset's collisions in a canonical form (see
    ``granudb.db.datasets``); two copies with the same hash hold the same measurements.
    """

    __tablename__ = "datasets"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200))
    description: Mapped[str | None] = mapped_column(Text)
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin;
    # what queries name at class level, for type checkers:
    if TYPE_CHECKING:
        version: Mapped[str]
        state: Mapped[str]
        content_hash: Mapped[str | None]
        released_at: Mapped[datetime | None]

    source: Mapped[Source | None] = relationship(lazy="joined")

    __table_args__ = (
        UniqueConstraint("name", *keyed("datasets")),
        CheckConstraint("length(name) > 0", name="name_not_empty"),
        *declared_checks("datasets"),
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


class Collision(_Collisions, Base):
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
    notes: Mapped[str | None] = mapped_column(Text)
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin

    dataset: Mapped[Dataset] = relationship()
    particle: Mapped[Material] = relationship(foreign_keys=[particle_id])
    wall: Mapped[Material] = relationship(foreign_keys=[wall_id])
    fluid: Mapped[Fluid | None] = relationship()

    __table_args__ = (
        UniqueConstraint("dataset_id", "run"),
        Index("ix_collisions_pair_fluid", "particle_id", "wall_id", "fluid_id"),
        Index("ix_collisions_fluid_id", "fluid_id"),
        CheckConstraint("length(run) > 0", name="run_not_empty"),
        *declared_checks("collisions"),
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


class PairValue(Timestamped, _PairValues, Base):
    """Dry values a source measured for one pair of materials (either way round: steel
    on Zerodur is Zerodur hit by steel), docs/physics.md §18. They come before the two
    materials' own values; ``created_at`` lets a release read only the pair values that
    existed when it was released."""

    __tablename__ = "pair_values"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    particle_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    wall_id: Mapped[int] = mapped_column(ForeignKey("materials.id", ondelete="RESTRICT"))
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))
    notes: Mapped[str | None] = mapped_column(Text)

    __table_args__ = (
        UniqueConstraint("particle_id", "wall_id"),
        *declared_checks("pair_values"),
    )


class ReportedRun(_ReportedRuns, Base):
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
    # the declared columns (``granudb.vocabulary.terms.STORED``) come from the mixin
    source_id: Mapped[int | None] = mapped_column(ForeignKey("sources.id", ondelete="RESTRICT"))
    source_locator: Mapped[str | None] = mapped_column(String(200))
    notes: Mapped[str | None] = mapped_column(Text)

    __table_args__ = (
        UniqueConstraint("collection", "run"),
        CheckConstraint("length(collection) > 0", name="collection_not_empty"),
        CheckConstraint("length(run) > 0", name="run_not_empty"),
        *declared_checks("reported_runs"),
    )


add_finite_checks(Base)
