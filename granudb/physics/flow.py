"""Fluid regime numbers of an immersed collision (docs/physics.md §3).

Inputs SI: densities [kg/m³], radius [m] (the particle's, R = d/2), speeds [m/s],
viscosity [Pa·s]. Results are dimensionless.
"""

from __future__ import annotations

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float

#: No rebound below this Stokes number "in the cited experiments" (Joseph & Hunt §1).
CRITICAL_STOKES_NUMBER = 10.0


@parameters
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


@parameters
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


@parameters
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


@parameters
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


#: Legendre, Zenit, Daniel & Guiraud (2006), Chem. Eng. Sci. 61, 3543: e/e_dry =
#: exp(−β_L/St) with β_L ≈ 35.
LEGENDRE_BETA = 35.0
#: Added-mass coefficient of a sphere, C_M = 1/2 (Legendre et al. 2006).
ADDED_MASS_COEFFICIENT = 0.5


@parameters
def added_mass_stokes_number(
    particle_density: Numeric,
    fluid_density: Numeric,
    radius: Numeric,
    speed: Numeric,
    viscosity: Numeric,
    added_mass: Numeric = ADDED_MASS_COEFFICIENT,
) -> Numeric:
    r"""Stokes number with added mass, St = (ρ_p + C_M ρ_f) 2 R V / (9 μ) [-]
    (Legendre, Zenit, Daniel & Guiraud 2006, Chem. Eng. Sci. 61, 3543; C_M = 1/2).

    Examples
    --------
    Figure 3's glass sphere (St = 95 without added mass) in 45 % glycerol:

    >>> round(float(added_mass_stokes_number(2540.0, 1112.0, 6.35e-3, 0.1193, 4.5e-3)), 1)
    115.8
    """
    return stokes_number(
        as_float(particle_density) + as_float(added_mass) * as_float(fluid_density),
        radius,
        speed,
        viscosity,
    )


@parameters(stokes="Stokes number St (the added-mass one the form was fitted with) [-]")
def predicted_restitution(
    stokes: Numeric,
    dry_restitution: Numeric = 0.97,
    critical_stokes: Numeric = CRITICAL_STOKES_NUMBER,
    coefficient: Numeric = LEGENDRE_BETA,
) -> Numeric:
    r"""Predicted wet restitution, e = e_dry exp(−β_L / St) above St_c, 0 below [-].

    The form and β_L ≈ 35 are Legendre et al. (2006); no rebound below St_c ≈ 10 is
    Gondret, Lance & Petit (2002), Phys. Fluids 14, 643. ``stokes`` should be the
    added-mass Stokes number the form was fitted with (``added_mass_stokes_number``);
    ``dry_restitution`` defaults to Joseph & Hunt's ē_dry = 0.97 (§3). A NaN Stokes
    number (dry) gives e_dry.

    Examples
    --------
    >>> [round(float(x), 4) for x in predicted_restitution(np.array([5.0, 35.0, 3500.0]))]
    [0.0, 0.3568, 0.9603]
    """
    st = as_float(stokes)
    with np.errstate(divide="ignore", invalid="ignore"):
        wet = as_float(dry_restitution) * np.exp(-as_float(coefficient) / st)
    return np.where(np.isnan(st), dry_restitution, np.where(st > critical_stokes, wet, 0.0))
