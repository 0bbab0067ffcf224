"""Runs as papers report them: from e_t, ω_out or a rebound angle to Walton's Ψ (§5).

Many papers give, per run or per figure point, the tangential restitution of the centre of
mass e_t = v_t,out / v_t,in, the spin after impact ω_out or a rebound angle, and not the
velocities. For a rigid sphere that arrives *without spin*, these are tied to Walton's
effective angles by exact relations (impulse and angular impulse about the centre: the
contact force's tangential impulse J changes v_t by −J/m and ωR by −J R²/I = −J/(m K²)):

    Ψ_in  = tan θ                                   (no spin in, θ from the normal)
    Ψ_out = Ψ_in ((1 + 1/K²) e_t − 1/K²)            (= Ψ_in (3.5 e_t − 2.5), solid sphere)
    ω_out = V sin θ (1 − e_t) / (K² R)

No relation here needs, or makes, a velocity: a run stated as e_t(θ) enters a Walton fit
through these (with its e), and nothing claims a measured speed. With spin in, v_T,in
needs ω_in, and the relations do not hold.
"""

from __future__ import annotations

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float

#: K² = I/(mR²) of a solid sphere.
SOLID_SPHERE_GYRATION = 0.4

_E_T = "tangential restitution of the centre of mass e_t = v_t,out / v_t,in [-]"
_THETA = "incidence angle θ of the centre-of-mass velocity from the wall normal [rad]"


@parameters(incidence_angle=_THETA)
def incidence_from_angle(incidence_angle: Numeric) -> Numeric:
    r"""Effective incidence of a run without spin in, Ψ_in = tan θ [-].

    Examples
    --------
    >>> round(float(incidence_from_angle(np.radians(45.0))), 12)
    1.0
    """
    return np.tan(as_float(incidence_angle))


@parameters(tangential_restitution=_E_T)
def rebound_from_tangential_restitution(
    psi_in: Numeric, tangential_restitution: Numeric, gyration: Numeric = SOLID_SPHERE_GYRATION
) -> Numeric:
    r"""Effective rebound of a run without spin in, Ψ_out = Ψ_in ((1+1/K²) e_t − 1/K²) [-].

    Exact for a rigid sphere (impulse and angular impulse about its centre); for a solid
    sphere Ψ_out = Ψ_in (3.5 e_t − 2.5). A sliding run (Ψ_out = Ψ_in − μ_f (1+e) 7/2) has
    e_t = 1 − μ_f (1+e) / Ψ_in.

    Examples
    --------
    >>> float(rebound_from_tangential_restitution(1.0, 1.0))
    1.0
    >>> round(float(rebound_from_tangential_restitution(0.5, 5 / 7)), 12)
    0.0
    """
    inverse = 1.0 / as_float(gyration)
    return as_float(psi_in) * ((1.0 + inverse) * as_float(tangential_restitution) - inverse)


@parameters(tangential_restitution=_E_T)
def tangential_restitution_from_rebound(
    psi_in: Numeric, psi_out: Numeric, gyration: Numeric = SOLID_SPHERE_GYRATION
) -> Numeric:
    r"""e_t of a run without spin in, (Ψ_out/Ψ_in + 1/K²) / (1 + 1/K²) [-]; the inverse of
    ``rebound_from_tangential_restitution``.

    Examples
    --------
    >>> round(float(tangential_restitution_from_rebound(0.5, 0.0)), 6)
    0.714286
    """
    inverse = 1.0 / as_float(gyration)
    return (as_float(psi_out) / as_float(psi_in) + inverse) / (1.0 + inverse)


@parameters(
    tangential_restitution=_E_T,
    incidence_angle=_THETA,
    speed="impact speed V of the centre of mass [m/s]",
)
def spin_from_tangential_restitution(
    speed: Numeric,
    incidence_angle: Numeric,
    tangential_restitution: Numeric,
    radius: Numeric,
    gyration: Numeric = SOLID_SPHERE_GYRATION,
) -> Numeric:
    r"""Spin after impact of a sphere arriving without spin, ω_out = V sin θ (1 − e_t)/(K² R)
    [rad/s].

    Examples
    --------
    Kharaz et al.'s 5 mm alumina at 3.9 m/s, θ = 30°, e_t = 0.69:
    >>> round(float(spin_from_tangential_restitution(3.9, np.radians(30), 0.69, 2.5e-3)))
    604
    """
    return (
        as_float(speed)
        * np.sin(as_float(incidence_angle))
        * (1.0 - as_float(tangential_restitution))
        / (as_float(gyration) * as_float(radius))
    )


@parameters(tangential_restitution=_E_T, incidence_angle=_THETA)
def centre_rebound_angle(
    incidence_angle: Numeric, tangential_restitution: Numeric, restitution: Numeric
) -> Numeric:
    r"""Rebound angle of the centre of mass from the normal, atan(e_t tan θ / e) [rad].

    Examples
    --------
    >>> round(float(np.degrees(centre_rebound_angle(np.radians(45.0), 0.9, 0.9))), 6)
    45.0
    """
    return np.arctan(
        as_float(tangential_restitution) * np.tan(as_float(incidence_angle)) / as_float(restitution)
    )


@parameters
def contact_rebound_angle(psi_out: Numeric, restitution: Numeric) -> Numeric:
    r"""Rebound angle of the contact point from the normal, atan(Ψ_out / e) [rad]: negative
    when the contact point recoils (Ψ_out < 0).

    Examples
    --------
    >>> round(float(np.degrees(contact_rebound_angle(-0.1, 1.0))), 4)
    -5.7106
    """
    return np.arctan(as_float(psi_out) / as_float(restitution))


@parameters(
    reynolds="Reynolds number Re = 2 ρ_f R V / μ as reported [-]",
)
def speed_for_reynolds_number(
    reynolds: Numeric, fluid_density: Numeric, radius: Numeric, viscosity: Numeric
) -> Numeric:
    r"""The impact speed a reported Reynolds number states, V = Re μ / (2 ρ_f R) [m/s].

    A derived speed (the paper's Re and fluid), never stored as a measured one.

    Examples
    --------
    >>> round(float(speed_for_reynolds_number(374.0, 1112.0, 6.35e-3, 4.5e-3)), 4)
    0.1192
    """
    return (
        as_float(reynolds)
        * as_float(viscosity)
        / (2.0 * as_float(fluid_density) * as_float(radius))
    )
