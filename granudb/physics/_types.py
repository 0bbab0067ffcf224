"""Shared typing helpers for the physics kernels."""

from __future__ import annotations

from typing import Any, TypeAlias

import numpy as np

Numeric: TypeAlias = Any  # float | numpy array (anything np.asarray accepts as float)


def as_float(value: Numeric) -> np.ndarray:
    """``value`` as a float array (0-d for scalars), without copying float arrays."""
    return np.asarray(value, dtype=float)


class PhysicsInputError(ValueError):
    """An input outside a relation's domain (a negative size, a temperature outside a
    fluid model's data).

    The physics layer imports nothing of granudb, so it raises this plain ``ValueError``
    with the offending ``field``, ``value`` and ``rule``; the layers above turn it into
    granudb's one-line ``ValidationError`` (naming the dataset, run or option).
    """

    def __init__(self, field: str, value: object, rule: str, *, row: int | None = None) -> None:
        self.field = field
        self.value = value
        self.rule = rule
        self.row = row
        where = f"row {row}: " if row is not None else ""
        super().__init__(f"{where}{field}: {value} {rule}")
