"""One label and one colour per group of runs, shared by every figure and table of a
report.

A group is particle/wall in a fluid; a dry run's fluid is missing in the database (None,
or NaN once pandas has had it), and it is called "dry" everywhere — never "nan". Colours
are assigned once per report from the sorted labels, so the same group has the same
colour in the Walton plot, the β and μ_f plots, the restitution plot and the tables.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

from granudb.lazy import numpy as np
from granudb.lazy import pandas as pd

#: Colour-blind-safe palette (Okabe & Ito), then a few more distinct hues.
PALETTE = [
    "#0072b2",
    "#d55e00",
    "#009e73",
    "#cc79a7",
    "#e69f00",
    "#56b4e9",
    "#000000",
    "#8c564b",
    "#7f7f7f",
    "#bcbd22",
]
DRY = "dry"


def fluid_name(fluid: Any) -> str:
    """The fluid as people read it: its name, or "dry" for a missing fluid."""
    if fluid is None or (isinstance(fluid, float) and math.isnan(fluid)):
        return DRY
    text = str(fluid)
    return DRY if text.lower() in {"", "nan", "none", DRY} else text


def is_dry(fluid: Any) -> bool:
    return fluid_name(fluid) == DRY


def group_label(particle: Any, wall: Any, fluid: Any) -> str:
    """``steel/Zerodur glycerol-37``; ``steel/Zerodur dry`` for a dry group."""
    return f"{particle}/{wall} {fluid_name(fluid)}"


def per_value(values: Any, function: Any) -> Any:
    """``function`` of each element of ``values`` (an object array), called once per
    distinct value: 100,000 runs have a handful of fluids and pairs."""
    codes, uniques = pd.factorize(np.asarray(values, dtype=object), use_na_sentinel=False)
    return np.array([function(u) for u in uniques] + [None], dtype=object)[codes]


def fluid_names(fluids: Any) -> Any:
    """``fluid_name`` of every element (an object array)."""
    return per_value(fluids, fluid_name)


def group_keys(*columns: Any) -> Any:
    """Each row's tuple of ``columns`` values (an object array of tuples), built once per
    distinct combination."""
    codes, keys = key_codes(columns)
    return keys[codes]


def key_codes(columns: Any) -> tuple[Any, Any]:
    """(each row's code, the distinct combinations of ``columns`` values as an object array
    of tuples, indexed by code): one factorize per column, then one of the combined codes
    (integers, not tuples)."""
    factors = [pd.factorize(np.asarray(c, dtype=object), use_na_sentinel=False) for c in columns]
    combined = np.zeros(len(factors[0][0]) if factors else 0, dtype=np.int64)
    for codes, uniques in factors:  # mixed radix: a handful of distinct values per column
        combined = combined * max(len(uniques), 1) + codes
    inverse, distinct = pd.factorize(combined)
    keys = np.empty(len(distinct), dtype=object)
    for i, code in enumerate(distinct.tolist()):
        key = []
        for _, uniques in reversed(factors):
            code, digit = divmod(code, max(len(uniques), 1))
            key.append(uniques[digit])
        keys[i] = tuple(reversed(key))
    return inverse, keys


def labels_of(frame: Any, fluids: Any = None) -> list[str]:
    """The group label of every row of a collisions DataFrame (one string per group);
    ``fluids``: its ``fluid_names``, where the caller has them."""
    fluids = fluid_names(frame["fluid"]) if fluids is None else fluids
    codes, keys = key_codes([frame["particle"], frame["wall"], fluids])
    labels = np.array([group_label(*key) for key in keys], dtype=object)
    return labels[codes].tolist()


def colours(labels: Iterable[str]) -> dict[str, str]:
    """A colour per distinct label, in sorted order (so two reports of the same groups
    agree)."""
    return {label: PALETTE[i % len(PALETTE)] for i, label in enumerate(sorted(set(labels)))}


def sorted_codes(values: Any) -> tuple[Any, list[Any]]:
    """(codes, names): each element's index in the sorted distinct ``names``.

    Why: hashing (``pandas.factorize``) then sorting the few distinct values is linear in
    the runs, where ``numpy.unique`` sorts a million strings. A report passes the same
    labels to every figure: the last few answers are kept by the identity of ``values``
    (a tuple or list a report never changes once made; the codes are a read-only copy)."""
    for seen, found in _SORTED:
        if seen is values:
            return found[0], list(found[1])
    codes, uniques = pd.factorize(np.asarray(values, dtype=object), use_na_sentinel=False)
    order = sorted(range(len(uniques)), key=lambda i: uniques[i])
    rank = np.empty(len(order), dtype=np.intp)
    rank[order] = np.arange(len(order))
    found = (rank[codes], [uniques[i] for i in order])
    found[0].flags.writeable = False
    if isinstance(values, list | tuple):
        _SORTED[:] = [(values, found), *_SORTED[: _SORTED_KEPT - 1]]
    return found[0], list(found[1])


#: ``sorted_codes``' last answers, (values, (codes, names)), newest first.
_SORTED: list[tuple[Any, tuple[Any, list[Any]]]] = []
_SORTED_KEPT = 4
