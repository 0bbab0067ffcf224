"""Griffe extension for the documentation site: render the docstrings physics generates.

The public relations of ``granudb.physics`` get their numpydoc ``Parameters`` section from
one table (``granudb/physics/arguments.py``) when they are defined, so the source text lacks
it. mkdocstrings reads the source; this extension gives each ``granudb.physics`` function
the docstring Python itself has (``inspect.getdoc``), the one ``help()`` and the doctests
see. Loaded by ``mkdocs.yml`` (handler option ``extensions``).
"""

from __future__ import annotations

import inspect
from typing import Any

import griffe


class GeneratedDocstrings(griffe.Extension):
    """Replace a physics function's static docstring by its runtime one."""

    def on_function_instance(self, *, func: griffe.Function, **kwargs: Any) -> None:
        if not func.path.startswith("granudb.physics.") or func.docstring is None:
            return
        text = inspect.getdoc(griffe.dynamic_import(func.path))
        if text and text != func.docstring.value:
            func.docstring = griffe.Docstring(
                text, lineno=func.docstring.lineno, parent=func, parser=func.docstring.parser
            )
