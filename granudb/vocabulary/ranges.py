"""An allowed range of a number (``Rule``) and the common ones: the one type both a
column's declaration (``granudb.vocabulary.terms``) and the checks before a write
(``granudb.vocabulary.rules``) use."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from granudb.lazy import numpy as np


@dataclass(frozen=True)
class Rule:
    """An allowed range: ``minimum``/``maximum`` with inclusive or exclusive ends."""

    minimum: float | None = None
    maximum: float | None = None
    min_inclusive: bool = True
    max_inclusive: bool = True

    @property
    def text(self) -> str:
        parts = []
        if self.minimum is not None:
            parts.append(f"{'≥' if self.min_inclusive else '>'} {self.minimum:g}")
        if self.maximum is not None:
            parts.append(f"{'≤' if self.max_inclusive else '<'} {self.maximum:g}")
        return "must be " + " and ".join(parts)

    def holds(self, value: float) -> bool:
        if math.isnan(value) or math.isinf(value):
            return False
        if self.minimum is not None and (
            value < self.minimum or (value == self.minimum and not self.min_inclusive)
        ):
            return False
        return self.maximum is None or not (
            value > self.maximum or (value == self.maximum and not self.max_inclusive)
        )

    def holds_array(self, values: Any) -> Any:
        """Vectorized ``holds`` (NaN counts as "no value" and passes; required-ness is
        checked separately)."""
        values = np.asarray(values, dtype=float)
        ok = np.isnan(values) | np.isfinite(values)
        if self.minimum is not None:
            ok &= np.isnan(values) | (
                values >= self.minimum if self.min_inclusive else values > self.minimum
            )
        if self.maximum is not None:
            ok &= np.isnan(values) | (
                values <= self.maximum if self.max_inclusive else values < self.maximum
            )
        return ok


POSITIVE = Rule(minimum=0.0, min_inclusive=False)
NON_NEGATIVE = Rule(minimum=0.0)
ABOVE_ABSOLUTE_ZERO = Rule(minimum=-273.15, min_inclusive=False)
