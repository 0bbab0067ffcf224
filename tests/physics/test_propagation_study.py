"""A small version of benchmarks/propagation.py (issue 36): derive's u and 95 % interval
of a few quantities against an independent Monte Carlo of derive itself (2·10⁵ draws,
another seed), where first order is curved (μ_f of (5.8) in 37 % glycerol at 10 %), at a
step (e near St_c, St_n = 11) and where first order holds (1 %). Both ends within 5 %
of the reference interval's width, and the method that gave them is the one named."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from granudb.physics.derive import derive
from granudb.physics.propagation_check import FIRST_ORDER

# the study's own scenarios and reference Monte Carlo (a benchmark imports no test module;
# the test imports the benchmark's, as tests/analysis/coverage.py does)
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from propagation import GLYCEROL_37, near_critical, reference, stated  # noqa: E402

DRAWS, SEED = 200_000, 777


def _case(scenario: dict, relative: float, names: tuple[str, ...]) -> str:
    got = derive(**scenario, uncertainties=stated(scenario, relative))
    ref = reference(scenario, relative, DRAWS, list(names), SEED)
    for name in names:
        _sd, ref_low, ref_high = ref[name]
        width = ref_high - ref_low
        low, high = float(got[f"low95_{name}"]), float(got[f"high95_{name}"])
        assert abs(low - ref_low) <= 0.05 * width, (name, low, ref_low, width)
        assert abs(high - ref_high) <= 0.05 * width, (name, high, ref_high, width)
    return str(np.asarray(got["propagation_method"]).item())


def test_first_order_holds_at_1_percent_and_says_so() -> None:
    names = ("lubricated_friction", "max_pressure_pa", "predicted_restitution")
    assert _case(near_critical(), 0.01, names) == FIRST_ORDER


def test_restitution_across_the_critical_stokes_number() -> None:
    """At 5 % about a quarter of the draws do not rebound (e = 0): the interval reaches
    0 and its top is the St_am interval's through e(St); first order with the step."""
    scenario = near_critical()
    low = derive(**scenario, uncertainties=stated(scenario, 0.05))["low95_predicted_restitution"]
    assert float(low) == 0.0
    method = _case(scenario, 0.05, ("predicted_restitution", "normal_stokes_number"))
    assert "predicted_restitution" not in method.split(";")[0]


@pytest.mark.parametrize("relative", [0.10])
def test_curved_friction_goes_to_the_monte_carlo(relative: float) -> None:
    names = ("lubricated_friction", "friction_integral", "maw_psi_in")
    method = _case(GLYCEROL_37, relative, names)
    assert method.startswith("Monte Carlo") and "lubricated_friction" in method
