"""Fits of measured collisions: Walton's β and μ_f, restitution against Stokes number, and
the gap viscosity of smooth sliding collisions (Joseph & Hunt §3–§5).

All fits take the DataFrame of ``granudb.analysis.query.select_collisions`` and work per group
(dataset × particle × wall × fluid).

Walton split rule (documented in README): on the Ψ_out–Ψ_in plane, sticking runs lie on
Ψ_out = −βΨ_in and sliding runs on Ψ_out = Ψ_in − μ_f(1+e)(1+1/K²). Runs are sorted by
Ψ_in and every split point is tried: runs below it are fitted by a line through the origin,
runs above it by a line of slope one; the split with the least total squared residual wins
(O(n) with cumulative sums). β is minus the slope of the first line; μ_f is the sliding
intercept divided by (1+ē)(7/2), ē the sliding runs' mean restitution — the same as the
mean of (2.9) over the sliding runs.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from granudb.physics.impact import gyration_factor

GROUP = ["dataset", "particle", "wall", "fluid"]
MIN_RUNS_PER_LINE = 2

WALTON_COLUMNS = [
    "dataset",
    "particle",
    "wall",
    "fluid",
    "rotational_restitution",
    "rotational_restitution_stderr",
    "sliding_friction",
    "sliding_friction_stderr",
    "normal_restitution_mean",
    "normal_restitution_std",
    "n_sliding",
    "n_sticking",
    "split_effective_incidence",
]

RESTITUTION_MODELS = {
    # name: (formula, citation)
    "threshold": (
        "e = e_dry (1 − St_c/St_n) for St_n > St_c, else 0",
        "Davis, Serayssol & Hinch (1986) J. Fluid Mech. 163, 479; the scaling used by "
        "Joseph et al. (2001) J. Fluid Mech. 433, 329",
    ),
    "exponential": (
        "e = e_dry exp(−k/St_n)",
        "Legendre, Zenit, Daniel & Guiraud (2006) Chem. Eng. Sci. 61, 3543",
    ),
}


def _groups(frame: Any) -> Any:
    keyed = frame.assign(fluid=frame["fluid"].fillna("dry"))
    return keyed.groupby(GROUP, sort=True, dropna=False)


def walton_split(psi_in: np.ndarray, psi_out: np.ndarray) -> int:
    """Index k (in Ψ_in order) such that runs [0, k) stick and [k, n) slide."""
    n = len(psi_in)
    x, y = psi_in, psi_out
    d = x - y
    # prefix sums for the sticking line through the origin: SSE = Σy² − (Σxy)²/Σx²
    sxx = np.concatenate([[0.0], np.cumsum(x * x)])
    sxy = np.concatenate([[0.0], np.cumsum(x * y)])
    syy = np.concatenate([[0.0], np.cumsum(y * y)])
    with np.errstate(invalid="ignore", divide="ignore"):
        stick = np.where(sxx > 0, syy - sxy**2 / sxx, syy)
    # suffix sums for the sliding line of slope one: SSE = Σd² − (Σd)²/m
    sd = np.concatenate([np.cumsum(d[::-1])[::-1], [0.0]])
    sdd = np.concatenate([np.cumsum((d * d)[::-1])[::-1], [0.0]])
    m = n - np.arange(n + 1)
    with np.errstate(invalid="ignore", divide="ignore"):
        slide = np.where(m > 0, sdd - sd**2 / np.maximum(m, 1), 0.0)
    total = stick + slide
    k = np.arange(n + 1)
    allowed = ((k == 0) | (k >= MIN_RUNS_PER_LINE)) & ((m == 0) | (m >= MIN_RUNS_PER_LINE))
    total = np.where(allowed, total, np.inf)
    return int(np.argmin(total))


def walton(frame: Any) -> list[dict[str, Any]]:
    """β and μ_f with standard errors per group, and ē ± std (Joseph & Hunt figures 4, 6, 9)."""
    factor = float(gyration_factor())
    results = []
    for key, group in _groups(frame):
        group = group[
            np.isfinite(group["effective_incidence"]) & np.isfinite(group["effective_rebound"])
        ]
        if group.empty:
            continue
        order = np.argsort(group["effective_incidence"].to_numpy(), kind="stable")
        x = group["effective_incidence"].to_numpy()[order]
        y = group["effective_rebound"].to_numpy()[order]
        e = group["normal_restitution"].to_numpy()[order]
        k = walton_split(x, y)
        beta = beta_se = mu = mu_se = math.nan
        if k >= 1 and np.sum(x[:k] ** 2) > 0:
            sxx = float(np.sum(x[:k] ** 2))
            beta = -float(np.sum(x[:k] * y[:k])) / sxx
            if k > 1:
                residual = y[:k] + beta * x[:k]
                beta_se = math.sqrt(float(np.sum(residual**2)) / (k - 1) / sxx)
        if k < len(x):
            friction = (x[k:] - y[k:]) / ((1.0 + e[k:]) * factor)
            mu = float(np.mean(friction))
            if len(friction) > 1:
                mu_se = float(np.std(friction, ddof=1)) / math.sqrt(len(friction))
        results.append(
            {
                **dict(zip(GROUP, key, strict=True)),
                "rotational_restitution": beta,
                "rotational_restitution_stderr": beta_se,
                "sliding_friction": mu,
                "sliding_friction_stderr": mu_se,
                "normal_restitution_mean": float(np.mean(e)),
                "normal_restitution_std": float(np.std(e, ddof=1)) if len(e) > 1 else math.nan,
                "n_sliding": int(len(x) - k),
                "n_sticking": int(k),
                "split_effective_incidence": float(x[k]) if k < len(x) else math.nan,
            }
        )
    return results


def restitution_curve(model: str, stokes: np.ndarray, e_dry: float, parameter: float) -> np.ndarray:
    """e(St_n) of ``model`` ("threshold": parameter St_c; "exponential": parameter k)."""
    st = np.asarray(stokes, dtype=float)
    if model == "threshold":
        return np.where(st > parameter, e_dry * (1.0 - parameter / st), 0.0)
    if model == "exponential":
        return e_dry * np.exp(-parameter / st)
    raise KeyError(model)


def restitution(frame: Any, model: str = "threshold") -> list[dict[str, Any]]:
    """Fit e(St_n) of the immersed runs per (dataset, particle, wall), all fluids together
    (figure 5): the dry limit e_dry and St_c (threshold) or k (exponential)."""
    from scipy.optimize import curve_fit

    from granudb.errors import ValidationError

    if model not in RESTITUTION_MODELS:
        raise ValidationError("--model", model, f"must be one of {', '.join(RESTITUTION_MODELS)}")
    immersed = frame[
        np.isfinite(frame["normal_stokes_number"]) & np.isfinite(frame["normal_restitution"])
    ]
    results = []
    for key, group in immersed.groupby(["dataset", "particle", "wall"], sort=True):
        st = group["normal_stokes_number"].to_numpy()
        e = group["normal_restitution"].to_numpy()
        row: dict[str, Any] = {
            "dataset": key[0],
            "particle": key[1],
            "wall": key[2],
            "model": model,
            "formula": RESTITUTION_MODELS[model][0],
            "citation": RESTITUTION_MODELS[model][1],
            "n_runs": len(st),
            "e_dry": math.nan,
            "e_dry_stderr": math.nan,
            "parameter": math.nan,
            "parameter_stderr": math.nan,
            "parameter_name": "critical_stokes" if model == "threshold" else "k",
        }
        # A two-parameter curve needs St_n to vary: at least 3 distinct values spanning a
        # factor of 2; otherwise the fit is left empty rather than made up.
        if len(np.unique(st)) >= 3 and float(np.max(st)) >= 2.0 * float(np.min(st)):
            guess = (min(1.0, float(np.max(e)) * 1.05), max(1.0, float(np.min(st)) * 0.5))
            try:
                values, covariance = curve_fit(
                    lambda s, a, b: restitution_curve(model, s, a, b),
                    st,
                    e,
                    p0=guess,
                    bounds=([0.0, 0.0], [1.2, np.inf]),
                    maxfev=20000,
                )
                errors = np.sqrt(np.diag(covariance))
                row.update(
                    e_dry=float(values[0]),
                    e_dry_stderr=float(errors[0]),
                    parameter=float(values[1]),
                    parameter_stderr=float(errors[1]),
                )
            except (RuntimeError, ValueError):
                pass  # not enough spread in St_n to fit: left as NaN, n_runs says why
        results.append(row)
    return results


def gap_viscosity(frame: Any, fluids: dict[str, Any]) -> list[dict[str, Any]]:
    """The gap viscosity μ₀ that makes (5.10) match each smooth sliding run's μ_f, and the
    gap temperature it implies through the fluid's μ(T) (figure 14, table 2).

    Uses immersed runs in gross slip whose roughness is within the gap (a full film), per
    (dataset, particle, wall, fluid). ``fluids`` maps fluid name to its viscosity model
    (with ``temperature_for_viscosity``) or None.
    """
    from granudb.physics import contact, lubrication

    smooth = frame[
        frame["fluid"].notna()
        & (frame["tangential_regime"] == "gross_slip")
        & ~frame["roughness_exceeds_gap"].astype(bool)
        & np.isfinite(frame["sliding_friction"])
        & (frame["sliding_friction"] > 0)
    ]
    results = []
    for key, group in smooth.groupby(GROUP, sort=True):
        eta_hat = group["eta_hat_pa_inv"].to_numpy()
        e_star = group["reduced_modulus_pa"].to_numpy()
        radius = group["effective_radius_m"].to_numpy()
        vn = group["v_n_in_m_s"].to_numpy()
        density = group["particle_density_kg_m3"].to_numpy()
        load = contact.hertz_impact_load(radius, e_star, density, vn)
        a = contact.max_contact_radius(radius, load, e_star)
        integral = lubrication.friction_integral(eta_hat * contact.max_pressure(load, a))
        mu0 = lubrication.viscosity_for_friction(
            group["sliding_friction"].to_numpy(),
            np.abs(group["tangential_speed_m_s"]),
            e_star,
            radius,
            eta_hat,
            density,
            vn,
            integral,
        )
        mu0 = mu0[np.isfinite(mu0)]
        if mu0.size == 0:
            continue
        mean = float(np.mean(mu0))
        model = fluids.get(key[3])
        temperature = math.nan
        note = ""
        if model is not None:
            try:
                temperature = float(model.temperature_for_viscosity(mean))
            except ValueError as exc:
                note = str(exc)
        results.append(
            {
                **dict(zip(GROUP, key, strict=True)),
                "gap_viscosity_pa_s": mean,
                "gap_viscosity_std_pa_s": float(np.std(mu0, ddof=1)) if mu0.size > 1 else math.nan,
                "ambient_viscosity_pa_s": float(np.mean(group["viscosity_pa_s"])),
                "gap_temperature_c": temperature,
                "n_runs": int(mu0.size),
                "note": note,
            }
        )
    return results
