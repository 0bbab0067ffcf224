"""A collision CSV file: its columns, the rules every row obeys, and its header.

The contract (README, "Importing collisions"): one row per run; text columns ``run``,
``particle``, ``wall``, ``fluid`` (empty = dry), ``notes``; numeric columns with their unit
in the header (``v_n_in [mm/s]``, ``incidence_angle (deg)``, ``Temperature [degC]``;
names case-insensitive) or under granudb's SI column name (``v_n_in_m_s``).

The header is checked before any transaction opens (``open_collision_file``): read with a
size limit, every column mapped and every unit parsed (all header problems in one
refusal), so a hostile header costs milliseconds and never holds SQLite's write lock.
The rows are checked with vectorized rules (``check_values``, ``check_chunk``) as
``granudb.io.collision_chunks`` reads them; every broken row is collected (``Problems``:
the first ``SHOWN_ROW_PROBLEMS`` kept in row order, all counted) and the file is refused
once, whole, naming it (``FileProblems``). A cell already refused is not refused again
by a rule across columns (e, the angle).

A header with semicolons (or tabs) and no comma is read as semicolon- (or tab-) delimited,
as European spreadsheets write CSV. A decimal comma is never guessed (in "1,234" it may be
a thousands separator): such cells are refused unless ``decimal=","`` (``--decimal ','``)
says so.
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from granudb.errors import ValidationError
from granudb.io.tables import (
    ColumnMap,
    Problems,
    base_name,
    check_shape,
    csv_options,
    map_headers,
    read_header,
)
from granudb.io.units import parse_uncertainty
from granudb.vocabulary import (
    COLLISION_MEASURED,
    COLLISION_REQUIRED,
    COLLISION_TEXT,
    COLLISION_UNCERTAIN,
    uncertainty_column,
    unit_of_column,
)
from granudb.vocabulary.rules import MAX_SPEED_M_S, RULES
from granudb.vocabulary.text import (
    MAX_NAME,
    MAX_TEXT,
    check_name,
    check_text,
    name_forbidden_pattern,
    text_forbidden_pattern,
)

NUMERIC = list(COLLISION_MEASURED)  # the measured columns, SI
TEXT = list(COLLISION_TEXT)
REQUIRED = list(COLLISION_REQUIRED)
#: Headers of earlier granudb files, read as today's columns.
ALIASES = {"incidence_angle": "nominal_angle"}
#: e = v_n_out / v_n_in above this is refused: energy from nowhere, beyond measurement error.
MAX_RESTITUTION = 1.05
#: Rules judged on relative velocities where a row has a free target (its wall_v_n_in):
#: the particle may move forward after an equal-sphere impact, or start at rest when an
#: approaching target hits it.
RELATIVE_RULES = ("v_n_in_m_s", "v_n_out_m_s")
#: How far a stated angle may differ from atan(v_t_in / v_n_in), the angle the velocities
#: give. Velocities from high-speed video are good to about 2 % of the speed (a pixel or
#: two of a track fifty to a hundred pixels long), which moves atan(v_t/v_n) by about
#: δv/|v| ≈ 0.02 rad ≈ 1.2°; an apparatus's nominal angle (a tilted plane, a launcher) is
#: set to about ±1°. Their sum rounds up to 3°; a difference larger than that is a wrong
#: column or a wrong unit (the physics review found one of tens of degrees), not noise.
ANGLE_TOLERANCE_RAD = math.radians(3.0)
#: The speed columns: none may be faster than ``MAX_SPEED_M_S`` (``vocabulary.rules``).
SPEEDS = [c for c in NUMERIC if c.endswith("_m_s")]
#: Rows checked and inserted at a time. About three chunks are in memory at once (one
#: read ahead, one being read, one being written): 50,000 rather than 100,000 took the
#: million-row import's peak from about 430 to 395 MB (benchmarks/import_speed.py), at the
#: same speed.
CHUNK_ROWS = 50_000


@dataclass(frozen=True)
class CollisionFile:
    """A collision CSV whose header has been read and mapped, ready to stream."""

    path: Path
    delimiter: str
    decimal: str
    mapping: dict[str, ColumnMap]


def stated_uncertainties(given: dict[str, str] | str | None) -> dict[str, tuple[float, bool]]:
    """A dataset's default standard uncertainties, by measured column: ``{"v_n_in": "± 3 %",
    "diameter": "0.01 mm"}`` or the same as text ``"v_n_in=± 3 %, diameter=0.01 mm"``
    (column names as a file's headers name them, or SI), each read by the one quantity
    parser (``parse_uncertainty``: absolute in the column's unit, or relative to each
    run's value). Returns ``{SI column: (u or fraction, relative)}``; a column that
    cannot carry an uncertainty (``COLLISION_UNCERTAIN``) is refused, naming those that can.
    """
    if not given:
        return {}
    if isinstance(given, str):
        pairs = [p.rpartition("=") for p in given.split(",") if p.strip()]
        for name, equals, text in pairs:
            if not equals or not name.strip() or not text.strip():
                raise ValidationError(
                    "uncertainty",
                    repr(f"{name}{equals}{text}".strip()),
                    "must be 'column=± u', e.g. 'v_n_in=± 3 %'",
                    parameter=True,
                )
        items = [(name.strip(), text.strip()) for name, _, text in pairs]
    else:
        items = list(given.items())
    by_base = {base_name(c): c for c in COLLISION_UNCERTAIN}
    stated: dict[str, tuple[float, bool]] = {}
    named: dict[str, str] = {}
    for name, text in items:
        column = name if name in COLLISION_UNCERTAIN else by_base.get(name.strip().lower())
        if column is None:
            raise ValidationError(
                "uncertainty",
                name,
                f"is not a column with an uncertainty (one of: {', '.join(by_base)})",
                parameter=True,
            )
        if column in stated:
            raise ValidationError(
                "uncertainty",
                repr(name),
                f"is given twice (as {named[column]!r} too): state each column once",
                parameter=True,
            )
        named[column] = name
        stated[column] = _stated(column, name, text)
    return stated


def _stated(column: str, name: str, text: str) -> tuple[float, bool]:
    """A stated uncertainty of ``column`` under the rules of its CSV cell ``u_…``: read by
    ``parse_uncertainty`` (finite, not subnormal, in the column's unit; a relative one of
    a Celsius temperature refused), a speed no faster than ``MAX_SPEED_M_S``, and a
    relative one at most 100 % (above, the value itself is not known)."""
    field = f"u({name})"
    u, relative = parse_uncertainty(text, unit_of_column(column), field)
    if relative and u > 1.0:
        rule = "is a relative uncertainty above 100 % of each value: give an absolute one"
        raise ValidationError(field, text, rule)
    if not relative and column in SPEEDS and u > MAX_SPEED_M_S:
        rule = f"is faster than {MAX_SPEED_M_S:g} m/s (beyond any impact apparatus)"
        raise ValidationError(field, text, rule)
    return u, relative


def fill_stated(values: dict[str, Any], stated: dict[str, tuple[float, bool]]) -> None:
    """Give each run the dataset's default uncertainty (``stated_uncertainties``) where its
    own ``u_`` cell is empty and its value is measured; a file's own cells win."""
    for column, (u, relative) in stated.items():
        measured = values.get(column)
        if measured is None:
            continue
        measured = np.asarray(measured, dtype=float)
        default = np.abs(measured) * u if relative else np.full(len(measured), u)
        default = np.where(np.isnan(measured), np.nan, default)
        own = values.get(uncertainty_column(column))
        values[uncertainty_column(column)] = (
            default if own is None else np.where(np.isnan(own), default, own)
        )


def file_sha256(path: Path) -> str:
    digest = hashlib.sha256()
    with path.open("rb") as handle:
        while chunk := handle.read(1 << 20):
            digest.update(chunk)
    return digest.hexdigest()


def estimate_rows(path: Path, sample_bytes: int = 1 << 16) -> int:
    """About how many rows the file holds: its size over the mean length of the lines in
    its first ``sample_bytes`` (a guess for deciding how to load, never for checking)."""
    size = path.stat().st_size
    with path.open("rb") as handle:
        sample = handle.read(sample_bytes)
    lines = sample.count(b"\n")
    if lines <= 1 or len(sample) >= size:
        return max(lines - 1, 0)
    return int(size / (len(sample) / lines))


def _header_of(mapping: dict[str, Any], column: str) -> str:
    return mapping[column].header if column in mapping else column


@dataclass
class Rows:
    """One chunk of rows being checked: SI arrays by column (every ``NUMERIC`` column,
    NaN = empty; required text columns as pandas Series, if given), ``cell(header,
    position)`` the file's text of a cell (for messages), where the chunk starts, and
    where its problems go. ``unreadable`` masks cells already refused as not numbers, so
    no later rule reports them again."""

    columns: dict[str, Any]
    cell: Callable[[str, int], str]
    mapping: dict[str, Any]
    first_row: int
    problems: Problems
    unreadable: dict[str, Any] = field(default_factory=dict)
    #: Rows with a refused cell: rules across columns (e, the angle) skip them, since a
    #: wrong cell would make them report a second, derived problem.
    broken: Any = None

    def refuse(
        self, mask: Any, problem: Callable[[int], ValidationError], *, derived: bool = False
    ) -> None:
        """Every position where ``mask`` holds breaks one rule: ``problem(position)``;
        a ``derived`` rule (from several cells) only where no cell was refused."""
        mask = np.asarray(mask, dtype=bool)
        if self.broken is None:
            self.broken = np.zeros(len(mask), dtype=bool)
            for unreadable in self.unreadable.values():
                self.broken |= unreadable
        if derived:
            mask = mask & ~self.broken
        if mask.any():
            self.problems.add(np.flatnonzero(mask), problem)
            self.broken |= mask

    def at(self, field: str, value: Any, rule: str) -> Callable[[int], ValidationError]:
        """A problem maker: ``value(position)`` shown, the row counted from the chunk."""
        return lambda pos: ValidationError(field, value(pos), rule, row=self.first_row + pos)


def check_chunk(
    frame: Any, raw: Any, mapping: dict[str, Any], first_row: int, problems: Problems
) -> None:
    """Every rule on one converted chunk (a DataFrame); its problems go to ``problems``."""
    columns = {c: frame[c] for c in REQUIRED if c in TEXT}
    columns.update({c: frame[c].to_numpy(dtype=float) for c in NUMERIC})
    cell = lambda h, p: str(raw[h].iloc[p]).strip()  # noqa: E731
    rows = Rows(columns, cell, mapping, first_row, problems, frame.attrs.get("unreadable", {}))
    check_values(rows)
    _check_text(frame, rows)


def check_values(rows: Rows) -> None:
    """The required, range, restitution and angle rules on one chunk's SI arrays; every
    broken row goes to ``rows.problems``."""
    columns, mapping = rows.columns, rows.mapping
    for column in REQUIRED:
        if column not in columns:
            continue
        values = columns[column]
        missing = np.isnan(values) if isinstance(values, np.ndarray) else values.isna()
        missing = np.asarray(missing)
        if column in rows.unreadable:
            missing &= ~rows.unreadable[column]
        header = _header_of(mapping, column)
        rows.refuse(missing, rows.at(header, lambda _: "(empty)", "is required"))
    target_in = columns.get("wall_v_n_in_m_s")
    free = np.isfinite(target_in) if target_in is not None else None
    for column in NUMERIC:
        rule = RULES.get(column)
        if rule is None:
            continue
        values = columns[column]
        if free is not None and column in RELATIVE_RULES:
            values = np.where(free, np.nan, values)  # judged on relative velocities below
        header = _header_of(mapping, column)
        shown = lambda pos, h=header: rows.cell(h, pos)  # noqa: E731
        rule_text = rule.text + _in_units(column, mapping)
        rows.refuse(~rule.holds_array(values), rows.at(header, shown, rule_text))
    for column in SPEEDS:
        header = _header_of(mapping, column)
        with np.errstate(invalid="ignore"):
            fast = np.abs(columns[column]) > MAX_SPEED_M_S
        shown = lambda pos, h=header: rows.cell(h, pos)  # noqa: E731
        too_fast = f"is faster than {MAX_SPEED_M_S:g} m/s (beyond any impact apparatus)"
        rows.refuse(fast, rows.at(header, shown, too_fast))
    v_n_in, v_n_out = columns["v_n_in_m_s"], columns["v_n_out_m_s"]
    if free is not None and free.any():
        v_n_in, v_n_out = _relative(rows, free)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        e = v_n_out / v_n_in
    rows.refuse(
        e > MAX_RESTITUTION,
        derived=True,
        problem=rows.at(
            "v_n_out / v_n_in",
            lambda pos: f"{e[pos]:.4g}",
            f"must be ≤ {MAX_RESTITUTION} (a rebound faster than the impact, beyond "
            "measurement error)",
        ),
    )
    _check_angle(rows)


def _relative(rows: Rows, free: Any) -> tuple[Any, Any]:
    """The normal velocities of a row with a free target, relative (docs/physics.md §9):
    the particle's speed towards the target minus the target's, before impact (must be
    > 0: they approach), and the particle's speed away plus the target's along the normal,
    after (must be ≥ 0: they separate; unknown without the target's rebound)."""
    columns = rows.columns
    target_out = columns.get("wall_v_n_out_m_s")
    if target_out is None:  # the target's rebound not measured: separation unknown
        target_out = np.full(len(free), np.nan)
    v_in = np.where(free, columns["v_n_in_m_s"] - columns["wall_v_n_in_m_s"], columns["v_n_in_m_s"])
    v_out = np.where(free, columns["v_n_out_m_s"] + target_out, columns["v_n_out_m_s"])
    checks = (
        ("v_n_in - wall_v_n_in", v_in, free & ~(v_in > 0),
         "must be > 0 (the particle and the target must approach)"),
        ("v_n_out + wall_v_n_out", v_out, free & (v_out < 0),
         "must be ≥ 0 (after impact the particle and the target separate)"),
    )  # fmt: skip
    for name, values, broken, rule in checks:
        shown = lambda pos, v=values: f"{v[pos]:.4g} m/s"  # noqa: E731
        rows.refuse(broken, rows.at(name, shown, rule), derived=True)
    return v_in, v_out


def _check_angle(rows: Rows) -> None:
    """A stated angle must agree with the velocities it describes (``ANGLE_TOLERANCE_RAD``)."""
    if "nominal_angle_rad" not in rows.mapping:
        return
    columns = rows.columns
    stated = columns["nominal_angle_rad"]
    derived = np.arctan2(columns["v_t_in_m_s"], columns["v_n_in_m_s"])
    with np.errstate(invalid="ignore"):
        off = np.abs(stated - derived) > ANGLE_TOLERANCE_RAD  # NaN (empty) compares False
    header = rows.mapping["nominal_angle_rad"].header

    def problem(pos: int) -> ValidationError:
        return ValidationError(
            header,
            rows.cell(header, pos),
            f"disagrees with atan(v_t_in / v_n_in) = {math.degrees(derived[pos]):.2f}° by more "
            f"than {math.degrees(ANGLE_TOLERANCE_RAD):g}° (check the column and its unit, or "
            "leave it empty: the angle is derived from the velocities)",
            row=rows.first_row + pos,
        )

    rows.refuse(off, problem, derived=True)


def _check_text(frame: Any, rows: Rows) -> None:
    """Names and notes obey ``granudb.vocabulary.text``'s rules (the same as every door).

    Found vectorized; each offender is re-checked by ``check_name``/``check_text``,
    whose message is the one every other door gives.
    """
    for column in TEXT:
        values = frame[column]
        present = values.notna()
        if not present.any():
            continue
        text = values.where(present, "").astype(str)
        if column == "notes":
            bad = text.str.contains(text_forbidden_pattern(), regex=True)
            bad |= text.str.len() > MAX_TEXT
        else:
            bad = text.str.contains(name_forbidden_pattern(), regex=True)
            bad |= (text.str.len() > MAX_NAME) | (text != text.str.strip())
        rows.refuse((bad & present).to_numpy(dtype=bool), _text_problem(rows, column, text))


def _text_problem(rows: Rows, column: str, text: Any) -> Callable[[int], ValidationError]:
    """The problem of the name or note at a position, as ``check_name``/``check_text``
    word it."""
    check = check_text if column == "notes" else check_name
    header = _header_of(rows.mapping, column)

    def problem(pos: int) -> ValidationError:
        try:
            check(column, text.iloc[pos])
        except ValidationError as exc:
            return ValidationError(header, exc.value, exc.rule, row=rows.first_row + pos)
        raise AssertionError(f"{column} {text.iloc[pos]!r} flagged but valid")

    return problem


def _in_units(column: str, mapping: dict[str, Any]) -> str:
    cmap = mapping.get(column)
    if cmap is None or (cmap.scale == 1.0 and cmap.offset == 0.0):
        return ""
    rule = RULES[column]
    if column == "nominal_angle_rad" and rule.maximum is not None:
        return " rad, i.e. below 90°"
    return f" {cmap.unit.pint} (in SI)"


def open_collision_file(
    path: Path,
    *,
    delimiter: str | None = None,
    decimal: str = ".",
    columns: dict[str, str] | None = None,
) -> CollisionFile:
    """Read and map the header; no database is touched.

    ``columns`` maps the file's own headers to granudb's columns (``{"speed [mm/s]":
    "v_n_in"}``, ``granudb.io.tables.check_column_mapping``).
    Everything here happens before ``store_collisions`` opens the write transaction, so a
    bad header is refused without ever holding the lock. Rows (their cell counts
    included) are checked as they are read, inside the transaction, which any refusal
    rolls back.
    """
    delimiter, decimal = csv_options(delimiter, decimal)
    path = Path(path)
    if not path.is_file():
        raise ValidationError("FILE", str(path), "is not a file")
    headers, delimiter = read_header(path, delimiter)
    csv_options(delimiter, decimal)  # a detected comma cannot be the decimal separator too
    try:
        mapping = map_headers(
            headers,
            NUMERIC,
            TEXT,
            table=path.name,
            aliases=ALIASES,
            required=REQUIRED,
            columns=columns,
        )
    except ValidationError:
        # A file that is not text or not a table is refused as such, as it always was,
        # rather than for the header that its bytes happen to make.
        try:
            check_shape(path, delimiter)
        except UnicodeDecodeError:
            raise ValidationError("FILE", path.name, "is not UTF-8 text") from None
        raise
    return CollisionFile(path, delimiter, decimal, mapping)
