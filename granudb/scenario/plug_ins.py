"""The catalogue's share of what a fit's runs stand on: the plug-in error they all share.

A restitution fit's runs (one dataset, particle and wall) get St_n from the catalogue's
values — the particle's density, the fluid's viscosity at the run's temperature, the
target's for a sphere — and the run's diameter; a gap-viscosity fit's runs (one fluid
too) get g of (5.8), μ_f = μ₀^(2/7) g, from the pair's E*, R*, the fluid's
pressure–viscosity coefficient and the same. Where the catalogue states their
uncertainty (or the runs state u(d)), that error is one for every run of the fit: the
fit must carry it (``granudb.analysis.shared_scale``). Its relative size is what
``granudb.pair`` propagates for the group's typical run (the medians of each fluid's
runs: diameter, temperature, impact speed and angle), with no u on the speed: the one
record of how a u reaches St_n and μ_f. For g, the fluid viscosity's own share
(μ_f ∝ μ^(2/7), and μ is what the fit replaces by μ₀) is taken out in quadrature: the
sources are independent. A restitution group in several fluids gets the root mean square
over its runs (each fluid's share weighted by its runs: the particle's share is common to
all, the fluids' are not, and taking them as one error is the cautious side).

The gap-viscosity fit turns μ₀ into a gap temperature through the fluid's μ(T): where the
catalogue states that curve's uncertainty, its relative u at the gap temperature
(``fluid_curves``: ``granudb.scenario.fluid_state.state_uncertainty``, the one record of
u(μ) at a temperature, with the reference temperature's share) is an error shared by
every run as well, and the temperature's interval carries it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np

from granudb.db import catalog_rows
from granudb.errors import ValidationError
from granudb.lazy import pandas as pd
from granudb.scenario.fluid_state import fluid_model, fluid_state, state_uncertainty
from granudb.scenario.pair import PairResult, derive_pair
from granudb.scenario.row_groups import group_rows

#: The group of a restitution fit (``granudb.analysis.restitution_fit``) and of a
#: gap-viscosity fit (``granudb.analysis.gap_viscosity_fit``).
GROUP = ("dataset", "particle", "wall")
GAP_GROUP = (*GROUP, "fluid")
#: The columns of the runs these read (a report reads only the columns it needs).
COLUMNS = (*GROUP, "fluid", "normal_stokes_number", "diameter_m", "u_diameter_m",
           "temperature_c", "wall_diameter_m", "wall_v_n_in_m_s", "v_n_in_m_s",
           "v_t_in_m_s")  # fmt: skip
#: What each share is made of, as the fit's method says it.
SOURCES = "ρ and d of the particle, μ(T) of the fluid, the target's for a sphere, as stored"
GAP_SOURCES = (
    "E and ν of both bodies, R*, the fluid's pressure–viscosity coefficient and "
    "density, d, as stored"
)


def fluid_curves(connection: Any) -> tuple[dict[str, Any], dict[str, Callable[[float], float]]]:
    """({fluid: its μ(T) model, or None}, {fluid with a model: the relative u of its μ(T)
    at a temperature in °C, from its reference viscosity's, its points' or its reference
    temperature's u, NaN where it states none}): what ``granudb.analysis.gap_viscosity_fit``
    turns μ₀ into a gap temperature with, and that curve's share."""
    models: dict[str, Any] = {}
    curves: dict[str, Callable[[float], float]] = {}
    for fluid in catalog_rows.fluid_rows(connection):
        models[fluid.name] = model = fluid_model(fluid)
        if model is not None:  # NaN where the fluid states no u: nothing is widened
            curves[fluid.name] = partial(_curve_share, fluid)
    return models, curves


def _curve_share(fluid: Any, temperature_c: float) -> float:
    """u(μ)/μ of the fluid's μ(T) at ``temperature_c`` (NaN where it cannot be had)."""
    try:
        state = fluid_state(fluid, temperature_c)
        u_mu, _ = state_uncertainty(fluid, state)
    except ValidationError:  # outside the fluid's data: no temperature to widen
        return math.nan
    if u_mu is None or not state.viscosity_pa_s > 0:
        return math.nan
    return u_mu / state.viscosity_pa_s


def catalogue_shares(reader: Any, frame: Any) -> tuple[dict, dict]:
    """(``stokes_scale``, ``gap_scale``) of one frame, each (group, fluid)'s typical run
    derived once for both (a report needs both)."""
    typical = _typical_runs(reader, frame)
    return stokes_scale(reader, frame, typical), gap_scale(reader, frame, typical)


#: One (group, fluid)'s typical run: its derivation (``_typical``), None where it has
#: none, and how many immersed runs it stands for.
Typical = tuple[PairResult | None, int]


def _typical_runs(reader: Any, frame: Any) -> dict[tuple, Typical]:
    """{(dataset, particle, wall, fluid): its typical run, in key order} (``Typical``)."""
    columns = _Columns(frame)
    return {
        key: (_typical(reader, key[:3], str(key[3]), columns, rows), len(rows))
        for key, rows in _immersed_groups(frame)
    }


def stokes_scale(
    reader: Any, frame: Any, typical: dict[tuple, Typical] | None = None
) -> dict[tuple, tuple[float, str]]:
    """{(dataset, particle, wall): (u_r, sources)} of the restitution groups whose
    immersed runs' St_n has a stated catalogue share u_r > 0 (the module docstring's
    rule); the others are left out. ``frame``: collisions as ``select_collisions`` gives
    them; ``typical``: ``_typical_runs`` of it, if already derived."""
    typical = _typical_runs(reader, frame) if typical is None else typical
    fluids: dict[tuple, list[Typical]] = {}  # each group's fluids, in key order
    for key, one in typical.items():
        fluids.setdefault(key[:3], []).append(one)
    shares: dict[tuple, tuple[float, str]] = {}
    for key, group in fluids.items():
        total = count = 0.0
        for found, runs in group:
            share = math.nan if found is None else _relative(found, "normal_stokes_number")
            if math.isfinite(share):
                total += share * share * runs
            count += runs
        if total > 0 and count:
            shares[key] = (math.sqrt(total / count), SOURCES)
    return shares


def gap_scale(
    reader: Any, frame: Any, typical: dict[tuple, Typical] | None = None
) -> dict[tuple, tuple[float, str]]:
    """{(dataset, particle, wall, fluid): (u_r, sources)} of the gap-viscosity groups
    whose g of (5.8) has a stated catalogue share u_r > 0: u_r(μ_f) as ``granudb.pair``
    propagates it, less the fluid viscosity's share (2/7 u_r(μ)) in quadrature."""
    typical = _typical_runs(reader, frame) if typical is None else typical
    shares: dict[tuple, tuple[float, str]] = {}
    for key, (found, _runs) in typical.items():
        if found is None:
            continue
        share = _relative(found, "lubricated_friction")
        state, u_mu = found.fluid_state, found.inputs.get("u_viscosity_pa_s")
        if state is not None and u_mu is not None and state.viscosity_pa_s > 0:
            share = math.sqrt(max(share**2 - (2 / 7 * u_mu / state.viscosity_pa_s) ** 2, 0.0))
        if share > 1e-6:  # more than rounding left once μ's share is out (1e-10 seen)
            shares[key] = (share, GAP_SOURCES)
    return shares


def _immersed_groups(frame: Any) -> list[tuple[tuple, np.ndarray]]:
    """[(key, rows)] of the immersed runs (a fluid, a finite St_n) by ``GAP_GROUP``, in
    key order; a run missing a key part is in none. Found from the key columns alone
    (``row_groups.group_rows``): no copy of the frame, no groupby of text columns."""
    needed = {*GAP_GROUP, "normal_stokes_number", "diameter_m"}
    if frame.empty or not needed <= set(frame.columns):
        return []
    immersed = frame["fluid"].notna().to_numpy() & np.isfinite(
        _floats(frame["normal_stokes_number"])
    )
    groups = []
    for key, rows in group_rows(frame, list(GAP_GROUP)).items():
        kept = rows[immersed[rows]]
        if kept.size and all(part is not None for part in key):
            groups.append((key, kept))
    return sorted(groups, key=lambda group: group[0])


class _Columns(dict[str, "np.ndarray | None"]):
    """A frame's number columns as float arrays, each read once when first asked for
    (None for a column the frame lacks)."""

    def __init__(self, frame: Any) -> None:
        super().__init__()
        self.frame = frame

    def __missing__(self, column: str) -> np.ndarray | None:
        found = _floats(self.frame[column]) if column in self.frame else None
        self[column] = found
        return found


def _floats(column: Any) -> np.ndarray:
    """A column as floats, NaN where empty (a nullable column's NA, or text)."""
    numbers = pd.to_numeric(column, errors="coerce")
    return np.asarray(numbers.to_numpy(dtype=float, na_value=np.nan))


def _median(columns: _Columns, rows: np.ndarray, column: str) -> float | None:
    """The median of ``column`` over ``rows`` (None where the column is missing or all
    empty there)."""
    found = columns[column]
    if found is None:
        return None
    values = found[rows]
    values = values[np.isfinite(values)]
    return float(np.median(values)) if values.size else None


def _relative(found: PairResult, name: str) -> float:
    """u(Q)/Q of one derived quantity of the typical run (NaN where no u reaches it)."""
    value, u = found.derived.get(name), found.derived.get(f"u_{name}")
    if value is None or u is None or not float(value) > 0:
        return math.nan
    return float(u) / float(value)


def _typical(
    reader: Any, key: tuple, fluid: str, columns: _Columns, rows: np.ndarray
) -> PairResult | None:
    """``granudb.pair``'s derivation of the runs' typical collision (the module's rule),
    with the catalogue's u and the runs' median u(d), none on the speed; None where the
    runs give no diameter or the scenario is refused (the runs' own rows say why)."""
    _dataset, particle, wall = key

    def median(column: str) -> float | None:
        return _median(columns, rows, column)

    diameter = median("diameter_m")
    if diameter is None:
        return None
    wall_diameter = median("wall_diameter_m")
    target = None
    if wall_diameter is not None:  # free where the runs give the target's speed
        speeds = columns["wall_v_n_in_m_s"]
        free = speeds is not None and bool((~np.isnan(speeds[rows])).any())
        target = "free" if free else "fixed"
    v_n, v_t = median("v_n_in_m_s") or 1.0, median("v_t_in_m_s") or 0.0
    try:
        return derive_pair(
            reader,
            str(particle),
            str(wall),
            diameter_m=diameter,
            speed_m_s=math.hypot(v_n, v_t),
            angle_rad=math.atan2(abs(v_t), abs(v_n)),
            fluid=fluid,
            temperature_c=median("temperature_c"),
            wall_diameter_m=wall_diameter,
            target=target,
            uncertainties={"u_diameter_m": median("u_diameter_m")},
        )
    except ValidationError:
        return None
