"""The rows of each group of a table of runs, found from the group's key columns alone.

A group is a distinct combination of key values (dataset × particle × wall × fluid, or
a part of them). The fits (``granudb.analysis.groups``) and the catalogue's shares of a
group's runs (``granudb.scenario.plug_ins``) both start from it.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from granudb.lazy import pandas as pd


def group_rows(frame: Any, keys: list[str]) -> dict[tuple, np.ndarray]:
    """{key tuple: the rows (positions, ascending) of that group}, in no set order, the
    groups of ``keys`` with a missing value (None or NaN) a key part of None; as
    ``frame[keys].groupby(keys, dropna=False).indices`` with missing values made None.

    Why: pandas' groupby of object columns with ``dropna=False`` checks every cell for a
    missing value once per column and copies the key columns; here each key column is
    factorized once (missing values one code) and the rows split by one stable sort."""
    combined = np.zeros(len(frame), dtype=np.int64)
    parts = []
    for name in keys:
        codes, uniques = pd.factorize(np.asarray(frame[name], dtype=object))
        parts.append([None, *uniques])  # code −1 (missing) → None
        combined = combined * (len(uniques) + 1) + (codes + 1)
    if len(combined) and combined.max() < 2**16:  # numpy's stable sort is then a radix sort
        combined = combined.astype(np.uint16)
    order = np.argsort(combined, kind="stable")
    ordered = combined[order]
    found: dict[tuple, np.ndarray] = {}
    if not len(order):
        return found
    starts = np.flatnonzero(np.r_[True, ordered[1:] != ordered[:-1]])
    ends = [*starts[1:], len(order)]
    for start, end in zip(starts, ends, strict=True):
        code, key = int(ordered[start]), []
        for values in reversed(parts):
            code, digit = divmod(code, len(values))
            key.append(values[digit])
        found[tuple(reversed(key))] = order[start:end]
    return found
