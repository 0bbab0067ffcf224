"""Turning what a caller passes (SI numbers, or strings with units) into checked SI floats.

The command line and the Python API share these, so ``"12.7 mm"`` means the same in both,
and an error names the parameter (``diameter``), which the command line shows as its
option (``--diameter``).
"""

from __future__ import annotations

import difflib
import inspect
import math
import numbers
from collections.abc import Callable, Iterable, Mapping
from decimal import Decimal
from typing import Any, TypeVar

from granudb.errors import MissingInput, ValidationError
from granudb.io.units import parse_quantity, parse_uncertain_quantity
from granudb.vocabulary import check_value, unit_of_column
from granudb.vocabulary.rules import MAX_SPEED_M_S
from granudb.vocabulary.text import MAX_NAME, MAX_TEXT, check_name, check_text

F = TypeVar("F", bound=Callable[..., Any])


def shows_keywords(defaults: Mapping[str, Any]) -> Callable[[F], F]:
    """The decorated function takes these keywords as ``**options``; its signature
    (``help()``, ``inspect``, editors that ask at run time) shows each as a keyword argument
    with its default, after the positional parameters, so one list (a catalogue's
    specification, the DEM model's options) defines them for Python and the command line."""

    def decorate(function: F) -> F:
        signature = inspect.signature(function)
        own = [p for p in signature.parameters.values() if p.kind is not p.VAR_KEYWORD]
        positional = [p for p in own if p.kind is not p.KEYWORD_ONLY]
        shown = [
            inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default)
            for name, default in defaults.items()
        ]
        keywords = [p for p in own if p.kind is p.KEYWORD_ONLY]
        # mypy has no attribute __signature__ on a function; inspect.signature reads it
        function.__signature__ = signature.replace(parameters=[*positional, *shown, *keywords])  # type: ignore[attr-defined]
        return function

    return decorate


def known_options(given: Mapping[str, Any], allowed: Iterable[str], what: str) -> dict[str, Any]:
    """``given`` (a public function's ``**options``) if each is one of ``allowed``, else
    ``ValidationError`` naming it, ``what`` it is not, and the nearest name."""
    allowed = list(allowed)
    for name, value in given.items():
        if name not in allowed:
            near = difflib.get_close_matches(name, allowed, n=1)
            rule = f"is not {what}" + (f"; did you mean {near[0]}?" if near else "")
            raise ValidationError(name, repr(value)[:60], rule, parameter=True)
    return dict(given)


def _as_parameter(exc: ValidationError, parameter: str) -> ValidationError:
    return ValidationError(parameter, exc.value, exc.rule, row=exc.row, parameter=True)


def number(value: Any, parameter: str) -> float | None:
    """A bare number as a float: ``int``, ``float``, numpy's scalars, ``Decimal`` and
    ``Fraction``; ``None`` stays. A bool, a complex number, NaN or ±inf is refused by name,
    and so is anything that is not a number (text is parsed by ``quantity``, not here).

    >>> import numpy as np
    >>> number(np.float32(0.5), "velocity"), number(Decimal("12.7"), "diameter")
    (0.5, 12.7)
    """
    if value is None:
        return None
    if isinstance(value, bool) or type(value).__name__ in ("bool_", "bool"):
        raise ValidationError(parameter, value, "must be a number, not True/False", parameter=True)
    if isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
        raise ValidationError(parameter, value, "must be a real number", parameter=True)
    if not isinstance(value, numbers.Real | Decimal):
        raise ValidationError(
            parameter, repr(value)[:60], "must be a number or a quantity", parameter=True
        )
    result = float(value)
    if not math.isfinite(result):
        raise ValidationError(parameter, value, "must be a finite number", parameter=True)
    return result


def quantity(value: Any, column: str, parameter: str, *, check: bool = True) -> float | None:
    """``value`` in ``column``'s SI unit: a number is taken as SI, a string is parsed with
    its unit (``"190 GPa"``); the column's physical rule is checked (unless ``check`` is
    false). ``None`` stays.

    >>> quantity("4.5 cP", "viscosity_pa_s", "viscosity")
    0.0045
    """
    if value is None:
        return None
    result: float | None
    try:
        if isinstance(value, str):
            result = parse_quantity(value, unit_of_column(column), parameter)
        else:
            result = number(value, parameter)
        if check:
            check_value(column, result, field=parameter, shown=str(value))
    except ValidationError as exc:
        raise _as_parameter(exc, parameter) from None
    return result


def uncertain_quantity(
    value: Any, column: str, parameter: str, *, check: bool = True
) -> tuple[float | None, float | None]:
    """``(value, standard uncertainty)`` in ``column``'s SI unit: ``"23.6 ± 2 nm"``,
    ``"190 GPa ± 5 %"`` (relative), a number, or a ``(value, u)`` pair of SI numbers;
    without a ± the uncertainty is None (not given). The value's rule is checked as
    ``quantity`` checks it.

    >>> uncertain_quantity("0.3 m/s ± 3 %", "v_n_in_m_s", "velocity")
    (0.3, 0.009)
    """
    if isinstance(value, tuple | list) and len(value) == 2:
        central = quantity(value[0], column, parameter, check=check)
        u = number(value[1], f"{parameter} uncertainty")
        if u is not None and u < 0:
            raise ValidationError(parameter, value, "needs an uncertainty ≥ 0", parameter=True)
        return central, u
    if not isinstance(value, str):
        return quantity(value, column, parameter, check=check), None
    try:
        result, u = parse_uncertain_quantity(value, unit_of_column(column), parameter)
        if check:
            check_value(column, result, field=parameter, shown=value)
        _bounded_uncertainty(column, result, u, parameter, value)
    except ValidationError as exc:
        raise _as_parameter(exc, parameter) from None
    return result, u


#: A standard uncertainty more than this many times its (non-zero) value says nothing
#: about the value, and its square would overflow the propagation long before 1e308.
MAX_RELATIVE_U = 1000.0


def _bounded_uncertainty(
    column: str, value: float, u: float | None, field: str, shown: str
) -> None:
    """The bounds a ``u_…`` cell has, for a u given with its value: a speed's u at most
    ``MAX_SPEED_M_S`` (as a CSV cell's), and any u at most ``MAX_RELATIVE_U`` times a
    non-zero value."""
    if u is None:
        return
    if unit_of_column(column).suffix == "m_s" and u > MAX_SPEED_M_S:
        rule = f"has an uncertainty faster than {MAX_SPEED_M_S:g} m/s (beyond any impact apparatus)"
        raise ValidationError(field, shown, rule)
    if value != 0 and u > MAX_RELATIVE_U * abs(value):
        rule = f"has an uncertainty more than {MAX_RELATIVE_U:g} times the value"
        raise ValidationError(field, shown, rule)


def angle(value: Any, parameter: str = "angle") -> float:
    """An incidence angle in radians from ``"30 deg"``, ``"0.5 rad"`` or a number (rad),
    in [0°, 90°)."""
    radians = quantity(value, "incidence_angle_rad", parameter, check=False)
    assert radians is not None
    if not 0.0 <= radians < math.pi / 2:
        raise ValidationError(parameter, value, "must be ≥ 0° and < 90°", parameter=True)
    return radians


def angle_range(value: Any, parameter: str = "angle_range") -> tuple[float, float] | None:
    """``"20..60 deg"``, ``"20 deg..60 deg"`` or a (low, high) pair → radians."""
    if value is None:
        return None
    if isinstance(value, str):
        low, sep, high = value.partition("..")
        if not sep or not low.strip() or not high.strip():
            raise ValidationError(
                parameter, value, "must be LOW..HIGH, e.g. '10..40 deg'", parameter=True
            )
        low, high = low.strip(), high.strip()
        unit = high.lstrip("0123456789.eE+- ").strip()
        if unit and not low.lstrip("0123456789.eE+- ").strip():
            low = f"{low} {unit}"  # "20..60 deg": the unit applies to both ends
        pair = (low, high)
    else:
        try:
            pair = tuple(value)
        except TypeError:
            raise ValidationError(
                parameter, value, "must be LOW..HIGH or a (low, high) pair", parameter=True
            ) from None
        if len(pair) != 2:
            raise ValidationError(
                parameter, value, "must be LOW..HIGH or a (low, high) pair", parameter=True
            )
    low_rad, high_rad = (angle(v, parameter) for v in pair)
    if low_rad > high_rad:
        raise ValidationError(parameter, value, "must have LOW ≤ HIGH", parameter=True)
    return (low_rad, high_rad)


def missing(parameter: str, rule: str = "is required") -> MissingInput:
    """The refusal of a required parameter that was not given (``None``)."""
    return MissingInput(parameter, rule)


def name(value: Any, parameter: str, *, max_length: int = MAX_NAME) -> str:
    """A name from outside (a dataset, a version, a title): text that follows the shared
    name rules (``granudb.vocabulary.text``), refused naming the parameter."""
    try:
        return check_name(parameter, text(value, parameter), max_length=max_length)
    except ValidationError as exc:
        raise _as_parameter(exc, parameter) from None


def free_text(value: Any, parameter: str, *, max_length: int = MAX_TEXT) -> str:
    """Free text from outside (a description, a reason): the shared text rules
    (``granudb.vocabulary.text.check_text``), in NFC, refused naming the parameter."""
    try:
        return check_text(parameter, text(value, parameter), max_length=max_length)
    except ValidationError as exc:
        raise _as_parameter(exc, parameter) from None


def text(value: Any, parameter: str) -> str:
    """A name or text given from outside: a ``str``, refused by name if anything else."""
    if not isinstance(value, str):
        if value is None:
            raise missing(parameter)
        raise ValidationError(parameter, repr(value)[:60], "must be text", parameter=True)
    return value


def choice(value: Any, allowed: tuple[str, ...] | list[str], parameter: str) -> str:
    """One of ``allowed`` (text), refused by name with the list otherwise."""
    if not isinstance(value, str) or value not in allowed:
        shown = value if isinstance(value, str) else repr(value)[:60]
        raise ValidationError(
            parameter, shown, f"must be one of {', '.join(allowed)}", parameter=True
        )
    return value


def flag(value: Any, parameter: str) -> bool:
    """A yes/no filter: ``True`` or ``False`` (numpy's too), nothing else."""
    if isinstance(value, bool) or type(value).__name__ in ("bool_", "bool"):
        return bool(value)
    raise ValidationError(parameter, repr(value)[:60], "must be True or False", parameter=True)


def critical_stokes(value: Any) -> float:
    """The critical normal Stokes number St_c below which no rebound is expected."""
    number = quantity(value, "critical_stokes", "critical_stokes")
    if number is None:
        raise missing("critical_stokes")
    return number


def path(value: Any, parameter: str) -> str:
    """A file or folder path: text or ``os.PathLike``."""
    if isinstance(value, str) or hasattr(value, "__fspath__"):
        return str(value)
    if value is None:
        raise missing(parameter)
    raise ValidationError(parameter, repr(value)[:60], "must be a path", parameter=True)


def sequence(value: Any, parameter: str) -> list[Any]:
    """A list (or tuple) of values; a lone string is refused (it is not a list of
    names)."""
    if isinstance(value, list | tuple):
        return list(value)
    if value is None:
        raise missing(parameter)
    raise ValidationError(parameter, repr(value)[:60], "must be a list", parameter=True)


def dataset_ref(dataset: Any, version: Any = None) -> tuple[str, str | None]:
    """(name, version) of a dataset given as ``NAME`` or ``NAME@VERSION`` (split at the
    last ``@``: ``@`` is refused in new names and versions), or as ``NAME`` with ``version``
    explicitly (then taken as it is: a name from before the rule stays reachable).

    >>> dataset_ref("lab@2024"), dataset_ref("lab"), dataset_ref("a@b", "1")
    (('lab', '2024'), ('lab', None), ('a@b', '1'))
    """
    given = text(dataset, "dataset")
    if version is not None:
        return given, text(version, "version")
    name, _, version_text = given.rpartition("@") if "@" in given else (given, "", "")
    return name, version_text or None
