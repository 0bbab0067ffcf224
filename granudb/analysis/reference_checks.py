"""Reproduction of the reference library's published data by granudb's fits and models.

Each dataset of the library (``granudb.io.reference_library``) is a list of reported values
(one dict per value: point, quantity, value, u, role, …). ``reproduce(name, rows)`` runs
what applies to it and returns checks, each a dict of ``CHECK_KEYS``: a measured value (or
a value the paper prints), what granudb computes for it, the residual, the combined
standard uncertainty and the verdict. The verdict is decided in one place (``verdict``):

- ``agrees``: |computed − reported| ≤ ``COVERAGE`` × u_c, u_c = √(u_reported² + u_computed²);
- ``differs``: otherwise;
- ``prediction only``: the public source holds no measured value to compare with.

Runs as papers report them (docs/reference/index.md): Kharaz et al.'s e_t(θ) enters a
Walton fit through the exact no-spin-in relations of ``granudb.physics.reported``
(Ψ_in = tan θ, Ψ_out = Ψ_in (3.5 e_t − 2.5)), with the normal restitution the dataset
states as a condition; no velocity is made.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from granudb.analysis import fits
from granudb.lazy import pandas as pd
from granudb.physics import flow, reported

#: Coverage factor of the verdicts (≈ 95 % for a normal distribution).
COVERAGE = 2.0
#: The resamples and seed of the Kharaz Walton fit (the bootstrap is seeded: same answer).
WALTON_SEED = 20260101

CHECK_KEYS = (
    "check",
    "point",
    "quantity",
    "reported",
    "u_reported",
    "computed",
    "u_computed",
    "residual",
    "u_combined",
    "verdict",
    "how",
)


def verdict(reported_value: float, computed: float, u_reported: float, u_computed: float) -> dict:
    """The residual, its combined u and the verdict of one comparison (the one rule)."""
    if reported_value is None or not math.isfinite(reported_value):
        return {
            "residual": math.nan,
            "u_combined": math.nan,
            "verdict": "prediction only (no measured value in the public source)",
        }
    u_c = math.hypot(u_reported or 0.0, u_computed or 0.0)
    residual = computed - reported_value
    return {
        "residual": residual,
        "u_combined": u_c,
        "verdict": "agrees" if abs(residual) <= COVERAGE * u_c else "differs",
    }


def compare(check: str, point: str, quantity: str, got: tuple, want: tuple, how: str) -> dict:
    """One check: ``got`` and ``want`` are (value, u); the verdict by ``verdict``."""
    row = dict.fromkeys(CHECK_KEYS)
    row.update(check=check, point=point, quantity=quantity, how=how)
    row.update(reported=want[0], u_reported=want[1], computed=got[0], u_computed=got[1])
    row.update(verdict(want[0], got[0], want[1], got[1]))
    return row


def figure_points(rows: list[dict], prefix: str) -> list[dict]:
    """Figure points ``prefix-NN`` as {point, theta (rad), u_theta, value, u}."""
    by_point: dict[str, dict] = {}
    for r in rows:
        if not r["point"].startswith(prefix + "-"):
            continue
        entry = by_point.setdefault(r["point"], {"point": r["point"]})
        if r["quantity"] == "incidence_angle_deg":
            entry["theta"] = math.radians(float(r["value"]))
            entry["u_theta"] = math.radians(float(r["u"]))
        else:
            entry["value"] = float(r["value"])
            entry["u"] = float(r["u"])
    return sorted(by_point.values(), key=lambda e: e["theta"])


def _condition(rows: list[dict], quantity: str) -> tuple[float, float]:
    row = next(r for r in rows if r["point"] == "conditions" and r["quantity"] == quantity)
    return float(row["value"]), float(row["u"])


def _walton_e_t(theta: float, beta: float, mu: float, e: float) -> float:
    """e_t of the fitted Walton model at θ (no spin in)."""
    psi = reported.incidence_from_angle(theta)
    psi_out = max(-beta * psi, psi - mu * (1.0 + e) * 3.5)
    return float(reported.tangential_restitution_from_rebound(psi, psi_out))


def kharaz(name: str, rows: list[dict]) -> dict[str, Any]:
    """Walton fit of e_t(θ), then e_t, spin and both rebound angles predicted per point."""
    e_n, u_e = _condition(rows, "normal_restitution")
    paper_mu, u_paper_mu = _condition(rows, "sliding_friction")
    speed, _ = _condition(rows, "impact_speed_m_s")
    diameter, _ = _condition(rows, "diameter_m")
    radius = diameter / 2.0
    et = figure_points(rows, "et")
    theta = np.array([p["theta"] for p in et])
    e_t = np.array([p["value"] for p in et])
    psi_in = reported.incidence_from_angle(theta)
    frame = pd.DataFrame(
        {
            "dataset": name,
            "particle": rows[0]["particle"],
            "wall": rows[0]["wall"],
            "fluid": None,
            "effective_incidence": psi_in,
            "effective_rebound": reported.rebound_from_tangential_restitution(psi_in, e_t),
            "normal_restitution": np.full(len(et), e_n),
        }
    )
    fit = fits.walton(frame, seed=WALTON_SEED)[0]
    mu, beta = fit["sliding_friction"], fit["rotational_restitution"]
    mu_se = fit["sliding_friction_stderr"]
    checks = [
        compare(
            "Walton fit of e_t(θ)",
            f"{fit['n_runs']} points ({fit['model']}: {fit['n_sticking']} sticking, "
            f"{fit['n_sliding']} sliding)",
            "sliding_friction",
            (mu, mu_se),
            (paper_mu, u_paper_mu),
            "Walton's model fitted by granudb (Ψ_in = tan θ, Ψ_out = Ψ_in (3.5 e_t − 2.5), "
            f"e = {e_n}); reported: Kharaz et al.'s μ_f as Chung & Ooi's test 4 quotes it",
        )
    ]
    beta_ok = math.isfinite(beta)
    b = beta if beta_ok else -1.0
    for p in et:
        got = _walton_e_t(p["theta"], b, mu, e_n)
        checks.append(
            compare(
                "e_t(θ) of the fitted Walton model",
                p["point"],
                "tangential_restitution",
                (got, 0.0),
                (p["value"], p["u"]),
                f"θ = {math.degrees(p['theta']):.2f}°",
            )
        )
    for p in figure_points(rows, "omega"):
        fitted_e_t = _walton_e_t(p["theta"], b, mu, e_n)
        got = float(
            reported.spin_from_tangential_restitution(speed, p["theta"], fitted_e_t, radius)
        )
        checks.append(
            compare(
                "spin after impact, ω_out = V sin θ (1 − e_t)/(K² R) of the fitted e_t",
                p["point"],
                "angular_velocity_out_rad_s",
                (got, 0.0),
                (p["value"], p["u"]),
                f"θ = {math.degrees(p['theta']):.2f}°, V = {speed} m/s, R = {radius} m",
            )
        )
    for prefix, quantity, words in (
        ("rcom", "rebound_angle_centre_deg", "centre-of-mass rebound angle atan(e_t tan θ / e)"),
        ("rcp", "rebound_angle_contact_deg", "contact-point rebound angle atan(Ψ_out / e)"),
    ):
        for p in figure_points(rows, prefix):
            fitted_e_t = _walton_e_t(p["theta"], b, mu, e_n)
            if prefix == "rcom":
                angle = reported.centre_rebound_angle(p["theta"], fitted_e_t, e_n)
            else:
                psi = reported.incidence_from_angle(p["theta"])
                psi_out = reported.rebound_from_tangential_restitution(psi, fitted_e_t)
                angle = reported.contact_rebound_angle(psi_out, e_n)
            checks.append(
                compare(
                    words + " of the fitted model",
                    p["point"],
                    quantity,
                    (math.degrees(float(angle)), 0.0),
                    (p["value"], p["u"]),
                    f"θ = {math.degrees(p['theta']):.2f}°",
                )
            )
    low, high = fit["sliding_friction_low"], fit["sliding_friction_high"]
    method = fit.get("sliding_friction_interval_method") or fit.get("interval_method", "")
    interval = (
        f"[{low:.4f}, {high:.4f}] ({fit['confidence_level']:.0%}, {method})"
        if math.isfinite(low)
        else f"none: {fit['reason']}"
    )
    summary = [
        f"Walton fit of {fit['n_runs']} e_t(θ) points: model {fit['model']}, "
        f"μ_f = {mu:.4f} ± {mu_se:.4f} (standard error), interval {interval}; "
        f"β = {beta:.3f}" + ("" if beta_ok else " (not determined)") + f"; e = {e_n} (stated)",
        f"paper: μ_f = {paper_mu:g} (as Chung & Ooi's test 4 and Lethe's example quote it)",
    ]
    grid = np.radians(np.linspace(0.5, 87.0, 175))
    fitted = np.array([_walton_e_t(t, b, mu, e_n) for t in grid])
    spin = reported.spin_from_tangential_restitution(speed, grid, fitted, radius)
    curves = {
        "tangential_restitution": {"x": np.degrees(grid).tolist(), "y": fitted.tolist()},
        "angular_velocity_out_rad_s": {"x": np.degrees(grid).tolist(), "y": spin.tolist()},
    }
    return {"fit": fit, "checks": checks, "summary": summary, "curves": curves}


def vssuq(name: str, rows: list[dict]) -> dict[str, Any]:
    """Mean and sample standard deviation of each pair's per-collision values against the
    ones VSSUQ prints."""
    checks, summary = [], []
    groups: dict[tuple[str, str], list[float]] = {}
    printed = {}
    for r in rows:
        stem = r["point"].rsplit("-", 1)[0]
        if r["point"].endswith("-printed"):
            printed[(stem, r["quantity"].rsplit("_", 1)[1])] = (float(r["value"]), float(r["u"]))
        else:
            groups.setdefault((stem, r["quantity"]), []).append(float(r["value"]))
    for (stem, quantity), values in groups.items():
        x = np.array(values)
        mean, sd = float(np.mean(x)), float(np.std(x, ddof=1))
        half = 1.96 * sd / math.sqrt(len(x))
        summary.append(
            f"{stem}: {quantity} n = {len(x)}, mean {mean:.4f}, sd {sd:.4f}, "
            f"95 % interval of the mean [{mean - half:.4f}, {mean + half:.4f}]"
        )
        for statistic, got in (("mean", mean), ("sd", sd)):
            checks.append(
                compare(
                    f"{statistic} of the per-collision values",
                    stem,
                    f"{quantity}_{statistic}",
                    (got, 0.0),
                    printed[(stem, statistic)],
                    f"{len(x)} values; sd with n − 1",
                )
            )
    return {"checks": checks, "summary": summary}


def _cases(rows: list[dict]) -> dict[str, dict[str, tuple[float, float]]]:
    cases: dict[str, dict] = {}
    for r in rows:
        cases.setdefault(r["point"], {})[r["quantity"]] = (float(r["value"]), float(r["u"]))
        cases[r["point"]]["_fluid"] = r["fluid"]
    return cases


def gondret(name: str, rows: list[dict]) -> dict[str, Any]:
    """Each case's St from its reported Re (St = Re ρ_p / (9 ρ_f)) against the St the case
    states, and Legendre et al.'s e(St) predicted (no measured e in the public source)."""
    checks, summary = [], []
    cases_st, cases_e = [], []
    for case, q in _cases(rows).items():
        re_, u_re = q["reynolds_number"]
        rho_p, rho_f = q["density_sphere_kg_m3"][0], q["density_fluid_kg_m3"][0]
        mu, d = q["dynamic_viscosity_pa_s"][0], q["diameter_m"][0]
        speed = float(reported.speed_for_reynolds_number(re_, rho_f, d / 2, mu))
        st = float(flow.stokes_number(rho_p, d / 2, speed, mu))
        checks.append(
            compare(
                "St from the reported Re, St = Re ρ_p / (9 ρ_f)",
                case,
                "stokes_number",
                (st, st * u_re / re_),
                q["stokes_number"],
                f"V = Re μ / (ρ_f D) = {speed:.4g} m/s (derived, not measured)",
            )
        )
        st_am = float(flow.added_mass_stokes_number(rho_p, rho_f, d / 2, speed, mu))
        e_dry, u_dry = q["dry_restitution"]
        e = float(flow.predicted_restitution(st_am, e_dry))
        u_e = e / e_dry * u_dry
        cases_st.append(st_am)
        cases_e.append(e)
        checks.append(
            compare(
                "Legendre et al. e = e_dry exp(−35/St_am)",
                case,
                "normal_restitution",
                (e, u_e),
                (math.nan, math.nan),
                f"St_am = {st_am:.1f}, e_dry = {e_dry}",
            )
        )
        summary.append(
            f"{case}: Re {re_:g}, St {st:.1f} from Re (stated {q['stokes_number'][0]:g}), "
            f"predicted e = {e:.3f} ± {u_e:.3f}; Gondret et al.'s measured e is in their "
            "figure, not in a readable public file"
        )
    stokes = np.geomspace(10.5, 2000.0, 120)
    curves = {
        "normal_restitution": {
            "x": stokes.tolist(),
            "y": flow.predicted_restitution(stokes, 0.97).tolist(),
        },
        "cases": {"x": cases_st, "y": cases_e},
    }
    return {"checks": checks, "summary": summary, "curves": curves}


def joseph_walberla(name: str, rows: list[dict], seeded: list[dict]) -> dict[str, Any]:
    """waLBerla's inputs for the four Joseph & Hunt cases against the values granudb seeds
    from the paper (dry e, μ_f of the immersed sphere, the fluid's ambient viscosity)."""
    checks, summary = [], []
    table = {}
    for r in seeded:
        u = float(r["u"]) if r["u"] else 0.0
        table[(r["quantity"], r["particle"], r["fluid"])] = (float(r["value"]), u, r["locator"])
    for case, q in _cases(rows).items():
        particle = next(r["particle"] for r in rows if r["point"] == case)
        fluid = q["_fluid"]
        pairs = (
            ("dry_restitution", ("normal_restitution_mean", particle, "")),
            ("friction", ("sliding_friction", particle, fluid)),
            ("dynamic_viscosity_pa_s", ("ambient_viscosity_pa_s", particle, fluid)),
        )
        for mine, key in pairs:
            if key not in table:
                continue
            value, u, locator = table[key]
            checks.append(
                compare(
                    f"waLBerla input {mine} against the paper's value",
                    f"{case} ({particle} in {fluid})",
                    mine,
                    q[mine],
                    (value, u),
                    f"paper: {key[0]}, {locator}",
                )
            )
        summary.append(f"{case}: {particle} in {fluid}")
    return {"checks": checks, "summary": summary}


def joseph_tables(name: str, rows: list[dict], walberla: list[dict]) -> dict[str, Any]:
    """Figure 3's collision (a 12.7 mm glass sphere in 45 % glycerol): St from its Re and
    Legendre et al.'s e against its measured e. The sphere and fluid are the library's
    joseph-hunt-2004-walberla case of glass in glycerol-45."""
    q = {
        r["quantity"]: (float(r["value"]), float(r["u"])) for r in rows if "figure 3" in r["point"]
    }
    dry = next(
        (float(r["value"]), float(r["u"]))
        for r in rows
        if r["quantity"] == "normal_restitution_mean" and r["particle"] == "glass"
    )
    cases = _cases(walberla)
    case = next((c for c in cases.values() if c["_fluid"] == "glycerol-45"), None)
    checks, summary = [], []
    if case and {"reynolds_number", "stokes_number", "normal_restitution"} <= set(q):
        rho_p, rho_f = case["density_sphere_kg_m3"][0], case["density_fluid_kg_m3"][0]
        mu, radius = case["dynamic_viscosity_pa_s"][0], case["diameter_m"][0] / 2
        re_, u_re = q["reynolds_number"]
        speed = float(reported.speed_for_reynolds_number(re_, rho_f, radius, mu))
        st = float(flow.stokes_number(rho_p, radius, speed, mu))
        how = f"glass {rho_p:g} kg/m³ in glycerol-45 {rho_f:g} kg/m³, {mu:g} Pa s (waLBerla case)"
        checks.append(
            compare(
                "St from the reported Re, St = Re ρ_p / (9 ρ_f)",
                "figure 3 collision",
                "stokes_number",
                (st, st * u_re / re_),
                q["stokes_number"],
                how,
            )
        )
        st_am = float(flow.added_mass_stokes_number(rho_p, rho_f, radius, speed, mu))
        e = float(flow.predicted_restitution(st_am, dry[0]))
        checks.append(
            compare(
                "Legendre et al. e = e_dry exp(−35/St_am)",
                "figure 3 collision",
                "normal_restitution",
                (e, e / dry[0] * dry[1]),
                q["normal_restitution"],
                f"St_am = {st_am:.1f}, e_dry = {dry[0]} ± {dry[1]} (§3, figure 4)",
            )
        )
        summary.append(f"figure 3 collision: predicted e = {e:.3f} at St_am = {st_am:.1f}")
    return {"checks": checks, "summary": summary}
