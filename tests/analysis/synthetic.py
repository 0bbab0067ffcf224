"""Synthetic collisions of known truth, generated (never fitted to themselves) for the fit tests."""

from __future__ import annotations

import numpy as np
import pandas as pd

from granudb.physics.uncertainty import ratio_uncertainty

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
) -> pd.DataFrame:
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


def with_stated_u(frame: pd.DataFrame, u_in, u_out, u_t_in, u_t_out) -> pd.DataFrame:
    """``frame`` with each run's stated u of v_n,in, v_n,out, v_T,in, v_T,out [m/s] and the
    u(e), u(Ψ_in), u(Ψ_out) a listing derives from them (``ratio_uncertainty``, as
    ``granudb.analysis.collisions`` does)."""
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
