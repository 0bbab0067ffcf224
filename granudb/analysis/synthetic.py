"""Synthetic collisions of known truth, generated (never fitted to themselves): the fit
tests' and the coverage benchmark's shared generators (issue 36: the benchmarks import no
test module). Every generator is seeded; none reads a file."""

from __future__ import annotations

from typing import Any

import numpy as np

from granudb.analysis.restitution_fit import restitution_curve
from granudb.lazy import pandas as pd
from granudb.physics import contact, lubrication
from granudb.physics.uncertainty import ratio_uncertainty

E_STAR = 65.6e9  # steel on Zerodur (Joseph & Hunt table 1)
STEEL = 7780.0
GLASS = 2540.0
ETA_HAT = 375e-12  # C = 6e-9 Pa⁻¹ (glycerol), η̂ = C/16
#: The stated-u restitution runs' truth (``measured``) and relative speed u.
TRUTH = {"e_dry": 0.95, "parameter": 35.0}
U_REL = 0.04

RADIUS = 6.35e-3  # 12.7 mm spheres
WALTON_FACTOR = 3.5  # 1 + 1/K², a solid sphere on a wall


def walton_frame(
    n: int,
    *,
    beta: float = 0.34,
    friction: float = 0.11,
    restitution: float = 0.97,
    psi_range: tuple[float, float] = (0.05, 2.5),
    spin: float = 30.0,
    noise: float = 0.01,
    seed: int = 0,
    walton_factor: float | None = None,
) -> Any:
    """Runs on Walton's model Ψ_out = max(−βΨ_in, Ψ_in − μ_f(1+e)B) (folded), with ω_in drawn
    from ±``spin`` rad/s, the contact point's Ψ_in uniform in ``psi_range`` in magnitude, and
    Gaussian scatter ``noise`` on Ψ_out and 0.01 on e."""
    rng = np.random.default_rng(seed)
    b = WALTON_FACTOR if walton_factor is None else walton_factor
    vn = rng.uniform(0.1, 0.38, n)
    omega = rng.uniform(-spin, spin, n)
    magnitude = rng.uniform(*psi_range, n)
    # choose the contact-point velocity, then the centre velocity that spin implies
    v_T = magnitude * vn * np.where(rng.random(n) < 0.5, -1.0, 1.0) if spin else magnitude * vn
    v_t = v_T - omega * RADIUS
    e = np.clip(restitution + rng.normal(0, 0.01, n), 0.0, 1.0)
    x = np.abs(v_T) / vn
    y = np.maximum(-beta * x, x - friction * (1 + e) * b) + rng.normal(0, noise, n)
    sign = np.sign(v_T)
    frame = pd.DataFrame(
        {
            "dataset": "synthetic",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": None,
            "v_n_in_m_s": vn,
            "v_t_in_m_s": v_t,
            "omega_in_rad_s": omega,
            "tangential_speed_m_s": v_T,
            "effective_incidence": sign * x,
            "effective_rebound": sign * y,
            "normal_restitution": e,
        }
    )
    if walton_factor is not None:
        frame["walton_factor"] = walton_factor
    return frame


def with_stated_u(frame: pd.DataFrame, u_in, u_out, u_t_in, u_t_out) -> Any:
    """``frame`` with each run's stated u of v_n,in, v_n,out, v_T,in, v_T,out [m/s] and the
    u(e), u(Ψ_in), u(Ψ_out) a listing derives from them (``ratio_uncertainty``, as
    ``granudb.scenario.collisions`` does)."""
    vn, e = frame["v_n_in_m_s"], frame["normal_restitution"]
    out = frame.assign(
        v_n_out_m_s=e * vn, u_v_n_in_m_s=u_in, u_v_n_out_m_s=u_out, u_v_t_in_m_s=u_t_in
    )
    out["u_v_t_out_m_s"] = u_t_out
    out["u_normal_restitution"] = ratio_uncertainty(e, vn, u_out, u_in)
    out["u_effective_incidence"] = ratio_uncertainty(frame["effective_incidence"], vn, u_t_in, u_in)
    out["u_effective_rebound"] = ratio_uncertainty(frame["effective_rebound"], vn, u_t_out, u_in)
    return out


def walton_measured(n: int, *, u: float = 0.004, stated: bool = True, seed: int = 0):
    """``walton_frame``'s split runs (β = 0.34, μ_f = 0.11, ē = 0.97) measured through
    speeds: v_n,in, v_n,out, v_T,in and v_T,out each with Gaussian noise of ``u`` [m/s]
    (1–4 % of v_n,in), and, with ``stated``, that u stated for every run."""
    true = walton_frame(n, seed=seed)
    rng = np.random.default_rng(10_000 + seed)
    vn = true["v_n_in_m_s"].to_numpy()
    speeds = [vn, true["normal_restitution"] * vn, true["effective_incidence"] * vn,
              true["effective_rebound"] * vn]  # fmt: skip
    vn_m, out_m, t_in, t_out = (v + u * rng.standard_normal(n) for v in speeds)
    frame = true.assign(
        v_n_in_m_s=vn_m,
        tangential_speed_m_s=t_in,
        effective_incidence=t_in / vn_m,
        effective_rebound=t_out / vn_m,
        normal_restitution=out_m / vn_m,
    )
    return with_stated_u(frame, u, u, u, u) if stated else frame


def sliding_runs(
    viscosity: float,
    *,
    n: int = 300,
    density: float = STEEL,
    radius: float = 6.35e-3,
    equivalent_density: float | None = None,
    eta_hat: float = ETA_HAT,
    noise: float = 0.02,
    seed: int = 0,
    fluid: str = "glycerol-37",
) -> Any:
    """Runs whose μ_f is (5.10) at gap viscosity ``viscosity``, all in gross slip, with
    every measured velocity scattered by ``noise`` (relative). ``equivalent_density`` is the
    density of a sphere of radius R* with mass m* (two spheres: 4ρ_p for equal spheres)."""
    rng = np.random.default_rng(seed)
    rho = density if equivalent_density is None else equivalent_density
    vn = rng.uniform(0.1, 0.4, n)
    x = rng.uniform(0.4, 1.5, n)  # Ψ_in: well above the sticking crossing
    u = x * vn
    load = contact.hertz_impact_load(radius, E_STAR, rho, vn)
    a = contact.max_contact_radius(radius, load, E_STAR)
    integral = lubrication.friction_integral(eta_hat * contact.max_pressure(load, a))
    mu = lubrication.lubricated_friction_dimensionless(
        viscosity, u, E_STAR, radius, eta_hat, rho, vn, integral
    )
    e = rng.uniform(0.75, 0.9, n)
    y = x - mu * (1 + e) * 3.5
    scatter = lambda v: v * (1 + rng.normal(0, noise, n))  # noqa: E731
    vn_in, vt_in, vn_out, vt_out = scatter(vn), scatter(u), scatter(e * vn), scatter(y * vn)
    psi_in, psi_out = vt_in / vn_in, vt_out / vn_in
    e_m = vn_out / vn_in
    mass = rho * 4 / 3 * np.pi * radius**3
    return pd.DataFrame(
        {
            "dataset": "synthetic",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": fluid,
            "v_n_in_m_s": vn_in,
            "tangential_speed_m_s": vt_in,
            "effective_incidence": psi_in,
            "effective_rebound": psi_out,
            "normal_restitution": e_m,
            "sliding_friction": (psi_in - psi_out) / ((1 + e_m) * 3.5),
            "effective_radius_m": radius,
            "effective_mass_kg": mass,
            "reduced_modulus_pa": E_STAR,
            "eta_hat_pa_inv": eta_hat,
            "particle_density_kg_m3": density,
            "viscosity_pa_s": 3e-3,
            "tangential_regime": "gross_slip",
            "roughness_exceeds_gap": False,
        }
    )


def restitution_runs(
    e_dry: float, model: str, parameter: float, *, n: int = 40, seed: int = 0, dry: int = 0
):
    """Immersed runs on e(St_n) of ``model`` (St_n geometric from 15 to 3000, scatter 0.02 on e)
    and ``dry`` dry runs (e_dry with scatter 0.01)."""
    rng = np.random.default_rng(seed)
    st = np.geomspace(15, 3000, n)
    e = restitution_curve(model, st, e_dry, parameter) + rng.normal(0, 0.02, n)
    immersed = pd.DataFrame(
        {
            "dataset": "d",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": "glycerol-37",
            "normal_stokes_number": st,
            "normal_restitution": e,
        }
    )
    dry_runs = pd.DataFrame(
        {
            "dataset": "d",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": None,
            "normal_stokes_number": np.nan,
            "normal_restitution": e_dry + rng.normal(0, 0.01, dry),
        }
    )
    return pd.concat([immersed, dry_runs], ignore_index=True) if dry else immersed


def measured(seed: int, *, n: int = 20, stated: bool = True) -> Any:
    """Runs whose true St_n and e follow the exponential law, measured through speeds with
    U_REL relative noise: St_n ∝ v_n,in and e = v_n,out / v_n,in carry it."""
    rng = np.random.default_rng(seed)
    st_true = np.geomspace(15, 3000, n)
    v_in_true = st_true * 1e-3  # m/s; St_n ∝ v_n,in at a fixed sphere and fluid
    e_true = restitution_curve("exponential", st_true, *TRUTH.values())
    v_in = v_in_true * (1 + U_REL * rng.standard_normal(n))
    v_out = e_true * v_in_true * (1 + U_REL * rng.standard_normal(n))
    frame = pd.DataFrame(
        {
            "dataset": "d",
            "particle": "steel",
            "wall": "Zerodur",
            "fluid": "glycerol-37",
            "v_n_in_m_s": v_in,
            "v_n_out_m_s": v_out,
            "normal_stokes_number": st_true * v_in / v_in_true,
            "normal_restitution": v_out / v_in,
        }
    )
    if stated:
        frame["u_v_n_in_m_s"] = U_REL * v_in
        frame["u_v_n_out_m_s"] = U_REL * v_out
    return frame


def sliding_measured(seed: int, *, n: int = 40, stated: bool = True) -> Any:
    """Gap-viscosity runs (1.6 mPa·s) whose four speeds carry 2 % relative noise, that u
    stated per run when ``stated``."""
    runs = sliding_runs(1.6e-3, n=n, seed=seed)
    if not stated:
        return runs
    vn, e = runs["v_n_in_m_s"], runs["normal_restitution"]
    t_out = runs["effective_rebound"] * vn
    u = 0.02
    return with_stated_u(runs, u * vn, u * e * vn, u * runs["tangential_speed_m_s"], u * t_out)
