"""How often each fit's nominal 95 % interval holds the truth, on synthetic sets generated
by ``granudb.analysis.synthetic`` (shared by ``benchmarks/fit_coverage.py`` and the quick
tests in ``tests/analysis/test_interval_coverage.py``; imports no test module)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import numpy as np

from granudb.analysis import fits
from granudb.analysis.restitution_fit import PARAMETER_NAMES, restitution_curve
from granudb.analysis.synthetic import TRUTH as STATED_TRUTH
from granudb.analysis.synthetic import (
    U_REL,
    measured,
    restitution_runs,
    sliding_measured,
    sliding_runs,
    walton_frame,
    walton_measured,
)
from granudb.lazy import pandas as pd

BOUND = 0.90  # issue 23: a nominal 95 % interval covers the truth at least 90 % of the time
SIZES = (3, 5, 10, 30, 100)


@dataclass(frozen=True)
class Case:
    """One parameter of one fit on one kind of synthetic set."""

    name: str
    truth: float
    make: Callable[[int, int], object]  # (n, seed) → frame
    fit: Callable[[object, int | None], dict]  # (frame, resamples) → the group's row
    keys: tuple[str, str, str]  # value, low, high
    most_sets: int | None = None  # a slow fit (the Bayesian option) runs at most this many
    sizes: tuple[int, ...] | None = None  # the only sizes this case runs at (None: any)


def _walton(frame, resamples):
    [row] = fits.walton(frame, resamples=resamples)
    return row


def _restitution(model, method="bootstrap"):
    def fit(frame, resamples):
        [row] = fits.restitution(frame, model, method=method)
        return row

    return fit


def _walton_bayes(frame, resamples):
    [row] = fits.walton(frame, resamples=resamples, method="bayes")
    return row


def _gap(frame, resamples):
    [row] = fits.gap_viscosity(frame, {}, resamples=resamples)
    return row


def _restitution_at(model, switch):
    def fit(frame, resamples):
        [row] = fits.restitution(frame, model, resamples=resamples, asymptotic_from=switch)
        return row

    return fit


def large_sets(model: str, stated: bool, dry: int) -> Callable[[int, int], object]:
    """Sets for the restitution fit's large-n cells (issue 36): runs on ``model``'s curve
    (``LARGE_TRUTH``; St_n geometric from 15 to 3000), measured through speeds with
    U_REL relative noise, that u stated when ``stated`` (else scatter 0.02 on e, as
    ``restitution_runs``), and ``dry`` dry runs (e_dry with scatter 0.01)."""

    def make(n, seed):
        if not stated:
            return restitution_runs(0.97, model, LARGE_TRUTH[model], n=n, seed=seed, dry=dry)
        rng = np.random.default_rng(seed)
        st_true = np.geomspace(15, 3000, n)
        v_in_true = st_true * 1e-3  # m/s; St_n ∝ v_n,in at a fixed sphere and fluid
        e_true = restitution_curve(model, st_true, 0.97, LARGE_TRUTH[model])
        v_in = v_in_true * (1 + U_REL * rng.standard_normal(n))
        v_out = e_true * v_in_true * (1 + U_REL * rng.standard_normal(n))
        immersed = pd.DataFrame({
            "dataset": "d", "particle": "steel", "wall": "Zerodur", "fluid": "glycerol-37",
            "v_n_in_m_s": v_in, "v_n_out_m_s": v_out, "u_v_n_in_m_s": U_REL * v_in,
            "u_v_n_out_m_s": U_REL * np.abs(v_out),
            "normal_stokes_number": st_true * v_in / v_in_true,
            "normal_restitution": v_out / v_in,
        })  # fmt: skip
        if not dry:
            return immersed
        dry_runs = pd.DataFrame({
            "dataset": "d", "particle": "steel", "wall": "Zerodur", "fluid": None,
            "normal_stokes_number": np.nan, "normal_restitution": 0.97 + rng.normal(0, 0.01, dry),
        })  # fmt: skip
        return pd.concat([immersed, dry_runs], ignore_index=True)

    return make


#: The large-n cells' truth (e_dry 0.97): St_c of the threshold form, k of the exponential.
LARGE_TRUTH = {"threshold": 10.0, "exponential": 35.0}
#: The large-n cells run at this size only; the fit's switch stays its default (10,000).
LARGE_N = 10_000


def large_cases(n: int = LARGE_N, switch: int = LARGE_N) -> list[Case]:
    """The restitution fit's asymptotic-interval cells at ``n`` runs (switch ``switch``):
    both forms, with and without stated u, e_dry fitted or from 4 or 50 dry runs."""
    found = []
    for model in ("threshold", "exponential"):
        fit = _restitution_at(model, switch)
        for stated in (False, True):
            for dry in (0, 4, 50):
                make = large_sets(model, stated, dry)
                words = (f"large n: restitution {model}, "
                         f"{f'stated u ({U_REL:.0%})' if stated else 'no stated u'}, "
                         + (f"e_dry of {dry} dry runs" if dry else "e_dry fitted"))  # fmt: skip
                name = PARAMETER_NAMES[model]
                found.append(Case(f"{words}: {name}", LARGE_TRUTH[model], make, fit, PARAMETER,
                                  sizes=(n,)))  # fmt: skip
                if not dry:
                    found.append(Case(f"{words}: e_dry", 0.97, make, fit, E_DRY, sizes=(n,)))
    return found


def _walton_keys(name):
    return (name, f"{name}_low", f"{name}_high")


def _split(n, seed):
    return walton_frame(n, spin=30.0, seed=seed)


def _threshold_runs(n, seed):
    return restitution_runs(0.97, "threshold", 10.0, n=n, seed=seed)


def _exponential_runs(n, seed):
    return restitution_runs(0.97, "exponential", 35.0, n=n, seed=seed)


def _threshold_dry(dry):
    def make(n, seed):
        return restitution_runs(0.97, "threshold", 10.0, n=n, seed=seed, dry=dry)

    return make


_THRESHOLD_DRY_4, _THRESHOLD_DRY_50 = _threshold_dry(4), _threshold_dry(50)
#: Threshold runs measured through speeds with U_REL noise, that u stated, and dry runs;
#: exponential runs (scatter 0.02 on e) with dry runs (issue 36: e_dry not held fixed).
_STATED_DRY_4, _STATED_DRY_50 = large_sets("threshold", True, 4), large_sets("threshold", True, 50)
_EXPONENTIAL_DRY_4, _EXPONENTIAL_DRY_50 = (
    large_sets("exponential", False, 4),
    large_sets("exponential", False, 50),
)


def _stated_runs(n, seed):
    """Runs measured through speeds with a stated relative u (issue 27), which the
    restitution fit's resamples perturb."""
    return measured(seed, n=n)


def _walton_stated(n, seed):
    """Split runs measured through speeds with 4 mm/s noise, that u stated (issue 27)."""
    return walton_measured(n, seed=seed)


def _gap_stated(n, seed):
    """Gap-viscosity runs with 2 % speed noise, that u stated (issue 27)."""
    return sliding_measured(seed, n=n)


_THRESHOLD, _EXPONENTIAL = _restitution("threshold"), _restitution("exponential")
_THRESHOLD_BAYES = _restitution("threshold", "bayes")
_EXPONENTIAL_BAYES = _restitution("exponential", "bayes")
#: Sets per cell of the Bayesian option's rows (a posterior costs 1–3 s CPU a set; 5–6 s
#: at 10,000 runs with stated u).
BAYES_SETS = 200
PARAMETER = ("parameter", "parameter_low", "parameter_high")
E_DRY = ("e_dry", "e_dry_low", "e_dry_high")
CASES = [
    Case(
        "Walton β, split data (β₀ = 0.34)",
        0.34,
        _split,
        _walton,
        _walton_keys("rotational_restitution"),
    ),
    Case(
        "Walton μ_f, split data (μ_f = 0.11)",
        0.11,
        _split,
        _walton,
        _walton_keys("sliding_friction"),
    ),
    Case(
        "Walton ē, split data (e = 0.97)",
        0.97,
        _split,
        _walton,
        _walton_keys("normal_restitution_mean")[:1]
        + ("normal_restitution_low",)
        + ("normal_restitution_high",),
    ),
    Case(
        "Walton β, all sticking (β₀ = −0.15)",
        -0.15,
        lambda n, s: walton_frame(n, beta=-0.15, psi_range=(0.02, 0.8), seed=s),
        _walton,
        _walton_keys("rotational_restitution"),
    ),
    Case(
        "Walton μ_f, all sliding",
        0.11,
        lambda n, s: walton_frame(n, psi_range=(0.75, 2.5), seed=s),
        _walton,
        _walton_keys("sliding_friction"),
    ),
    Case(
        "restitution threshold St_c = 10",
        10.0,
        _threshold_runs,
        _THRESHOLD,
        PARAMETER,
    ),
    Case(
        "restitution threshold e_dry = 0.97",
        0.97,
        _threshold_runs,
        _THRESHOLD,
        E_DRY,
    ),
    Case(
        "restitution threshold St_c, e_dry of 4 dry runs",
        10.0,
        _THRESHOLD_DRY_4,
        _THRESHOLD,
        PARAMETER,
    ),
    Case(
        "restitution threshold St_c, e_dry of 50 dry runs",
        10.0,
        _THRESHOLD_DRY_50,
        _THRESHOLD,
        PARAMETER,
    ),
    Case(
        f"restitution threshold St_c, stated u ({U_REL:.0%}), e_dry of 4 dry runs",
        10.0,
        _STATED_DRY_4,
        _THRESHOLD,
        PARAMETER,
    ),
    Case(
        f"restitution threshold St_c, stated u ({U_REL:.0%}), e_dry of 50 dry runs",
        10.0,
        _STATED_DRY_50,
        _THRESHOLD,
        PARAMETER,
    ),
    Case(
        "restitution exp. k, e_dry of 4 dry runs",
        35.0,
        _EXPONENTIAL_DRY_4,
        _EXPONENTIAL,
        PARAMETER,
    ),
    Case(
        "restitution exp. k, e_dry of 50 dry runs",
        35.0,
        _EXPONENTIAL_DRY_50,
        _EXPONENTIAL,
        PARAMETER,
    ),
    Case(
        "restitution exponential k = 35",
        35.0,
        _exponential_runs,
        _EXPONENTIAL,
        PARAMETER,
    ),
    Case(
        "restitution exponential e_dry = 0.97",
        0.97,
        _exponential_runs,
        _EXPONENTIAL,
        E_DRY,
    ),
    Case(
        f"restitution exp. k = 35, with stated u ({U_REL:.0%})",
        STATED_TRUTH["parameter"],
        _stated_runs,
        _EXPONENTIAL,
        PARAMETER,
    ),
    Case(
        f"restitution exp. e_dry = 0.95, stated u ({U_REL:.0%})",
        STATED_TRUTH["e_dry"],
        _stated_runs,
        _EXPONENTIAL,
        E_DRY,
    ),
    Case(
        "Walton β, split, stated u (4 mm/s)",
        0.34,
        _walton_stated,
        _walton,
        _walton_keys("rotational_restitution"),
    ),
    Case(
        "Walton μ_f, split, stated u (4 mm/s)",
        0.11,
        _walton_stated,
        _walton,
        _walton_keys("sliding_friction"),
    ),
    Case(
        "Walton ē, split, stated u (4 mm/s)",
        0.97,
        _walton_stated,
        _walton,
        ("normal_restitution_mean", "normal_restitution_low", "normal_restitution_high"),
    ),
    Case(
        "Bayes: Walton β, split data (β₀ = 0.34)",
        0.34,
        _split,
        _walton_bayes,
        _walton_keys("rotational_restitution"),
        BAYES_SETS,
    ),
    Case(
        "Bayes: Walton μ_f, split data (μ_f = 0.11)",
        0.11,
        _split,
        _walton_bayes,
        _walton_keys("sliding_friction"),
        BAYES_SETS,
    ),
    Case(
        "Bayes: Walton ē, split data (e = 0.97)",
        0.97,
        _split,
        _walton_bayes,
        ("normal_restitution_mean", "normal_restitution_low", "normal_restitution_high"),
        BAYES_SETS,
    ),
    Case(
        "Bayes: restitution threshold St_c = 10",
        10.0,
        _threshold_runs,
        _THRESHOLD_BAYES,
        PARAMETER,
        BAYES_SETS,
    ),
    Case(
        "Bayes: restitution exponential k = 35",
        35.0,
        _exponential_runs,
        _EXPONENTIAL_BAYES,
        PARAMETER,
        BAYES_SETS,
    ),
    Case(
        "Bayes: Walton μ_f, split, stated u (4 mm/s)",
        0.11,
        _walton_stated,
        _walton_bayes,
        _walton_keys("sliding_friction"),
        BAYES_SETS,
    ),
    Case(
        "Bayes: Walton β, split, stated u (4 mm/s)",
        0.34,
        _walton_stated,
        _walton_bayes,
        _walton_keys("rotational_restitution"),
        BAYES_SETS,
    ),
    Case(
        f"Bayes: restitution exp. k = 35, stated u ({U_REL:.0%})",
        STATED_TRUTH["parameter"],
        _stated_runs,
        _EXPONENTIAL_BAYES,
        PARAMETER,
        BAYES_SETS,
    ),
    Case(
        f"Bayes: restitution exp. e_dry = 0.95, stated u ({U_REL:.0%})",
        STATED_TRUTH["e_dry"],
        _stated_runs,
        _EXPONENTIAL_BAYES,
        E_DRY,
        BAYES_SETS,
    ),
    Case(
        "Bayes: restitution threshold St_c, e_dry of 4 dry runs",
        10.0,
        _THRESHOLD_DRY_4,
        _THRESHOLD_BAYES,
        PARAMETER,
        BAYES_SETS,
    ),
    Case(
        "Bayes: restitution threshold St_c, e_dry of 50 dry runs",
        10.0,
        _THRESHOLD_DRY_50,
        _THRESHOLD_BAYES,
        PARAMETER,
        BAYES_SETS,
    ),
    Case(
        f"Bayes: restitution threshold St_c, stated u ({U_REL:.0%}), e_dry of 4 dry runs",
        10.0,
        _STATED_DRY_4,
        _THRESHOLD_BAYES,
        PARAMETER,
        BAYES_SETS,
    ),
    Case(
        f"Bayes: restitution threshold St_c, stated u ({U_REL:.0%}), e_dry of 50 dry runs",
        10.0,
        _STATED_DRY_50,
        _THRESHOLD_BAYES,
        PARAMETER,
        BAYES_SETS,
    ),
    Case(
        "gap viscosity μ₀ = 1.6 mPa·s",
        1.6e-3,
        lambda n, s: sliding_runs(1.6e-3, n=n, seed=s),
        _gap,
        ("gap_viscosity_pa_s", "gap_viscosity_low_pa_s", "gap_viscosity_high_pa_s"),
    ),
    Case(
        "stated u (2 %): gap viscosity μ₀",
        1.6e-3,
        _gap_stated,
        _gap,
        ("gap_viscosity_pa_s", "gap_viscosity_low_pa_s", "gap_viscosity_high_pa_s"),
    ),
    *large_cases(),
]


@dataclass
class Tally:
    sets: int = 0
    fitted: int = 0  # a value was given
    given: int = 0  # an interval was given
    hits: int = 0
    zero_width: int = 0
    reason: str = ""
    methods: set = field(default_factory=set)  # short names of the methods that gave them

    @property
    def method(self) -> str:
        return "+".join(sorted(self.methods)) or "-"

    @property
    def coverage(self) -> float:
        return self.hits / self.given if self.given else math.nan


def tally(case: Case, n: int, sets: int, *, resamples: int | None = None, first_seed: int = 0):
    """Coverage of ``case`` over ``sets`` synthetic sets of ``n`` runs."""
    out = Tally()
    for row in rows(case, n, sets, resamples, first_seed):
        value, low, high = (row.get(k, math.nan) for k in case.keys)
        out.sets += 1
        out.fitted += _finite(value)
        if _finite(low) and _finite(high):
            out.methods.add(short_method(row, case.keys[1]))
            out.given += 1
            out.hits += low <= case.truth <= high
            out.zero_width += not high > low
        elif _finite(value):
            out.reason = str(row.get("interval_reason") or row.get("reason") or "")
    return out


_FITTED: dict = {}  # (family, n, seed, resamples) → row: cases on the same sets share fits


def rows(case: Case, n: int, sets: int, resamples: int | None, first_seed: int) -> Iterator:
    for seed in range(first_seed, first_seed + sets):
        key = (case.make, case.fit, n, seed, resamples)
        if key not in _FITTED:
            if len(_FITTED) > 5000:
                _FITTED.clear()
            _FITTED[key] = case.fit(case.make(n, seed), resamples)
        yield _FITTED[key]


def _finite(value) -> bool:
    return isinstance(value, int | float) and math.isfinite(value)


def short_method(row: dict, low_key: str) -> str:
    """The short name of the method that gave a row's interval of ``low_key``: its own
    ``_interval_method`` (the Walton fit's parameters) or the row's ``interval_method``."""
    said = str(row.get(low_key.replace("_low", "_interval_method").replace("_mean", ""))
               or row.get("interval_method") or "")  # fmt: skip
    if said.startswith("asymptotic"):
        return "asymptotic"
    if said.startswith("profile likelihood"):
        return "profile"
    if "t-interval" in said:
        return "small-n t"
    if "posterior" in said or "credible" in said or "emcee" in said:
        return "Bayes"
    return "bootstrap-t" if "bootstrap" in said else said[:20]
