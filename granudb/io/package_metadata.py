"""Who made a dataset and how to cite it, for the tools that read an exported package:
``CITATION.cff`` (checked by ``cffconvert --validate``), ``.zenodo.json`` (Zenodo deposit
metadata) and the Data Package's ``contributors``, ``licenses`` and ``keywords``.

Authors are people (family and given names, ORCID) or, when none are known, an entity.
They come from the dataset's ``authors`` (JSON list of ``given_names``, ``family_names``,
``orcid``, ``affiliation``) when the schema has that column; otherwise from the source
paper's citation ("Family, G. & Other, H. (2004). Title. …"), parsed into people. The
paper itself is cited under ``references`` (CFF) and ``related_identifiers`` (Zenodo),
never as the dataset: the dataset's own DOI is given only when it has one.
"""

from __future__ import annotations

import json
import re
from typing import Any

#: SPDX identifiers CFF accepts that datasets commonly use; another license is named in
#: the README and the Data Package but left out of CITATION.cff (CFF allows SPDX only).
SPDX = {
    "CC-BY-4.0", "CC-BY-SA-4.0", "CC-BY-NC-4.0", "CC-BY-NC-SA-4.0", "CC-BY-ND-4.0",
    "CC-BY-3.0", "CC0-1.0", "ODbL-1.0", "ODC-By-1.0", "PDDL-1.0", "MIT", "Apache-2.0",
    "BSD-3-Clause", "GPL-3.0-or-later", "GPL-3.0-only", "LGPL-3.0-or-later", "MPL-2.0",
}  # fmt: skip
ARTICLE_KINDS = {"publication", "journal-article", "article", "paper"}
BASE_KEYWORDS = ["granudb", "particle-wall collisions", "restitution", "friction"]
_CITATION = re.compile(r"^(?P<authors>.+?)\s*\((?P<year>\d{4})[a-z]?\)\.?\s*(?P<title>[^.]+)")
_ORCID = re.compile(r"^(https://orcid\.org/)?(\d{4}-\d{4}-\d{4}-\d{3}[\dX])$")


def _person(family: str, given: str, orcid: str | None = None, affiliation: str = "") -> dict:
    person: dict[str, str] = {"family-names": family.strip()}
    if given.strip():
        person["given-names"] = given.strip()
    match = _ORCID.match((orcid or "").strip())
    if match:
        person["orcid"] = f"https://orcid.org/{match.group(2)}"
    if affiliation.strip():
        person["affiliation"] = affiliation.strip()
    return person


def parse_citation(citation: str) -> tuple[list[dict[str, str]], str | None, int | None]:
    """(authors as people, title, year) of "Family, G. & Other, H. (2004). Title. …";
    ([], None, None) when the citation does not read that way."""
    match = _CITATION.match(citation or "")
    if not match:
        return [], None, None
    people = []
    for part in re.split(r"\s*(?:&|\band\b|;)\s*", match.group("authors")):
        family, _, given = part.partition(",")
        if family.strip():
            people.append(_person(family, given))
    return people, match.group("title").strip() or None, int(match.group("year"))


def authors(dataset: dict[str, Any]) -> list[dict[str, str]]:
    """CFF authors of the dataset: its own people, else the source's, else an entity."""
    people = [
        _person(
            str(a.get("family_names") or ""),
            str(a.get("given_names") or ""),
            a.get("orcid"),
            str(a.get("affiliation") or ""),
        )
        for a in dataset["authors"]
        if isinstance(a, dict) and str(a.get("family_names") or "").strip()
    ]
    if not people and dataset["source"]:
        people = parse_citation(dataset["source"]["citation"])[0]
    return people or [{"name": f"Authors of granudb dataset {dataset['name']} (not recorded)"}]


def keywords(dataset: dict[str, Any]) -> list[str]:
    """The dataset's keywords, then granudb's, without repeats or empty strings."""
    found = [str(k).strip() for k in dataset["keywords"] if str(k).strip()] + BASE_KEYWORDS
    return list(dict.fromkeys(found))


def _yaml(value: Any, indent: int = 0) -> list[str]:
    """YAML lines for plain dicts, lists and strings (strings as JSON, valid YAML)."""
    pad = " " * indent
    lines: list[str] = []
    for key, item in value.items():
        if isinstance(item, list):
            lines.append(f"{pad}{key}:")
            for element in item:
                if isinstance(element, dict):
                    inner = _yaml(element, indent + 4)
                    lines.append(f"{pad}  - {inner[0].lstrip()}")
                    lines.extend(inner[1:])
                else:
                    lines.append(f"{pad}  - {json.dumps(element, ensure_ascii=False)}")
        elif isinstance(item, dict):
            lines.append(f"{pad}{key}:")
            lines.extend(_yaml(item, indent + 2))
        else:
            lines.append(f"{pad}{key}: {json.dumps(item, ensure_ascii=False)}")
    return lines


def _reference(source: dict[str, Any]) -> dict[str, Any]:
    people, title, year = parse_citation(source["citation"])
    reference: dict[str, Any] = {
        "type": "article" if source.get("kind") in ARTICLE_KINDS else "generic",
        "title": title or source["citation"],
        "authors": people or [{"name": source["citation"][:200]}],
    }
    stated_year = source.get("year") or year
    if stated_year:
        reference["year"] = int(stated_year)
    if source.get("doi"):
        reference["doi"] = source["doi"]
    elif source.get("url"):
        reference["url"] = source["url"]
    return reference


def citation_cff(dataset: dict[str, Any], content_hash: str, created: str) -> str:
    """``CITATION.cff`` (CFF 1.2.0) for the dataset."""
    cff: dict[str, Any] = {
        "cff-version": "1.2.0",
        "message": "If you use this dataset, please cite it as below.",
        "type": "dataset",
        "title": dataset["title"] or dataset["name"],
        "version": dataset["version"],
        "date-released": created[:10],
        "authors": authors(dataset),
    }
    if dataset["description"] and dataset["description"].strip():
        cff["abstract"] = dataset["description"]
    if dataset["license"] in SPDX:
        cff["license"] = dataset["license"]
    if dataset["doi"]:
        cff["doi"] = dataset["doi"]
    cff["keywords"] = keywords(dataset)
    cff["identifiers"] = [
        {
            "type": "other",
            "value": f"sha256:{content_hash}",
            "description": "granudb content hash of the collisions",
        }
    ]
    if dataset["source"]:
        cff["references"] = [_reference(dataset["source"])]
    return "\n".join(_yaml(cff)) + "\n"


def _creator(author: dict[str, str]) -> dict[str, str]:
    if "name" in author:
        return {"name": author["name"]}
    creator = {"name": f"{author['family-names']}, {author.get('given-names', '')}".strip(", ")}
    if "orcid" in author:
        creator["orcid"] = author["orcid"].removeprefix("https://orcid.org/")
    if "affiliation" in author:
        creator["affiliation"] = author["affiliation"]
    return creator


def zenodo_json(dataset: dict[str, Any], content_hash: str, created: str) -> str:
    """``.zenodo.json``: the deposit metadata Zenodo reads from an uploaded release."""
    description = dataset["description"] or f"granudb dataset {dataset['name']}."
    deposit: dict[str, Any] = {
        "upload_type": "dataset",
        "title": dataset["title"] or dataset["name"],
        "creators": [_creator(a) for a in authors(dataset)],
        "description": f"{description}\n\nContent hash (granudb): sha256:{content_hash}",
        "version": dataset["version"],
        "publication_date": created[:10],
        "keywords": keywords(dataset),
    }
    if dataset["license"]:
        deposit["license"] = (
            dataset["license"].lower() if dataset["license"] in SPDX else (dataset["license"])
        )
    if dataset["doi"]:
        deposit["doi"] = dataset["doi"]
    source = dataset["source"]
    if source and source.get("doi"):
        deposit["related_identifiers"] = [
            {"identifier": source["doi"], "relation": "isDerivedFrom", "scheme": "doi"}
        ]
    return json.dumps(deposit, indent=2, ensure_ascii=False) + "\n"


def contributors(dataset: dict[str, Any]) -> list[dict[str, Any]]:
    """Data Package ``contributors``: the dataset's authors, with their roles."""
    found = []
    for author in authors(dataset):
        if "name" in author:
            found.append({"title": author["name"], "roles": ["creator"]})
            continue
        entry: dict[str, Any] = {
            "title": f"{author.get('given-names', '')} {author['family-names']}".strip(),
            "familyName": author["family-names"],
            "roles": ["creator"],
        }
        if "given-names" in author:
            entry["givenName"] = author["given-names"]
        if "orcid" in author:
            entry["path"] = author["orcid"]
        if "affiliation" in author:
            entry["organization"] = author["affiliation"]
        found.append(entry)
    return found
