"""Roles on a shared PostgreSQL server (issue 25): a reader reads and is refused every
write in one line naming the role it needs, with the database unchanged; a contributor
imports drafts but cannot release or change the catalogue; a curator runs the whole tour.

The accounts are made by ``granudb db grant`` with unique names and dropped afterwards
(the server is shared). On SQLite there are no accounts and ``db grant`` refuses.
"""

from __future__ import annotations

import os
import uuid
from collections.abc import Iterator
from pathlib import Path

import pytest
from support import dump_hash

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "collisions_example.csv"
BACKEND = os.environ.get("GRANUDB_TEST_BACKEND", "sqlite")
on_postgresql = pytest.mark.skipif(
    BACKEND != "postgresql",
    reason="roles are PostgreSQL accounts; SQLite has none (the file's permissions decide)",
)
PAIR = ["pair", "steel", "Zerodur", "--diameter", "12.7 mm", "--velocity", "0.3 m/s"]


def _refused(result, *expected: str) -> str:
    assert result.exit_code == 1, (result.stdout, result.stderr)
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("Error: ") and "internal error" not in lines[0]
    assert "Traceback" not in result.stderr
    for text in expected:
        assert text in lines[0], lines[0]
    return lines[0]


def _ok(result) -> str:
    assert result.exit_code == 0, (result.stdout, result.stderr)
    return result.stdout


@pytest.fixture
def accounts(db: str, cli) -> Iterator[dict[str, str]]:
    """reader, contributor and curator login accounts of ``db``: {role: URL as that
    account}; granted by ``granudb db grant`` as the administrator, dropped afterwards."""
    from sqlalchemy import create_engine, text
    from sqlalchemy.engine import make_url

    tag = uuid.uuid4().hex[:10]
    names = {role: f"granudb_{role}_{tag}" for role in ("reader", "contributor", "curator")}
    urls = {}
    try:
        for role, name in names.items():
            out = _ok(cli("db", "grant", name, "--as", role, db=db))
            assert f"created login role {name}" in out and f"is a {role}" in out
            urls[role] = make_url(db).set(username=name).render_as_string(hide_password=False)
        yield urls
    finally:
        admin = create_engine(db, isolation_level="AUTOCOMMIT")
        with admin.connect() as connection:
            for name in names.values():
                exists = connection.execute(
                    text("SELECT 1 FROM pg_roles WHERE rolname = :n"), {"n": name}
                ).scalar()
                if exists:
                    connection.execute(text(f'DROP OWNED BY "{name}"'))
                    connection.execute(text(f'DROP ROLE "{name}"'))
        admin.dispose()


@on_postgresql
def test_reader_and_curator_through_the_tour(cli, db: str, accounts, tmp_path: Path) -> None:
    curator, reader = accounts["curator"], accounts["reader"]
    _ok(cli("collisions", "import", str(EXAMPLE), "--dataset", "tour", db=curator))
    _ok(cli("collisions", "import", str(EXAMPLE), "--dataset", "spare", db=curator))
    _ok(cli("materials", "add", "PTFE", "--density", "2.2 g/cm^3", "--youngs-modulus", "0.5 GPa",
            "--poisson-ratio", "0.46", "--roughness", "0.2 um", db=curator))  # fmt: skip
    before = dump_hash(db)

    # the reader reads everything
    assert "steel" in _ok(cli(*PAIR, db=reader))
    assert "steel" in _ok(cli("materials", "list", db=reader))
    assert "glass-g45-1" in _ok(cli("collisions", "list", "--dataset", "tour", db=reader))
    report = tmp_path / "tour.md"
    _ok(cli("report", "--dataset", "tour", "--format", "md", "--output", str(report), db=reader))
    assert report.stat().st_size > 0
    package = tmp_path / "tour.zip"
    _ok(cli("dataset", "export", "tour", "--output", str(package), db=reader))

    # and every write is refused in one line naming the role it needs
    writes = [
        (("collisions", "import", str(EXAMPLE), "--dataset", "tour2"), "contributor"),
        (("collisions", "remove", "tour", "steel-dry-5", "--yes"), "contributor"),
        (("dataset", "import", str(package), "--as", "copy"), "contributor"),
        (("dataset", "edit", "tour", "--title", "Mine"), "contributor"),
        (("dataset", "release", "tour"), "curator"),
        (("dataset", "remove", "spare", "--yes"), "contributor"),
        (("dataset", "new-version", "tour", "--version", "2.0.0"), "contributor"),
        (("materials", "update", "steel", "--youngs-modulus", "100 GPa"), "curator"),
        (("materials", "add", "PEEK", "--density", "2.2 g/cm^3", "--youngs-modulus", "0.5 GPa",
          "--poisson-ratio", "0.46", "--roughness", "0.2 um"), "curator"),
        (("fluids", "update", "water", "--reference-viscosity", "2 cP"), "curator"),
        (("materials", "remove", "PTFE", "--yes"), "curator"),
    ]  # fmt: skip
    for argv, role in writes:
        line = _refused(cli(*argv, db=reader), f"needs the {role} role")
        assert "nothing was changed" in line, line
    assert dump_hash(db) == before

    # the curator runs the rest of the tour
    _ok(cli("dataset", "release", "tour", db=curator))
    _ok(cli("dataset", "remove", "spare", "--yes", db=curator))
    _ok(cli("materials", "update", "steel", "--youngs-modulus", "190 GPa", db=curator))
    assert dump_hash(db) != before
    # a grant cannot come from an account that is not an administrator
    _refused(cli("db", "grant", "granudb_nobody_x", "--as", "curator", db=reader))


@on_postgresql
def test_contributor_imports_drafts_but_cannot_release(cli, db: str, accounts) -> None:
    contributor = accounts["contributor"]
    _ok(cli("collisions", "import", str(EXAMPLE), "--dataset", "draft", db=contributor))
    _ok(cli("collisions", "remove", "draft", "steel-dry-5", "--yes", db=contributor))
    _ok(cli("dataset", "edit", "draft", "--title", "Drafted", db=contributor))
    before = dump_hash(db)
    _refused(cli("dataset", "release", "draft", db=contributor), "needs the curator role")
    _refused(
        cli("materials", "update", "steel", "--youngs-modulus", "1 GPa", db=contributor),
        "needs the curator role",
    )
    assert dump_hash(db) == before
    # released by a curator, the version is out of the contributor's reach
    _ok(cli("dataset", "release", "draft", db=accounts["curator"]))
    _ok(cli("dataset", "new-version", "draft", "--version", "1.1.0", db=contributor))
    _ok(cli("dataset", "release", "draft@1.1.0", db=accounts["curator"]))
    before = dump_hash(db)
    _refused(cli("dataset", "remove", "draft@1.0.0", "--yes", db=contributor), "curator role")
    _refused(cli("dataset", "edit", "draft@1.1.0", "--doi", "10.5281/x", db=contributor),
             "curator role")  # fmt: skip
    assert dump_hash(db) == before


@pytest.mark.sqlite_only
def test_sqlite_has_no_roles(cli, db: str) -> None:
    before = dump_hash(db)
    _refused(cli("db", "grant", "lab", "--as", "reader", db=db), "PostgreSQL only", "SQLite")
    assert dump_hash(db) == before


def test_a_bad_account_or_role_is_one_line(cli, db: str) -> None:
    _refused(cli("db", "grant", "lab; DROP TABLE x", "--as", "reader", db=db), "role name")
    result = cli("db", "grant", "lab", "--as", "owner", db=db)
    assert result.exit_code == 2 and "'owner' is not one of" in result.stderr


@on_postgresql
@pytest.mark.parametrize("role", ["reader", "contributor", "curator"])
def test_a_superuser_cannot_be_made_a_role(cli, db: str, role: str) -> None:
    """The test server's administrator is a superuser: every privilege check passes, so
    "reads everything, writes nothing" would be false; refused, saying what it takes."""
    from sqlalchemy.engine import make_url

    admin = make_url(db).username
    before = dump_hash(db)
    line = _refused(
        cli("db", "grant", admin, "--as", role, db=db),
        f"db grant: {admin} is a superuser",
        f"cannot be made a {role}",
        "not a superuser and does not own the tables",
    )
    assert "nothing was changed" in line
    assert dump_hash(db) == before


@on_postgresql
def test_an_owner_of_the_tables_cannot_be_made_a_reader(cli, db: str) -> None:
    """An account that owns a granudb table, or belongs to the role that does, keeps
    every right on it whatever is revoked: refused, and the account can still write (the
    refusal was true)."""
    from sqlalchemy import create_engine, text
    from sqlalchemy.engine import make_url

    tag = uuid.uuid4().hex[:10]
    owner, member = f"granudb_owner_{tag}", f"granudb_member_{tag}"
    admin = create_engine(db, isolation_level="AUTOCOMMIT")
    try:
        with admin.connect() as connection:
            connection.execute(text(f'CREATE ROLE "{owner}" LOGIN'))
            connection.execute(text(f'CREATE ROLE "{member}" LOGIN IN ROLE "{owner}"'))
            connection.execute(text(f'ALTER TABLE materials OWNER TO "{owner}"'))
        before = dump_hash(db)
        for account in (owner, member):
            _refused(
                cli("db", "grant", account, "--as", "reader", db=db),
                f"db grant: {account} owns granudb's tables (materials",
                "cannot be made a reader",
            )
        assert dump_hash(db) == before
        as_owner = make_url(db).set(username=owner).render_as_string(hide_password=False)
        owner_engine = create_engine(as_owner)
        with owner_engine.begin() as connection:  # an owner writes whatever was revoked
            connection.execute(text(f'REVOKE ALL ON materials FROM "{owner}"'))
            connection.execute(text(f'GRANT ALL ON materials TO "{owner}"'))
            assert connection.execute(text("UPDATE materials SET name = name")).rowcount > 0
        owner_engine.dispose()
    finally:
        with admin.connect() as connection:
            connection.execute(text("ALTER TABLE materials OWNER TO CURRENT_USER"))
            for name in (member, owner):
                connection.execute(text(f'DROP OWNED BY "{name}"'))
                connection.execute(text(f'DROP ROLE "{name}"'))
        admin.dispose()
