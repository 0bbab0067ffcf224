"""The rules every name and free text obeys, wherever it comes from.

One set for the command line, CSV files and Data Packages, so a string that one door
accepts every other door and every later read accepts too. Names (materials, fluids,
datasets, runs, sources) are single-line, printable, without surrounding spaces, without
bidirectional overrides or zero-width characters (which make two different names look the
same, or one name read backwards in a terminal), and at most ``MAX_NAME`` characters.
Free text (descriptions, notes) may hold line breaks and tabs but no other control
character, and no bare carriage return (spreadsheets and CSV readers disagree about it).
Both are normalised to Unicode NFC (a decomposed "é" is stored composed), and names are
compared case- and normalisation-insensitively (``name_key``), so two names that print
the same are the same name.
"""

from __future__ import annotations

import re
import unicodedata
from typing import Any, overload

from granudb.errors import ValidationError

MAX_NAME = 200
MAX_TEXT = 10_000

#: C0 and C1 control characters (tab, line feed excepted for free text).
_CONTROL = "\x00-\x08\x0b-\x1f\x7f-\x9f"
#: Bidirectional embeddings, overrides and isolates, and marks (Unicode TR9).
_BIDI = "\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069"
#: Zero-width and invisible formatting characters.
_INVISIBLE = "\u200b-\u200d\u2060-\u2064\ufeff\u00ad"

_NAME_FORBIDDEN = re.compile(f"[\t\n\r{_CONTROL}{_BIDI}{_INVISIBLE}]")
_TEXT_FORBIDDEN = re.compile(f"[\r{_CONTROL}{_BIDI}{_INVISIBLE}]")


def _describe(character: str) -> str:
    return f"U+{ord(character):04X}"


def name_key(name: str) -> str:
    """The case-insensitive lookup key of a name ("Zerodur", "ZERODUR" → "zerodur").

    Computed in Python (``str.casefold``) rather than with SQL ``lower()``, which folds only
    ASCII in SQLite but all of Unicode in PostgreSQL.

    Canonical caseless matching (Unicode §3.13): a name in decomposed form (NFD) has the
    key of its composed twin.

    >>> name_key("Cafe\u0301") == name_key("CAF\u00c9")
    True
    """
    folded = unicodedata.normalize("NFD", " ".join(name.split())).casefold()
    return unicodedata.normalize("NFC", folded)


def nfc(value: str) -> str:
    """``value`` in Unicode normal form C (composed), as every stored name and text is."""
    return unicodedata.normalize("NFC", value)


def check_name(field: str, value: str, *, max_length: int = MAX_NAME) -> str:
    """``value`` in NFC if it is a valid name, else ``ValidationError`` naming the rule.

    >>> check_name("name", "Zerodur")
    'Zerodur'
    """
    if not isinstance(value, str) or not value.strip():
        raise ValidationError(field, repr(value), "must not be empty")
    if value != value.strip():
        raise ValidationError(field, repr(value), "must not begin or end with spaces")
    return _within(field, value, max_length, _NAME_FORBIDDEN, "")


@overload
def check_text(field: str, value: str, *, max_length: int = ...) -> str: ...
@overload
def check_text(field: str, value: None, *, max_length: int = ...) -> None: ...
@overload
def check_text(field: str, value: str | None, *, max_length: int = ...) -> str | None: ...
def check_text(field: str, value: str | None, *, max_length: int = MAX_TEXT) -> str | None:
    """``value`` in NFC if it is valid free text (``None`` stays ``None``), else
    ``ValidationError``."""
    if value is None:
        return None
    return _within(field, value, max_length, _TEXT_FORBIDDEN, "; line breaks are \\n")


def in_nfc(values: list[Any]) -> list[Any]:
    """Each text of ``values`` in NFC (None and other values stay), as every door stores
    it: ``values`` itself where every text is already, checked at once (joined by a line
    feed, a starter that composes with nothing, the whole is NFC exactly when every part
    is), so a file's labels cost one pass of C, not one call each.

    >>> in_nfc(["Cafe\u0301-1", None, "run 2"]) == ["Caf\u00e9-1", None, "run 2"]
    True
    """
    texts = [v for v in values if isinstance(v, str)]
    if unicodedata.is_normalized("NFC", "\n".join(texts)):
        return values
    return [unicodedata.normalize("NFC", v) if isinstance(v, str) else v for v in values]


def _within(field: str, value: str, max_length: int, forbidden: re.Pattern[str], note: str) -> str:
    """``value`` if it is at most ``max_length`` long and holds no ``forbidden`` character
    (``note`` ends the message), else ``ValidationError``."""
    if len(value) > max_length:
        raise ValidationError(
            field, repr(value[:20] + "…"), f"must be at most {max_length} characters"
        )
    bad = forbidden.search(value)
    if bad:
        raise ValidationError(
            field,
            repr(value[:40]),
            f"must not contain {_describe(bad.group())} (control, bidirectional or "
            f"invisible characters{note})",
        )
    return nfc(value)


def name_pattern() -> str:
    """A regular expression (for Table Schema ``pattern``) that valid names match."""
    return (
        f"^[^\\s{_CONTROL}{_BIDI}{_INVISIBLE}](?:[^\t\n\r{_CONTROL}{_BIDI}{_INVISIBLE}]*"
        f"[^\\s{_CONTROL}{_BIDI}{_INVISIBLE}])?$"
    )


def name_forbidden_pattern() -> str:
    """The characters no name may hold, as a regular expression.

    For vectorized checks of many names at once (a million run labels through pandas'
    ``str.contains``); the first value it flags is then passed to ``check_name`` for the
    message, so both paths apply the same rule.
    """
    return _NAME_FORBIDDEN.pattern


def text_forbidden_pattern() -> str:
    """The characters no free text may hold, as a regular expression (see
    ``name_forbidden_pattern``; the message comes from ``check_text``)."""
    return _TEXT_FORBIDDEN.pattern
