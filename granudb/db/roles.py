"""Roles on a shared PostgreSQL server: reader, contributor, curator.

``granudb db grant ACCOUNT --as ROLE`` gives a login account one of three sets of table
privileges (SQLite has no accounts: the file's permissions are the control there):

- **reader**: ``SELECT`` on every table. Lists, reports, exports, fits, DEM decks.
- **contributor**: a reader that may also write the dataset tables (``datasets``,
  ``collisions``, ``collision_imports``): import runs and packages into drafts, edit,
  copy and remove drafts. No catalogue change (materials, fluids, fluid points, sources,
  seed records, published values), so a package that brings a material this database
  lacks needs a curator.
- **curator**: every table (not the schema): catalogue changes, releases, DOIs of
  released versions, removal of superseded versions.

What separates a contributor from a curator inside the dataset tables (a release, and
any change to a released version) is checked by granudb before it writes
(``require_curator``), by the same test the server applies to the catalogue: a curator is
an account that may update ``materials``. An account that writes SQL directly is held
only by the table privileges, so give people you do not trust with releases the reader
or contributor role, never table owner.

A command run by an account without the right is refused in one line naming the role it
needs (``translate_db_error`` maps PostgreSQL's InsufficientPrivilege, SQLSTATE 42501,
with ``needed_role``); the transaction is rolled back, so nothing changes.
"""

from __future__ import annotations

import re

from sqlalchemy import text
from sqlalchemy.engine import Connection

from granudb.errors import DatabaseAccessError, ValidationError

ROLES = ("reader", "contributor", "curator")
#: The tables a contributor writes: a dataset's own rows, never the catalogue.
DATASET_TABLES = ("datasets", "collisions", "collision_imports", "reported_runs")
#: The table whose UPDATE privilege marks a curator (the catalogue's central table).
CURATOR_MARK = "materials"
#: A PostgreSQL role name granudb creates or grants (no quoting games).
_ACCOUNT = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,62}")


def check_account(account: str) -> str:
    if not isinstance(account, str) or not _ACCOUNT.fullmatch(account):
        raise ValidationError(
            "ROLE",
            account,
            "must be a PostgreSQL role name: a letter or _, then letters, digits or _ (at most 63)",
        )
    return account


def check_role(role: str) -> str:
    if role not in ROLES:
        raise ValidationError("role", role, f"must be one of {', '.join(ROLES)}", parameter=True)
    return role


def needed_role(message: str) -> str | None:
    """The role that holds the privilege a PostgreSQL "permission denied" message names:
    the contributor for a dataset table or its id sequence, the curator for any other
    table; None when it is no table's (creating roles, granting: an administrator's)."""
    match = re.search(r"permission denied for (?:table|relation|sequence) (\w+)", message)
    if match is None:
        return None
    table = match.group(1)
    if any(table == t or table.startswith(f"{t}_") for t in DATASET_TABLES):
        return "contributor"
    return "curator"


def refusal(message: str) -> DatabaseAccessError:
    """InsufficientPrivilege as one line naming the role needed."""
    role = needed_role(message)
    if role is None:
        return DatabaseAccessError(
            f"needs a PostgreSQL administrator (a superuser, or CREATEROLE and ownership of "
            f"granudb's tables): {message}; nothing was changed"
        )
    return DatabaseAccessError(
        f"needs the {role} role: {message} (a PostgreSQL administrator runs "
        f"`granudb db grant ACCOUNT --as {role}`); nothing was changed"
    )


def require_curator(connection: Connection, action: str) -> None:
    """Refuse ``action`` (a release, a change to a released version) unless the account
    is a curator; on SQLite there are no accounts and nothing is checked."""
    if connection.dialect.name != "postgresql":
        return
    allowed = connection.execute(
        text("SELECT has_table_privilege(current_user, :table, 'UPDATE')"),
        {"table": CURATOR_MARK},
    ).scalar()
    if not allowed:
        user = connection.execute(text("SELECT current_user")).scalar()
        raise DatabaseAccessError(
            f"needs the curator role: {action} (connected as {user}; a PostgreSQL "
            "administrator runs `granudb db grant ACCOUNT --as curator`); nothing was changed"
        )


def grant(connection: Connection, account: str, role: str) -> list[str]:
    """Create the login ``account`` if it does not exist and give it exactly ``role``'s
    privileges on this database (earlier grants of granudb's tables are revoked first).
    Returns what was done, one line each."""
    check_account(account)
    check_role(role)
    if connection.dialect.name != "postgresql":
        raise DatabaseAccessError(
            "db grant: roles exist on PostgreSQL only; on SQLite the database file's "
            "permissions decide who reads and writes"
        )
    preparer = connection.dialect.identifier_preparer
    who = preparer.quote(account)
    database = preparer.quote(connection.execute(text("SELECT current_database()")).scalar_one())
    done = []
    exists = connection.execute(
        text("SELECT 1 FROM pg_roles WHERE rolname = :name"), {"name": account}
    ).scalar()
    if exists:
        _refuse_unrestrictable(connection, account, role)
    if not exists:
        connection.execute(text(f"CREATE ROLE {who} LOGIN"))
        done.append(f"created login role {account} (no password: set one with ALTER ROLE)")
    statements = [
        f"REVOKE ALL ON ALL TABLES IN SCHEMA public FROM {who}",
        f"REVOKE ALL ON ALL SEQUENCES IN SCHEMA public FROM {who}",
        f"GRANT CONNECT ON DATABASE {database} TO {who}",
        f"GRANT USAGE ON SCHEMA public TO {who}",
        f"GRANT SELECT ON ALL TABLES IN SCHEMA public TO {who}",
    ]
    if role == "contributor":
        tables = ", ".join(DATASET_TABLES)
        statements += [
            f"GRANT INSERT, UPDATE, DELETE ON {tables} TO {who}",
            f"GRANT USAGE, SELECT ON ALL SEQUENCES IN SCHEMA public TO {who}",
        ]
    if role == "curator":
        statements += [
            f"GRANT INSERT, UPDATE, DELETE ON ALL TABLES IN SCHEMA public TO {who}",
            f"REVOKE INSERT, UPDATE, DELETE ON alembic_version FROM {who}",
            f"GRANT USAGE, SELECT ON ALL SEQUENCES IN SCHEMA public TO {who}",
        ]
    for statement in statements:
        connection.execute(text(statement))
    done.append(f"{account} is a {role} of this database ({ROLE_RIGHTS[role]})")
    return done


def _refuse_unrestrictable(connection: Connection, account: str, role: str) -> None:
    """Refuse to call ``account`` a ``role`` when table privileges cannot hold it: a
    superuser passes every privilege check, and the owner of a table (or a member of the
    owning role) may grant itself back anything revoked, alter or drop it. Saying "reads
    everything, writes nothing" of such an account would be false."""
    superuser = connection.execute(
        text("SELECT rolsuper FROM pg_roles WHERE rolname = :name"), {"name": account}
    ).scalar()
    owned = (
        connection.execute(
            text(
                "SELECT tablename FROM pg_tables WHERE schemaname = 'public' "
                "AND pg_has_role(:name, tableowner, 'USAGE') ORDER BY tablename"
            ),
            {"name": account},
        )
        .scalars()
        .all()
    )
    if not superuser and not owned:
        return
    why = (
        "is a superuser (PostgreSQL lets it write whatever it is granted)"
        if superuser
        else f"owns granudb's tables ({', '.join(owned[:3])}{'…' if len(owned) > 3 else ''}: "
        "an owner can grant itself back any right)"
    )
    raise DatabaseAccessError(
        f"db grant: {account} {why}, so it cannot be made a {role}; a {role} must be a "
        "login that is not a superuser and does not own the tables: grant the role to a new "
        f"account (`granudb db grant {account}_{role} --as {role}`); nothing was changed"
    )


ROLE_RIGHTS = {
    "reader": "reads everything, writes nothing",
    "contributor": "reads everything; imports into, edits and removes draft datasets",
    "curator": "everything but the schema: catalogue, releases, removals",
}
