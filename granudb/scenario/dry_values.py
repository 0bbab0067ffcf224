"""The one rule for a pair's dry restitution and friction, and where each came from
(docs/physics.md §18).

For a particle material hitting a wall (or second sphere) material, each of e_dry and
μ_dry is taken, in this order, from:

1. **the pair table** (``pair_values``): a source measured it for this pair, either way
   round (steel on Zerodur, Joseph & Hunt 2004 §3);
2. **the two materials' own values**: e_dry the lower of the two (the more dissipative
   body bounds the pair's rebound), μ_dry the geometric mean √(μ₁μ₂) (symmetric, and
   equal to both when they agree). No source gives a rule for combining them: these are
   granudb's, and the output says so. Where only one material has a value, it is used and
   the output names the material whose value is missing;
3. **borrowed**: Joseph & Hunt's steel on Zerodur, ē_dry = 0.97 and μ_f = 0.11 (§3),
   labelled "borrowed" in every output.

``predicted_restitution`` (``pair``, reports, ``derive`` of stored runs), the verdicts and
the DEM export all take the values and their sources from ``dry_values``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass
from types import SimpleNamespace
from typing import Any

import numpy as np
from sqlalchemy.engine import Connection

from granudb.db import catalog_rows
from granudb.db.catalog_rows import MaterialRow
from granudb.lazy import pandas as pd
from granudb.physics.derive import DRY_FRICTION, DRY_RESTITUTION

#: A material as ``resolve`` reads it: a Core row, or the stand-in ``per_run`` builds from
#: a run's own columns (name, dry_restitution, dry_friction, dry_provenance).
Material = MaterialRow | SimpleNamespace

#: What a value borrowed from the global default says.
BORROWED = "borrowed: steel on Zerodur, Joseph & Hunt 2004 §3"
#: The bases, in the order they are tried.
BASES = ("pair", "materials", "borrowed")


@dataclass(frozen=True)
class DryValues:
    """A pair's dry restitution and friction, each with its basis ("pair",
    "materials", "borrowed") and its source in words; and the friction used where
    asperities touch in a liquid (the pair's measured value, else the dry one)."""

    restitution: float
    restitution_basis: str
    restitution_source: str
    friction: float
    friction_basis: str
    friction_source: str
    #: Where asperities touch in a liquid: the pair's measured value, else the dry one.
    immersed_friction: float
    immersed_friction_basis: str
    immersed_friction_source: str
    #: The database's source keys each value cites ("; "-joined, None: none), so a
    #: report lists every one of them among its references.
    restitution_source_keys: str | None = None
    friction_source_keys: str | None = None
    immersed_friction_source_keys: str | None = None

    def record(self) -> dict[str, Any]:
        """The values as JSON/CSV fields (``dry_restitution``, ``dry_restitution_basis``,
        ``dry_restitution_source``, ``dry_restitution_source_keys``, the same for
        ``dry_friction`` and ``immersed_friction``)."""
        return {
            key if key.startswith("immersed") else f"dry_{key}": value
            for key, value in asdict(self).items()
        }

    def keys(self) -> set[str]:
        """Every source key the three values cite."""
        joined = (self.restitution_source_keys, self.friction_source_keys,
                  self.immersed_friction_source_keys)  # fmt: skip
        return {key for text in joined if text for key in text.split("; ")}


def material_dry_source(material: Any) -> str:
    """Where a material's own dry e and μ come from, in the words ``materials show``
    gives (its ``dry_provenance``, set by ``--dry-source``), or "not stated". A record
    (dict) or a row."""
    text = material.get("dry_provenance") if isinstance(material, dict) else (
        getattr(material, "dry_provenance", None))  # fmt: skip
    return text if text else "not stated"


def provenance_keys(text: str | None, sources: Mapping[str, Any] | None) -> tuple[str, ...]:
    """The stored sources a free-text provenance names: a source's key written in it, or
    its first author's surname with its year ("Nijssen, Ottens & Padding 2022" names
    ``nijssen-ottens-padding-2022``, whose citation begins "Nijssen, T. M. J., … (2022)").

    >>> from types import SimpleNamespace as S
    >>> row = S(citation="Nijssen, T. M. J., Ottens, M. & Padding, J. T. (2022). Script", year=2022)
    >>> provenance_keys("Nijssen, Ottens & Padding 2022, model code", {"nijssen-2022": row})
    ('nijssen-2022',)
    >>> provenance_keys("lab note 12", {"nijssen-2022": row})
    ()
    """
    if not text or not sources:
        return ()
    found = []
    for key, row in sorted(sources.items()):
        citation = row if isinstance(row, str) else row.citation
        surname = citation.split(",")[0].strip()
        year = None if isinstance(row, str) else row.year
        if key in text or (
            year is not None and len(surname) > 1 and surname in text and str(year) in text
        ):
            found.append(key)
    return tuple(found)


def _joined(keys: Any) -> str | None:
    keys = sorted({k for k in keys if k})
    return "; ".join(keys) if keys else None


#: The borrowed values, for a caller without a pair (``verdicts`` of an old document).
#: The source key of the borrowed values.
BORROWED_KEY = "joseph-hunt-2004"
BORROWED_VALUES = DryValues(
    DRY_RESTITUTION, "borrowed", BORROWED, DRY_FRICTION, "borrowed", BORROWED,
    DRY_FRICTION, "borrowed", BORROWED, BORROWED_KEY, BORROWED_KEY, BORROWED_KEY,
)  # fmt: skip
#: What the immersed friction says when the pair has no measured value of its own.
NO_IMMERSED = "the dry value (no immersed value measured for the pair): "


def _cited(row: catalog_rows.PairValueRow, where_measured: str = "") -> str:
    """ "measured for steel on Zerodur (joseph-hunt-2004, §3, figure 4)": the source's key
    (``granudb sources show`` gives the citation) and where in it; without a source, the
    notes."""
    key = catalog_rows.source_key(row.source)
    pair = f"measured for {row.particle} on {row.wall}" + (
        f" {where_measured}" if where_measured else ""
    )
    if key is None:
        return f"{pair} ({row.notes or 'no source given'})"
    where = f", {row.source_locator}" if row.source_locator else ""
    return f"{pair} ({key}{where})"


def _own(material: Material, column: str) -> float | None:
    value = getattr(material, column)
    return None if value is None or not math.isfinite(value) else float(value)


def _from_materials(
    first: Material, second: Material, column: str
) -> tuple[float, str, list[Material]] | None:
    """The combination rule (module doc) for ``column`` of the two materials, or None;
    with the materials whose value it uses."""
    bodies = (first,) if first.name == second.name else (first, second)
    known = [(m, v) for m in bodies if (v := _own(m, column)) is not None]
    if not known:
        return None
    where = "; ".join(f"{m.name}: {material_dry_source(m)}" for m, _ in known)
    used = [m for m, _ in known]
    if len(known) == 1:
        material, value = known[0]
        missing = [m.name for m in bodies if _own(m, column) is None]
        note = f" ({missing[0]}'s not known)" if missing else ""
        return value, f"{material.name}'s own value{note} [{where}]", used
    (a, x), (b, y) = known
    if column == "dry_restitution":
        words = f"the lower of {a.name}'s and {b.name}'s (granudb's rule) [{where}]"
        return min(x, y), words, used
    words = f"√(μ₁μ₂) of {a.name}'s and {b.name}'s (granudb's rule) [{where}]"
    return math.sqrt(x * y), words, used


def resolve(
    first: Material,
    second: Material,
    measured: list[catalog_rows.PairValueRow],
    sources: Mapping[str, Any] | None = None,
) -> DryValues:
    """The rule of the module doc, for two material rows and the pair's measured rows;
    ``sources`` (key → stored source) name the keys a material's provenance cites."""
    chosen: dict[str, tuple[float, str, str]] = {}
    keys: dict[str, str | None] = {}
    for column, default in (("dry_restitution", DRY_RESTITUTION), ("dry_friction", DRY_FRICTION)):
        pair = next((r for r in measured if getattr(r, column) is not None), None)
        if pair is not None:
            chosen[column] = (float(getattr(pair, column)), "pair", _cited(pair))
            keys[column] = _joined([catalog_rows.source_key(pair.source)])
        elif (combined := _from_materials(first, second, column)) is not None:
            chosen[column] = (combined[0], "materials", combined[1])
            keys[column] = _joined(
                k for m in combined[2] for k in provenance_keys(m.dry_provenance, sources)
            )
        else:
            chosen[column] = (default, "borrowed", BORROWED)
            keys[column] = BORROWED_KEY
    e, mu = chosen["dry_restitution"], chosen["dry_friction"]
    wet = next((r for r in measured if r.immersed_friction is not None), None)
    if wet is not None and wet.immersed_friction is not None:
        immersed = (float(wet.immersed_friction), "pair", _cited(wet, "in a liquid"))
        wet_keys = _joined([catalog_rows.source_key(wet.source)])
    else:
        immersed = (mu[0], mu[1], NO_IMMERSED + mu[2])
        wet_keys = keys["dry_friction"]
    return DryValues(*e, *mu, *immersed, keys["dry_restitution"], keys["dry_friction"], wet_keys)


def dry_values(
    connection: Connection,
    particle: str,
    wall: str,
    dataset_id: int | None = None,
) -> DryValues:
    """The dry e and μ of ``particle`` on ``wall`` with where each came from; with
    ``dataset_id`` as that dataset's runs use the materials (a release reads the values
    it was released with, and only the pair values stored before its release)."""
    first = catalog_rows.get_material_row(connection, particle, dataset_id)
    second = catalog_rows.get_material_row(connection, wall, dataset_id)
    before = catalog_rows.released_at(connection, dataset_id)
    measured = catalog_rows.pair_value_rows(connection, particle, wall, before=before)
    return resolve(first, second, measured, catalog_rows.sources_as_of(connection, before))


def per_run(
    particle: np.ndarray,
    wall: np.ndarray,
    own: dict[str, np.ndarray],
    measured: list[catalog_rows.PairValueRow],
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The same rule for stored runs: each run's dry e, μ and immersed μ (NaN: the dry
    one) from the material names,
    the two materials' own values as the runs use them (``own``:
    ``particle_dry_restitution``, ``wall_dry_friction``, …; NaN where not known) and the
    measured pair values. One resolution per distinct pair and values."""
    arrays = [particle, wall, *(own[c] for c in _OWN)]
    first, inverse = _distinct_rows(arrays)
    by_pair = {frozenset((row.particle.casefold(), row.wall.casefold())): row for row in measured}
    found = []
    for index in first.tolist():
        p_name, w_name, p_e, w_e, p_mu, w_mu = (
            None if _missing(a[index]) else a[index].item() if isinstance(a[index], np.generic)
            else a[index] for a in arrays
        )  # fmt: skip
        if not isinstance(p_name, str) or not isinstance(w_name, str):
            found.append(BORROWED_VALUES)
            continue
        first_m = SimpleNamespace(name=p_name, dry_restitution=p_e, dry_friction=p_mu,
                                  dry_provenance=None)  # fmt: skip
        second = SimpleNamespace(name=w_name, dry_restitution=w_e, dry_friction=w_mu,
                                 dry_provenance=None)  # fmt: skip
        pair = by_pair.get(frozenset((p_name.casefold(), w_name.casefold())))
        found.append(resolve(first_m, second, [pair] if pair is not None else []))
    e = np.array([v.restitution for v in found], dtype=float)[inverse]
    mu = np.array([v.friction for v in found], dtype=float)[inverse]
    wet = np.array(
        [v.immersed_friction if v.immersed_friction_basis == "pair" else np.nan for v in found],
        dtype=float,
    )[inverse]
    return e, mu, wet


def _missing(value: Any) -> bool:
    return value is None or (isinstance(value, float | np.floating) and value != value)


def _distinct_rows(arrays: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """(the first run of each distinct row of ``arrays``' columns, each run's distinct
    row): hashed column by column (``pd.factorize``, NaN and None a value of their own),
    the combined code kept below the number of runs so it cannot overflow."""
    combined = np.zeros(len(arrays[0]), dtype=np.int64)
    for values in arrays:
        codes, uniques = pd.factorize(values, use_na_sentinel=False)
        combined, _ = pd.factorize(combined * len(uniques) + codes)
    return np.unique(combined, return_index=True)[1], combined


#: The materials' own dry values a stored run carries, in ``per_run``'s key order.
_OWN = ("particle_dry_restitution", "wall_dry_restitution",
        "particle_dry_friction", "wall_dry_friction")  # fmt: skip
