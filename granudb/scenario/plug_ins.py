"""The catalogue's share of each restitution fit's St_n: the plug-in error its runs share.

A group's runs (one dataset, particle and wall) get St_n from the catalogue's values —
the particle's density, the fluid's viscosity at the run's temperature, the target's
for a sphere — and the run's diameter. Where the catalogue states their uncertainty (or
the runs state u(d)), that error is one for every run in a fluid: the fit must carry it
(``granudb.analysis.shared_scale``). Its relative size is what ``granudb.pair``
propagates for the group's typical run (median diameter and temperature of each fluid's
runs; St_n ∝ v_N, so the speed does not change it), with no u on the speed: the one
record of how a u reaches St_n. A group in several fluids gets the root mean square
over its runs (each fluid's share weighted by its runs: the particle's share is common
to all, the fluids' are not, and taking them as one error is the cautious side).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from granudb.errors import ValidationError
from granudb.scenario.pair import derive_pair

#: The group of a restitution fit (``granudb.analysis.restitution_fit``).
GROUP = ("dataset", "particle", "wall")
#: The columns of the runs ``stokes_scale`` reads (a report reads only the columns it needs).
COLUMNS = (*GROUP, "fluid", "normal_stokes_number", "diameter_m", "u_diameter_m",
           "temperature_c", "wall_diameter_m", "wall_v_n_in_m_s")  # fmt: skip
#: What the share is made of, as the fit's method says it.
SOURCES = "ρ and d of the particle, μ(T) of the fluid, the target's for a sphere, as stored"


def stokes_scale(reader: Any, frame: Any) -> dict[tuple, tuple[float, str]]:
    """{(dataset, particle, wall): (u_r, sources)} of the groups whose immersed runs' St_n
    has a stated catalogue share u_r > 0 (the module docstring's rule); the others are
    left out. ``frame``: collisions as ``select_collisions`` gives them."""
    needed = {*GROUP, "fluid", "normal_stokes_number", "diameter_m"}
    if frame.empty or not needed <= set(frame.columns):
        return {}
    immersed = frame[frame["fluid"].notna() & np.isfinite(frame["normal_stokes_number"])]
    shares: dict[tuple, tuple[float, str]] = {}
    for key, group in immersed.groupby(list(GROUP), sort=True):
        total = count = 0.0
        for fluid, runs in group.groupby("fluid", sort=True):
            share = _fluid_share(reader, key, str(fluid), runs)
            if math.isfinite(share):
                total += share * share * len(runs)
            count += len(runs)
        if total > 0 and count:
            shares[tuple(key)] = (math.sqrt(total / count), SOURCES)
    return shares


def _median(runs: Any, column: str) -> float | None:
    """The runs' median of ``column`` (None where the column is missing or all empty)."""
    if column not in runs:
        return None
    values = runs[column].to_numpy(dtype=float)
    values = values[np.isfinite(values)]
    return float(np.median(values)) if values.size else None


def _fluid_share(reader: Any, key: tuple, fluid: str, runs: Any) -> float:
    """u_r of St_n for the typical run of one fluid (NaN where nothing states a u)."""
    _dataset, particle, wall = key
    diameter = _median(runs, "diameter_m")
    if diameter is None:
        return math.nan
    wall_diameter = _median(runs, "wall_diameter_m")
    target = None
    if wall_diameter is not None:  # free where the runs give the target's speed
        free = "wall_v_n_in_m_s" in runs and runs["wall_v_n_in_m_s"].notna().any()
        target = "free" if free else "fixed"
    try:
        result = derive_pair(
            reader,
            str(particle),
            str(wall),
            diameter_m=diameter,
            speed_m_s=1.0,
            fluid=fluid,
            temperature_c=_median(runs, "temperature_c"),
            wall_diameter_m=wall_diameter,
            target=target,
            uncertainties={"u_diameter_m": _median(runs, "u_diameter_m")},
        )
    except ValidationError:  # the runs' own rows say why (derivation_note): no share
        return math.nan
    st = float(result.derived["normal_stokes_number"])
    u = result.derived.get("u_normal_stokes_number")
    if u is None or not (st > 0) or not math.isfinite(float(u)):
        return math.nan
    return float(u) / st
