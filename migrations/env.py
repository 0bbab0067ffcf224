"""Alembic environment for granudb.

granudb calls Alembic with an open connection (``cfg.attributes["connection"]``); run
from the command line (``alembic -c alembic.ini …``, for developers writing a revision)
it connects to granudb's configured database (``GRANUDB_DATABASE_URL`` or the default).
"""

from __future__ import annotations

from alembic import context
from sqlalchemy.engine import Connection

from granudb.db.models import Base

target_metadata = Base.metadata


def run_with(connection: Connection) -> None:
    context.configure(
        connection=connection,
        target_metadata=target_metadata,
        render_as_batch=connection.dialect.name == "sqlite",
        compare_type=True,
    )
    with context.begin_transaction():
        context.run_migrations()


def run_migrations_online() -> None:
    connection = context.config.attributes.get("connection")
    if connection is not None:
        run_with(connection)
        return
    from granudb.config import resolve_database_url
    from granudb.db.engine import make_engine

    engine = make_engine(resolve_database_url(None))
    with engine.connect() as connection:
        run_with(connection)
        connection.commit()
    engine.dispose()


if context.is_offline_mode():
    raise SystemExit("granudb migrations run online only (they need a connection)")
run_migrations_online()
