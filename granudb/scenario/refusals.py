"""Turning the physics layer's plain ``PhysicsInputError`` into granudb's one-line refusal.

The physics kernels know nothing of options, runs or datasets; the service layer does, so
it names the offending input the way the caller gave it.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from granudb.errors import ValidationError
from granudb.physics.numeric import PhysicsInputError


@contextmanager
def physics_refusal(field: str | None = None) -> Iterator[None]:
    """Re-raise a ``PhysicsInputError`` as ``ValidationError`` naming ``field`` (a parameter
    of the caller, shown as its option on the command line) or the kernel's own field."""
    try:
        yield
    except PhysicsInputError as exc:
        raise ValidationError(
            field or exc.field, exc.value, exc.rule, row=exc.row, parameter=field is not None
        ) from None
