"""Selecting measured collisions by dataset, pair, fluid, Stokes number, angle and regime.

Shared by ``granudb collisions list``, the fits, the reports and the Python API
(``granudb.collisions()``), so a query means the same everywhere.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from granudb.errors import ValidationError

REGIMES = ("stick", "slip_then_stick", "gross_slip", "rough", "no_rebound")


@dataclass(frozen=True)
class CollisionQuery:
    dataset: str | None = None
    version: str | None = None
    particle: str | None = None
    wall: str | None = None
    fluid: str | None = None
    min_st: float | None = None
    max_st: float | None = None
    angle_range: tuple[float, float] | None = None
    regime: str | None = None
    critical_stokes: float = 10.0

    def describe(self) -> str:
        parts = [
            f"{k}={v}" for k, v in self.__dict__.items() if v is not None and k != "critical_stokes"
        ]
        return ", ".join(parts) or "all collisions"


def select_collisions(session: Any, query: CollisionQuery) -> Any:
    """The collisions matching ``query``, with every derived column (a DataFrame)."""
    from granudb.analysis.derivation import collision_table

    if query.regime is not None and query.regime not in REGIMES:
        raise ValidationError("--regime", query.regime, f"must be one of {', '.join(REGIMES)}")
    if query.critical_stokes <= 0:
        raise ValidationError("--critical-stokes", query.critical_stokes, "must be > 0")
    frame = collision_table(
        session,
        dataset=query.dataset,
        version=query.version,
        particle=query.particle,
        wall=query.wall,
        fluid=query.fluid,
        critical_stokes=query.critical_stokes,
    )
    keep = frame["run"].notna()
    st = frame["normal_stokes_number"]
    if query.min_st is not None:
        keep &= st >= query.min_st
    if query.max_st is not None:
        keep &= st <= query.max_st
    if query.angle_range is not None:
        low, high = query.angle_range
        keep &= frame["incidence_angle_rad"].between(low, high)
    if query.regime in {"stick", "slip_then_stick", "gross_slip"}:
        keep &= frame["tangential_regime"] == query.regime
    elif query.regime == "rough":
        keep &= frame["roughness_exceeds_gap"].astype(bool)
    elif query.regime == "no_rebound":
        keep &= ~frame["rebound_expected"].astype(bool)
    return frame[keep].reset_index(drop=True)
