"""Two bodies in contact: a particle (1) and a target (2) that may move (docs/physics.md §9).

The target is a flat wall (R₂ → ∞, m₂ → ∞), a fixed sphere (R₂ finite, m₂ → ∞) or a free
sphere (both finite). With a free target every collision parameter is built from the
**relative** velocities of the contact point, and the pair's inertia enters the Walton
relations through B = 1 + m*(R₁²/I₁ + R₂²/I₂) and the Stokes number through m* and R*.

Sign convention (granudb's, documented again in ``granudb.physics.derive``): the normal n
points from the particle to the target, the tangential axis t along the particle's
incoming tangential motion; both spins are about the same axis n × t, positive where the
*particle's* spin moves its contact point along +t. A positive target spin then moves the
target's contact point along −t, so the relative tangential velocity of the contact point
is v_T = (v₁ − v₂)·t + ω₁R₁ + ω₂R₂.
"""

from __future__ import annotations

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float

#: Squared radius of gyration over R² of a solid sphere, K² = I/(mR²) = 2/5.
SOLID_SPHERE_GYRATION = 0.4


@parameters
def relative_normal_velocity(particle_v_n: Numeric, target_v_n: Numeric = 0.0) -> Numeric:
    r"""Relative normal velocity, v_N = (v₁ − v₂)·n [m/s] (§9).

    Examples
    --------
    A particle at 0.3 m/s overtaking a sphere moving away at 0.1 m/s approaches at 0.2:

    >>> round(float(relative_normal_velocity(0.3, 0.1)), 12)
    0.2
    """
    return as_float(particle_v_n) - as_float(target_v_n)


@parameters
def relative_tangential_velocity(
    particle_v_t: Numeric,
    particle_omega: Numeric,
    particle_radius: Numeric,
    target_v_t: Numeric = 0.0,
    target_omega: Numeric = 0.0,
    target_radius: Numeric = 0.0,
) -> Numeric:
    r"""Relative tangential velocity of the contact point,
    v_T = (v₁ − v₂)·t + ω₁R₁ + ω₂R₂ [m/s] (§9; sign convention in the module doc).

    Examples
    --------
    Two equal spheres spinning the same way (both +10 rad/s about n × t) roll against
    each other: their contact points move in opposite directions, so the spins add:

    >>> round(float(relative_tangential_velocity(0.0, 10.0, 6.35e-3, 0.0, 10.0, 6.35e-3)), 6)
    0.127
    """
    return (
        as_float(particle_v_t)
        - as_float(target_v_t)
        + as_float(particle_omega) * as_float(particle_radius)
        + as_float(target_omega) * as_float(target_radius)
    )


@parameters
def walton_factor(
    effective_mass: Numeric,
    particle_mass: Numeric,
    target_mass: Numeric = np.inf,
    particle_gyration: Numeric = SOLID_SPHERE_GYRATION,
    target_gyration: Numeric = SOLID_SPHERE_GYRATION,
) -> Numeric:
    r"""Walton factor B = 1 + m*(R₁²/I₁ + R₂²/I₂) [-] (§9, from the impulse balance).

    Written with I = K² m R², so R²/I = 1/(K² m) and an immovable target (m₂ = ∞)
    contributes nothing. For solid spheres (K² = 2/5) B = 1 + 1/K² = 7/2 for a sphere on a
    wall, on a fixed sphere and for any two free spheres, since m*(1/m₁ + 1/m₂) = 1.

    Examples
    --------
    >>> float(walton_factor(8.3e-3, 8.3e-3))
    3.5
    >>> float(walton_factor(1.0, 2.0, 2.0))
    3.5
    """
    m_eff = as_float(effective_mass)
    return (
        1.0
        + (m_eff / as_float(particle_mass)) / as_float(particle_gyration)
        + (m_eff / as_float(target_mass)) / as_float(target_gyration)
    )


@parameters
def walton_sliding_rebound(
    psi_in: Numeric, friction: Numeric, restitution: Numeric, factor: Numeric = 3.5
) -> Numeric:
    r"""Walton, sliding, for a pair: Ψ_out = Ψ_in − μ_f (1+e) B [-] ((2.6) generalised, §9).

    Examples
    --------
    >>> round(float(walton_sliding_rebound(2.0, 0.11, 0.97)), 4)
    1.2415
    """
    return as_float(psi_in) - as_float(friction) * (1.0 + as_float(restitution)) * as_float(factor)


@parameters
def pair_sliding_friction(
    psi_in: Numeric, psi_out: Numeric, restitution: Numeric, factor: Numeric = 3.5
) -> Numeric:
    r"""Friction from one collision of a pair, μ_f = (Ψ_in − Ψ_out) / ((1+e) B) [-]
    ((2.9) generalised, §9; B = 7/2 gives (2.9)).

    Examples
    --------
    >>> round(float(pair_sliding_friction(2.0, 2.0 - 0.11 * 1.97 * 3.5, 0.97)), 6)
    0.11
    """
    return (as_float(psi_in) - as_float(psi_out)) / (
        (1.0 + as_float(restitution)) * as_float(factor)
    )


@parameters(speed="relative impact speed V [m/s]")
def pair_stokes_number(
    effective_mass: Numeric, speed: Numeric, viscosity: Numeric, effective_radius: Numeric
) -> Numeric:
    r"""Stokes number of a pair, St = m* V / (6π μ R*²) [-] (Davis, Serayssol & Hinch 1986,
    J. Fluid Mech. 163, 479; docs/physics.md §9).

    For a sphere on a flat wall (m* = m, R* = R) it is Joseph & Hunt's 2ρ_p R V/(9μ);
    for two equal free spheres (m* = m/2, R* = R/2) it is twice that.

    Examples
    --------
    Figure 3's glass sphere on the wall (St = 95), then against an equal free sphere:

    >>> m = 2540.0 * np.pi * 12.7e-3**3 / 6
    >>> round(float(pair_stokes_number(m, 0.1193, 4.5e-3, 6.35e-3)))
    95
    >>> round(float(pair_stokes_number(m / 2, 0.1193, 4.5e-3, 6.35e-3 / 2)))
    190
    """
    return (
        as_float(effective_mass)
        * as_float(speed)
        / (6.0 * np.pi * as_float(viscosity) * as_float(effective_radius) ** 2)
    )


@parameters
def pair_normal_stokes_number(
    effective_mass: Numeric, normal_speed: Numeric, viscosity: Numeric, effective_radius: Numeric
) -> Numeric:
    r"""Normal Stokes number of a pair, St_n = m* v_N / (6π μ R*²) [-] (§4, §9).

    ``normal_speed`` is the relative normal approach speed v_N,in [m/s].

    Examples
    --------
    >>> m = 2540.0 * np.pi * 12.7e-3**3 / 6
    >>> round(float(pair_normal_stokes_number(m, 0.1193 * 0.9397, 4.5e-3, 6.35e-3)), 1)
    89.3
    """
    return pair_stokes_number(effective_mass, normal_speed, viscosity, effective_radius)


@parameters
def contact_incidence_angle(v_T_in: Numeric, v_N_in: Numeric) -> Numeric:
    r"""Incidence angle of the contact point's path, ζ_in = atan(|v_T,in| / v_N,in) [rad] (§5).

    ``v_T_in`` is the relative tangential velocity of the contact point (spin counts),
    ``v_N_in`` the relative normal approach speed (> 0). In [0, π/2).

    Examples
    --------
    >>> round(float(np.degrees(contact_incidence_angle(-0.1, 0.1))), 6)
    45.0
    """
    return np.arctan2(np.abs(as_float(v_T_in)), as_float(v_N_in))
