"""Alembic migrations, installed as ``granudb.migrations``."""
