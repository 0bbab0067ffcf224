"""Write the ``if TYPE_CHECKING:`` re-exports of ``granudb/__init__.py`` and
``granudb/api/__init__.py`` from the name tables ``granudb.api.NAMES`` and ``FACE``.

Type checkers cannot follow the lazy ``__getattr__`` that serves the public names at run
time, so each name is also imported explicitly for them; this keeps those imports equal
to the tables (tests/test_typing.py fails until it is run after a name is added):

    python -m tools.type_exports
"""

from __future__ import annotations

import re
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
HEAD = (
    "if TYPE_CHECKING:\n"
    "    # One `from m import (a as a, …)` per module, the explicit re-exports checkers need:\n"
    "    # isort: off\n"
)
TAIL = "    # isort: on\nelse:\n"


def _imports(groups: dict[str, list[str]]) -> str:
    lines = []
    for module in sorted(groups):
        lines.append(f"    from {module} import (")
        lines.extend(f"        {name} as {name}," for name in sorted(groups[module]))
        lines.append("    )")
    return "\n".join(lines) + "\n"


def _rewrite(path: Path, comment: str, groups: dict[str, list[str]]) -> None:
    text = path.read_text(encoding="utf-8")
    pattern = re.compile(re.escape(HEAD) + r".*?" + re.escape(TAIL), re.DOTALL)
    block = HEAD + comment + _imports(groups) + TAIL
    new, count = pattern.subn(lambda _: block, text)
    if count != 1:
        raise SystemExit(f"{path}: no TYPE_CHECKING block to rewrite")
    path.write_text(new, encoding="utf-8")


def main() -> None:
    sys.path.insert(0, str(ROOT))
    from granudb import api

    by_module: dict[str, list[str]] = defaultdict(list)
    for name, module in {**api.NAMES, **api.FACE}.items():
        by_module[f"granudb.api.{module}"].append(name)
    _rewrite(
        ROOT / "granudb" / "api" / "__init__.py",
        "    # What static type checkers see: every name of the tables above, with its real\n"
        "    # signature (tools/type_exports.py writes this list from them). At run time the\n"
        "    # names load on first use through ``__getattr__`` below.\n",
        by_module,
    )
    _rewrite(
        ROOT / "granudb" / "__init__.py",
        "    # Static type checkers see each public function with its signature (and an unknown\n"
        "    # name as an error); at run time the names load on first use. Written by\n"
        "    # tools/type_exports.py from granudb.api.NAMES.\n",
        {"granudb.api": [n for n in api.NAMES if n != "__version__"]},
    )
    subprocess.run(
        [sys.executable, "-m", "ruff", "format", "granudb/__init__.py", "granudb/api/__init__.py"],
        cwd=ROOT,
        check=False,
        capture_output=True,
    )


if __name__ == "__main__":
    main()
