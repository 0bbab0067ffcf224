"""Fluid regime numbers of an immersed collision (PHYSICS.md §3).

Inputs SI: densities [kg/m³], radius [m] (the particle's, R = d/2), speeds [m/s],
viscosity [Pa·s]. Results are dimensionless.
"""

from __future__ import annotations

from granudb.physics._types import Numeric, as_float

#: No rebound below this Stokes number "in the cited experiments" (Joseph & Hunt §1).
CRITICAL_STOKES_NUMBER = 10.0


def reynolds_number(
    fluid_density: Numeric, radius: Numeric, speed: Numeric, viscosity: Numeric
) -> Numeric:
    r"""Particle Reynolds number, Re = 2 ρ_f R V / μ (Joseph & Hunt §1).

    Examples
    --------
    Figure 3: a 12.7 mm glass sphere at 0.1193 m/s in 45 % glycerol (4.5 cP, 1112 kg/m³):

    >>> round(float(reynolds_number(1112.0, 6.35e-3, 0.1193, 4.5e-3)))
    374
    """
    return 2.0 * as_float(fluid_density) * as_float(radius) * as_float(speed) / as_float(viscosity)


def stokes_number(
    particle_density: Numeric, radius: Numeric, speed: Numeric, viscosity: Numeric
) -> Numeric:
    r"""Stokes number, St = m V / (6π μ R²) = 2 ρ_p R V / (9 μ) (Joseph & Hunt §1).

    The ratio of the particle's inertia to the viscous force; equal to Re (ρ_p/ρ_f) / 9.

    Examples
    --------
    Figure 3 (glass, ρ_p = 2540 kg/m³):

    >>> round(float(stokes_number(2540.0, 6.35e-3, 0.1193, 4.5e-3)))
    95
    """
    return (
        2.0
        * as_float(particle_density)
        * as_float(radius)
        * as_float(speed)
        / (9.0 * as_float(viscosity))
    )


def normal_stokes_number(
    particle_density: Numeric, radius: Numeric, normal_speed: Numeric, viscosity: Numeric
) -> Numeric:
    r"""Normal Stokes number, St_n = St cos ζ_in = 2 ρ_p R v_N,in / (9 μ) (§4).

    Rebound is expected when St_n exceeds the critical Stokes number (about 10).

    Examples
    --------
    >>> round(float(normal_stokes_number(2540.0, 6.35e-3, 0.1193 * 0.9397, 4.5e-3)), 1)
    89.3
    """
    return stokes_number(particle_density, radius, normal_speed, viscosity)


def speed_for_stokes_number(
    stokes: Numeric, particle_density: Numeric, radius: Numeric, viscosity: Numeric
) -> Numeric:
    r"""The speed giving Stokes number ``stokes``: V = 9 μ St / (2 ρ_p R) [m/s].

    Examples
    --------
    >>> round(float(speed_for_stokes_number(95.0, 2540.0, 6.35e-3, 4.5e-3)), 4)
    0.1193
    """
    return (
        9.0
        * as_float(viscosity)
        * as_float(stokes)
        / (2.0 * as_float(particle_density) * as_float(radius))
    )
