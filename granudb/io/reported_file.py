"""Read a CSV file of runs as papers report them (``granudb reported import``).

One row per run. Columns (case and spaces around a header do not matter): ``run``,
``particle``, ``wall``, ``fluid`` (empty: dry), and what the paper states:
``incidence_angle`` (θ from the normal), ``e`` (or ``normal_restitution``), ``e_t`` (or
``tangential_restitution``), ``omega_out``, ``diameter``; ``u(NAME)`` or ``u_NAME`` the
standard uncertainty of NAME; ``no_spin_in`` (yes/no: the paper states the sphere arrives
without spin); ``source_locator``, ``digitiser`` (who read the values from the figure),
``licence`` (of the file they were read from) and ``notes``. A header may carry its unit in brackets
(``incidence_angle [deg]``), else each cell carries its own (``20 deg``). A velocity column
is refused: runs as reported hold no velocity.
"""

from __future__ import annotations

import csv
import difflib
import re
from pathlib import Path

from granudb.errors import ValidationError

#: Header (as people write it) → granudb's stored column.
ALIASES = {
    "run": "run",
    "particle": "particle",
    "wall": "wall",
    "fluid": "fluid",
    "diameter": "diameter_m",
    "diameter_m": "diameter_m",
    "incidence_angle": "incidence_angle_rad",
    "incidence_angle_rad": "incidence_angle_rad",
    "e": "normal_restitution",
    "normal_restitution": "normal_restitution",
    "e_t": "tangential_restitution",
    "tangential_restitution": "tangential_restitution",
    "omega_out": "omega_out_rad_s",
    "omega_out_rad_s": "omega_out_rad_s",
    "no_spin_in": "no_spin_in",
    "source_locator": "source_locator",
    "digitiser": "digitiser",
    "licence": "licence",
    "notes": "notes",
}
#: Columns whose standard uncertainty a file may state.
UNCERTAIN = ("incidence_angle_rad", "normal_restitution", "tangential_restitution",
             "omega_out_rad_s")  # fmt: skip
VELOCITIES = re.compile(r"^(wall_)?v_[nt]_(in|out)")
_UNIT = re.compile(r"^(.*?)\s*[\[(]([^\])]*)[\])]\s*$")
_U = re.compile(r"^u\s*\(\s*(.+?)\s*\)$|^u_(.+)$")
MAX_ROWS = 100_000


def column_of(header: str) -> tuple[str, str | None]:
    """(granudb column, unit in the header or None) of one header; ``ValidationError``
    naming it when it is not a column of reported runs."""
    text = header.strip()
    unit = None
    found = _UNIT.match(text)
    if found and not _U.match(text.lower()):  # "u(e_t)" is a name, not "u" in unit e_t
        text, unit = found.group(1), found.group(2).strip()
    key = text.lower().replace(" ", "_")
    u = _U.match(key)
    if u:
        base = ALIASES.get(u.group(1) or u.group(2))
        if base in UNCERTAIN:
            return f"u_{base}", unit
    if key in ALIASES:
        return ALIASES[key], unit
    if VELOCITIES.match(key):
        raise ValidationError(
            "header", header, "is a velocity: runs as reported hold none (a run with its "
            "velocities goes to granudb collisions import)",
        )  # fmt: skip
    near = difflib.get_close_matches(key, list(ALIASES), n=1)
    rule = "is not a column of reported runs" + (f"; did you mean {near[0]}?" if near else "")
    raise ValidationError("header", header, rule)


def read(path: Path) -> tuple[dict[str, tuple[str, str | None]], list[dict[str, str]]]:
    """({header: (column, unit)}, rows as {header: cell text}) of the file."""
    if not path.is_file():
        raise ValidationError("file", str(path), "is not a file")
    with path.open(encoding="utf-8-sig", newline="") as f:
        reader = csv.DictReader(f)
        fieldnames = list(reader.fieldnames or [])
        headers = {h: column_of(h) for h in fieldnames}
        columns = [column_of(h)[0] for h in fieldnames]
        for needed in ("run", "particle", "wall"):
            if needed not in columns:
                raise ValidationError("header", needed, "is missing")
        repeated = {c for c in columns if columns.count(c) > 1}
        if repeated:
            raise ValidationError("header", ", ".join(sorted(repeated)), "is given twice")
        rows = []
        for number, row in enumerate(reader, start=2):
            if number > MAX_ROWS + 1:
                raise ValidationError("file", str(path), f"has more than {MAX_ROWS} rows")
            if None in row:
                raise ValidationError("row", number, "has more cells than the header")
            rows.append({h: (v or "").strip() for h, v in row.items()})
    return headers, rows
