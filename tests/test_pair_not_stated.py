""" "Not stated is not zero" (issue 33): an uncertainty no input states is null in
``pair --format json`` and NaN in ``granudb.pair``, never 0 (which a program reads as
"known exactly"); with one stated input only the values it reaches carry a u; 0 only
where the inputs that reach a value were stated exact."""

from __future__ import annotations

import json
import math

import numpy as np

import granudb
from granudb.physics.derive import derive

SCENARIO = ("glass", "Zerodur", "--fluid", "water", "--diameter", "12.7 mm")


def _u(document: dict) -> dict:
    return {k: v for k, v in document.items() if k.startswith("u_")}


def test_no_stated_uncertainty_gives_no_zero_u(cli, db: str) -> None:
    out = cli("pair", *SCENARIO, "--velocity", "0.3 m/s", "--format", "json", db=db)
    assert out.exit_code == 0, out.stderr
    u = _u(json.loads(out.stdout))
    assert len(u) > 30
    assert all(v is None for v in u.values()), {k: v for k, v in u.items() if v is not None}
    python = granudb.pair("glass", "Zerodur", fluid="water", diameter="12.7 mm",
                          velocity="0.3 m/s", db=db)  # fmt: skip
    assert all(math.isnan(v) for v in _u(python).values())


def test_one_stated_input_reaches_only_its_values(cli, db: str) -> None:
    out = cli("pair", *SCENARIO, "--velocity", "0.3 m/s ± 3 %", "--format", "json", db=db)
    u = _u(json.loads(out.stdout))
    # the speed reaches the Stokes numbers, the Hertz load and the gap …
    for name in ("u_impact_speed_m_s", "u_normal_stokes_number", "u_impact_load_n", "u_min_gap_m"):
        assert u[name] is not None and u[name] > 0, name
    assert u["u_impact_speed_m_s"] == 0.009
    # … not the materials' properties alone, nor the roughness
    for name in ("u_reduced_modulus_pa", "u_effective_radius_m", "u_composite_roughness_m"):
        assert u[name] is None, name
    assert not any(v == 0 for k, v in u.items() if k != "u_incidence_angle_rad")


def test_an_input_stated_exact_gives_zero_where_it_reaches(cli, db: str) -> None:
    out = cli("pair", "glass", "Zerodur", "--fluid", "water", "--diameter", "12.7 mm ± 0 mm",
              "--velocity", "0.3 m/s", "--format", "json", db=db)  # fmt: skip
    u = _u(json.loads(out.stdout))
    assert u["u_effective_radius_m"] == 0.0 and u["u_normal_stokes_number"] == 0.0
    assert u["u_reduced_modulus_pa"] is None  # the diameter does not reach E*
    assert u["u_impact_speed_m_s"] is None


def test_the_table_shows_no_plus_minus_when_nothing_is_stated(cli, db: str) -> None:
    out = cli("pair", *SCENARIO, "--velocity", "0.3 m/s", db=db)
    assert out.exit_code == 0 and "±" not in out.stdout


def test_a_table_of_runs_gives_no_u_where_its_row_states_none() -> None:
    """Runs where one input's u is stated for some rows only: the others' rows have no u
    (NaN, not the 0 their missing u would add), the stated rows have it."""
    materials = {
        f"{side}_{name}": value
        for side, values in (("particle", (2540.0, 60e9, 0.23, 130e-9)),
                             ("wall", (2540.0, 91e9, 0.24, 15e-9)))
        for name, value in zip(("density_kg_m3", "youngs_modulus_pa", "poisson_ratio",
                                "roughness_rms_m"), values, strict=True)
    }  # fmt: skip
    out = derive(
        diameter_m=np.array([12.7e-3, 12.7e-3]), v_n_in_m_s=0.3, v_t_in_m_s=0.0,
        viscosity_pa_s=1e-3, fluid_density_kg_m3=998.0, **materials,
        uncertainties={"u_diameter_m": np.array([1e-5, np.nan])},
    )  # fmt: skip
    for name in ("u_effective_radius_m", "u_normal_stokes_number", "u_impact_load_n"):
        assert out[name][0] > 0 and math.isnan(out[name][1]), name
    assert np.isnan(out["u_reduced_modulus_pa"]).all()  # the diameter does not reach E*
