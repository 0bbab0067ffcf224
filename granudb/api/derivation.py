"""``granudb.derive()``: every derived column for a table of your own.

A table from outside passes one gate before the physics sees it, and is refused in one
line (column, value, rule, row) rather than computed wrongly:

- a column that looks like an input but is misnamed (``viscosity`` for
  ``viscosity_pa_s``) is refused with the name it should have, instead of being ignored
  (which would compute a dry collision); other extra columns are carried through;
- every required input missing is named at once;
- a cell must be a real, finite number in SI: text (``"12.7 mm"``), a bool, a complex
  number or ±inf is refused; NaN is "not given" for an optional input and refused for a
  required one;
- each input obeys the same physical rule as the catalogue and the collision import
  (``granudb.vocabulary.rules``): a negative roughness is refused, not used as positive;
- the options are checked as the command line checks them (``critical_stokes`` > 0).
"""

from __future__ import annotations

import difflib
import inspect
from collections.abc import Mapping
from typing import Any

from granudb.api import inputs
from granudb.errors import ValidationError
from granudb.lazy import numpy as np
from granudb.lazy import pandas as pd
from granudb.physics.derive import UNCERTAIN_INPUTS
from granudb.physics.derive import derive as derive_arrays
from granudb.scenario.refusals import physics_refusal
from granudb.vocabulary import RULES
from granudb.vocabulary.listings import units_of

_PARAMETERS = inspect.signature(derive_arrays).parameters
#: The keyword options of ``derive`` (numbers for the whole table, not columns).
OPTIONS = (
    "critical_stokes",
    "dry_friction",
    "gap_fraction",
    "dry_restitution",
    "monte_carlo",
    "monte_carlo_draws",
)
_NOT_OFFERED = (
    "limiting_shear_slope",
    "threads",
    "uncertainties",
    "correlated_materials",
    "one_speed",
)
#: Columns of standard uncertainties a table may have: ``u_<input>`` (same unit).
UNCERTAINTY_COLUMNS = tuple(f"u_{name}" for name in UNCERTAIN_INPUTS)
#: The input columns: every other parameter of the physics' ``derive``.
INPUTS = tuple(n for n in _PARAMETERS if n not in OPTIONS + _NOT_OFFERED)
#: The inputs without a default: a table must have them, with a value in every row.
REQUIRED = tuple(n for n in INPUTS if _PARAMETERS[n].default is inspect.Parameter.empty)
#: Option rules (the column rules come from the vocabulary).
_OPTION_COLUMNS = {"critical_stokes": "critical_stokes"}
_FRACTIONS = ("dry_friction", "gap_fraction", "dry_restitution")


def _rule_of(column: str) -> Any:
    """The vocabulary's rule for an input column: its own, or the material's or fluid's
    property it names (``wall_roughness_rms_m`` → ``roughness_rms_m``)."""
    if column in RULES:
        return RULES[column]
    for prefix in ("particle_", "wall_", "fluid_"):
        if column.startswith(prefix) and column.removeprefix(prefix) in RULES:
            stem = column.removeprefix(prefix)
            return None if stem.startswith(("v_", "omega")) else RULES[stem]
    return None


#: Velocities are signed (a free target may move either way): only finiteness is checked
#: here, and the approach rule by the physics on the relative velocity.
_RULES = {
    c: _rule_of(c) for c in INPUTS if not c.startswith(("v_", "omega", "wall_v_", "wall_omega"))
}


def _misnamed(columns: list[str]) -> None:
    """Refuse a column that is an input's near miss while that input is absent."""
    present = set(columns)
    for column in columns:
        if column in OPTIONS:
            raise ValidationError(
                column, "(a column)", "is an option of derive, not a column: pass it by keyword"
            )
        if column in _PARAMETERS or column in UNCERTAINTY_COLUMNS:
            continue
        absent = [n for n in INPUTS if n not in present]
        near = [n for n in absent if n.startswith(f"{column}_")]
        near += difflib.get_close_matches(column, absent, n=1, cutoff=0.8)
        if near:
            raise ValidationError(
                column, "(a column)", f"is not an input of derive; did you mean {near[0]}?"
            )


def _cells(frame: Any, column: str) -> Any:
    """A column as float64, refusing text, bools, complex numbers and ±inf by row."""
    series = frame[column]
    values = series.to_numpy()
    kind = values.dtype.kind
    if kind in "iuf":
        floats = values.astype(float)
    elif kind == "b":
        raise ValidationError(column, bool(values[0]), "must be a number, not True/False", row=1)
    elif kind == "c":
        raise ValidationError(column, str(complex(values[0])), "must be a real number", row=1)
    else:
        floats = np.empty(len(values))
        for row, cell in enumerate(values, start=1):
            if cell is None or (isinstance(cell, float) and cell != cell):
                floats[row - 1] = np.nan
                continue
            try:
                floats[row - 1] = inputs.number(cell, column)
            except ValidationError as exc:
                rule = exc.rule
                if isinstance(cell, str):
                    rule = "must be a number in SI; derive takes numbers, not text with units"
                raise ValidationError(column, cell, rule, row=row) from None
    bad = np.isinf(floats)
    if bad.any():
        row = int(np.flatnonzero(bad)[0])
        raise ValidationError(column, f"{floats[row]:g}", "must be a finite number", row=row + 1)
    return floats


def _checked(column: str, floats: Any) -> None:
    if column in REQUIRED and np.isnan(floats).any():
        row = int(np.flatnonzero(np.isnan(floats))[0])
        raise ValidationError(column, "NaN", "is required in every row", row=row + 1)
    rule = _RULES.get(column)
    if rule is not None:
        ok = rule.holds_array(floats)
        if not ok.all():
            row = int(np.flatnonzero(~ok)[0])
            raise ValidationError(column, f"{floats[row]:g}", rule.text, row=row + 1)


def _options(options: Mapping[str, Any]) -> dict[str, float]:
    checked = {}
    for option, value in options.items():
        if option not in OPTIONS:
            near = difflib.get_close_matches(option, OPTIONS, n=1)
            rule = "is not an option of derive" + (f"; did you mean {near[0]}?" if near else "")
            raise ValidationError(option, repr(value)[:60], rule, parameter=True)
        if option == "critical_stokes":
            checked[option] = inputs.critical_stokes(value)
            continue
        if option == "monte_carlo":
            if not isinstance(value, bool | np.bool_):
                rule = "must be True or False"
                raise ValidationError(option, repr(value)[:60], rule, parameter=True)
            checked[option] = bool(value)
            continue
        if option == "monte_carlo_draws":
            if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 0:
                rule = "must be a whole number of draws ≥ 0"
                raise ValidationError(option, repr(value)[:60], rule, parameter=True)
            checked[option] = int(value)
            continue
        number = inputs.number(value, option)
        if number is None:
            raise inputs.missing(option)
        if option in _FRACTIONS and not 0.0 <= number <= 1.0:
            raise ValidationError(option, value, "must be ≥ 0 and ≤ 1", parameter=True)
        checked[option] = number
    return checked


def derive(frame: Any, **options: Any) -> Any:
    """Every derived column for a DataFrame of your own collisions or scenarios.

    ``frame`` (a DataFrame, or a mapping of columns) has the SI input columns
    ``granudb.api.derivation.INPUTS`` (e.g. ``particle_density_kg_m3``,
    ``wall_youngs_modulus_pa``, ``diameter_m``, ``v_n_in_m_s``); the ten in ``REQUIRED``
    in every row, the others optional (NaN: not given). ``options`` are
    ``critical_stokes``, ``dry_friction``, ``gap_fraction`` and ``dry_restitution``, and,
    for the propagation, ``monte_carlo`` (False: first order everywhere, the method naming
    where its check failed) and ``monte_carlo_draws`` (the call's Monte Carlo budget,
    default 5,000,000 draws; docs/propagation.md).
    Columns ``u_<input>`` (``UNCERTAINTY_COLUMNS``: ``u_viscosity_pa_s``, …; ≥ 0, NaN:
    not given) are the inputs' standard uncertainties: then every continuous derived
    quantity gets its ``u_<column>`` and each verdict its probability
    (``probability_asperity_contact``, ``probability_rebound``, ``probability_yield``;
    docs/physics.md, "Uncertainty").
    Returns a copy with the derived columns added (their units in ``attrs["units"]``).
    Refuses what it cannot compute correctly (see the module's docstring).

    Examples
    --------
    >>> import granudb, pandas as pd
    >>> scenarios = pd.DataFrame({
    ...     "particle_density_kg_m3": [7780.0], "particle_youngs_modulus_pa": [190e9],
    ...     "particle_poisson_ratio": [0.27], "particle_roughness_rms_m": [23.6e-9],
    ...     "wall_density_kg_m3": [2540.0], "wall_youngs_modulus_pa": [91e9],
    ...     "wall_poisson_ratio": [0.24], "wall_roughness_rms_m": [15.5e-9],
    ...     "diameter_m": [0.0127], "v_n_in_m_s": [0.3]})
    >>> round(float(granudb.derive(scenarios)["reduced_modulus_pa"][0]) / 1e9, 2)
    65.64
    >>> granudb.derive(scenarios.rename(columns={"diameter_m": "diameter"}))
    Traceback (most recent call last):
    ...
    granudb.errors.ValidationError: diameter: (a column) is not an input of derive; did ...
    """
    if isinstance(frame, Mapping):
        frame = pd.DataFrame(dict(frame))
    if not isinstance(frame, pd.DataFrame):
        raise ValidationError(
            "frame", type(frame).__name__, "must be a pandas DataFrame", parameter=True
        )
    columns = [str(c) for c in frame.columns]
    _misnamed(columns)
    missing = [n for n in REQUIRED if n not in columns]
    if missing:
        raise ValidationError(
            "frame",
            "(a table)",
            f"lacks the required input column(s) {', '.join(missing)}",
            parameter=True,
        )
    checked: dict[str, Any] = _options(options)
    arrays = {}
    for column in INPUTS:
        if column in columns:
            arrays[column] = _cells(frame, column)
            _checked(column, arrays[column])
    uncertain = {}
    for column in UNCERTAINTY_COLUMNS:
        if column in columns:
            uncertain[column] = _cells(frame, column)
            bad = uncertain[column] < 0
            if bad.any():
                row = int(np.flatnonzero(bad)[0])
                value = f"{uncertain[column][row]:g}"
                raise ValidationError(column, value, "must be ≥ 0 (NaN: not given)", row=row + 1)
    if uncertain:
        checked["uncertainties"] = uncertain
    with physics_refusal():
        derived = derive_arrays(**arrays, **checked)
    added = pd.DataFrame(dict(derived), index=frame.index)
    kept = frame.drop(columns=[c for c in added.columns if c in frame.columns])
    out = pd.concat([kept, added], axis=1)
    out.attrs["units"] = units_of(out.columns)
    return out
