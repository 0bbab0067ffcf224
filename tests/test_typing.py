"""What static type checkers see of the public API (issue 34).

``granudb`` and ``granudb.api`` load their names lazily at run time (``__getattr__`` over the
tables ``granudb.api.NAMES`` and ``FACE``); under ``TYPE_CHECKING`` they import each name
explicitly, so mypy and pyright see real signatures and refuse unknown names. These tests
keep the explicit imports and the tables equal, and ask mypy itself when it is installed;
the last one runs ``mypy granudb`` with the repository's configuration (pyproject.toml,
``[tool.mypy]``: strict for ``api``, ``physics`` and ``vocabulary``) and wants no error, so
a type error fails here, locally, as well as in ``.ci/run``.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

import granudb
from granudb import api

PACKAGE = Path(granudb.__file__).parent
ROOT = Path(__file__).resolve().parents[1]  # the repository: pyproject.toml and granudb/


def _type_checking_imports(path: Path) -> dict[str, str]:
    """name → module of every ``from m import name as name`` under ``if TYPE_CHECKING``."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found: dict[str, str] = {}
    for node in tree.body:
        if isinstance(node, ast.If) and getattr(node.test, "id", None) == "TYPE_CHECKING":
            for statement in node.body:
                assert isinstance(statement, ast.ImportFrom), ast.dump(statement)
                for alias in statement.names:
                    assert alias.asname == alias.name, f"{alias.name} must be re-exported as itself"
                    found[alias.name] = statement.module or ""
    return found


def _mypy_env() -> dict[str, str]:
    """An installed granudb is found by mypy in site-packages (which mypy refuses in
    MYPYPATH); a checkout's editable install is found by an import hook mypy cannot
    follow, so its folder is named."""
    installed = any(part in {"site-packages", "dist-packages"} for part in PACKAGE.parts)
    return dict(os.environ) if installed else {**os.environ, "MYPYPATH": str(PACKAGE.parent)}


def test_api_type_checking_imports_equal_the_tables() -> None:
    seen = _type_checking_imports(PACKAGE / "api" / "__init__.py")
    expected = {name: f"granudb.api.{module}" for name, module in {**api.NAMES, **api.FACE}.items()}
    assert seen == expected, "run: python -m tools.type_exports"


def test_package_type_checking_imports_equal_the_public_names() -> None:
    seen = _type_checking_imports(PACKAGE / "__init__.py")
    assert set(seen) == set(api.NAMES) - {"__version__"}
    assert set(seen.values()) == {"granudb.api"}


def test_every_explicit_import_is_the_runtime_object() -> None:
    for name in api.NAMES:
        assert getattr(granudb, name) is getattr(api, name)


def test_unknown_name_raises_at_run_time() -> None:
    with pytest.raises(AttributeError, match="no_such_function"):
        granudb.no_such_function  # noqa: B018


def test_mypy_sees_signatures_and_refuses_unknown_names(tmp_path: Path) -> None:
    script = tmp_path / "use_granudb.py"
    script.write_text(
        textwrap.dedent(
            """
            import granudb
            reveal_type(granudb.pair)
            granudb.no_such_function()
            """
        ),
        encoding="utf-8",
    )
    result = subprocess.run(
        [sys.executable, "-m", "mypy", "--follow-imports=silent", str(script)],
        capture_output=True,
        text=True,
        check=False,
        cwd=tmp_path,
        env=_mypy_env(),
    )
    lines = [line for line in result.stdout.splitlines() if "use_granudb.py" in line]
    revealed = next(line for line in lines if "Revealed type" in line)
    assert "def (particle: builtins.str, wall: builtins.str" in revealed or (
        "def (particle: str, wall: str" in revealed
    ), revealed
    assert any('has no attribute "no_such_function"' in line for line in lines), lines


def test_mypy_finds_no_error_in_the_package(tmp_path: Path) -> None:
    """``mypy granudb`` as ``.ci/run`` runs it (the checked-out source, the pyproject
    configuration); its cache goes to a temporary folder, not the repository."""
    result = subprocess.run(
        [sys.executable, "-m", "mypy", "--cache-dir", str(tmp_path / "cache"), "granudb"],
        capture_output=True,
        text=True,
        check=False,
        cwd=ROOT,
    )
    assert result.returncode == 0, result.stdout[-4000:] + result.stderr[-2000:]
    assert result.stdout.startswith("Success: no issues found"), result.stdout
