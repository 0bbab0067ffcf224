"""The catalogue's two kinds of entry, materials and fluids, as one specification each.

Everything that differs between a material and a fluid is written once: the stored
properties in the order every door shows them, which are needed to add one, defaults and
the columns a narrow table shows come from each column's declaration
(``granudb.vocabulary.terms.STORED``); the names that are reserved are here. Everything else — the
Python functions ``granudb.add_material`` / ``add_fluid`` …, the command-line options
(``--density``, ``--reference-viscosity``), the listing columns of JSON, CSV and tables,
the seed files' columns, the checks before a write — is generated from these two
objects by one implementation (``granudb.db.catalog_changes``, ``granudb.api.catalog``,
``granudb.cli.catalog``).

A property's Python parameter and command-line option come from its term: the option
``--youngs-modulus`` of ``youngs_modulus_pa`` is the parameter ``youngs_modulus``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Any
from urllib.parse import urlsplit

from granudb.errors import ValidationError
from granudb.vocabulary.terms import (
    SOURCE_YEARS,
    STORED,
    TERMS,
    stored,
    stored_values,
    uncertainty_column,
)
from granudb.vocabulary.text import check_name, check_text

#: Text fields every catalogue entry has besides its properties.
TEXT_FIELDS = ("description", "source_locator")


@dataclass(frozen=True)
class Catalogue:
    """One kind of catalogue entry (``material`` or ``fluid``).

    ``properties`` are the stored SI properties, in display order; ``required`` the ones
    an entry cannot be added without (each property may carry a standard uncertainty,
    ``uncertainties``); ``defaults`` what an omitted property is set to on
    adding; ``companions`` columns a listing shows right after a property (a flag saying
    the value was derived); ``trailing`` listing columns after the source (more sources,
    counts); ``narrow`` what a table for people shows; ``reserved`` names an entry
    cannot take (compared case-insensitively).
    """

    kind: str
    plural: str
    properties: tuple[str, ...]
    required: tuple[str, ...]
    narrow: tuple[str, ...]
    defaults: dict[str, float] = field(default_factory=dict)
    companions: dict[str, str] = field(default_factory=dict)
    trailing: tuple[str, ...] = ()
    reserved: dict[str, str] = field(default_factory=dict)
    #: Text fields of this kind only (besides ``TEXT_FIELDS``), each with its allowed
    #: words (empty: free text), shown in listings right after the properties.
    texts: dict[str, tuple[str, ...]] = field(default_factory=dict)

    @property
    def columns(self) -> list[str]:
        """Every column of a listing (JSON, CSV, DataFrame), in order."""
        shown = ["name", "description"]
        for name in self.properties:
            shown.append(name)
            if name in self.companions:
                shown.append(self.companions[name])
            shown.append(uncertainty_column(name))  # u of the value; empty: not given
        shown.extend(self.texts)
        return [*shown, "source", "source_locator", *self.trailing]

    @property
    def fields(self) -> frozenset[str]:
        """The stored fields a user may set: the properties and the text fields."""
        return frozenset(
            (*self.properties, *self.uncertainties.values(), *self.texts, *TEXT_FIELDS)
        )

    @property
    def uncertainties(self) -> dict[str, str]:
        """Property → the stored column of its standard uncertainty (``u_<property>``),
        set with the property (``"190 GPa ± 5 %"``)."""
        return {name: uncertainty_column(name) for name in self.properties}

    @property
    def parameters(self) -> dict[str, str]:
        """Python parameter → stored column, for the properties and the text fields
        (``youngs_modulus`` → ``youngs_modulus_pa``); the option is the parameter with
        dashes."""
        return {parameter_of(c): c for c in (*self.properties, *self.texts, *TEXT_FIELDS)}


def parameter_of(column: str) -> str:
    """The Python parameter (and, with dashes, the option) that sets ``column``."""
    option = TERMS[column].option
    return option.removeprefix("--").replace("-", "_") if option else column


def declared_catalogue(kind: str, plural: str, **rest: Any) -> Catalogue:
    """A catalogue whose properties, required properties, defaults, companions, text
    fields and narrow table come from its table's declarations (``vocabulary.terms``)."""
    declared = stored(plural)
    numbers = [s for s in declared if s.sql == "float"]
    return Catalogue(
        kind=kind,
        plural=plural,
        properties=tuple(s.column for s in numbers),
        required=tuple(s.column for s in numbers if not s.nullable and s.default is None),
        narrow=("name", *(s.column for s in numbers if s.listed), *rest.pop("narrow_end")),
        defaults={s.column: float(s.default) for s in numbers if s.default is not None},
        companions={s.column: s.companion for s in numbers if s.companion},
        texts={s.column: s.words for s in declared if s.sql in ("text", "string")},
        **rest,
    )


#: A material's own dry values (docs/physics.md §18): optional, with where they came from
#: (``dry_provenance``, set by ``--dry-source``); a pair's measured values are kept apart
#: (``PAIR_VALUE_COLUMNS``).
DRY_VALUE_PROPERTIES = tuple(stored_values("materials", "dry"))
#: Text fields kept to one line (a name's rules: no line break, tab or surrounding
#: spaces), with their longest length; every door checks them so.
ONE_LINE_TEXTS: dict[str, int] = {s.column: s.one_line for s in STORED if s.one_line}

MATERIALS = declared_catalogue("material", "materials", narrow_end=("source",))
FLUIDS = declared_catalogue(
    "fluid",
    "fluids",
    narrow_end=("points", "source"),
    trailing=("density_source", "pressure_viscosity_source", "points"),
    reserved={"dry": "is reserved: 'dry' means no fluid"},
)

#: A fluid's measured point: viscosity (and density) at a temperature.
POINT_COLUMNS = [*stored_values("fluid_points"), "source"]
#: The standard uncertainties a point may carry (``"1.31 ± 0.01 cP"``), shown after it.
POINT_UNCERTAINTIES = [s.uncertainty.column for s in stored("fluid_points") if s.uncertain]
#: The columns of a source, and those every source has.
SOURCE_COLUMNS = [s.column for s in stored("sources")]
SOURCE_REQUIRED = [s.column for s in stored("sources") if not s.nullable]
#: The fields a user sets (``sources add|update`` options, ``add_source`` keywords): all
#: but the key, which names the source.
SOURCE_FIELDS = [c for c in SOURCE_COLUMNS if c != "key"]
#: What a table of sources shows.
SOURCE_NARROW = ["key", "year", "kind", "citation", "doi"]
#: The longest text each column of a source holds (``granudb.db.models.Source``).
SOURCE_LENGTHS = {s.column: s.length for s in stored("sources") if s.length}
#: A DOI: "10.", the registrant's number, "/", a suffix without spaces (DOI Handbook §2.2;
#: stored without "https://doi.org/", which the reports add).
_DOI = re.compile(r"10\.[0-9]{4,9}(?:\.[0-9]+)*/\S+")


def check_source(values: dict[str, Any]) -> None:
    """The rules of a source's fields, for each field in ``values`` (a field set to
    None is absent, except the citation, which every source has): the key and kind are
    names, the citation and notes free text, the DOI ``10.NNNN/suffix``, the URL an
    ``http(s)://`` address with a host, the year a whole number in 1600–3000. Text
    fields are set to their NFC form in ``values``.

    >>> check_source({"doi": "10.1017/S002211200400919X", "url": "https://doi.org"})
    >>> check_source({"doi": "https://doi.org/10.1017/S0022"})
    Traceback (most recent call last):
    ...
    granudb.errors.ValidationError: doi: 'https://doi.org/10.1017/S0022' must look like \
10.NNNN/suffix (the DOI itself, without https://doi.org/ or doi:)
    """
    for column in ("key", "kind"):
        if column in values:
            values[column] = check_name(column, values[column], max_length=SOURCE_LENGTHS[column])
    if "citation" in values:
        citation = values["citation"]
        if not isinstance(citation, str) or not citation.strip():
            raise ValidationError("citation", repr(citation), "must not be empty")
        values["citation"] = check_text("citation", citation)
    if values.get("notes") is not None:
        values["notes"] = check_text("notes", values["notes"])
    doi = values.get("doi")
    if doi is not None:
        check_name("doi", doi, max_length=SOURCE_LENGTHS["doi"])
        if not _DOI.fullmatch(doi):
            raise ValidationError(
                "doi", repr(doi[:60]), "must look like 10.NNNN/suffix (the DOI itself, "
                "without https://doi.org/ or doi:)",
            )  # fmt: skip
    url = values.get("url")
    if url is not None:
        check_name("url", url, max_length=SOURCE_LENGTHS["url"])
        parts = urlsplit(url)
        if parts.scheme not in ("http", "https") or not parts.hostname or " " in url:
            raise ValidationError(
                "url", repr(url[:60]), "must be an http:// or https:// address with a host"
            )
    year = values.get("year")
    low, high = SOURCE_YEARS
    if year is not None and (
        isinstance(year, bool) or not isinstance(year, int) or not low <= year <= high
    ):
        raise ValidationError("year", repr(year), f"must be a whole year from {low} to {high}")


#: The columns of a pair's measured dry values (``granudb pairs list``): a source measured
#: them for this particle material on this wall material (either way round).
PAIR_VALUE_COLUMNS = [
    "particle",
    "wall",
    *stored_values("pair_values"),
    "source",
    "source_locator",
    "notes",
]

CATALOGUES = {c.kind: c for c in (MATERIALS, FLUIDS)}
MATERIAL_PROPERTIES = list(MATERIALS.properties)
FLUID_PROPERTIES = list(FLUIDS.properties)


def check_words(catalogue: Catalogue, values: dict[str, object]) -> None:
    """A text field with allowed words (``Catalogue.texts``) takes only those words."""
    for column, words in catalogue.texts.items():
        value = values.get(column)
        if words and value is not None and value not in words:
            raise ValidationError(column, value, f"must be one of {', '.join(words)}")


def check_entry(catalogue: Catalogue, values: dict[str, float | None]) -> None:
    """The rules between an entry's properties (each property's own range is
    ``granudb.vocabulary.rules``): a material's explicit shear modulus G may differ from
    E / (2(1 + ν)) (anisotropic or measured), but the Poisson ratio E, G imply,
    ν = E/(2G) − 1, must lie in (−1, 0.5)."""
    if catalogue.kind != "material":
        return
    shear, youngs = values.get("shear_modulus_pa"), values.get("youngs_modulus_pa")
    if shear is None or youngs is None:
        return
    implied = youngs / (2.0 * shear) - 1.0
    if not -1.0 < implied < 0.5:
        raise ValidationError(
            "shear_modulus_pa",
            shear,
            f"with youngs_modulus_pa {youngs:g} implies a Poisson ratio of {implied:.3g}, "
            "outside (−1, 0.5)",
        )
