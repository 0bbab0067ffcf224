"""Lubrication of an immersed impact: EHD gap, piezoviscosity, lubricated friction
(docs/physics.md §3, §4 and §6; Joseph & Hunt §1 and §5).

Two film thicknesses appear and must not be confused: the normal-approach gap
h_m = x₁/3 (``ehd_min_gap``; tens of nanometres), compared with the surface roughness, and
Gohar's traction film (``traction_film_thickness``, (5.6); below a nanometre for water),
used only inside the friction model (5.8).
"""

from __future__ import annotations

from math import comb

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float

#: h_m = x₁ × this (the paper uses 1/3; Davis et al. 1986 give 1/4 to 1/3).
GAP_FRACTION = 1.0 / 3.0
#: Chu–Cameron exponent: μ(p) = μ₀ (1 + η̂ p)^16 (5.1).
CHU_CAMERON_EXPONENT = 16
#: Gohar's traction-film prefactor in (5.6).
GOHAR_FILM_FACTOR = 4.3384
#: The constant of the dimensionless friction (5.10) as the paper prints it (rounded).
PRINTED_FRICTION_FACTOR = 0.87
#: The exact constant of (5.10), from (5.6), (5.8), (2.1) and (2.2):
#: (2π/4.3384) (3/4)^{2/3} (4/3)^{−2/7} (5π/4)^{−6/35} = 0.871008… (see
#: ``lubricated_friction_dimensionless``). (5.10) with it equals (5.8) to rounding.
DIMENSIONLESS_FRICTION_FACTOR = (
    2.0
    * np.pi
    / GOHAR_FILM_FACTOR
    * 0.75 ** (2.0 / 3.0)
    * (4.0 / 3.0) ** (-2.0 / 7.0)
    * (1.25 * np.pi) ** (-6.0 / 35.0)
)

# A(c) = ∫₀¹ s (1 + c s)^16 ds = Σ_k C(16, k) c^k / (k + 2): coefficients, lowest power first.
_A_COEFFICIENTS = np.array(
    [comb(CHU_CAMERON_EXPONENT, k) / (k + 2) for k in range(CHU_CAMERON_EXPONENT + 1)]
)


@parameters
def davis_elastic_length(
    viscosity: Numeric, approach_speed: Numeric, radius: Numeric, reduced_modulus_pa: Numeric
) -> Numeric:
    r"""Davis et al. (1986) elastic length, x₁ = (4 μ v₀ R^{3/2} / (π E*))^{2/5} [m] (§1).

    The scale of the gap at which the approaching sphere's pressure deforms the surfaces.

    Examples
    --------
    Glass on Zerodur (E* = 38.25 GPa) at 0.1 m/s in 4.5 cP glycerol:

    >>> round(float(davis_elastic_length(4.5e-3, 0.1, 6.35e-3, 38.25e9)) * 1e9, 1)
    141.9
    """
    r = as_float(radius)
    return (
        4.0
        * as_float(viscosity)
        * as_float(approach_speed)
        * (r * np.sqrt(r))  # R^{3/2}; a square root costs a third of a power
        / (np.pi * as_float(reduced_modulus_pa))
    ) ** 0.4


@parameters
def ehd_min_gap(elastic_length: Numeric, fraction: float = GAP_FRACTION) -> Numeric:
    r"""Elastohydrodynamic minimum gap of a normal approach, h_m ≈ x₁/3 [m] (§1, §4).

    Examples
    --------
    >>> round(float(ehd_min_gap(141.8e-9)) * 1e9, 2)
    47.27
    """
    return as_float(elastic_length) * fraction


@parameters
def piezoviscous_length(
    eta_hat: Numeric, viscosity: Numeric, approach_speed: Numeric, radius: Numeric
) -> Numeric:
    r"""Piezoviscous length, x₃ = (η̂ μ₀ v₀ R)^{1/2} [m] (§1, Barnocky & Davis 1989).

    Examples
    --------
    >>> round(float(piezoviscous_length(375e-12, 4.5e-3, 0.1, 6.35e-3)) * 1e9, 1)
    32.7
    """
    return np.sqrt(
        as_float(eta_hat) * as_float(viscosity) * as_float(approach_speed) * as_float(radius)
    )


@parameters
def barus_viscosity(
    viscosity: Numeric, pressure_coefficient: Numeric, pressure: Numeric
) -> Numeric:
    r"""Barus law, μ(p) = μ₀ exp(C p) [Pa·s] (§5).

    Examples
    --------
    >>> round(float(barus_viscosity(1e-3, 6e-9, 1e8)), 6)
    0.001822
    """
    return as_float(viscosity) * np.exp(as_float(pressure_coefficient) * as_float(pressure))


@parameters
def chu_cameron_coefficient(pressure_coefficient: Numeric) -> Numeric:
    r"""η̂ = C/16, matching Chu–Cameron to Barus at low pressure [1/Pa] (§5).

    Examples
    --------
    Glycerol, C = 6×10⁻⁹ Pa⁻¹, gives the paper's 375×10⁻¹² Pa⁻¹:

    >>> float(chu_cameron_coefficient(6e-9))
    3.75e-10
    """
    return as_float(pressure_coefficient) / CHU_CAMERON_EXPONENT


@parameters
def chu_cameron_viscosity(viscosity: Numeric, eta_hat: Numeric, pressure: Numeric) -> Numeric:
    r"""Chu–Cameron law, μ(p) = μ₀ (1 + η̂ p)^{16} [Pa·s] (5.1).

    Examples
    --------
    >>> round(float(chu_cameron_viscosity(1e-3, 375e-12, 1e8)), 6)
    0.001802
    """
    return as_float(viscosity) * (1.0 + as_float(eta_hat) * as_float(pressure)) ** 16


@parameters
def friction_integral(c: Numeric) -> Numeric:
    r"""A(c) = ∫₀¹ (1 + c√(1−z²))^{16} z dz, evaluated exactly [-] (5.9).

    With s = √(1−z²), A(c) = ∫₀¹ s (1 + c s)^{16} ds = Σ_{k=0}^{16} C(16,k) c^k/(k+2): a
    polynomial, evaluated by Horner's rule (no quadrature). A(0) = 1/2.

    Examples
    --------
    >>> float(friction_integral(0.0))
    0.5
    >>> round(float(friction_integral(0.06)), 6)
    0.956659
    """
    c = as_float(c)
    result = np.zeros_like(c)
    if result.ndim == 0:  # a 0-d array cannot be updated in place
        for coefficient in _A_COEFFICIENTS[::-1]:
            result = result * c + coefficient
        return result
    for coefficient in _A_COEFFICIENTS[::-1]:  # in place: no new array per step
        result *= c
        result += coefficient
    return result


@parameters(integral="A(c) if already computed (``friction_integral``), else None [-]")
def friction_integral_log_slope(c: Numeric, integral: Numeric | None = None) -> Numeric:
    r"""Logarithmic slope of (5.9), d ln A / d ln c = c A'(c) / A(c) [-], exactly.

    From the same polynomial: c A'(c) = Σ k C(16,k) c^k/(k+2). Used to propagate the
    uncertainty of c = η̂ p_max into A and (5.8) (``granudb.physics.uncertainty``).

    Examples
    --------
    A(c) → 1/2 + (16/3) c for small c, so the slope is ≈ (32/3) c there:

    >>> round(float(friction_integral_log_slope(1e-6)) / 1e-6, 3)
    10.667
    >>> float(friction_integral_log_slope(0.0))
    0.0
    """
    c = as_float(c)
    slope = np.zeros_like(c)
    for k, coefficient in reversed(list(enumerate(_A_COEFFICIENTS))):
        if slope.ndim:  # in place, as friction_integral
            slope *= c
            slope += k * coefficient
        else:
            slope = slope * c + k * coefficient
    return slope / (friction_integral(c) if integral is None else as_float(integral))


@parameters
def traction_film_thickness(
    radius: Numeric,
    viscosity: Numeric,
    tangential_speed: Numeric,
    eta_hat: Numeric,
    load: Numeric,
    reduced_modulus_pa: Numeric,
) -> Numeric:
    r"""Gohar's traction film, h = 4.3384 R (μ₀ U η̂ / R)^{5/7} (W/(E* R²))^{−1/21} [m] (5.6).

    ``tangential_speed`` U is the contact point's tangential speed, ``load`` W from (2.2).

    Examples
    --------
    >>> round(float(traction_film_thickness(6.35e-3, 1e-3, 0.1, 375e-12, 132.1, 65.64e9))
    ...       * 1e9, 3)
    0.421
    """
    r = as_float(radius)
    return (
        GOHAR_FILM_FACTOR
        * r
        * (as_float(viscosity) * as_float(tangential_speed) * as_float(eta_hat) / r) ** (5.0 / 7.0)
        * (as_float(load) / (as_float(reduced_modulus_pa) * r**2)) ** (-1.0 / 21.0)
    )


@parameters(integral="A(η̂ p_max) of (5.9) if already computed, else None [-]")
def lubricated_friction(
    viscosity: Numeric,
    tangential_speed: Numeric,
    load: Numeric,
    film_thickness: Numeric,
    contact_radius: Numeric,
    eta_hat: Numeric,
    max_pressure_pa: Numeric,
    integral: Numeric | None = None,
) -> Numeric:
    r"""Friction of a lubricated smooth contact (5.8):
    μ_f = (2π μ₀ U / (W h)) a² A(η̂ p_max).

    The shear stress μ(r)U/h of the piezoviscous film integrated over the Hertz contact.
    Where U = 0 the result is 0 (μ_f ∝ U^{2/7} as U → 0). ``integral``: A(η̂ p_max) if
    the caller has it already (``friction_integral``), else it is computed here.

    Examples
    --------
    >>> round(float(lubricated_friction(1e-3, 0.1, 132.1, 0.4211e-9, 212.4e-6, 375e-12,
    ...                                 1.398e9)), 4)
    0.062
    """
    u = as_float(tangential_speed)
    h = as_float(film_thickness)
    if integral is None:
        integral = friction_integral(as_float(eta_hat) * as_float(max_pressure_pa))
    with np.errstate(invalid="ignore", divide="ignore"):
        value = (
            2.0
            * np.pi
            * as_float(viscosity)
            * u
            * as_float(contact_radius) ** 2
            * as_float(integral)
            / (as_float(load) * h)
        )
    return np.where(u == 0.0, 0.0, value)


@parameters(factor="the constant of (5.10), 0.87 rounded; its exact value by default [-]")
def lubricated_friction_dimensionless(
    viscosity: Numeric,
    tangential_speed: Numeric,
    reduced_modulus_pa: Numeric,
    radius: Numeric,
    eta_hat: Numeric,
    particle_density: Numeric,
    normal_speed: Numeric,
    integral: Numeric,
    factor: float = DIMENSIONLESS_FRICTION_FACTOR,
) -> Numeric:
    r"""The dimensionless form of (5.8) (5.10):
    μ_f = K (μ₀U/(E*R))^{2/7} (1/(η̂E*))^{5/7} (ρ_pV²/E*)^{−6/35} A [-].

    Derivation: with S = μ₀U/(E*R), w = W/(E*R²) and q = ρ_pV²/E*, (2.2) gives
    w = (4/3)(5π/4)^{3/5} q^{3/5}, (2.1) gives a² = R²(3w/4)^{2/3} and (5.6) gives
    h = 4.3384 R (S η̂E*)^{5/7} w^{−1/21}; then (5.8) is
    μ_f = (2π/4.3384)(3/4)^{2/3} S^{2/7} (η̂E*)^{−5/7} w^{−2/7} A, so
    K = (2π/4.3384)(3/4)^{2/3}(4/3)^{−2/7}(5π/4)^{−6/35} = 0.8710080… exactly
    (``DIMENSIONLESS_FRICTION_FACTOR``); the paper prints it rounded as 0.87
    (``PRINTED_FRICTION_FACTOR``, pass it as ``factor`` to reproduce the printed form).
    With the exact K this equals ``lubricated_friction`` (with W from (2.2)) to rounding.

    Examples
    --------
    >>> round(float(lubricated_friction_dimensionless(1e-3, 0.1, 65.64e9, 6.35e-3, 375e-12,
    ...                                               7780.0, 0.3, 121.68)), 4)
    0.062
    """
    e_star = as_float(reduced_modulus_pa)
    return (
        factor
        * shear_strain(viscosity, tangential_speed, e_star, radius)
        * (1.0 / (as_float(eta_hat) * e_star)) ** (5.0 / 7.0)
        * (as_float(particle_density) * as_float(normal_speed) ** 2 / e_star) ** (-6.0 / 35.0)
        * as_float(integral)
    )


@parameters
def shear_strain(
    viscosity: Numeric, tangential_speed: Numeric, reduced_modulus_pa: Numeric, radius: Numeric
) -> Numeric:
    r"""The shear-strain regime axis of figure 15, (μ₀U/(E*R))^{2/7} [-] (§5).

    Examples
    --------
    >>> round(float(shear_strain(1e-3, 0.1, 65.64e9, 6.35e-3)) * 1e4, 3)
    2.479
    """
    return (
        as_float(viscosity)
        * as_float(tangential_speed)
        / (as_float(reduced_modulus_pa) * as_float(radius))
    ) ** (2.0 / 7.0)


@parameters(
    friction="measured friction coefficient μ_f [-]",
    factor="the constant K of (5.10); its exact value by default [-]",
)
def viscosity_for_friction(
    friction: Numeric,
    tangential_speed: Numeric,
    reduced_modulus_pa: Numeric,
    radius: Numeric,
    eta_hat: Numeric,
    particle_density: Numeric,
    normal_speed: Numeric,
    integral: Numeric,
    factor: float = DIMENSIONLESS_FRICTION_FACTOR,
) -> Numeric:
    r"""Invert (5.10) for the gap viscosity μ₀ that gives a measured friction μ_f [Pa·s].

    μ_f ∝ μ₀^{2/7}, so μ₀ = (E*R/U) (μ_f / (K (1/(η̂E*))^{5/7} (ρ_pV²/E*)^{−6/35} A))^{7/2}.
    The paper fits μ₀ this way (figure 14) to find the temperature in the gap (table 2).
    K is the exact constant (``DIMENSIONLESS_FRICTION_FACTOR``) unless ``factor`` says
    otherwise.

    Examples
    --------
    >>> mu = viscosity_for_friction(0.062008, 0.1, 65.64e9, 6.35e-3, 375e-12, 7780.0, 0.3,
    ...                             121.68)
    >>> round(float(mu) * 1e3, 3)
    1.0
    """
    # At μ₀ = E*R/U the shear strain is 1, so (5.10) there is the rest of the product
    reference = as_float(reduced_modulus_pa) * as_float(radius) / as_float(tangential_speed)
    rest = lubricated_friction_dimensionless(
        reference, tangential_speed, reduced_modulus_pa, radius, eta_hat, particle_density,
        normal_speed, integral, factor,
    )  # fmt: skip
    return reference * (as_float(friction) / rest) ** 3.5
