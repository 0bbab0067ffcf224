"""The package reads one way: modules named for what they hold, imports at the top, no
cycles, no reaching into another module's private names.

Laziness has three homes only (README, "Layout"): ``granudb.lazy`` for heavy libraries,
the API's table of names (``granudb.api.NAMES``) and the command table
(``granudb.cli.main.COMMANDS``); every other import stands at the top of its module, so
the import graph below is the whole graph.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "granudb"


def _modules() -> dict[str, Path]:
    found = {}
    for path in PACKAGE.rglob("*.py"):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        found[name] = path
    return found


MODULES = _modules()


def _resolve(module: str, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    base = module.split(".")
    if MODULES[module].name != "__init__.py":
        base = base[:-1]
    base = base[: len(base) - node.level + 1]
    return ".".join([*base, node.module] if node.module else base)


def _imports(module: str) -> list[tuple[str, str | None, ast.stmt]]:
    """(imported module, imported name or None, node) for every import of ``module``."""
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    for block in ast.walk(tree):
        if isinstance(block, ast.If) and getattr(block.test, "id", "") == "TYPE_CHECKING":
            for inner in ast.walk(block):
                inner._type_checking = True  # type: ignore[attr-defined]
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(alias.name, None, node) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            source = _resolve(module, node)
            for alias in node.names:
                child = f"{source}.{alias.name}"
                if child in MODULES:  # ``from granudb.db import catalog_rows``
                    found.append((child, None, node))
                else:
                    found.append((source, alias.name, node))
    return found


def test_no_module_is_named_as_private_or_after_history() -> None:
    names = [p.stem for p in PACKAGE.rglob("*.py") if p.stem != "__init__"]
    assert [n for n in names if n.startswith("_") and not n.startswith("__")] == []
    assert [n for n in names if n.endswith(("_extra", "_new", "_old", "_steps", "2"))] == []


#: Private names of other packages granudb needs, each with its reason.
FOREIGN_PRIVATE = {
    # Typer 0.26-0.28 ship their own copy of click (pinned in pyproject for start-up
    # time); the command line's exceptions and context are that copy's.
    "typer._click",
}


def test_nothing_imports_another_modules_private_names() -> None:
    offences = []
    for module in MODULES:
        for source, name, node in _imports(module):
            if f"{source}.{name}" in FOREIGN_PRIVATE:
                continue
            if name and name.startswith("_") and not name.startswith("__"):
                offences.append(f"{module}:{node.lineno} imports {source}.{name}")
    assert offences == []


def test_imports_stand_at_the_top_of_their_module() -> None:
    offences = []
    for module, path in MODULES.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                for inner in ast.walk(node):
                    if isinstance(inner, ast.Import | ast.ImportFrom):
                        offences.append(f"{module}:{inner.lineno} (in {node.name})")
    assert offences == []


def _graph() -> dict[str, set[str]]:
    graph: dict[str, set[str]] = {m: set() for m in MODULES}
    for module in MODULES:
        for source, _name, node in _imports(module):
            if source in MODULES and source != module and not _type_checking_only(node):
                graph[module].add(source)
    return graph


def _type_checking_only(node: ast.stmt) -> bool:
    return getattr(node, "_type_checking", False)


def test_no_import_cycle() -> None:
    """Tarjan's strongly connected components over the module graph: none larger than one
    module (a package's ``__init__`` importing its own submodules excepted)."""
    graph = _graph()
    for module in graph:  # a package may import its submodules; they import the package
        graph[module] = {t for t in graph[module] if not module.startswith(t + ".")}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in graph[node]:
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for module in sorted(graph):
        if module not in index:
            visit(module)
    assert cycles == []


def test_every_public_physics_relation_documents_each_argument_with_its_unit() -> None:
    """numpydoc ``Parameters``: every argument of every public relation, with ``[unit]``
    (``[-]`` when dimensionless)."""
    import importlib
    import inspect
    import re

    missing = []
    for name in ("apparatus", "contact", "flow", "impact", "limits", "lubrication", "pair",
                 "reported", "viscosity"):  # fmt: skip
        module = importlib.import_module(f"granudb.physics.{name}")
        for function_name, function in inspect.getmembers(module, inspect.isfunction):
            if function.__module__ != module.__name__ or function_name.startswith("_"):
                continue
            doc = inspect.getdoc(function) or ""
            section = doc.split("Parameters\n----------\n", 1)[-1] if "Parameters" in doc else ""
            for argument in inspect.signature(function).parameters:
                line = re.search(rf"^(?:\w+, )*{argument}(?:, \w+)* :[^\n]*", section, re.MULTILINE)
                if line is None or not re.search(r"\[[^\]]+\]", line.group(0)):
                    missing.append(f"{name}.{function_name}({argument})")
    assert missing == []


def test_no_benchmark_imports_a_test_module() -> None:
    """The benchmarks run without the test extras (issue 36): no benchmark puts the tests
    on its path or imports pytest, the tests' support or a test module; shared cases live
    in benchmarks/ and the tests import them from there."""
    tests = {path.stem for path in (PACKAGE.parent / "tests").rglob("*.py")}
    tests |= {path.name for path in (PACKAGE.parent / "tests").iterdir() if path.is_dir()}
    benchmarks = {path.stem for path in (PACKAGE.parent / "benchmarks").glob("*.py")}
    for path in sorted((PACKAGE.parent / "benchmarks").glob("*.py")):
        text = path.read_text(encoding="utf-8")
        assert '/ "tests"' not in text and "'tests'" not in text, path.name
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            else:
                continue
            for name in names:
                top = name.split(".")[0]
                assert top != "pytest", (path.name, name)
                assert top not in tests - benchmarks, (path.name, name)
