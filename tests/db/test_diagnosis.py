"""A database that cannot be opened or written is diagnosed by its cause, never by the
symptom SQLite reports (issue 35): a good file on a read-only mount or a full disk is not
"not a SQLite database" (a user may delete it). Each cause has its own one-line message,
exit 1, and the file's bytes are the same afterwards.

The read-only mount and the full disk are real (a bind mount remounted read-only, a tiny
tmpfs); they need root and a kernel that lets the test mount, and are skipped with the
reason otherwise. Root ignores file permissions, so permission is taken away with
``chattr +i`` (immutable) when running as root, ``chmod`` otherwise.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import sqlite3
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest

pytestmark = pytest.mark.sqlite_only

ADD = (
    "materials",
    "add",
    "probe",
    "--density",
    "1 g/cm^3",
    "--youngs-modulus",
    "1 GPa",
    "--poisson-ratio",
    "0.3",
    "--roughness",
    "1 nm",
)


def _sha(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _copy(db: str, folder: Path, *, wal: bool) -> Path:
    """The test database in ``folder``, in WAL mode (as granudb leaves it) or not."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "granudb.sqlite"
    shutil.copy(db, path)
    with sqlite3.connect(path) as connection:
        connection.execute(f"PRAGMA journal_mode={'WAL' if wal else 'DELETE'}")
    connection.close()
    return path


def _mount(*args: str) -> None:
    done = subprocess.run(["mount", *args], capture_output=True, text=True)
    if done.returncode != 0:
        pytest.skip(f"cannot mount here ({done.stderr.strip() or done.returncode})")


def _umount(target: Path) -> None:
    subprocess.run(["umount", "-l", str(target)], check=False, capture_output=True)


@pytest.fixture
def read_only_mount(tmp_path: Path) -> Iterator[tuple[Path, Path]]:
    """(writable folder, the same folder mounted read-only)."""
    if os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("mounting needs root and mount(8)")
    source, target = tmp_path / "source", tmp_path / "ro"
    source.mkdir()
    target.mkdir()
    _mount("--bind", str(source), str(target))
    try:
        done = subprocess.run(
            ["mount", "-o", "remount,ro,bind", str(target)], capture_output=True, text=True
        )
        if done.returncode != 0:
            pytest.skip(f"cannot remount read-only here ({done.stderr.strip()})")
        yield source, target
    finally:
        _umount(target)


@pytest.fixture
def small_tmpfs(tmp_path: Path) -> Iterator[Path]:
    if os.geteuid() != 0 or shutil.which("mount") is None:
        pytest.skip("mounting needs root and mount(8)")
    target = tmp_path / "small"
    target.mkdir()
    _mount("-t", "tmpfs", "-o", "size=2m", "tmpfs", str(target))
    try:
        yield target
    finally:
        _umount(target)


def _fill(folder: Path) -> None:
    """Write zeros into ``folder`` until its file system has no byte left."""
    handle = os.open(folder / "filler", os.O_WRONLY | os.O_CREAT)
    try:
        while os.write(handle, b"\0" * 4096):
            pass
    except OSError:
        pass
    finally:
        os.close(handle)


def _refused(cli, *args: str, db: Path) -> str:
    before = _sha(db)
    result = cli(*args, db=db)
    assert result.exit_code == 1, result.stdout
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("Error: database:")
    assert "Traceback" not in result.stderr
    assert _sha(db) == before
    return result.stderr.strip()


def test_a_good_file_on_a_read_only_mount_is_not_called_a_foreign_file(
    cli, db: str, read_only_mount
) -> None:
    source, target = read_only_mount
    _copy(db, source, wal=True)  # WAL: even a read must create -shm beside the file
    message = _refused(cli, "materials", "list", db=target / "granudb.sqlite")
    assert "is on a read-only file system" in message
    assert "not a SQLite database" not in message
    assert sorted(p.name for p in source.iterdir()) == ["granudb.sqlite"]


def test_a_write_on_a_read_only_mount_names_the_mount(cli, db: str, read_only_mount) -> None:
    source, target = read_only_mount
    _copy(db, source, wal=False)  # a rollback journal: the probe reads, opening must write
    path = target / "granudb.sqlite"
    for command in (("materials", "list"), ADD):
        message = _refused(cli, *command, db=path)
        assert "is on a read-only file system" in message


def test_a_good_file_on_a_full_disk_is_not_called_a_foreign_file(
    cli, db: str, small_tmpfs: Path
) -> None:
    path = _copy(db, small_tmpfs, wal=True)
    _fill(small_tmpfs)
    message = _refused(cli, "materials", "list", db=path)
    assert "is full (" in message and "free some space" in message
    assert "not a SQLite database" not in message


def test_a_write_on_a_full_disk_says_full(cli, db: str, small_tmpfs: Path) -> None:
    path = _copy(db, small_tmpfs, wal=False)
    _fill(small_tmpfs)
    message = _refused(cli, *ADD, db=path)
    assert "is full (" in message


@pytest.fixture
def no_write_permission(tmp_path: Path) -> Iterator[Path]:
    """A folder whose contents cannot be written: immutable as root, mode 0555 otherwise."""
    folder = tmp_path / "locked-folder"
    folder.mkdir()
    yield folder
    if os.geteuid() == 0:
        subprocess.run(["chattr", "-i", str(folder)], check=False, capture_output=True)
    folder.chmod(0o755)


def _take_write_permission(folder: Path) -> None:
    if os.geteuid() == 0:
        if shutil.which("chattr") is None:
            pytest.skip("root ignores file modes and chattr(1) is not installed")
        done = subprocess.run(["chattr", "+i", str(folder)], capture_output=True, text=True)
        if done.returncode != 0:
            pytest.skip(f"this file system has no immutable flag ({done.stderr.strip()})")
    else:
        folder.chmod(0o555)


def test_permission_denied_is_said_as_such(cli, db: str, no_write_permission: Path) -> None:
    _copy(db, no_write_permission, wal=True)
    _take_write_permission(no_write_permission)
    message = _refused(cli, "materials", "list", db=no_write_permission / "granudb.sqlite")
    assert message.startswith(f"Error: database: permission denied on {no_write_permission}")


def test_a_file_held_exclusively_is_locked_not_foreign(cli, db: str, tmp_path: Path) -> None:
    path = _copy(db, tmp_path / "held", wal=True)
    holder = sqlite3.connect(path, isolation_level=None)
    try:
        holder.execute("PRAGMA locking_mode=EXCLUSIVE")
        holder.execute("BEGIN EXCLUSIVE")
        holder.execute("UPDATE materials SET name = name WHERE 0")
        holder.execute("CREATE TABLE held_here (x)")
        message = _refused(cli, "materials", "list", db=path)
    finally:
        holder.execute("ROLLBACK")
        holder.close()
    assert "is locked by another program" in message and "try again" in message
    assert cli("materials", "list", db=path).exit_code == 0  # nothing was harmed


def test_each_cause_has_its_own_message(cli, db: str, tmp_path: Path) -> None:
    """Not a database and a newer schema (the two causes a file itself carries) beside the
    diagnoses above: six distinct first words after "database:"."""
    garbage = tmp_path / "garbage" / "granudb.sqlite"
    garbage.parent.mkdir()
    garbage.write_bytes(b"SQLite format 2\0" + os.urandom(2000))
    assert "is not a SQLite database" in _refused(cli, "materials", "list", db=garbage)

    newer = _copy(db, tmp_path / "newer", wal=False)
    with sqlite3.connect(newer) as connection:
        connection.execute("UPDATE alembic_version SET version_num = '9999_from_the_future'")
    connection.close()
    result = cli("materials", "list", db=newer)
    assert result.exit_code == 1
    assert "is newer than this granudb knows" in result.stderr
    assert result.stderr.count("\n") == 1


def test_the_diagnosis_reads_the_file_system_not_sqlites_words(tmp_path: Path) -> None:
    """The same SQLite text gives different causes depending on the folder: a writable,
    roomy folder is "cannot open", never a guess."""
    from granudb.db.engine import sqlite_failure

    path = tmp_path / "granudb.sqlite"
    path.write_bytes(b"")
    said = str(sqlite_failure(path, "unable to open database file"))
    assert said.startswith(f"database: cannot open {path}")
    assert "read-only" not in said and "full" not in said and "permission" not in said
