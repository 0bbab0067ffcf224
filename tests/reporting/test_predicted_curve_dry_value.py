"""The report's predicted e(St) curve and ``derive``'s ``predicted_restitution`` are one
answer: both use the pair's own dry restitution (here 0.8, not the borrowed 0.97)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from granudb.physics.derive import derive
from granudb.reporting.figures import WET_COLUMNS, predicted_curves


def test_curve_passes_through_derive_s_prediction_with_the_pair_s_dry_e() -> None:
    speeds = np.array([0.1, 0.2, 0.4])
    derived = derive(
        diameter_m=12.7e-3, v_n_in_m_s=speeds, v_t_in_m_s=0.0,
        particle_density_kg_m3=2540.0, particle_youngs_modulus_pa=60e9,
        particle_poisson_ratio=0.23, particle_roughness_rms_m=130e-9,
        wall_density_kg_m3=2540.0, wall_youngs_modulus_pa=91e9, wall_poisson_ratio=0.24,
        wall_roughness_rms_m=15e-9, viscosity_pa_s=4.5e-3, fluid_density_kg_m3=1112.0,
        dry_restitution=0.8,
    )  # fmt: skip
    frame = pd.DataFrame({c: derived[c] for c in WET_COLUMNS if c in derived})
    [curve] = predicted_curves(frame, ["glass in glycerol"] * 3, 10.0)
    at_runs = np.interp(frame["normal_stokes_number"], curve["st_n"], curve["e"])
    assert np.allclose(at_runs, derived["predicted_restitution"], rtol=2e-3)
    assert float(np.max(curve["e"])) < 0.8  # bounded by the pair's 0.8, not 0.97
