"""granudb: a materials-and-regime database for particle collisions in liquids.

The library is the product; the ``granudb`` command is its face. Every public function
lives in ``granudb.api`` and is available here under the same name, imported on first
use (the table ``granudb.api.NAMES``), so that ``import granudb`` and ``granudb --help``
stay fast.
"""

from __future__ import annotations

from typing import Any

from granudb import api
from granudb.version import __version__ as __version__

#: Every public name: the functions named after the commands, ``connect``, the errors.
__all__ = sorted({"__version__", *api.NAMES})


def __getattr__(name: str) -> Any:
    if name in api.NAMES:
        return getattr(api, name)
    raise AttributeError(f"module 'granudb' has no attribute {name!r}")


def __dir__() -> list[str]:
    return __all__
