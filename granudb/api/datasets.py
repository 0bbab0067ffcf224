"""The dataset lifecycle for Python users and the command line: remove a dataset or some
runs, edit its metadata, release it, start a new version.

A version is a draft until released; a released version is immutable (no import, no run
removed, no metadata changed except a DOI set once) and can be removed only after a newer
version has been released (it is then superseded), as with Granta MI record versions and
Zenodo's versioned records. Every function takes ``db=`` like the rest of the API
(an opened database, a URL, a SQLite path or nothing for the default) and runs in one
transaction: it happens whole or not at all.

Removal happens in two steps for the command line, which must ask first:
``removal_plan``/``run_removal_plan`` say what would be deleted, and the removing function
takes that list back as ``accepted`` and refuses if the database has changed since.
Called from Python without ``accepted``, the call itself is the consent.
"""

from __future__ import annotations

import json
import re
from collections.abc import Sequence
from typing import Any

from granudb.api.database import opened
from granudb.errors import ConfirmationNeeded, ValidationError
from granudb.vocabulary.text import check_name, check_text

_ORCID = re.compile(r"^(?:https://orcid\.org/)?(\d{4}-\d{4}-\d{4}-\d{3}[\dX])$")
_DOI = re.compile(r"^10\.\d{4,9}/\S+$")
AUTHOR_FIELDS = ("given_names", "family_names", "orcid", "affiliation")


def split_ref(text: str) -> tuple[str, str | None]:
    """``NAME@VERSION`` → (name, version); ``NAME`` → (name, None)."""
    name, _, version = text.rpartition("@") if "@" in text else (text, "", "")
    return name, version or None


def check_orcid(value: str, field: str = "orcid") -> str:
    """The ORCID iD ``0000-0002-1825-0097`` if its form and ISO 7064 11,2 check digit are
    right (a bare iD, or the https://orcid.org/ URL), else ``ValidationError``."""
    match = _ORCID.match(value.strip())
    if match is None:
        raise ValidationError(field, value, "is not an ORCID iD (0000-0000-0000-0000)")
    digits = match.group(1).replace("-", "")
    total = 0
    for digit in digits[:-1]:
        total = (total + int(digit)) * 2
    check = (12 - total % 11) % 11
    if digits[-1] != ("X" if check == 10 else str(check)):
        raise ValidationError(field, value, "has a wrong check digit (not a real ORCID iD)")
    return match.group(1)


def check_author(person: Any, where: str = "author") -> dict[str, str | None]:
    """One author as {"given_names", "family_names", "orcid", "affiliation"}; family
    names are required, the rest optional."""
    if not isinstance(person, dict):
        raise ValidationError(where, person, "must be an object with family_names")
    unknown = set(person) - set(AUTHOR_FIELDS)
    if unknown:
        raise ValidationError(
            where, sorted(unknown)[0], f"is not an author field ({', '.join(AUTHOR_FIELDS)})"
        )
    values = {k: person.get(k) or None for k in AUTHOR_FIELDS}
    for key, text in values.items():
        if text is not None and not isinstance(text, str):
            raise ValidationError(f"{where} {key}", text, "must be text")
    if values["family_names"] is None:
        raise ValidationError(f"{where} family_names", "(missing)", "is required")
    check_name(f"{where} family_names", values["family_names"])
    if values["given_names"] is not None:
        check_name(f"{where} given_names", values["given_names"])
    if values["affiliation"] is not None:
        check_name(f"{where} affiliation", values["affiliation"], max_length=500)
    if values["orcid"] is not None:
        values["orcid"] = check_orcid(values["orcid"], f"{where} orcid")
    return values


def parse_author(text: str) -> dict[str, str | None]:
    """``"Family, Given; orcid=0000-…; affiliation=Lab"`` (the command line's
    ``--author``) as an author record."""
    first, *rest = [part.strip() for part in text.split(";")]
    family, _, given = (p.strip() for p in first.partition(","))
    person: dict[str, str | None] = {"family_names": family, "given_names": given or None}
    for part in rest:
        key, eq, value = (p.strip() for p in part.partition("="))
        if not eq or key not in ("orcid", "affiliation"):
            raise ValidationError(
                "--author", text, "must be 'Family, Given; orcid=…; affiliation=…'"
            )
        person[key] = value
    return check_author(person, "--author")


def check_metadata(values: dict[str, Any]) -> dict[str, str | None]:
    """Check and normalise dataset metadata: title, description, license, doi as text;
    authors as a list of author records; keywords as a list of names. Returns the values
    as stored (authors and keywords as JSON text; ``""`` clears a field)."""
    out: dict[str, str | None] = {}
    for field, value in values.items():
        if value == "" or value == []:
            out[field] = None
        elif field == "title":
            out[field] = check_name("--title", value, max_length=500)
        elif field == "license":
            out[field] = check_name("--license", value)
        elif field == "description":
            out[field] = check_text("--description", value)
        elif field == "doi":
            value = re.sub(r"^https://doi\.org/", "", check_name("--doi", value))
            if not _DOI.match(value):
                raise ValidationError("--doi", value, "is not a DOI (10.NNNN/…)")
            out[field] = value
        elif field == "authors":
            people = [check_author(p, f"author {i + 1}") for i, p in enumerate(value)]
            out[field] = json.dumps(people, ensure_ascii=False)
        elif field == "keywords":
            words = [check_name("--keyword", w, max_length=100) for w in value]
            out[field] = json.dumps(list(dict.fromkeys(words)), ensure_ascii=False)
        else:
            raise ValidationError(field, value, "is not an editable dataset field")
    return out


def _accept(losses: list[str], accepted: list[str] | None) -> None:
    if accepted is not None and accepted != losses:
        raise ConfirmationNeeded(
            f"the data changed since you confirmed (now: {'; '.join(losses)}); nothing was changed"
        )


def removal_plan(name: str, version: str | None = None, *, db: Any = None) -> list[str]:
    """What ``remove_dataset`` would delete (one phrase per version); refuses a released
    version."""
    from granudb.db import datasets

    with opened(db) as database, database.session() as session:
        return datasets.removal_losses(session, datasets.datasets_to_remove(session, name, version))


def remove_dataset(
    name: str,
    version: str | None = None,
    *,
    db: Any = None,
    accepted: list[str] | None = None,
) -> list[str]:
    """Delete a dataset version (or every version, when ``version`` is None) with its runs
    and import records; returns what was deleted. Released versions are refused."""
    from granudb.db import datasets

    with opened(db) as database, database.session(write=True) as session:
        chosen = datasets.datasets_to_remove(session, name, version)
        losses = datasets.removal_losses(session, chosen)
        _accept(losses, accepted)
        datasets.remove_datasets(session, chosen)
    return losses


def run_removal_plan(
    name: str, runs: Sequence[str], version: str | None = None, *, db: Any = None
) -> list[str]:
    """What ``remove_runs`` would delete; refuses unknown runs and non-draft versions."""
    from granudb.db import datasets

    with opened(db) as database, database.session() as session:
        dataset = datasets.get_dataset(session, name, version)
        wanted = datasets.runs_to_remove(session, dataset, runs)
        return [f"{len(wanted)} runs of dataset {datasets.label(dataset)} ({_few(wanted)})"]


def _few(runs: list[str]) -> str:
    return ", ".join(runs[:5]) + (f", … {len(runs) - 5} more" if len(runs) > 5 else "")


def remove_runs(
    name: str,
    runs: Sequence[str],
    version: str | None = None,
    *,
    db: Any = None,
    accepted: list[str] | None = None,
) -> int:
    """Delete runs (by label) from a draft dataset version; returns how many."""
    from granudb.db import datasets

    with opened(db) as database, database.session(write=True) as session:
        dataset = datasets.get_dataset(session, name, version)
        wanted = datasets.runs_to_remove(session, dataset, runs)
        losses = [f"{len(wanted)} runs of dataset {datasets.label(dataset)} ({_few(wanted)})"]
        _accept(losses, accepted)
        return datasets.remove_runs(session, dataset, wanted)


def edit_dataset(
    name: str, version: str | None = None, *, db: Any = None, **values: Any
) -> list[tuple[str, Any, Any]]:
    """Change metadata of a draft version: ``title``, ``description``, ``license``,
    ``doi`` (text; "" clears), ``authors`` (a list of {"given_names", "family_names",
    "orcid", "affiliation"}, ORCID check digit verified), ``keywords`` (a list of text).
    Returns (field, old, new) for each change."""
    from granudb.db import datasets

    checked = check_metadata(values)
    with opened(db) as database, database.session(write=True) as session:
        dataset = datasets.get_dataset(session, name, version)
        return datasets.edit_dataset(session, dataset, checked)


def release_dataset(name: str, version: str | None = None, *, db: Any = None) -> list[str]:
    """Release a draft version (it becomes immutable); returns the versions it supersedes."""
    from granudb.db import datasets

    with opened(db) as database, database.session(write=True) as session:
        dataset = datasets.get_dataset(session, name, version)
        return [d.version for d in datasets.release_dataset(session, dataset)]


def new_version(name: str, version: str | None, new: str, *, db: Any = None) -> str:
    """Copy a version (metadata, runs, import records) as a new draft ``new``; returns
    its content hash (the same as the copied version's)."""
    from granudb.db import datasets

    with opened(db) as database, database.session(write=True) as session:
        dataset = datasets.get_dataset(session, name, version)
        return datasets.new_version(session, dataset, new).content_hash or ""
