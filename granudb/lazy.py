"""The heavy libraries granudb loads only when they are first used, listed in one place.

``granudb --help`` must stay within 4× Python's own start-up, and ``materials list`` or
``pair`` within 1.3× and 1.5× the time Python takes to import SQLAlchemy (the speed
issue's bounds, measured by ``benchmarks/cli_latency.py``). pandas (about 0.30 s to
import here), Pint (0.18 s, and its registry as much again), pyarrow (0.15 s), SciPy
(0.08 s), NumPy (0.06 s), Jinja2 (0.04 s), Alembic and SQLAlchemy's ORM each cost more
than a short command does, and most commands never touch them. So a module that needs
one imports it from here, at the top of the module like any other import::

    from granudb.lazy import pandas as pd

and the library is imported on the first attribute access (``pd.DataFrame``).

Why not ``lazy_loader.load`` (scientific-python's loader): for a submodule such as
``pyarrow.csv`` it imports the parent package at once (so merely importing this module
would cost pyarrow's 0.15 s), and it puts unexecuted modules into ``sys.modules``, so
``"pandas" in sys.modules`` would no longer say whether pandas was loaded. The proxy
below imports nothing until used and leaves ``sys.modules`` truthful.

This is the one place a library is loaded lazily; granudb's own modules are loaded
lazily only through the public API's table of names (``granudb.api``) and the command
line's table of sub-commands (``granudb.cli.main.COMMANDS``). Everywhere else, imports
stand at the top of the module.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any


class LazyModule:
    """Stands for module ``name`` and imports it on the first attribute access."""

    __slots__ = ("_name", "_module")

    def __init__(self, name: str) -> None:
        self._name = name
        self._module: ModuleType | None = None

    def __getattr__(self, attribute: str) -> Any:
        module = self._module
        if module is None:
            module = self._module = importlib.import_module(self._name)
        return getattr(module, attribute)

    def __repr__(self) -> str:
        state = "loaded" if self._module is not None else "not loaded yet"
        return f"<lazy module {self._name!r} ({state})>"


pandas: Any = LazyModule("pandas")
numpy: Any = LazyModule("numpy")
pint: Any = LazyModule("pint")
pyarrow: Any = LazyModule("pyarrow")
pyarrow_csv: Any = LazyModule("pyarrow.csv")
pyarrow_compute: Any = LazyModule("pyarrow.compute")
scipy_optimize: Any = LazyModule("scipy.optimize")
threadpoolctl: Any = LazyModule("threadpoolctl")
scipy_stats: Any = LazyModule("scipy.stats")
emcee: Any = LazyModule("emcee")
jinja2: Any = LazyModule("jinja2")
contourpy: Any = LazyModule("contourpy")
platformdirs: Any = LazyModule("platformdirs")
sqlalchemy_orm: Any = LazyModule("sqlalchemy.orm")
alembic_command: Any = LazyModule("alembic.command")
alembic_config: Any = LazyModule("alembic.config")
alembic_script: Any = LazyModule("alembic.script")
alembic_migration: Any = LazyModule("alembic.runtime.migration")
alembic_errors: Any = LazyModule("alembic.util.exc")
rich_console: Any = LazyModule("rich.console")
rich_table: Any = LazyModule("rich.table")
rich_text: Any = LazyModule("rich.text")
rich_box: Any = LazyModule("rich.box")
rich_markup: Any = LazyModule("rich.markup")
rich_progress: Any = LazyModule("rich.progress")
