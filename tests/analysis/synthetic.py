"""Synthetic collisions of known truth, generated (never fitted to themselves) for the fit tests."""

from __future__ import annotations

import numpy as np
import pandas as pd

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
