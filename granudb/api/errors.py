"""The refusals a caller can catch, and the version, as the API offers them.

``GranudbError`` is every refusal a user can act on; ``ValidationError`` (a subclass)
names the field or parameter, the value and the rule; ``ConfirmationNeeded`` is a
destructive change without consent; ``PackageError`` a Data Package that fails
validation (its ``problems`` lists each one).
"""

from __future__ import annotations

from granudb.errors import (
    ConfirmationNeeded,
    GranudbError,
    MissingInput,
    PackageError,
    ValidationError,
)
from granudb.version import __version__

__all__ = [
    "ConfirmationNeeded",
    "GranudbError",
    "MissingInput",
    "PackageError",
    "ValidationError",
    "__version__",
]
