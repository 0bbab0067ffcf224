"""What every table shares: the declarative base with stable constraint names, timestamps,
the case-insensitive name key, and the CHECK that keeps NaN and infinity out of every
floating-point column."""

from __future__ import annotations

from datetime import UTC, datetime

from sqlalchemy import CheckConstraint, DateTime, Float, MetaData, func
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column

from granudb.vocabulary.text import name_key

__all__ = ["Base", "Timestamped", "finite_check", "name_key", "utcnow"]

# Stable constraint names, so migrations can refer to them on every dialect.
NAMING_CONVENTION = {
    "ix": "ix_%(table_name)s_%(column_0_N_name)s",
    "uq": "uq_%(table_name)s_%(column_0_N_name)s",
    "ck": "ck_%(table_name)s_%(constraint_name)s",
    "fk": "fk_%(table_name)s_%(column_0_name)s_%(referred_table_name)s",
    "pk": "pk_%(table_name)s",
}


def utcnow() -> datetime:
    return datetime.now(UTC)


class Base(DeclarativeBase):
    metadata = MetaData(naming_convention=NAMING_CONVENTION)


class Timestamped:
    # server_default too, so rows written by other tools (sqlite3, psql) get a timestamp.
    created_at: Mapped[datetime] = mapped_column(
        DateTime(timezone=True), default=utcnow, server_default=func.current_timestamp()
    )
    updated_at: Mapped[datetime] = mapped_column(
        DateTime(timezone=True),
        default=utcnow,
        onupdate=utcnow,
        server_default=func.current_timestamp(),
    )


#: The largest finite double: a column is finite when it lies within ±FINITE_MAX. The same
#: text works on both backends: PostgreSQL sorts 'NaN' above every number and SQLite stores
#: a NaN as NULL, so NaN, +inf and −inf all fail it.
FINITE_MAX = "1.7976931348623157e308"


def finite_check(column: str) -> str:
    """SQL that holds when ``column`` is NULL or a finite number (not NaN, not ±inf)."""
    return f"{column} IS NULL OR ({column} >= -{FINITE_MAX} AND {column} <= {FINITE_MAX})"


def add_finite_checks(base: type[DeclarativeBase]) -> None:
    """Every floating-point column refuses NaN and ±infinity, even from other tools."""
    for table in base.metadata.tables.values():
        for column in table.columns:
            if isinstance(column.type, Float):
                table.append_constraint(
                    CheckConstraint(finite_check(column.name), name=f"{column.name}_finite")
                )
