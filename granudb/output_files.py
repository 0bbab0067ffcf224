"""Files the product writes: nothing outside the target, nothing half-written.

Every file granudb writes (a report and its figures, a Data Package as a zip or a folder,
a DEM deck) goes through here:

- the content is first written to a temporary file created exclusively
  (``tempfile.mkstemp``: a fresh random name, ``O_EXCL``, so no planted file or symlink is
  written through) in the target's own folder;
- it is then put in place atomically: ``os.link`` when an existing target must not be
  replaced (it fails if anything — a file, a folder, a dangling symlink — has the name),
  ``os.replace`` when the caller may replace it (a rename replaces a symlink itself, never
  the file it points to);
- on any failure (disk full, permission, an interrupted write) the temporary file is
  removed and the error is one line naming the path and the cause;
- the file gets the permissions any new file gets (``0o666`` less the umask: 0644 under
  umask 022), not ``mkstemp``'s private 0600, so a colleague can open a shared report; a
  folder likewise ``0o777`` less the umask.

A folder of files (a package exported to a folder) is written into a temporary sibling
folder and renamed into place in one step: all or nothing. A folder that belongs to a file
(a Markdown report's figures) lands with it (``land_with``): a write killed between the
two leaves a folder marked as granudb's own unfinished write, which the rerun replaces.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import tempfile
from collections.abc import Mapping
from pathlib import Path

from granudb.errors import ValidationError


def refuse(field: str, path: Path, exc: OSError) -> ValidationError:
    """An ``OSError`` while writing ``path`` as granudb's one-line refusal."""
    cause = exc.strerror or type(exc).__name__
    return ValidationError(field, str(path), f"cannot be written ({cause}); nothing was written")


def current_umask() -> int:
    """The process's umask (read by setting it and putting it back at once)."""
    mask = os.umask(0o077)
    os.umask(mask)
    return mask


def _temporary(folder: Path, name: str) -> Path:
    handle, temporary = tempfile.mkstemp(prefix=f".{name}.", suffix=".part", dir=folder)
    try:
        os.fchmod(handle, 0o666 & ~current_umask())  # as open() would create it
    finally:
        os.close(handle)
    return Path(temporary)


def write_bytes(
    path: Path, payload: bytes, *, replace: bool = False, field: str = "output"
) -> Path:
    """Write ``payload`` to ``path`` as described in the module docstring; an existing
    ``path`` (or a symlink of that name) is refused unless ``replace``."""
    path = Path(path)
    if path.is_symlink() and not replace:
        raise ValidationError(field, str(path), "is a symbolic link (choose a new file)")
    try:
        temporary = _temporary(path.parent, path.name)
    except OSError as exc:
        raise refuse(field, path, exc) from None
    try:
        with temporary.open("wb") as handle:
            handle.write(payload)
        if replace:
            os.replace(temporary, path)
        else:
            os.link(temporary, path, follow_symlinks=False)
    except FileExistsError:
        raise ValidationError(field, str(path), "exists already (choose a new file)") from None
    except OSError as exc:
        raise refuse(field, path, exc) from None
    finally:
        temporary.unlink(missing_ok=True)
    return path


def write_text(path: Path, text: str, *, replace: bool = False, field: str = "output") -> Path:
    """``write_bytes`` of ``text`` in UTF-8."""
    return write_bytes(path, text.encode("utf-8"), replace=replace, field=field)


def write_folder(
    folder: Path, files: Mapping[str, bytes], *, replace: bool = False, field: str = "output"
) -> Path:
    """Every file of ``files`` (relative path → bytes) in ``folder``, all or nothing: they
    are written into a temporary sibling folder that then takes ``folder``'s name. An
    existing empty ``folder`` is taken; a non-empty one only with ``replace``."""
    folder = Path(folder)
    if folder.is_symlink():
        raise ValidationError(field, str(folder), "is a symbolic link (choose a new folder)")
    if folder.exists() and not folder.is_dir():
        raise ValidationError(field, str(folder), "exists and is not a folder")
    if folder.is_dir() and any(folder.iterdir()) and not replace:
        raise ValidationError(field, str(folder), "is a folder that is not empty")
    try:
        staging = Path(
            tempfile.mkdtemp(prefix=f".{folder.name}.", suffix=".part", dir=folder.parent)
        )
    except OSError as exc:
        raise refuse(field, folder, exc) from None
    try:
        for relative, payload in files.items():
            target = staging / relative
            if not target.resolve().is_relative_to(staging.resolve()):
                raise ValidationError(field, relative, "is outside the package folder")
            target.parent.mkdir(parents=True, exist_ok=True)
            with target.open("xb") as handle:
                handle.write(payload)
        os.chmod(staging, 0o777 & ~current_umask())  # as mkdir() would create it
        if folder.is_dir() and any(folder.iterdir()):
            shutil.rmtree(folder)  # replace: the caller said so
        os.rename(staging, folder)  # onto an absent or empty folder: one step
    except OSError as exc:
        raise refuse(field, folder, exc) from None
    finally:
        if staging.exists():
            shutil.rmtree(staging, ignore_errors=True)
    return folder


#: The mark inside a folder that lands with a file (a Markdown report's figures): JSON
#: naming that file and the folder's files; removed once the file is in place.
LANDING_MARK = ".granudb-landing"


def land_with(
    folder: Path,
    files: Mapping[str, bytes],
    path: Path,
    payload: bytes,
    *,
    replace: bool = False,
    field: str = "output",
) -> Path:
    """``files`` in a new ``folder`` and ``payload`` at ``path``, landing together: the
    folder is staged whole with a mark (``LANDING_MARK``) and renamed into place
    (``write_folder``), then ``path`` is written, then the mark goes. A write killed
    between the two leaves a folder whose mark names a file that is not there:
    ``unfinished`` recognises it as granudb's own, so it never blocks the rerun."""
    mark = json.dumps({"file": path.name, "files": sorted(files)}).encode("utf-8")
    write_folder(folder, {**files, LANDING_MARK: mark}, field=field)
    try:
        write_bytes(path, payload, replace=replace, field=field)
    except BaseException:
        clear_unfinished(folder, path)
        raise
    (folder / LANDING_MARK).unlink(missing_ok=True)
    return path


def unfinished(folder: Path, path: Path) -> list[str] | None:
    """The files of ``folder`` if it is a leftover of a ``land_with`` that did not finish
    (its mark names ``path``, which does not exist); None otherwise."""
    mark = folder / LANDING_MARK
    if folder.is_symlink() or mark.is_symlink() or not mark.is_file() or path.exists():
        return None
    try:
        said = json.loads(mark.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if not isinstance(said, dict) or said.get("file") != path.name:
        return None
    names = said.get("files")
    if not isinstance(names, list) or not all(isinstance(n, str) and "/" not in n for n in names):
        return None
    return names


def clear_unfinished(folder: Path, path: Path) -> bool:
    """Remove a leftover ``unfinished`` folder: only the files its mark lists, the mark,
    and the folder if nothing else is in it. True when one was removed."""
    names = unfinished(folder, path)
    if names is None:
        return False
    for name in [*names, LANDING_MARK]:
        target = folder / name
        if not target.is_symlink() and target.is_file():
            target.unlink()
    with contextlib.suppress(OSError):
        folder.rmdir()
    return True
