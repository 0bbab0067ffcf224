"""Which collisions: the query every listing, fit, report and export selects runs by.

Kept apart from ``granudb.scenario.collisions`` (which reads and derives them, with numpy
and pandas) so that naming a query — the command line's filter options, a refusal — needs
neither.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from granudb.errors import ValidationError
from granudb.vocabulary.listings import STORED_FILTERS

#: Maw's regimes as the ``regime`` filter names them.
TANGENTIAL_REGIMES = ("stick", "slip_then_stick", "gross_slip")


@dataclass(frozen=True)
class CollisionQuery:
    """Which collisions: every field ``None`` means "any". Field names are the Python
    API's parameters and, with dashes, the command line's options."""

    dataset: str | None = None
    version: str | None = None
    particle: str | None = None
    wall: str | None = None
    fluid: str | None = None
    min_normal_stokes: float | None = None
    max_normal_stokes: float | None = None
    angle_range: tuple[float, float] | None = None
    regime: str | None = None
    roughness_exceeds_gap: bool | None = None
    rebound_expected: bool | None = None
    critical_stokes: float = 10.0

    @property
    def stored(self) -> dict[str, str | None]:
        """The filters that select the stored runs (``STORED_FILTERS``), by name."""
        return {name: getattr(self, name) for name in STORED_FILTERS}

    def describe(self) -> str:
        parts = [
            f"{k}={v}" for k, v in self.__dict__.items() if v is not None and k != "critical_stokes"
        ]
        return ", ".join(parts) or "all collisions"

    def check(self) -> None:
        """Refuse a query that cannot mean anything, naming the parameter."""
        if self.regime is not None and self.regime not in TANGENTIAL_REGIMES:
            raise ValidationError(
                "regime",
                self.regime,
                f"must be one of {', '.join(TANGENTIAL_REGIMES)}",
                parameter=True,
            )
        if not (math.isfinite(self.critical_stokes) and self.critical_stokes > 0):
            raise ValidationError(
                "critical_stokes", self.critical_stokes, "must be > 0", parameter=True
            )
        if self.angle_range is not None:
            low, high = self.angle_range
            if not 0 <= low <= high < math.pi / 2:
                raise ValidationError(
                    "angle_range",
                    f"{math.degrees(low):g}..{math.degrees(high):g} deg",
                    "must be LOW..HIGH with 0° ≤ LOW ≤ HIGH < 90°",
                    parameter=True,
                )


#: The filters of a query, as the Python API's parameters and the command line's options.
COLLISION_FILTERS: tuple[str, ...] = tuple(CollisionQuery.__dataclass_fields__)
