"""Thornton's elastic–plastic restitution (docs/physics.md §15) and Hertz's small-strain
measures (§16): published checks and properties that must hold."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from granudb.physics import contact, limits
from granudb.physics.derive import derive

speeds = st.floats(1e-4, 1e2)
ceilings = st.floats(0.05, 1.0)


def test_thornton_at_the_published_checks() -> None:
    """r = 1 → 1.000; r = 1/11 → 0.644; V ≫ V_y → 1.185 r^{1/4} (Johnson 1985 §11.5)."""
    assert float(limits.thornton_restitution(1.0, 1.0)) == pytest.approx(1.0, abs=1e-12)
    assert float(limits.thornton_restitution(1.0, 11.0)) == pytest.approx(0.644, abs=5e-4)
    r = 1e-8
    limit = (6 * np.sqrt(3) / 5) ** 0.5 * (1 / (2 * np.sqrt(6 / 5))) ** 0.25
    assert round(limit, 3) == 1.185
    assert float(limits.thornton_restitution(r, 1.0)) / r**0.25 == pytest.approx(limit, rel=1e-6)


@given(ceilings, speeds, st.floats(1.0001, 1e4))
def test_continuous_at_yield_and_decreasing_above_it(e_dry, v_y, factor) -> None:
    speeds = v_y * np.array([1.0, factor, factor * 1.01])
    e = limits.elastic_plastic_restitution(e_dry, v_y, speeds)
    assert e[0] == e_dry  # at V_y: the elastic value, no jump
    assert e[1] <= e_dry and e[2] <= e[1]
    t = limits.thornton_restitution(v_y, speeds)
    assert t[2] < t[1] < 1.0  # strictly decreasing past V_y


@given(ceilings, speeds, st.floats(1e-4, 1.0))
def test_below_yield_the_dry_value_stands(e_dry, v_y, fraction) -> None:
    assert float(limits.elastic_plastic_restitution(e_dry, v_y, v_y * fraction)) == e_dry


def _bodies(particle: tuple, wall: tuple) -> dict[str, float]:
    """derive's material inputs from (ρ, E, ν, Y) of the particle and the wall."""
    names = ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "yield_stress_pa")
    out = {"particle_roughness_rms_m": 0.0, "wall_roughness_rms_m": 0.0}
    for prefix, values in (("particle", particle), ("wall", wall)):
        out.update({f"{prefix}_{n}": v for n, v in zip(names, values, strict=True)})
    return out


def test_derive_uses_thornton_only_past_yield() -> None:
    bodies = _bodies((7800.0, 210e9, 0.3, 2e9), (2700.0, 70e9, 0.33, 300e6))
    out = derive(
        v_n_in_m_s=np.array([1e-4, 0.3, 0.3]),
        diameter_m=0.0127,
        dry_restitution=np.array([0.9, 0.9, 0.6]),
        **bodies,
    )
    # the third: past yield, but Thornton's 0.64 is above its e_dry 0.6, so e_dry applies
    assert out["restitution_model"].tolist() == ["elastic", "elastic_plastic", "elastic"]
    e_t = float(limits.thornton_restitution(out["yield_speed_m_s"][1], 0.3))
    assert out["predicted_restitution"].tolist() == pytest.approx([0.9, e_t, min(0.6, e_t)])


def test_hertz_strain_is_independent_of_size_and_matches_the_rubber_figure() -> None:
    """δ/R = (5πρV²/(4E*))^{2/5} for a sphere on a rigid wall (no R): rubber, E = 5 MPa,
    ν = 0.49, ρ = 1100 kg/m³ at 5 m/s gives a/R = 0.44, δ/R = 0.19 (the issue's figure)."""
    e_star = float(contact.reduced_modulus(5e6, 0.49, 190e9, 0.27))
    expected = (5 * np.pi * 1100 * 25 / (4 * e_star)) ** 0.4
    bodies = _bodies((1100.0, 5e6, 0.49, np.nan), (7780.0, 190e9, 0.27, np.nan))
    for diameter in (1e-3, 0.0127, 0.1):
        out = derive(diameter_m=diameter, v_n_in_m_s=5.0, **bodies)
        a_ratio, d_ratio = (float(out[k]) for k in ("contact_radius_ratio", "approach_ratio"))
        assert d_ratio == pytest.approx(expected, rel=1e-9)
        assert a_ratio == pytest.approx(np.sqrt(expected), rel=1e-9)
        assert (round(a_ratio, 2), round(d_ratio, 2)) == (0.44, 0.19)
        assert not bool(out["hertz_strain_valid"])
