"""granudb: a materials-and-regime database for particle-wall collisions in liquids.

The library is the product; the ``granudb`` command is a thin layer over it. The public
functions live in ``granudb.api`` and are imported here on first use, so that
``import granudb`` and ``granudb --help`` stay fast.
"""

from __future__ import annotations

from typing import Any

from granudb.version import __version__

_API = {
    "connect": "granudb.api.database",
    "pair": "granudb.api.pair",
    "materials": "granudb.api.catalog",
    "fluids": "granudb.api.catalog",
    "collisions": "granudb.api.collisions",
    "derive": "granudb.api.derive",
    "fit_walton": "granudb.api.fits",
    "fit_restitution": "granudb.api.fits",
    "fit_gap_viscosity": "granudb.api.fits",
    "dem_export": "granudb.api.dem",
    "dem_verify": "granudb.api.dem",
}

__all__ = ["__version__", *_API]


def __getattr__(name: str) -> Any:
    if name in _API:
        from importlib import import_module

        return getattr(import_module(_API[name]), name)
    raise AttributeError(f"module 'granudb' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
