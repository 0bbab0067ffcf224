"""Units read from granudb's own table must mean exactly what Pint reads (issue 17).

``granudb.io.units`` converts expressions made only of ``KNOWN_UNITS`` without Pint. Every
spelling that table accepts (each unit, each SI prefix on each prefixable unit) and the
usual compound expressions are converted here both ways, to every stored unit: the same
scale and offset to 1e-12, or the same refusal, word for word. And the quantities people
type most, through parse_quantity and ``granudb pair``, never import Pint.
"""

from __future__ import annotations

import math
import subprocess
import sys

import pytest

from granudb.io.units import (
    UnitSyntaxError,
    _fast_conversion,
    _pint_conversion,
    check_unit_expression,
    parse_quantity,
)
from granudb.vocabulary.units import (
    KNOWN_UNITS,
    NOT_PREFIXED,
    SI_PREFIXES,
    UNITS,
    known_unit,
    si_value,
)


def _spellings() -> list[str]:
    names = list(KNOWN_UNITS)
    for symbol, unit in KNOWN_UNITS.items():
        if unit.prefixable:
            names += [
                prefix + symbol for prefix in SI_PREFIXES if prefix + symbol not in NOT_PREFIXED
            ]
    return names


SPELLINGS = _spellings()
COMPOUNDS = [
    "kg/m**3",
    "g/cm**3",
    "kg m**-3",
    "kg/L",
    "g/mL",
    "m/s",
    "mm/s",
    "m s**-1",
    "km/h",
    "m/s/s",
    "kg/m s",
    "kg/m*s",
    "rad/s",
    "deg/s",
    "mrad/ms",
    "mPa*s",
    "Pa s",
    "Pa*s",
    "N*m",
    "uN m",
    "1/Pa",
    "1/GPa",
    "1/bar",
    "1/s",
    "s**-1",
    "percent/s",
    "Hz*s",
    "m**2",
    "m**-2",
    "MPa**2/GPa",
    "deg*m/s",
    "dimensionless",
]


def _outcome(convert, spelled: str, suffix: str) -> tuple[str, object]:
    try:
        return "value", convert(spelled, suffix)
    except UnitSyntaxError as exc:
        return "refused", str(exc)


@pytest.mark.parametrize("spelled", SPELLINGS + COMPOUNDS)
def test_every_known_unit_converts_and_refuses_as_pint_does(spelled: str) -> None:
    assert si_value(spelled) is not None, spelled  # read from the table, not by Pint
    for suffix in UNITS:
        fast = _outcome(lambda s, to: _fast_conversion(s, UNITS[to]), spelled, suffix)
        slow = _outcome(_pint_conversion, spelled, suffix)
        assert fast[0] == slow[0], (spelled, suffix, fast, slow)
        if fast[0] == "refused":
            assert fast[1] == slow[1], (spelled, suffix)
        else:
            (scale, offset), (pint_scale, pint_offset) = fast[1], slow[1]
            assert scale == pytest.approx(pint_scale, rel=1e-12, abs=0.0), (spelled, suffix)
            assert offset == pytest.approx(pint_offset, rel=1e-12, abs=0.0), (spelled, suffix)


def test_the_table_covers_every_stored_unit_and_the_usual_spellings() -> None:
    for unit in UNITS.values():
        assert si_value(check_unit_expression(unit.pint)) is not None, unit.pint
    for typed in ("12.7 mm", "0.3 m/s", "30 deg", "190 GPa", "4.5 cP", "20 degC", "10 Hz"):
        assert si_value(check_unit_expression(typed.split(" ", 1)[1])) is not None, typed


@pytest.mark.parametrize(
    "spelled",
    ["hbar", "m**(1/2)", "cSt * 0.96 g/cm**3", "degC/s", "K**2", "degF", "ft", "(m/s)", "2 m"],
)
def test_anything_else_is_left_to_pint(spelled: str) -> None:
    assert si_value(spelled) is None


def test_an_exact_spelling_wins_over_a_prefix() -> None:
    assert known_unit("Pa")[0] == "pascal"  # not peta-annum
    assert known_unit("min")[0] == "minute"
    assert known_unit("cP")[0] == "centipoise"
    assert known_unit("hbar") is None  # Pint's ħ, not a hectobar


@pytest.mark.parametrize(
    ("text", "unit", "expected"),
    [
        ("293.15 K", "c", 20.0),
        ("20 degC", "c", 20.0),
        ("-40 °C", "c", -40.0),
        ("0 K", "c", -273.15),
        ("4.5 cP", "pa_s", 0.0045),
        ("10 Hz", "rad_s", 20 * math.pi),
        ("600 rpm", "rad_s", 20 * math.pi),
        ("45 %", "fraction", 0.45),
        ("7.78 g/cm^3", "kg_m3", 7780.0),
    ],
)
def test_typed_quantities_are_stored_as_before(text: str, unit: str, expected: float) -> None:
    assert parse_quantity(text, unit, "--x") == pytest.approx(expected, rel=1e-12, abs=1e-12)


def test_the_usual_quantities_and_granudb_pair_import_no_pint(tmp_path) -> None:
    db = tmp_path / "g.sqlite"
    code = (
        "import sys\n"
        "from granudb.io.units import parse_quantity\n"
        "for text, unit in [('12.7 mm', 'm'), ('0.3 m/s', 'm_s'), ('30 deg', 'rad'),\n"
        "                   ('190 GPa', 'pa'), ('4.5 cP', 'pa_s'), ('20 degC', 'c')]:\n"
        "    parse_quantity(text, unit, 'x')\n"
        "from granudb.cli.main import app\n"
        "args = ['pair', 'steel', 'Zerodur', '--diameter', '12.7 mm', '--velocity',\n"
        "        '0.3 m/s', '--fluid', 'water', '--angle', '30 deg', '--format', 'json',\n"
        "        '--db', sys.argv[1]]\n"
        "try:\n    app(args)\nexcept SystemExit as exc:\n    assert not exc.code, exc.code\n"
        "heavy = [m for m in ('pint', 'pandas', 'scipy', 'matplotlib') if m in sys.modules]\n"
        "print('HEAVY=' + ','.join(heavy))"
    )
    run = [sys.executable, "-c", code, str(db)]
    subprocess.run(run, capture_output=True, text=True, check=True)  # creates and seeds
    out = subprocess.run(run, capture_output=True, text=True, check=True)
    assert '"particle"' in out.stdout
    assert out.stdout.strip().splitlines()[-1] == "HEAVY="
