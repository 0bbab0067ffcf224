"""The runs of each group (dataset × particle × wall × fluid), as the fits read them.

Every fit works per group; this module finds the groups from their key columns, copies only
the columns a fit reads, and gives a Walton fit its runs as folded, sorted arrays.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from granudb.analysis import walton as core
from granudb.lazy import pandas as pd
from granudb.scenario.row_groups import group_rows

#: The columns that name a group; a fit's row starts with them.
GROUP = ["dataset", "particle", "wall", "fluid"]
#: Walton's B = 1 + 1/K² for a solid sphere on a wall, K² = 2/5 (docs/physics.md §9).
SPHERE_ON_WALL_FACTOR = 3.5

#: The columns a Walton fit reads (the group's, then its runs').
WALTON_INPUTS = [*GROUP, "effective_incidence", "effective_rebound", "normal_restitution",
                 "tangential_speed_m_s", "walton_factor"]  # fmt: skip


def narrow(frame: Any, names: list[str]) -> Any:
    """``frame`` with only those of ``names`` it has."""
    return frame[[name for name in names if name in frame]]


def group_frames(
    frame: Any, keys: list[str], columns: list[str] | None = None, *, fill: dict | None = None
) -> Any:
    """(key, rows) per group of ``keys`` in sorted key order, rows in frame order; a row
    with a missing key is in no group (``fill``: {key: value} for a key whose missing value
    is a group of its own, as "dry" for the fluid). ``rows`` holds only ``columns`` (those
    the frame has; default all).

    Why this way: iterating a groupby first copies the whole frame sorted by group, and
    taking each group's rows of every column copies the group keys too; here the groups are
    found from the key columns alone (no copy of the frame), and each group copies only
    the columns its fit reads, one group at a time (a third of a million runs, not all)."""
    fill = fill or {}
    indices: dict[tuple, Any] = {}
    for found, rows in group_rows(frame, keys).items():
        key = tuple(fill.get(k) if v is None else v for k, v in zip(keys, found, strict=True))
        if any(v is None for v in key):
            continue
        if key in indices:  # a filled missing value and the fill value itself: one group
            rows = np.sort(np.concatenate([indices[key], rows]))
        indices[key] = rows
    names = list(frame.columns) if columns is None else [c for c in columns if c in frame]
    for key in sorted(indices):
        at = indices[key]
        yield key, pd.DataFrame({name: frame[name].take(at) for name in names}, copy=False)


def walton_arrays(
    group: Any,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, int, np.ndarray, np.ndarray]:
    """Folded, Ψ_in-sorted (x, y, c = (1+e)B, e, n_folded, order) of one group's finite runs;
    ``order`` indexes the group's rows."""
    psi_in = group["effective_incidence"].to_numpy(dtype=float)
    psi_out = group["effective_rebound"].to_numpy(dtype=float)
    e = group["normal_restitution"].to_numpy(dtype=float)
    v_t = (
        group["tangential_speed_m_s"].to_numpy(dtype=float)
        if "tangential_speed_m_s" in group
        else psi_in
    )
    factor = (
        group["walton_factor"].to_numpy(dtype=float)
        if "walton_factor" in group
        else np.full(len(group), SPHERE_ON_WALL_FACTOR)
    )
    factor = np.where(np.isfinite(factor), factor, SPHERE_ON_WALL_FACTOR)
    finite = np.isfinite(psi_in) & np.isfinite(psi_out) & np.isfinite(e)
    x, y = core.fold(psi_in, psi_out, v_t)
    rows = np.flatnonzero(finite)
    order = rows[np.argsort(x[rows], kind="stable")]
    folded = int(np.sum((v_t < 0) & finite))
    return x[order], y[order], (1 + e[order]) * factor[order], e[order], folded, order, factor
