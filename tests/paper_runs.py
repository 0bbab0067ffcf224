"""The paper's pairs as synthetic runs: glass and steel on Zerodur, dry and in glycerol (37 %
for steel, 45 % for glass), made with the Walton model of known β and μ_f (Joseph & Hunt
§3–§4) and 1 % seeded noise on the rebound, so the fits have honest non-zero uncertainties.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "collisions_example.csv"
RADIUS_MM = 6.35
#: (particle, fluid, β, μ_f, e, v_n,in in mm/s, temperature)
PAPER_GROUPS = [
    ("steel", "", 0.34, 0.11, 0.97, (150.0, 380.0), ""),
    ("glass", "", 0.39, 0.106, 0.97, (150.0, 380.0), ""),
    ("steel", "glycerol-37", 0.6, 0.02, 0.80, (200.0, 400.0), "20"),
    ("glass", "glycerol-45", 0.4, 0.15, 0.70, (100.0, 250.0), "20"),
]
HEADER = [
    "run", "particle", "wall", "fluid", "diameter [mm]", "incidence_angle [deg]",
    "v_n_in [mm/s]", "v_t_in [mm/s]", "omega_in [rad/s]", "v_n_out [mm/s]",
    "v_t_out [mm/s]", "omega_out [rad/s]", "temperature [degC]", "notes",
]  # fmt: skip


def paper_rows(runs_per_group: int = 10, seed: int = 2004) -> list[list[str]]:
    """Runs of known β and μ_f: Ψ_out = −βΨ_in while sticking, Ψ_in − 3.5 μ_f (1+e) once
    sliding; the spin after impact from the tangential impulse of a solid sphere."""
    rng = np.random.default_rng(seed)
    rows = []
    for particle, fluid, beta, mu, e, (v_low, v_high), temperature in PAPER_GROUPS:
        angles = np.linspace(4.0, 62.0, runs_per_group)
        speeds = np.linspace(v_low, v_high, runs_per_group)[rng.permutation(runs_per_group)]
        for index, (angle, v_n) in enumerate(zip(angles, speeds, strict=True), start=1):
            psi_in = math.tan(math.radians(angle))
            sliding = psi_in - 3.5 * mu * (1 + e)
            psi_out = max(-beta * psi_in, sliding) * (1 + 0.01 * rng.standard_normal())
            v_t = psi_in * v_n
            v_t_out = v_t + (psi_out * v_n - v_t) / 3.5
            omega_out = (psi_out * v_n - v_t_out) / RADIUS_MM  # rad/s: mm/s over mm
            label = f"{particle}-{fluid or 'dry'}-{index}"
            rows.append(
                [label, particle, "Zerodur", fluid, "12.7", f"{angle:.3f}", f"{v_n:.3f}",
                 f"{v_t:.4f}", "0", f"{e * v_n * (1 + 0.005 * rng.standard_normal()):.4f}",
                 f"{v_t_out:.4f}", f"{omega_out:.5f}", temperature, "synthetic"]
            )  # fmt: skip
    return rows


def write_csv(path: Path, rows: list[list[str]]) -> Path:
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(HEADER)
        writer.writerows(rows)
    return path
