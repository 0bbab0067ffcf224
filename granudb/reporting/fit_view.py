"""A fit's result as a person reads it: each value with its interval, or — where either
is missing — the reason in the fit's own words ("interval not determined: 4 runs, at
least 10 needed"), one line per quantity.

Every word comes from the fit's record (``granudb.analysis.fits``): the values and their
``_low``/``_high`` bounds, ``interval_reason`` and the parts of ``reason`` that name the
quantity's symbol, the model and why it was chosen, the interval method, resamples and
seed. ``granudb fit walton|restitution|gap-viscosity`` print these lines for each group
(a record shown vertically, so no number is ever cut at any terminal width); JSON and CSV
keep the record itself.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from granudb.reporting.format import interval, is_number, plus_minus
from granudb.reporting.groups import group_label


@dataclass(frozen=True)
class Quantity:
    """One fitted value of a fit's record: its label for people, its key, the keys of its
    interval's bounds, the symbol its reasons name it by, and the display scale/unit."""

    label: str
    key: str
    low: str
    high: str
    symbol: str
    scale: float = 1.0
    unit: str = ""


WALTON = (
    Quantity("β (rotational restitution)", "rotational_restitution",
             "rotational_restitution_low", "rotational_restitution_high", "β"),
    Quantity("μ_f (sliding friction)", "sliding_friction", "sliding_friction_low",
             "sliding_friction_high", "μ_f"),
    Quantity("ē (mean normal restitution)", "normal_restitution_mean", "normal_restitution_low",
             "normal_restitution_high", "ē"),
)  # fmt: skip
GAP = (
    Quantity("μ₀ (gap viscosity)", "gap_viscosity_pa_s", "gap_viscosity_low_pa_s",
             "gap_viscosity_high_pa_s", "μ₀", 1e3, "mPa·s"),
    Quantity("gap temperature", "gap_temperature_c", "gap_temperature_low_c",
             "gap_temperature_high_c", "temperature", 1.0, "°C"),
)  # fmt: skip


def _said(value: Any) -> str:
    """A text field of the record; "" where it has none (None, or NaN in a frame)."""
    return value.strip() if isinstance(value, str) else ""


def _parts(reason: Any) -> list[str]:
    return [p.strip() for p in _said(reason).split(";") if p.strip()]


def _about(fit: Mapping[str, Any], symbol: str) -> list[str]:
    """The parts of the fit's ``reason`` that name ``symbol``."""
    return [p for p in _parts(fit.get("reason")) if symbol in p]


def _without_interval(fit: Mapping[str, Any], symbol: str) -> str:
    """Why a value has no interval: the record's ``interval_reason``, else the part of
    its ``reason`` about the symbol's interval, else the whole reason."""
    own = _said(fit.get("interval_reason"))
    about = [p for p in _about(fit, symbol) if "interval" in p]
    found = [own] if own else [p.split(f"interval of {symbol} ", 1)[-1] for p in about]
    found = found or _parts(fit.get("reason")) or ["the fit gave no bounds"]
    return "; ".join(p.split("not determined: ", 1)[-1] for p in found)


def value_line(fit: Mapping[str, Any], quantity: Quantity) -> str:
    """``0.34 [0.30, 0.39]``, ``0.34 (interval not determined: 4 runs, at least 10
    needed)`` or ``not determined: all runs slide: β is not determined by sliding runs``."""
    value = fit.get(quantity.key)
    unit = f" {quantity.unit}" if quantity.unit else ""
    if not is_number(value):
        reasons = _about(fit, quantity.symbol) or _parts(fit.get("reason"))
        return "not determined: " + ("; ".join(reasons) or "the fit gave no value")
    low, high = fit.get(quantity.low), fit.get(quantity.high)
    scaled = [float(v) * quantity.scale if is_number(v) else v for v in (value, low, high)]
    if is_number(low) and is_number(high):
        text = interval(*scaled)
        if "not determined" not in text:
            return text.replace(" [", f"{unit} [", 1) if unit else text
        return f"{text.split(' (')[0]}{unit} ({text.split(' (', 1)[1]}"
    why = _without_interval(fit, quantity.symbol)
    stderr = fit.get(f"{quantity.key}_stderr")
    if is_number(stderr) and float(stderr) > 0:  # a least-squares standard error
        shown = plus_minus(scaled[0], float(stderr) * quantity.scale)
        return f"{shown}{unit} (standard error; interval not determined: {why})"
    return f"{scaled[0]:.3g}{unit} (interval not determined: {why})"


def _group(fit: Mapping[str, Any]) -> str:
    """``ex: steel/Zerodur glycerol-37``; a restitution fit (over the group's fluids) names
    no fluid."""
    label = (
        group_label(fit.get("particle"), fit.get("wall"), fit.get("fluid"))
        if "fluid" in fit
        else f"{fit.get('particle')}/{fit.get('wall')}"
    )
    dataset = _said(fit.get("dataset"))
    return f"{dataset}: {label}" if dataset else label


def method_line(fit: Mapping[str, Any]) -> str | None:
    """How the intervals were made, from the record, with their level unless the method
    says it itself (a posterior's "95 % … credible interval"; another percentage in it,
    such as a share u_r = 5.00 %, is not a level).

    >>> method_line({"interval_method": "bootstrap-t; widened (u_r = 5.00%)",
    ...              "confidence_level": 0.95})
    '95% bootstrap-t; widened (u_r = 5.00%)'
    >>> method_line({"interval_method": "posterior median and 95 % credible interval",
    ...              "confidence_level": 0.95})
    'posterior median and 95 % credible interval'
    """
    method = _said(fit.get("interval_method"))
    if not method:
        return None
    level = fit.get("confidence_level")
    said_itself = is_number(level) and re.search(
        rf"(?<![\d.]){round(float(level) * 100):d} ?%", method
    )
    stated = is_number(level) and not said_itself and "no interval" not in method
    said = f"{level:.0%} " if stated else ""
    count, seed = fit.get("bootstrap_resamples"), fit.get("bootstrap_seed")
    extra = ""
    if is_number(count) and "bootstrap" in method:  # a Bayesian fit draws, not resamples
        extra = f", {int(count)} resamples, seed {seed}"
    return f"{said}{method}{extra}"


def _count(fit: Mapping[str, Any], key: str) -> str:
    value = fit.get(key)
    return str(int(value)) if is_number(value) else "—"


def walton_lines(fit: Mapping[str, Any]) -> list[tuple[str, str]]:
    model, why = _said(fit.get("model")), _said(fit.get("model_reason"))
    said = (why if why.startswith(f"{model}:") else f"{model}: {why}") if model and why else model
    lines = [("model", said or f"none: {_said(fit.get('reason')) or 'too few runs'}")]
    lines += [(q.label, value_line(fit, q)) for q in WALTON]
    bound = fit.get("sliding_friction_lower_bound")
    if is_number(bound) and not is_number(fit.get("sliding_friction")):
        lines.append(("μ_f lower bound", f"μ_f ≥ {float(bound):.3g} (a bound, not a value)"))
    lines.append(("runs (sticking / sliding / all)", " / ".join(
        _count(fit, k) for k in ("n_sticking", "n_sliding", "n_runs"))))  # fmt: skip
    return lines


def restitution_lines(fit: Mapping[str, Any]) -> list[tuple[str, str]]:
    name = _said(fit.get("parameter_name")) or "parameter"
    symbol = {"fitted_critical_stokes": "St_c"}.get(name, name)
    lines = [("model", f"{_said(fit.get('model'))}: {_said(fit.get('formula'))}")]
    e_dry = Quantity("e_dry (dry restitution)", "e_dry", "e_dry_low", "e_dry_high", "e_dry")
    source = _said(fit.get("e_dry_source"))
    fixed = "(fixed)" in source and not is_number(fit.get("e_dry_low"))
    if fixed and is_number(fit.get("e_dry")):  # not fitted: no interval of the fit's own
        text = f"{float(fit['e_dry']):.3g} (interval not determined: not fitted, {source})"
    else:
        text = value_line(fit, e_dry) + (f"; e_dry: {source}" if source else "")
    lines.append((e_dry.label, text))
    lines.append((symbol, value_line(fit, Quantity(symbol, "parameter", "parameter_low",
                                                   "parameter_high", symbol))))  # fmt: skip
    lines.append(("runs (immersed / dry)", f"{_count(fit, 'n_runs')} / "
                                           f"{_count(fit, 'n_dry_runs')}"))  # fmt: skip
    return lines


def gap_lines(fit: Mapping[str, Any]) -> list[tuple[str, str]]:
    lines = [(q.label, value_line(fit, q)) for q in GAP]
    ambient = fit.get("ambient_viscosity_pa_s")
    if is_number(ambient):
        lines.insert(1, ("ambient μ", f"{float(ambient) * 1e3:.4g} mPa·s"))
    if _said(fit.get("method")):
        lines.append(("method", _said(fit.get("method"))))
    lines.append(("sliding runs used", _count(fit, "n_runs")))
    return lines


LINES = {"walton": walton_lines, "restitution": restitution_lines, "gap_viscosity": gap_lines}


def people_view(kind: str, fit: Mapping[str, Any]) -> tuple[str, list[tuple[str, str]]]:
    """(the group's heading, [(quantity, what a person reads)]) of one fit record; a
    Bayesian fit's record says whether its chain converged."""
    lines = LINES[kind](fit)
    method = method_line(fit)
    if method:
        lines.append(("intervals", method))
    if "converged" in fit and fit.get("converged") is not None:
        lines.append(("chain converged", "yes" if fit.get("converged") is True else "no"))
    return _group(fit), lines
