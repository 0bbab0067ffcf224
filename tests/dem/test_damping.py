"""The damping maps: integrating the Hertz contact law gives the target e back."""

from __future__ import annotations

import pytest

from granudb.dem import damping
from granudb.errors import ValidationError


@pytest.mark.parametrize("e", [0.97, 0.8, 0.5, 0.2, 0.06])
def test_liggghts_hertz_damping_is_exact(e: float) -> None:
    assert damping.hertz_restitution(damping.hertz_damping(e)) == pytest.approx(e, abs=2e-5)


@pytest.mark.parametrize("e", [0.97, 0.5, 0.2])
def test_yade_clamped_damping_inverts(e: float) -> None:
    c = damping.clamped_hertz_damping(e)
    assert damping.hertz_restitution(c, clamp_attraction=True) == pytest.approx(e, abs=1e-4)


def test_lammps_tsuji_polynomial_is_corrected() -> None:
    # typed as is, 0.97 gives 0.979 (LAMMPS #2812); the corrected input gives 0.97
    assert damping.hertz_restitution(damping.tsuji_alpha(0.97)) == pytest.approx(0.9794, abs=1e-3)
    e_in = damping.lammps_tsuji_input(0.97, "x")
    assert damping.hertz_restitution(
        damping.tsuji_alpha(e_in), clamp_attraction=True
    ) == pytest.approx(0.97, abs=2e-5)


def test_lammps_tsuji_floor() -> None:
    # with limit_damping the force is clamped: alpha(0) = 1.2728 gives e = 0.263, not 0.114
    low, high = damping.lammps_tsuji_range()
    assert 0.26 < low < 0.27 and 0.999 < high < 1.0


@pytest.mark.parametrize("e", [0.97, 0.6, 0.3])
def test_clamped_inputs_give_the_target(e: float) -> None:
    """LIGGGHTS (limitForce) and LAMMPS (limit_damping) clamp the force: their inputs,
    turned into damping as each code does, give e back on the clamped law."""
    ligg = damping.hertz_damping(damping.liggghts_hertz_input(e))
    tsuji = damping.tsuji_alpha(damping.lammps_tsuji_input(e, "x"))
    for c in (ligg, tsuji):
        assert damping.hertz_restitution(c, clamp_attraction=True) == pytest.approx(e, abs=1e-4)


def test_stick_rebound_limits() -> None:
    """No tangential spring: the contact point keeps its speed (beta = -1); a spring gives
    a rebound the chosen stiffness reproduces."""
    c = damping.clamped_hertz_damping(0.97)
    assert float(damping.stick_rebound(1e-9, c)) == pytest.approx(-1.0, abs=1e-6)
    # a finer step agrees: the end of contact is interpolated, not stepped over
    coarse, fine = damping.stick_rebound(0.7, c), damping.stick_rebound(0.7, c, step=5e-4)
    assert float(coarse) == pytest.approx(float(fine), abs=2e-4)


@pytest.mark.parametrize(("beta", "e"), [(0.34, 0.97), (0.39, 0.97), (0.6, 0.94), (0.34, 0.3)])
def test_stiffness_for_a_measured_beta(beta: float, e: float) -> None:
    c = damping.clamped_hertz_damping(e)
    mindlin = 1.29  # 8 G* / (4/3 E*) for steel on Zerodur
    ratio = damping.stiffness_ratio_for_rebound(beta, c, mindlin)
    assert 0.0 < ratio < mindlin
    assert float(damping.stick_rebound(ratio, c, step=1e-3)) == pytest.approx(beta, abs=2e-3)


def test_sliding_friction_falls_short_where_the_damped_contact_sticks() -> None:
    """Properties the incremental, capped spring must have: an undamped, stiff contact
    slides from first touch (Walton's μ_f comes back); heavy damping makes it stick at
    first and lose friction impulse, less so the more oblique the impact."""
    sqrt3 = 3**0.5
    stiff = float(damping.sliding_friction(0.15, 1e-6, 1e6, sqrt3, step=2e-3))
    assert stiff == pytest.approx(0.15, rel=2e-3)
    dry = float(damping.sliding_friction(0.15, damping.clamped_hertz_damping(0.97), 1.3, sqrt3))
    assert dry == pytest.approx(0.15, rel=5e-4)
    c = damping.clamped_hertz_damping(0.274)
    wet = damping.sliding_friction(0.15, c, 1.3, [1.0, sqrt3, 5.67])
    assert 0.13 < wet[0] < wet[1] < wet[2] < 0.15
    # a finer step agrees
    fine = float(damping.sliding_friction(0.15, c, 1.3, sqrt3, step=5e-4))
    assert float(wet[1]) == pytest.approx(fine, rel=2e-3)


@pytest.mark.parametrize(("mu", "e"), [(0.15, 0.274), (0.11, 0.5), (0.106, 0.97)])
def test_friction_input_gives_the_target_on_the_sliding_branch(mu: float, e: float) -> None:
    c = damping.clamped_hertz_damping(e)
    mu_in = damping.friction_for_sliding(mu, c, 1.3, 3**0.5)
    assert mu_in >= mu
    back = float(damping.sliding_friction(mu_in, c, 1.3, 3**0.5, step=1e-3))
    assert back == pytest.approx(mu, rel=2e-3)


def test_friction_input_stops_at_its_limit() -> None:
    """A contact that sticks too long (a soft spring, heavy damping, a near-normal impact)
    cannot be given the target by any input up to the limit: the limit is returned, and
    what it gives falls short (the writer checks it)."""
    c = damping.clamped_hertz_damping(0.2)
    mu_in = damping.friction_for_sliding(0.5, c, 0.05, 0.3)
    assert mu_in == pytest.approx(0.5 * damping.FRICTION_INPUT_LIMIT)
    assert float(damping.sliding_friction(mu_in, c, 0.05, 0.3)) < 0.5


@pytest.mark.parametrize("e", [0.02, 0.01, 0.005])
def test_clamped_damping_reaches_tiny_restitution(e: float) -> None:
    """Below e = 0.02 the clamped law needs more than 3 times the unclamped C plus 1 (the
    first bracket); the search extends it, and the C found gives e back."""
    c = damping.clamped_hertz_damping(e)
    assert c > 3.0 * damping.hertz_damping(e) + 1.0
    assert damping.hertz_restitution(c, clamp_attraction=True, step=1e-3) == pytest.approx(
        e, abs=2e-4
    )


def test_clamped_damping_refuses_no_rebound() -> None:
    with pytest.raises(ValidationError, match="must be > 0"):
        damping.clamped_hertz_damping(0.0)


def test_a_total_spring_loses_less_friction_than_an_incremental_one() -> None:
    """LIGGGHTS's and LAMMPS's total spring F_t = −ρ√δ u: undamped and stiff it slides
    from first touch (μ_f back); with heavy damping it loses friction impulse, less than
    Yade's incremental spring (its force follows √δ as the overlap grows), and the input
    from ``friction_for_sliding`` gives the target back on that law."""
    sqrt3 = 3**0.5
    stiff = float(damping.sliding_friction(0.15, 1e-6, 1e6, sqrt3, step=2e-3, incremental=False))
    assert stiff == pytest.approx(0.15, rel=2e-3)
    c = damping.clamped_hertz_damping(0.274)
    total = float(damping.sliding_friction(0.15, c, 1.3, sqrt3, incremental=False))
    incremental = float(damping.sliding_friction(0.15, c, 1.3, sqrt3))
    assert incremental < total < 0.15
    mu_in = damping.friction_for_sliding(0.15, c, 1.3, sqrt3, incremental=False)
    back = damping.sliding_friction(mu_in, c, 1.3, sqrt3, step=1e-3, incremental=False)
    assert float(back) == pytest.approx(0.15, rel=2e-3)
