"""Database layer: models, engine and session setup, schema migration, queries."""
