"""Measured collisions as a DataFrame with every derived column, and the query that selects
them (by dataset, pair, fluid, Stokes number, angle and regime).

Shared by ``granudb collisions list``, the fits, the reports and the Python API
(``granudb.collisions()``), so a query means the same everywhere. A row the physics
cannot derive (say, a temperature outside its fluid's data) is kept, with its derived
columns empty and the reason in ``derivation_note``: one bad row never hides the others.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from granudb.db.catalog_rows import fluid_rows_by_id, pair_value_rows
from granudb.db.collision_queries import iter_collisions, reading, survey_collisions
from granudb.lazy import pandas as pd
from granudb.physics import uncertainty
from granudb.physics.derive import derive
from granudb.scenario import dry_values
from granudb.scenario.collision_query import CollisionQuery
from granudb.scenario.fluid_state import assumptions_per_row, fluid_states_per_row
from granudb.scenario.refusals import physics_refusal
from granudb.vocabulary import (
    COLLISION_MEASURED,
    COLLISION_TARGET,
    COLLISION_UNCERTAINTIES,
    DERIVED_TERMS,
    MATERIAL_PROPERTIES,
    UNCERTAINTY_TERMS,
)
from granudb.vocabulary.catalog import DRY_VALUE_PROPERTIES
from granudb.vocabulary.listings import COLLISION_WIDE, units_of

#: The material properties ``derive`` takes per body; the dry values go through the pair
#: rule (``granudb.scenario.dry_values.per_run``) first.
_MATERIAL = [
    c for c in MATERIAL_PROPERTIES if c not in ("correlation_length_m", *DRY_VALUE_PROPERTIES)
]


def select_collisions(
    session: Any,
    query: CollisionQuery,
    *,
    columns: Sequence[str] | None = None,
    shared_text: bool = False,
) -> Any:
    """The collisions matching ``query``, with every derived column (a DataFrame, SI,
    units in ``attrs["units"]``); with ``columns``, only those (in that order);
    ``shared_text``: see ``collision_table``.

    The query's conditions on derived values are applied chunk by chunk as the runs are
    read and derived, so neither the rows left out nor the columns not asked for are ever
    held for every run."""
    query.check()
    return collision_table(
        session,
        shared_text=shared_text,
        critical_stokes=query.critical_stokes,
        columns=columns,
        where=lambda frame: _matches(frame, query),
        **query.stored,
    )


def _matches(chunk: dict[str, np.ndarray], query: CollisionQuery) -> np.ndarray:
    """Which rows of ``chunk`` (every derived column, as arrays) satisfy the query's
    conditions (a missing value satisfies none, a missing flag counts as its opposite)."""
    keep = np.ones(len(chunk["normal_stokes_number"]), dtype=bool)
    st = chunk["normal_stokes_number"]
    with np.errstate(invalid="ignore"):
        if query.min_normal_stokes is not None:
            keep &= st >= query.min_normal_stokes
        if query.max_normal_stokes is not None:
            keep &= st <= query.max_normal_stokes
        if query.angle_range is not None:
            angle = chunk["incidence_angle_rad"]
            keep &= (angle >= query.angle_range[0]) & (angle <= query.angle_range[1])
    if query.regime is not None:
        keep &= np.asarray(chunk["tangential_regime"] == query.regime, dtype=bool)
    for flag in ("roughness_exceeds_gap", "rebound_expected"):
        wanted = getattr(query, flag)
        if wanted is not None:
            values = pd.Series(chunk[flag], copy=False)
            keep &= (values.fillna(not wanted).astype(bool) == wanted).to_numpy(dtype=bool)
    return keep


def collision_table(
    session: Any,
    *,
    critical_stokes: float = 10.0,
    columns: Sequence[str] | None = None,
    where: Callable[[dict[str, np.ndarray]], np.ndarray] | None = None,
    shared_text: bool = False,
    **filters: Any,
) -> Any:
    """Measured collisions with every derived column, as a pandas DataFrame (SI).

    ``filters``: dataset, version, particle, wall, fluid ("dry" for none). ``columns``:
    keep only these (in this order); ``where``: a function of a chunk's columns (a dict of
    arrays) giving the rows to keep. Both act on each chunk of runs as it is derived
    (``iter_collisions``), which bounds the memory of a million runs to the columns asked
    for. ``shared_text``: text columns stay object columns holding one string object per
    distinct value (the same cells; missing text is NaN where the column holds names, as
    pandas' string dtype shows it), instead of pandas' string dtype, which holds the text
    in Arrow buffers and makes a new Python string per cell each time a column is read
    as objects: a report reads its group columns that way several times.
    """
    session = reading(session)  # a Core connection: no ORM on a read of runs
    fluids = fluid_rows_by_id(session)
    measured = pair_value_rows(session)
    chunk_filters = {k: v for k, v in filters.items() if k != "chunk_rows"}
    count, present = survey_collisions(session, **chunk_filters)
    out = _Columns(count)
    stated = bool(present & set(COLLISION_UNCERTAINTIES))  # then every chunk has the u columns
    text = columns is None or bool({"run", "notes"} & set(columns))
    for stored in iter_collisions(session, text=text, measured=present, **filters):
        chunk = _derive_stored(stored, fluids, critical_stokes, measured, stated)
        del stored
        keep = where(chunk) if where is not None else None
        names = list(chunk) if columns is None else [c for c in columns if c in chunk]
        out.append({c: chunk[c] if c in _SHARED else _values(chunk[c]) for c in names}, keep)
        del chunk
    if out.names is None:
        empty = pd.DataFrame({c: [] for c in (COLLISION_WIDE if columns is None else columns)})
        empty.attrs["units"] = units_of(empty.columns)
        return empty
    arrays = out.arrays()
    if shared_text:
        arrays = {
            name: pd.Series(values, dtype=object, copy=False) if values.dtype == object else values
            for name, values in arrays.items()
        }
    table = pd.DataFrame(arrays, copy=False)
    table.attrs["units"] = units_of(table.columns)
    return table


class _Columns:
    """Column arrays allocated once for the counted runs and filled chunk by chunk.

    Why not collect the chunks and concatenate: the chunks' copies and the result would
    both be live at the end (twice the table), and the freed chunks leave the heap
    fragmented, so the process's peak memory would be twice the table it returns."""

    def __init__(self, capacity: int) -> None:
        self.capacity = capacity
        self.filled = 0
        self.names: list[str] | None = None
        self.data: dict[str, np.ndarray] = {}

    def append(self, chunk: dict[str, np.ndarray], keep: np.ndarray | None) -> None:
        if self.names is None:
            self.names = list(chunk)
        rows = len(next(iter(chunk.values()))) if keep is None else int(np.sum(keep))
        end = self.filled + rows
        for name in self.names:
            values = chunk[name] if keep is None else chunk[name][keep]
            column = self.data.get(name)
            if column is None:
                column = np.empty(max(self.capacity, end), dtype=values.dtype)
            dtype = np.result_type(column.dtype, values.dtype)
            if dtype != column.dtype:  # say a flag column that a later chunk leaves blank
                column = column.astype(dtype)
            if len(column) < end:  # runs added since they were counted
                column = np.concatenate([column, np.empty(end - len(column), column.dtype)])
            column[self.filled : end] = values
            self.data[name] = column
        self.filled = end

    def arrays(self) -> dict[str, np.ndarray]:
        return {name: self.data[name][: self.filled] for name in self.names or ()}


#: Text columns a chunk (``iter_collisions``) already holds as ``_values`` would make them:
#: names looked up per id (one string per distinct name) and the run labels (a string
#: per run, never missing: a dataset's labels are distinct, so factorizing shares none).
_SHARED = frozenset({"dataset", "particle", "wall", "run"})


def _values(column: Any) -> np.ndarray:
    """A chunk's column as numpy, a text column's equal values as one shared object each.

    pandas 3 keeps text in Arrow and ``to_numpy()`` makes a new Python string for every
    cell: a million runs' six name and verdict columns were about 300 MB held until the
    table was built (issue 17: memory bounded). Factorizing first makes one string per
    distinct value. The cells and the missing value are what pandas would give: for a
    column (a Series, or an object array as pandas would hold it) of text, NaN (the
    string dtype's); for one of other objects (flags a blank row leaves empty), None.
    """
    if column.dtype.kind in "biufcmM":
        return np.asarray(column)
    codes, distinct = pd.factorize(column, use_na_sentinel=True)
    if isinstance(column, np.ndarray):
        # every distinct value a str (in C: a run label column has a value per run)
        text = pd.api.types.infer_dtype(distinct, skipna=False) == "string"
        missing = np.nan if text else None
    else:
        missing = getattr(column.dtype, "na_value", None)
    lookup = np.array([*distinct, missing], dtype=object)  # code −1 (missing) → last
    return lookup[codes]


def _floats(frame: Any, name: str) -> np.ndarray:
    values = frame[name]
    if isinstance(values, np.ndarray) and values.dtype.kind == "f":
        return values
    return pd.to_numeric(values, errors="coerce").to_numpy(dtype=float)


def _derive_stored(
    stored: Any,
    fluids: dict[int, Any],
    critical_stokes: float,
    measured: list[Any],
    uncertain: bool = False,
) -> dict[str, np.ndarray]:
    """One chunk of stored runs (``iter_collisions``) with every derived column, as arrays
    in presentation order (no DataFrame per chunk: pandas would turn every text column into
    Arrow strings, to be turned back when the chunk is kept). ``uncertain``: some run read
    states an uncertainty, so every chunk carries the u columns (``_stated``)."""
    # dict[str, Any]: spread into derive's keywords, whose other parameters are not arrays
    c: dict[str, Any] = {name: _floats(stored, name) for name in COLLISION_MEASURED}
    fluid_ids = np.nan_to_num(_floats(stored, "fluid_id"), nan=-1).astype(int)
    viscosity, density, reason = fluid_states_per_row(fluids, fluid_ids, c["temperature_c"])
    props: dict[str, Any] = {
        f"{p}_{name}": _floats(stored, f"{p}_{name}")
        for p in ("particle", "wall")
        for name in _MATERIAL
    }
    barus = _per_fluid(fluids, fluid_ids, "pressure_viscosity_pa_inv")
    own = {
        f"{p}_{name}": _floats(stored, f"{p}_{name}")
        for p in ("particle", "wall")
        for name in DRY_VALUE_PROPERTIES
    }
    particles, walls = (np.asarray(stored[k], dtype=object) for k in ("particle", "wall"))
    dry_e, dry_mu, wet_mu = dry_values.per_run(particles, walls, own, measured)
    stated = _stated(c) if uncertain else None
    with physics_refusal():
        result = derive(
            **props,
            **{k: c[k] for k in ("diameter_m", "wall_diameter_m", "v_n_in_m_s", "v_t_in_m_s")},
            **{k: c[k] for k in ("v_n_out_m_s", "v_t_out_m_s")},
            **{k: c[k] for k in COLLISION_TARGET},
            omega_in_rad_s=np.nan_to_num(c["omega_in_rad_s"], nan=0.0),
            omega_out_rad_s=c["omega_out_rad_s"],
            fluid_density_kg_m3=density,
            viscosity_pa_s=viscosity,
            pressure_viscosity_pa_inv=barus,
            critical_stokes=critical_stokes,
            dry_restitution=dry_e,
            dry_friction=dry_mu,
            immersed_friction=wet_mu,
            uncertainties=stated,
            # a table read runs first order, its method naming where the check failed:
            # reading runs never pays for draws (granudb.derive and pair do)
            monte_carlo=False,
        )
    if stated is not None:
        # a run stating none of derive's input uncertainties has none propagated (not 0)
        none = np.all([np.isnan(u) for u in stated.values()], axis=0)
        for name in UNCERTAINTY_TERMS:
            result[name] = np.where(none, np.nan, result[name])
        result.update(_measured_uncertainties(c, result))
    chunk: dict[str, np.ndarray] = {
        **{k: np.asarray(stored[k], dtype=object) for k in ("dataset", "version")},
        **{k: np.asarray(stored[k], dtype=object) for k in ("run",) if k in stored},
        **{k: np.asarray(stored[k], dtype=object) for k in ("particle", "wall")},
        "fluid": _per_fluid(fluids, fluid_ids, "name"),
        **c,
        "viscosity_pa_s": viscosity,
        "particle_density_kg_m3": props["particle_density_kg_m3"],
        **{k: np.asarray(stored[k], dtype=object) for k in ("notes",) if k in stored},
    }
    for name, values in result.items():
        if name not in chunk:
            chunk[name] = np.asarray(values)
    assumed = assumptions_per_row(fluids, fluid_ids, c["temperature_c"])
    chunk["derivation_note"] = np.where(reason != None, reason, assumed)  # noqa: E711
    _blank_underivable(chunk, reason != None)  # noqa: E711 - elementwise on an object array
    return {
        **{n: chunk[n] for n in COLLISION_WIDE if n in chunk},
        **{n: values for n, values in chunk.items() if n not in COLLISION_WIDE},
    }


def _stated(c: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The chunk's stated uncertainties of derive's inputs (d, v_n,in, v_t,in)."""
    return {u: c[u] for u in ("u_diameter_m", "u_v_n_in_m_s", "u_v_t_in_m_s")}


def _measured_uncertainties(
    c: dict[str, np.ndarray], result: dict[str, np.ndarray]
) -> dict[str, np.ndarray]:
    """u(e), u(β), u(Ψ_in), u(Ψ_out) of each run from its stated speed, spin and diameter
    uncertainties (``granudb.physics.uncertainty``; a free target's speeds count as exact:
    their u is not stored)."""
    v_n = result["normal_speed_m_s"]
    radius, u_radius = c["diameter_m"] / 2.0, c["u_diameter_m"] / 2.0
    u_t_in = uncertainty.contact_speed_uncertainty(
        c["u_v_t_in_m_s"], c["omega_in_rad_s"], c["u_omega_in_rad_s"], radius, u_radius
    )
    u_t_out = uncertainty.contact_speed_uncertainty(
        c["u_v_t_out_m_s"], c["omega_out_rad_s"], c["u_omega_out_rad_s"], radius, u_radius
    )
    psi_in, psi_out = result["effective_incidence"], result["effective_rebound"]
    ratio = uncertainty.ratio_uncertainty
    u_n_in = c["u_v_n_in_m_s"]
    return {
        "u_normal_restitution": ratio(
            result["normal_restitution"], v_n, c["u_v_n_out_m_s"], u_n_in
        ),
        "u_rotational_restitution": ratio(
            result["rotational_restitution"], psi_in * v_n, u_t_out, u_t_in
        ),
        "u_effective_incidence": ratio(psi_in, v_n, u_t_in, u_n_in),
        "u_effective_rebound": ratio(psi_out, v_n, u_t_out, u_n_in),
    }


def _per_fluid(fluids: dict[int, Any], fluid_ids: np.ndarray, attribute: str) -> np.ndarray:
    """Each run's fluid ``attribute`` ("name": an object array, None for a dry run or an
    unknown id; else floats, NaN there)."""
    ids = np.array(sorted(fluids), dtype=np.int64)
    values = [getattr(fluids[i], attribute) for i in ids.tolist()]
    if attribute == "name":
        table = np.array([*values, None], dtype=object)
    else:
        table = np.array([*(np.nan if v is None else v for v in values), np.nan], dtype=float)
    at = np.searchsorted(ids, fluid_ids)
    found = at < len(ids)
    found[found] = ids[at[found]] == fluid_ids[found]
    return table[np.where(found, at, len(ids))]


def _blank_underivable(chunk: dict[str, np.ndarray], bad: np.ndarray) -> None:
    """Rows without a fluid state keep their measurements but no derived value (a wrong
    number is worse than none): None in object and flag columns, NaN in number columns."""
    if not bad.any():
        return
    for name in DERIVED_TERMS:
        if name in chunk:
            column = chunk[name]
            if column.dtype == object or column.dtype == bool:
                column = column.astype(object)
                column[bad] = None
            else:
                column = np.where(bad, np.nan, column)
            chunk[name] = column
