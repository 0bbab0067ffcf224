"""Pair properties and Hertz contact mechanics (docs/physics.md §1–§2).

All inputs SI: moduli [Pa], lengths [m], masses [kg], densities [kg/m³], speeds [m/s].
Infinite values are allowed where a limit is meant (a flat wall has infinite radius and
mass; a rigid wall infinite modulus).
"""

from __future__ import annotations

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float, hypot

#: Hertz contact duration prefactor, t_c ≈ 2.87 (m² / (R E*² V))^{1/5} (Johnson 1985 §11.4).
CONTACT_TIME_FACTOR = 2.87


@parameters
def shear_modulus(youngs_modulus: Numeric, poisson_ratio: Numeric) -> Numeric:
    r"""Shear modulus of an isotropic solid, G = E / (2(1 + ν)).

    Returns
    -------
    Shear modulus G [Pa]

    Examples
    --------
    >>> float(shear_modulus(190e9, 0.27)) / 1e9
    74.80314960629921
    """
    return as_float(youngs_modulus) / (2.0 * (1.0 + as_float(poisson_ratio)))


@parameters
def reduced_modulus(
    youngs_1: Numeric, poisson_1: Numeric, youngs_2: Numeric, poisson_2: Numeric
) -> Numeric:
    r"""Reduced (plane-strain) modulus of a pair, 1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂.

    Joseph & Hunt §1; Johnson (1985) p. 92. A rigid body has E = ∞ (its term vanishes).

    Returns
    -------
    E* [Pa]

    Examples
    --------
    Steel on Zerodur (table 1):

    >>> round(float(reduced_modulus(190e9, 0.27, 91e9, 0.24)) / 1e9, 2)
    65.64
    """
    compliance = (1.0 - as_float(poisson_1) ** 2) / as_float(youngs_1) + (
        1.0 - as_float(poisson_2) ** 2
    ) / as_float(youngs_2)
    return 1.0 / compliance


@parameters
def reduced_shear_modulus(
    shear_1: Numeric, poisson_1: Numeric, shear_2: Numeric, poisson_2: Numeric
) -> Numeric:
    r"""Reduced shear modulus of a pair, 1/G* = (2−ν₁)/G₁ + (2−ν₂)/G₂ (Appendix).

    Returns
    -------
    G* [Pa]

    Examples
    --------
    >>> g1 = shear_modulus(190e9, 0.27); g2 = shear_modulus(91e9, 0.24)
    >>> round(float(reduced_shear_modulus(g1, 0.27, g2, 0.24)) / 1e9, 2)
    14.07
    """
    compliance = (2.0 - as_float(poisson_1)) / as_float(shear_1) + (
        2.0 - as_float(poisson_2)
    ) / as_float(shear_2)
    return 1.0 / compliance


@parameters
def effective_radius(radius_1: Numeric, radius_2: Numeric = np.inf) -> Numeric:
    r"""Effective radius of curvature, 1/R = 1/R₁ + 1/R₂; a flat wall has R₂ = ∞ (thesis).

    Examples
    --------
    >>> float(effective_radius(6.35e-3))
    0.00635
    >>> float(effective_radius(6.35e-3, 6.35e-3))
    0.003175
    """
    return 1.0 / (1.0 / as_float(radius_1) + 1.0 / as_float(radius_2))


@parameters
def effective_mass(mass_1: Numeric, mass_2: Numeric = np.inf) -> Numeric:
    r"""Effective mass, m = m₁m₂/(m₁+m₂) = 1/(1/m₁ + 1/m₂); a wall has m₂ = ∞.

    Examples
    --------
    >>> float(effective_mass(2.0, 2.0))
    1.0
    """
    return 1.0 / (1.0 / as_float(mass_1) + 1.0 / as_float(mass_2))


@parameters
def sphere_mass(density: Numeric, diameter: Numeric) -> Numeric:
    r"""Mass of a solid sphere, m = ρ π d³ / 6 [kg] from density [kg/m³] and diameter [m].

    Examples
    --------
    >>> round(float(sphere_mass(7780.0, 12.7e-3)) * 1e3, 3)
    8.344
    """
    d = as_float(diameter)
    return as_float(density) * np.pi * (d * d * d) / 6.0  # d·d·d: a pow costs ~10× more


@parameters
def composite_roughness(roughness_1: Numeric, roughness_2: Numeric) -> Numeric:
    r"""Composite RMS roughness of two surfaces, σ = √(σ₁² + σ₂²) [m] (tribology).

    Examples
    --------
    >>> round(float(composite_roughness(0.1305e-6, 0.0155e-6)) * 1e9, 1)
    131.4
    """
    return hypot(roughness_1, roughness_2)


@parameters(density="density ρ of the material [kg/m³]")
def wave_speed(youngs_modulus: Numeric, density: Numeric) -> Numeric:
    r"""Bulk elastic wave speed, c = √(E/ρ) [m/s] (thesis §3).

    Examples
    --------
    >>> round(float(wave_speed(190e9, 7780.0)))
    4942
    """
    return np.sqrt(as_float(youngs_modulus) / as_float(density))


@parameters
def hertz_force(reduced_modulus_pa: Numeric, radius: Numeric, approach: Numeric) -> Numeric:
    r"""Static Hertz force, F = (4/3) E* R^{1/2} δ^{3/2} [N] (thesis (3.1)).

    Examples
    --------
    >>> round(float(hertz_force(65.6e9, 6.35e-3, 1e-6)), 3)
    6.97
    """
    delta = as_float(approach)
    # δ^{3/2} as δ√δ: the same to an ulp, and a square root is far cheaper than a power.
    return (
        4.0
        / 3.0
        * as_float(reduced_modulus_pa)
        * np.sqrt(as_float(radius))
        * (delta * np.sqrt(delta))
    )


@parameters
def contact_radius_from_approach(radius: Numeric, approach: Numeric) -> Numeric:
    r"""Hertz contact radius under approach δ, a = √(R δ) [m] (thesis (3.5)).

    Examples
    --------
    >>> float(contact_radius_from_approach(1e-2, 1e-6))
    0.0001
    """
    return np.sqrt(as_float(radius) * as_float(approach))


@parameters
def elastic_energy(reduced_modulus_pa: Numeric, radius: Numeric, approach: Numeric) -> Numeric:
    r"""Elastic energy stored at approach δ, W_el = (8/15) E* R^{1/2} δ^{5/2} [J].

    The integral of (3.1) over δ.

    Examples
    --------
    >>> round(float(elastic_energy(65.6e9, 6.35e-3, 1e-6)) * 1e6, 4)
    2.788
    """
    return (
        8.0
        / 15.0
        * as_float(reduced_modulus_pa)
        * np.sqrt(as_float(radius))
        * as_float(approach) ** 2.5
    )


@parameters
def max_approach(
    mass: Numeric, speed: Numeric, reduced_modulus_pa: Numeric, radius: Numeric
) -> Numeric:
    r"""Maximum approach in an elastic impact, δ_max = (15 m V² / (16 E* R^{1/2}))^{2/5} [m].

    Found by equating the kinetic energy ½mV² with the stored energy (8/15)E*R^{1/2}δ^{5/2}
    (Johnson 1985 §11.4). ``mass`` is the effective mass, ``speed`` the normal speed.

    Examples
    --------
    >>> round(float(max_approach(8.33e-3, 0.3, 65.6e9, 6.35e-3)) * 1e6, 3)
    7.103
    """
    return (
        15.0
        * as_float(mass)
        * as_float(speed) ** 2
        / (16.0 * as_float(reduced_modulus_pa) * np.sqrt(as_float(radius)))
    ) ** 0.4


@parameters
def contact_time(
    mass: Numeric, radius: Numeric, reduced_modulus_pa: Numeric, speed: Numeric
) -> Numeric:
    r"""Hertz contact duration, t_c ≈ 2.87 (m² / (R E*² V))^{1/5} [s] (Johnson §11.4).

    Examples
    --------
    >>> round(float(contact_time(8.33e-3, 6.35e-3, 65.6e9, 0.3)) * 1e6, 2)
    69.73
    """
    return (
        CONTACT_TIME_FACTOR
        * (
            as_float(mass) ** 2
            / (as_float(radius) * as_float(reduced_modulus_pa) ** 2 * as_float(speed))
        )
        ** 0.2
    )


@parameters(approach="maximum approach δ_max [m]")
def contact_time_from_approach(approach: Numeric, speed: Numeric) -> Numeric:
    r"""Hertz contact duration from the maximum approach, t_c = 2.87 (16/15)^{2/5} δ_max / V [s].

    The same t_c as ``contact_time`` (Johnson §11.4), written with δ_max: since
    δ_max = (15/16)^{2/5} (m/(E*R^{1/2}))^{2/5} V^{4/5}, the factor (m²/(R E*² V))^{1/5} of
    ``contact_time`` is (16/15)^{2/5} δ_max / V. ``derive`` has δ_max already, and a
    division is far cheaper than a fifth root.

    Examples
    --------
    >>> delta = max_approach(8.33e-3, 0.3, 65.6e9, 6.35e-3)
    >>> round(float(contact_time_from_approach(delta, 0.3)) * 1e6, 2)
    69.73
    """
    return CONTACT_TIME_FACTOR * (16.0 / 15.0) ** 0.4 * as_float(approach) / as_float(speed)


@parameters
def peak_impact_force(
    mass: Numeric, speed: Numeric, reduced_modulus_pa: Numeric, radius: Numeric
) -> Numeric:
    r"""Peak Hertz force of an elastic impact, F(δ_max) [N], for any effective mass.

    For a sphere of density ρ_p on a flat wall this equals the equivalent impact load
    (2.2) exactly (``hertz_impact_load``); for two spheres it uses the effective mass.

    Examples
    --------
    >>> m = float(sphere_mass(7780.0, 12.7e-3))
    >>> round(float(peak_impact_force(m, 0.3, 65.6e9, 6.35e-3)), 2)
    132.07
    """
    delta = max_approach(mass, speed, reduced_modulus_pa, radius)
    return hertz_force(reduced_modulus_pa, radius, delta)


@parameters
def hertz_impact_load(
    radius: Numeric, reduced_modulus_pa: Numeric, particle_density: Numeric, speed: Numeric
) -> Numeric:
    r"""Equivalent impact load, W = (4/3) R² E* (5π ρ_p V² / (4E*))^{3/5} [N] (2.2).

    ``speed`` is the normal component v_N,in for an oblique impact.

    Examples
    --------
    >>> round(float(hertz_impact_load(6.35e-3, 65.6e9, 7780.0, 0.3)), 2)
    132.07
    """
    e_star = as_float(reduced_modulus_pa)
    return (
        4.0
        / 3.0
        * as_float(radius) ** 2
        * e_star
        * (5.0 * np.pi * as_float(particle_density) * as_float(speed) ** 2 / (4.0 * e_star)) ** 0.6
    )


@parameters
def max_contact_radius(radius: Numeric, load: Numeric, reduced_modulus_pa: Numeric) -> Numeric:
    r"""Contact radius at the peak load, a = (3 R W / (4 E*))^{1/3} [m] (2.1).

    Examples
    --------
    >>> round(float(max_contact_radius(6.35e-3, 132.07, 65.6e9)) * 1e6, 1)
    212.4
    """
    return np.cbrt(3.0 * as_float(radius) * as_float(load) / (4.0 * as_float(reduced_modulus_pa)))


@parameters
def max_pressure(load: Numeric, contact_radius: Numeric) -> Numeric:
    r"""Maximum Hertz pressure, p_max = 3W / (2π a²) [Pa] (5.5).

    Examples
    --------
    >>> round(float(max_pressure(132.07, 212.5e-6)) / 1e9, 3)
    1.396
    """
    return 3.0 * as_float(load) / (2.0 * np.pi * as_float(contact_radius) ** 2)


@parameters
def max_pressure_from_impact(
    particle_density: Numeric, speed: Numeric, reduced_modulus_pa: Numeric
) -> Numeric:
    r"""Maximum Hertz pressure of a sphere hitting a flat wall,
    p_max = (40 ρ_p V² E*⁴ / π⁴)^{1/5} [Pa] (5.5).

    Examples
    --------
    >>> round(float(max_pressure_from_impact(7780.0, 0.3, 65.6e9)) / 1e9, 3)
    1.397
    """
    return (
        40.0
        * as_float(particle_density)
        * as_float(speed) ** 2
        * as_float(reduced_modulus_pa) ** 4
        / np.pi**4
    ) ** 0.2


@parameters
def quasi_static_ratio(
    contact_radius: Numeric, wave_speed_m_s: Numeric, contact_time_s: Numeric
) -> Numeric:
    r"""Hertz quasi-static criterion a / λ, with λ ≈ c t_c the radiated wavelength [-].

    Hertz's static solution holds during impact when the contact lies in the near field
    of the elastic waves it radiates, λ ≫ a (thesis (3.18); Johnson 1985 pp. 351–360).
    granudb calls the impact quasi-static when this ratio is below
    ``QUASI_STATIC_LIMIT``.

    Examples
    --------
    >>> round(float(quasi_static_ratio(212.5e-6, 4942.0, 69.7e-6)), 5)
    0.00062
    """
    return as_float(contact_radius) / (as_float(wave_speed_m_s) * as_float(contact_time_s))


#: a/λ below this counts as "≪ 1" for the quasi-static verdict.
QUASI_STATIC_LIMIT = 0.1
