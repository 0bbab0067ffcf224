"""The people who made a dataset: one author record, checked the same at every door
(``dataset edit --author``, ``granudb.edit_dataset(authors=…)`` and a Data Package's
``granudb:authors``), so what one accepts the others accept and store alike."""

from __future__ import annotations

import re
from typing import Any

from granudb.errors import ValidationError
from granudb.vocabulary.text import check_name

_ORCID = re.compile(r"^(?:https://orcid\.org/)?(\d{4}-\d{4}-\d{4}-\d{3}[\dX])$")
AUTHOR_FIELDS = ("given_names", "family_names", "orcid", "affiliation")


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


def check_keyword(word: Any, where: str = "--keyword") -> str:
    """One keyword: a name of at most 100 characters."""
    if not isinstance(word, str):
        raise ValidationError(where, word, "must be text")
    return check_name(where, word, max_length=100)


def author_words(person: dict[str, Any]) -> str:
    """An author as people read one: ``Jane Doe (ORCID 0000-0002-1825-0097, Lab A)``."""
    name = " ".join(
        str(person.get(k)).strip() for k in ("given_names", "family_names") if person.get(k)
    )
    more = [f"ORCID {person['orcid']}" if person.get("orcid") else "",
            str(person.get("affiliation") or "").strip()]  # fmt: skip
    said = ", ".join(m for m in more if m)
    return f"{name} ({said})" if said else name
