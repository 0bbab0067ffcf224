"""Level lines of a field sampled on a grid (marching squares), for the regime map's
σ = x₁/3, σ = x₁/4 and St_n = St_c lines.

Each grid cell whose corners straddle the level gets one segment (two at a saddle,
resolved by the cell's mean), with end points interpolated linearly along the cell's
edges; segments sharing an edge are joined into polylines, so a dashed line keeps its
pattern. Interpolation is in grid-index space and mapped to data through the axes'
values, piecewise linearly in log space on a log axis (the regime map's grids are
geometric, where this is exact).
"""

from __future__ import annotations

from typing import Any

import numpy as np

#: For each of the 16 corner cases (bit 0: corner (j, i), 1: (j, i+1), 2: (j+1, i+1),
#: 3: (j+1, i); set where the value is above the level): the pairs of edges joined.
#: Edges: 0 bottom (j, i→i+1), 1 right (i+1, j→j+1), 2 top (j+1, i→i+1), 3 left (i, j→j+1).
_CASES: dict[int, tuple[tuple[int, int], ...]] = {
    0: (), 15: (),
    1: ((3, 0),), 14: ((3, 0),),
    2: ((0, 1),), 13: ((0, 1),),
    3: ((3, 1),), 12: ((3, 1),),
    4: ((1, 2),), 11: ((1, 2),),
    6: ((0, 2),), 9: ((0, 2),),
    7: ((3, 2),), 8: ((3, 2),),
}  # fmt: skip


def _edge_key(j: int, i: int, edge: int) -> tuple[int, int, int]:
    """A cell edge named by its owner, so neighbouring cells share the key."""
    if edge == 0:
        return (j, i, 0)
    if edge == 2:
        return (j + 1, i, 0)
    if edge == 3:
        return (j, i, 1)
    return (j, i + 1, 1)


def _point(field: np.ndarray, key: tuple[int, int, int], level: float) -> tuple[float, float]:
    """Where the level crosses an edge, as fractional (row, column) indices."""
    j, i, vertical = key
    if vertical:
        a, b = field[j, i], field[j + 1, i]
        return j + (level - a) / (b - a), float(i)
    a, b = field[j, i], field[j, i + 1]
    return float(j), i + (level - a) / (b - a)


def _to_data(axis: np.ndarray, index: np.ndarray, log: bool) -> np.ndarray:
    positions = np.arange(len(axis), dtype=float)
    values = np.log10(axis) if log else np.asarray(axis, float)
    out = np.interp(index, positions, values)
    return 10**out if log else out


def level_lines(
    x: Any, y: Any, field: Any, level: float, *, log: bool = True
) -> list[tuple[np.ndarray, np.ndarray]]:
    """Polylines (x, y in data units) where ``field[j, i]`` (rows on ``y``, columns on
    ``x``) crosses ``level``; cells with a non-finite corner are skipped.

    >>> x = y = np.array([1.0, 2.0, 3.0])
    >>> [(a.tolist(), b.tolist()) for a, b in level_lines(x, y, np.add.outer(y, x), 3.5, log=False)]
    [([2.5, 2.0, 1.5, 1.0], [1.0, 1.5, 2.0, 2.5])]
    """
    field = np.asarray(field, dtype=float)
    above = field > level
    finite = np.isfinite(field)
    ok = finite[:-1, :-1] & finite[:-1, 1:] & finite[1:, 1:] & finite[1:, :-1]
    case = above[:-1, :-1] * 1 + above[:-1, 1:] * 2 + above[1:, 1:] * 4 + above[1:, :-1] * 8
    case = np.where(ok, case, 0)
    links: dict[tuple[int, int, int], list[tuple[int, int, int]]] = {}
    for j, i in zip(*np.nonzero((case != 0) & (case != 15)), strict=True):
        j, i, c = int(j), int(i), int(case[j, i])
        if c in (5, 10):  # saddle: the mean decides which corners connect
            centre_above = field[j : j + 2, i : i + 2].mean() > level
            pairs = ((3, 0), (1, 2)) if (c == 5) != centre_above else ((0, 1), (3, 2))
        else:
            pairs = _CASES[c]
        for a, b in pairs:
            ka, kb = _edge_key(j, i, a), _edge_key(j, i, b)
            links.setdefault(ka, []).append(kb)
            links.setdefault(kb, []).append(ka)
    lines = []
    seen: set[tuple[int, int, int]] = set()
    # Open lines start at an edge with one neighbour; what is left are closed loops.
    starts = [k for k, v in links.items() if len(v) == 1] + list(links)
    for start in starts:
        if start in seen:
            continue
        chain, current = [start], start
        seen.add(start)
        while True:
            following = [k for k in links[current] if k not in seen]
            if not following:
                break
            current = following[0]
            seen.add(current)
            chain.append(current)
        if len(chain) < 2:
            continue
        if len(links[start]) == 2 and start in links[chain[-1]]:
            chain.append(start)  # a closed loop
        rows, cols = zip(*(_point(field, key, level) for key in chain), strict=True)
        lines.append((_to_data(np.asarray(x), np.array(cols), log),
                      _to_data(np.asarray(y), np.array(rows), log)))  # fmt: skip
    return lines
