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
folder and renamed into place in one step: all or nothing.
"""

from __future__ import annotations

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
