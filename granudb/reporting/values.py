"""Derived values for a table (the report's derived quantities, ``granudb pair``'s
terminal view), with the words a bare number or "—" would hide."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from granudb.reporting.format import display, display_uncertain, is_number
from granudb.reporting.verdicts import ROUGHNESS_WORDS, in_words

#: Quantities of (5.6)–(5.9) that need the fluid's pressure–viscosity coefficient.
_NEEDS_PRESSURE_COEFFICIENT = (
    "eta_hat_pa_inv",
    "piezoviscous_length_m",
    "traction_film_m",
    "friction_integral",
    "lubricated_friction",
)


def qualified_value(derived: Mapping[str, Any], name: str) -> str:
    """A derived value for a table, with the words a bare number or "—" would hide: a
    (5.8) above its bound is "outside the model's range, not used"; a value that could not
    be computed says why; state columns are said in words."""
    value = derived.get(name)
    state = derived.get("lubricated_friction_state")
    if name == "lubricated_friction" and state == "above_limit":
        return f"outside the model's range, not used ((5.8) gives {in_words(value)})"
    if name == "roughness_regime" and value in ROUGHNESS_WORDS:
        return ROUGHNESS_WORDS[str(value)]
    if is_number(value) and is_number(derived.get(f"u_{name}")):
        return display_uncertain(value, derived[f"u_{name}"], name)  # "951 ± 38"
    if is_number(value) or isinstance(value, bool | str):
        return display(value, name)
    if name == "yield_speed_m_s":
        return "not known (no yield stress)"
    if state == "dry" or derived.get("roughness_regime") == "dry":
        return "— (dry)"
    if name in _NEEDS_PRESSURE_COEFFICIENT and state == "no_pressure_coefficient":
        return "not computed (no pressure–viscosity coefficient)"
    return "not computed"


def interval_text(derived: Mapping[str, Any], name: str) -> str:
    """The 95 % coverage interval of a derived value as a table shows it ("95 %: 0.031 –
    0.204"), from its ``low95_``/``high95_`` columns; "" where it has none (no u stated).
    The method that gave it is ``method_text``'s."""
    low, high = derived.get(f"low95_{name}"), derived.get(f"high95_{name}")
    if not (is_number(low) and is_number(high)) or low != low or high != high:
        return ""
    return f"95 %: {display(low, name)} – {display(high, name)}"


#: What the propagation method of a scenario's u and intervals is said as.
METHOD_WORDS = "u and 95 % intervals: {method}"


def method_text(derived: Mapping[str, Any]) -> str:
    """How a scenario's u, 95 % intervals and verdict probabilities were obtained (its
    ``propagation_method``), in the words every table gives it; "" where no u is stated."""
    method = derived.get("propagation_method")
    return METHOD_WORDS.format(method=method) if isinstance(method, str) and method else ""
