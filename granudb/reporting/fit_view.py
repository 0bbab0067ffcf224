"""A fit's result as a person reads it: each value with its interval, or — where either
is missing — the reason in the fit's own words ("interval not determined: 4 runs, at
least 10 needed"), one line per quantity.

Every word comes from the fit's record (``granudb.analysis.fits``): the values and their
``_low``/``_high`` bounds, ``interval_reason`` and the parts of ``reason`` that name the
quantity's symbol, the model and why it was chosen, the interval method, resamples and
seed. ``granudb fit walton|restitution|gap-viscosity`` print these lines for each group
(a record shown vertically, so no number is ever cut at any terminal width); the lab
report's fit tables (``granudb.reporting.tables``) put the same words in their cells, so
the command and the report never say a quantity two ways. JSON and CSV keep the record
itself.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from granudb.analysis.defaults import CONFIDENCE_LEVEL, DEFAULT_RESAMPLES
from granudb.reporting.format import display, interval, is_number, plus_minus
from granudb.reporting.groups import group_label

#: What a value the fit could not determine reads as, before the fit's reason.
NOT_DETERMINED = "not determined by these runs"


@dataclass(frozen=True)
class Quantity:
    """One fitted value of a fit's record: its label for people, its key, the keys of its
    interval's bounds, the symbol its reasons name it by, and the display scale/unit;
    ``method``: the key of its own interval method (a Walton parameter's), ``determined``:
    the key of the share of resamples that determined it, ``bound``: the key of a lower
    bound given where the value is not, said with ``bound_words``."""

    label: str
    key: str
    low: str
    high: str
    symbol: str
    scale: float = 1.0
    unit: str = ""
    method: str = ""
    determined: str = ""
    bound: str = ""
    bound_words: str = ""


WALTON = (
    Quantity("β (rotational restitution)", "rotational_restitution",
             "rotational_restitution_low", "rotational_restitution_high", "β",
             method="rotational_restitution_interval_method",
             determined="rotational_restitution_determined"),
    Quantity("μ_f (sliding friction)", "sliding_friction", "sliding_friction_low",
             "sliding_friction_high", "μ_f", method="sliding_friction_interval_method",
             determined="sliding_friction_determined", bound="sliding_friction_lower_bound",
             bound_words="Lower bound (2.10) at the largest Ψ_in"),
    Quantity("ē (mean normal restitution)", "normal_restitution_mean", "normal_restitution_low",
             "normal_restitution_high", "ē", method="normal_restitution_interval_method",
             determined="normal_restitution_determined"),
)  # fmt: skip
GAP = (
    Quantity("μ₀ (gap viscosity)", "gap_viscosity_pa_s", "gap_viscosity_low_pa_s",
             "gap_viscosity_high_pa_s", "μ₀", 1e3, "mPa·s"),
    Quantity("gap temperature", "gap_temperature_c", "gap_temperature_low_c",
             "gap_temperature_high_c", "temperature", 1.0, "°C"),
)  # fmt: skip
E_DRY = Quantity("e_dry (dry restitution)", "e_dry", "e_dry_low", "e_dry_high", "e_dry")
#: A restitution form's parameter: its symbol in the fit's reasons and in people's lines.
PARAMETER_SYMBOLS = {"fitted_critical_stokes": "St_c"}


def _said(value: Any) -> str:
    """A text field of the record; "" where it has none (None, or NaN in a frame)."""
    return value.strip() if isinstance(value, str) else ""


def _parts(reason: Any) -> list[str]:
    return [p.strip() for p in _said(reason).split(";") if p.strip()]


def _about(fit: Mapping[str, Any], symbol: str) -> list[str]:
    """The parts of the fit's ``reason`` that name ``symbol``."""
    return [p for p in _parts(fit.get("reason")) if symbol in p]


def _without_interval(fit: Mapping[str, Any], symbol: str) -> str:
    """Why a value has no interval: the record's ``interval_reason`` (its part about the
    symbol, "k: …", where it names each parameter's), else the part of its ``reason``
    about the symbol's interval, else the whole reason."""
    own = _parts(fit.get("interval_reason"))
    mine = [p.split(":", 1)[1].strip() for p in own if p.startswith(f"{symbol}:")]
    about = [p for p in _about(fit, symbol) if "interval" in p]
    found = mine or own or [p.split(f"interval of {symbol} ", 1)[-1] for p in about]
    found = found or _parts(fit.get("reason")) or ["the fit gave no bounds"]
    return "; ".join(p.split("not determined: ", 1)[-1] for p in found)


def _why_not(fit: Mapping[str, Any], symbol: str) -> str:
    """Why the fit gave no value for ``symbol``: the parts of its reason about the symbol,
    else the whole reason, in its own words (a leading "not determined: " said once)."""
    reasons = _about(fit, symbol) or _parts(fit.get("reason"))
    reasons = [p.removeprefix("not determined: ") for p in reasons]
    words = "; ".join(reasons) or "the fit gave no value"
    return words.replace("(sliding_friction_lower_bound is a bound)", "(a lower bound is shown)")


def _resampled(fit: Mapping[str, Any]) -> int:
    """The bootstrap's resample count behind the record (0: none ran, or a posterior)."""
    count = fit.get("bootstrap_resamples")
    if fit.get("fit_method") == "bayes" or not is_number(count):
        return 0
    return int(count)


def resamples_remark(fit: Mapping[str, Any], quantity: Quantity | None = None) -> str:
    """Beside an interval a bootstrap made with other than the default count (a large
    group under the resample rule, or a count asked for): that count and the seed;
    "" otherwise (the quantity's own interval not a bootstrap's included)."""
    count = _resampled(fit)
    method = _said(fit.get(quantity.method)) if quantity and quantity.method else ""
    method = method or _said(fit.get("interval_method"))
    if not count or count == DEFAULT_RESAMPLES or "bootstrap" not in method:
        return ""
    return f" ({count} resamples, seed {fit.get('bootstrap_seed')})"


def _remarks(fit: Mapping[str, Any], quantity: Quantity) -> str:
    """What follows a given value: the share of resamples that determined it, where not
    all did and its interval is the bootstrap's (a t-interval, asymptotic or refused one
    has no share), and its interval's resample count where not the default."""
    text = ""
    share = fit.get(quantity.determined) if quantity.determined else None
    own = _said(fit.get(quantity.method)) if quantity.method else ""
    if _resampled(fit) and "bootstrap" in own and is_number(share) and share < 0.995:
        text += f" (determined in {share:.0%} of resamples)"  # a bootstrap's share only
    bounded = is_number(fit.get(quantity.low)) and is_number(fit.get(quantity.high))
    return text + (resamples_remark(fit, quantity) if bounded else "")


def value_line(fit: Mapping[str, Any], quantity: Quantity) -> str:
    """A quantity's words, the same in ``granudb fit`` and in the report's table:
    ``0.34 [0.30, 0.39]``, ``4.1 [3.9, 4.3] mPa·s``, ``0.34 (interval not determined: 4
    runs, at least 10 needed)``, ``0.3399 ± 0.00003 (standard error; interval not
    determined: …)`` or ``not determined by these runs: all runs slide: β is not
    determined by sliding runs`` (with the lower bound where the record gives one).

    >>> value_line({"rotational_restitution": 0.3412, "rotational_restitution_low": 0.30,
    ...             "rotational_restitution_high": 0.39}, WALTON[0])
    '0.34 [0.30, 0.39]'
    >>> value_line({"gap_viscosity_pa_s": float("nan"), "reason": "2 runs: too few"}, GAP[0])
    'not determined by these runs: 2 runs: too few'
    """
    value = fit.get(quantity.key)
    unit = f" {quantity.unit}" if quantity.unit else ""
    if not is_number(value):
        text = f"{NOT_DETERMINED}: {_why_not(fit, quantity.symbol)}"
        bound = fit.get(quantity.bound) if quantity.bound else None
        if is_number(bound):
            text += (
                f". {quantity.bound_words}: {quantity.symbol} ≥ {float(bound):.3g} "
                "(a bound, not a value)"
            )
        return text
    low, high = fit.get(quantity.low), fit.get(quantity.high)
    scaled = [float(v) * quantity.scale if is_number(v) else v for v in (value, low, high)]
    if is_number(low) and is_number(high):
        text = interval(*scaled)
        if "not determined" not in text:
            return f"{text}{unit}" + _remarks(fit, quantity)
        return f"{text.split(' (')[0]}{unit} ({text.split(' (', 1)[1]}" + _remarks(fit, quantity)
    why = _without_interval(fit, quantity.symbol)
    stderr = fit.get(f"{quantity.key}_stderr")
    if is_number(stderr) and float(stderr) > 0:  # a least-squares standard error
        shown = plus_minus(scaled[0], float(stderr) * quantity.scale)
        text = f"{shown}{unit} (standard error; interval not determined: {why})"
    else:
        text = f"{scaled[0]:.3g}{unit} (interval not determined: {why})"
    return text + _remarks(fit, quantity)


def group_words(fit: Mapping[str, Any]) -> str:
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
    such as a share u_r = 5.00 %, is not a level) or gives none, and the resamples and
    seed of a bootstrap. The command's "intervals" line, and the report table's note.

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
    level = float(level) if is_number(level) else CONFIDENCE_LEVEL
    said_itself = re.search(rf"(?<![\d.]){round(level * 100):d} ?%", method)
    said = "" if said_itself or "no interval" in method else f"{level:.0%} "
    extra = ""
    if _resampled(fit) and "bootstrap" in method:  # a Bayesian fit draws, not resamples
        extra = f", {_resampled(fit)} resamples, seed {fit.get('bootstrap_seed')}"
    return f"{said}{method}{extra}"


def _count(fit: Mapping[str, Any], key: str) -> str:
    value = fit.get(key)
    return str(int(value)) if is_number(value) else "—"


def walton_model(fit: Mapping[str, Any]) -> str:
    """The Walton model chosen and why (the record's BIC words), with the share of
    resamples that chose it; or none and why."""
    model, why = _said(fit.get("model")), _said(fit.get("model_reason"))
    if not model:
        return f"none: {why or _said(fit.get('reason')) or 'too few runs'}"
    said = (why if why.startswith(f"{model}:") else f"{model}: {why}") if why else model
    support = fit.get(f"model_support_{model}")
    if is_number(support):
        said += f"; chosen in {support:.0%} of resamples"
    return said


def walton_runs(fit: Mapping[str, Any]) -> str:
    """``10 / 50 (of 60)``: runs on the sticking and the sliding line, of all the group's."""
    shown = " / ".join(_count(fit, k) for k in ("n_sticking", "n_sliding"))
    return f"{shown} (of {_count(fit, 'n_runs')})"


def restitution_model(fit: Mapping[str, Any]) -> str:
    """A restitution fit's form in words, from its record: name, formula, citation and
    why it was chosen ("threshold form e = … (Legendre …), the report's choice")."""
    words = f"{_said(fit.get('model')) or 'fitted'} form {_said(fit.get('formula'))}".strip()
    if _said(fit.get("citation")):
        words += f" ({_said(fit.get('citation'))})"
    if _said(fit.get("model_reason")):
        words += f", {_said(fit.get('model_reason'))}"
    return words


def restitution_parameter(fit: Mapping[str, Any]) -> Quantity:
    """The restitution form's parameter (St_c or k) as a quantity of the record."""
    name = _said(fit.get("parameter_name")) or "parameter"
    symbol = PARAMETER_SYMBOLS.get(name, name)
    return Quantity(symbol, "parameter", "parameter_low", "parameter_high", symbol)


def parameter_label(fit: Mapping[str, Any]) -> str:
    """``fitted St_c``, ``fitted k``: the restitution form's parameter as a table's column,
    a legend and a caption name it (its symbol, ``restitution_parameter``).

    >>> parameter_label({"parameter_name": "fitted_critical_stokes"}), parameter_label({})
    ('fitted St_c', 'fitted parameter')
    """
    return f"fitted {restitution_parameter(fit).symbol}"


def e_dry_words(fit: Mapping[str, Any]) -> str:
    """e_dry with its interval or why none, and where it comes from: ``0.948 [0.936,
    0.959]; source: fitted, bounded 0 ≤ e_dry ≤ 1``; a value fixed to the dry runs' mean
    has no interval of the fit's own."""
    source = _said(fit.get("e_dry_source"))
    value = fit.get("e_dry")
    bounded = is_number(fit.get("e_dry_low")) and is_number(fit.get("e_dry_high"))
    if not is_number(value):
        return value_line(fit, E_DRY)
    if "fixed" in source and not bounded:  # not fitted: no interval of the fit's own
        text = f"{float(value):.3g} (interval not determined: not fitted)"
    else:
        text = value_line(fit, E_DRY)
    return f"{text}; source: {source}" if source else text


def stokes_number(fit: Mapping[str, Any]) -> str:
    """Which Stokes number the restitution fit's e(St) is of, as its record says."""
    return _said(fit.get("stokes_number"))


def restitution_runs(fit: Mapping[str, Any]) -> str:
    """``40 immersed, 5 dry``."""
    return f"{_count(fit, 'n_runs')} immersed, {_count(fit, 'n_dry_runs')} dry"


def gap_runs(fit: Mapping[str, Any]) -> str:
    """The sliding runs the gap viscosity fit used."""
    return _count(fit, "n_runs")


def gap_method(fit: Mapping[str, Any]) -> str:
    """How μ₀ was fitted, as the record says ("least squares of (5.8) …"); "" if it
    does not."""
    return _said(fit.get("method"))


def ambient_viscosity(fit: Mapping[str, Any]) -> str:
    """The mean viscosity of the group's fluid at its runs' states, ``3.1 mPa·s``."""
    return display(fit.get("ambient_viscosity_pa_s"), "viscosity_pa_s")


def walton_lines(fit: Mapping[str, Any]) -> list[tuple[str, str]]:
    lines = [("model", walton_model(fit))]
    lines += [(q.label, value_line(fit, q)) for q in WALTON]
    lines.append(("runs (sticking / sliding)", walton_runs(fit)))
    return lines


def restitution_lines(fit: Mapping[str, Any]) -> list[tuple[str, str]]:
    parameter = restitution_parameter(fit)
    return [
        ("model", restitution_model(fit)),
        (E_DRY.label, e_dry_words(fit)),
        (parameter.label, value_line(fit, parameter)),
        ("runs", restitution_runs(fit)),
    ] + ([("Stokes number", stokes_number(fit))] if stokes_number(fit) else [])


def gap_lines(fit: Mapping[str, Any]) -> list[tuple[str, str]]:
    lines = [(GAP[0].label, value_line(fit, GAP[0])), ("ambient μ", ambient_viscosity(fit))]
    lines.append((GAP[1].label, value_line(fit, GAP[1])))
    if gap_method(fit):
        lines.append(("method", gap_method(fit)))
    lines.append(("sliding runs used", gap_runs(fit)))
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
    return group_words(fit), lines
