"""Shared typing helpers for the physics kernels."""

from __future__ import annotations

from typing import Any, TypeAlias

import numpy as np

Numeric: TypeAlias = Any  # float | numpy array (anything np.asarray accepts as float)


def as_float(value: Numeric) -> np.ndarray:
    """``value`` as a float array (0-d for scalars), without copying float arrays."""
    return np.asarray(value, dtype=float)
