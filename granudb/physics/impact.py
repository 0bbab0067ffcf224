"""Oblique impact: the three-parameter model of Joseph & Hunt §2 (docs/physics.md §5).

Sign convention (as stored by granudb): normal speeds v_n_in > 0 towards the wall and
v_n_out ≥ 0 away from it, so e = v_n_out / v_n_in (the paper's e = −v_N,out / v_N,in); the
tangential axis points along the incoming tangential motion; spin is positive where it adds
to the contact point's tangential velocity, so the contact point moves at v_T = v_t + ωR.

The Poisson ratio in Maw's χ and ψ: for one material the factor is (1−ν)/(2−ν). For a
pair of different materials granudb uses the ratio 2G*/E*, which equals (1−ν)/(2−ν)
exactly when both bodies are the same material, and for a rigid wall reduces to the
particle's (1−ν)/(2−ν). It weighs each body by its compliance, as Maw's tangential-to-normal
stiffness ratio does.
"""

from __future__ import annotations

import numpy as np

from granudb.physics import pair
from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float

#: Squared radius of gyration over R² of a solid sphere, K² = 2/5.
SOLID_SPHERE_GYRATION = 0.4

TANGENTIAL_REGIME_NAMES = ("stick", "slip_then_stick", "gross_slip")
STICK, SLIP_THEN_STICK, GROSS_SLIP = 0, 1, 2


@parameters
def normal_restitution(v_n_in: Numeric, v_n_out: Numeric) -> Numeric:
    r"""Normal coefficient of restitution e = v_n_out / v_n_in (§2, stored speeds positive).

    Examples
    --------
    >>> float(normal_restitution(0.3, 0.291))
    0.97
    """
    return as_float(v_n_out) / as_float(v_n_in)


@parameters
def contact_point_velocity(v_t: Numeric, omega: Numeric, radius: Numeric) -> Numeric:
    r"""Tangential velocity of the contact point, v_T = v_t + ωR [m/s] (§2).

    Examples
    --------
    >>> round(float(contact_point_velocity(0.1, -10.0, 6.35e-3)), 6)
    0.0365
    """
    return as_float(v_t) + as_float(omega) * as_float(radius)


@parameters
def rotational_restitution(v_T_in: Numeric, v_T_out: Numeric) -> Numeric:
    r"""Rotational (tangential) restitution β = −v_T,out / v_T,in (2.8).

    −1 pure sliding, 0 rolling, +1 full recoil. Undefined (NaN, never ±inf) for a normal
    impact, v_T,in = 0.

    Examples
    --------
    >>> float(rotational_restitution(0.1, -0.034))
    0.34
    >>> float(rotational_restitution(0.0, 0.001))
    nan
    """
    v_in = as_float(v_T_in)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(v_in == 0.0, np.nan, -as_float(v_T_out) / v_in)


@parameters
def effective_incidence(v_T_in: Numeric, v_n_in: Numeric) -> Numeric:
    r"""Effective incidence angle Ψ_in = v_T,in / v_N,in = tan ζ_in (2.5).

    Examples
    --------
    >>> float(effective_incidence(0.1, 0.2))
    0.5
    """
    return as_float(v_T_in) / as_float(v_n_in)


@parameters
def effective_rebound(v_T_out: Numeric, v_n_in: Numeric) -> Numeric:
    r"""Effective rebound angle Ψ_out = v_T,out / v_N,in = e tan ζ_out (2.5).

    Examples
    --------
    >>> float(effective_rebound(-0.034, 0.2))
    -0.17
    """
    return effective_incidence(v_T_out, v_n_in)


@parameters
def gyration_factor(gyration: Numeric = SOLID_SPHERE_GYRATION) -> Numeric:
    r"""1 + 1/K², the factor of the Walton relations; 7/2 for a solid sphere.

    Examples
    --------
    >>> float(gyration_factor())
    3.5
    """
    return 1.0 + 1.0 / as_float(gyration)


@parameters
def sliding_friction(
    psi_in: Numeric,
    psi_out: Numeric,
    restitution: Numeric,
    gyration: Numeric = SOLID_SPHERE_GYRATION,
) -> Numeric:
    r"""Friction from one collision, μ_f = (Ψ_in − Ψ_out) / ((1+e)(1 + 1/K²)) (2.9).

    Equals the sliding friction coefficient for a sliding collision; for a sticking one it
    is 2(1+β)Ψ_in / (7(1+e)) (2.10), a lower bound.

    Examples
    --------
    >>> round(float(sliding_friction(2.0, 2.0 - 0.11 * 1.97 * 3.5, 0.97)), 6)
    0.11
    """
    return pair.pair_sliding_friction(psi_in, psi_out, restitution, gyration_factor(gyration))


@parameters
def sticking_friction(psi_in: Numeric, beta: Numeric, restitution: Numeric) -> Numeric:
    r"""(2.10): μ_f = 2(1+β) Ψ_in / (7(1+e)), i.e. (2.9) with Ψ_out = −βΨ_in, K² = 2/5.

    Examples
    --------
    >>> round(float(sticking_friction(0.5, 0.34, 0.97)), 6)
    0.097172
    """
    return 2.0 * (1.0 + as_float(beta)) * as_float(psi_in) / (7.0 * (1.0 + as_float(restitution)))


@parameters
def walton_rebound(
    psi_in: Numeric,
    beta: Numeric,
    friction: Numeric,
    restitution: Numeric,
    gyration: Numeric = SOLID_SPHERE_GYRATION,
) -> Numeric:
    r"""Walton's Ψ_out: −βΨ_in when sticking (2.7), Ψ_in − μ_f(1+e)(1+1/K²) when sliding
    (2.6), whichever is larger (the collision slides only while it can).

    Examples
    --------
    >>> [round(float(x), 4) for x in walton_rebound(np.array([0.2, 2.0]), 0.34, 0.11, 0.97)]
    [-0.068, 1.2415]
    """
    psi = as_float(psi_in)
    sliding = psi - as_float(friction) * (1.0 + as_float(restitution)) * gyration_factor(gyration)
    return np.maximum(-as_float(beta) * psi, sliding)


@parameters
def stiffness_ratio(reduced_shear_modulus_pa: Numeric, reduced_modulus_pa: Numeric) -> Numeric:
    r"""2G*/E*, the pair's (1−ν)/(2−ν) (exactly so for identical materials; see module doc).

    Examples
    --------
    >>> from granudb.physics.contact import reduced_modulus, reduced_shear_modulus, shear_modulus
    >>> g = shear_modulus(60e9, 0.23)
    >>> r = stiffness_ratio(reduced_shear_modulus(g, 0.23, g, 0.23),
    ...                     reduced_modulus(60e9, 0.23, 60e9, 0.23))
    >>> round(float(r), 12) == round((1 - 0.23) / (2 - 0.23), 12)
    True
    """
    return 2.0 * as_float(reduced_shear_modulus_pa) / as_float(reduced_modulus_pa)


@parameters
def maw_chi(ratio: Numeric, gyration: Numeric = SOLID_SPHERE_GYRATION) -> Numeric:
    r"""Maw's modified radius of gyration χ = (1−ν)(1 + 1/K²)/(2−ν) (2.3).

    ``ratio`` is (1−ν)/(2−ν) for one material, or ``stiffness_ratio`` for a pair.

    Examples
    --------
    >>> round(float(maw_chi((1 - 0.27) / (2 - 0.27))), 4)
    1.4769
    """
    return as_float(ratio) * gyration_factor(gyration)


@parameters
def maw_psi(ratio: Numeric, v_T: Numeric, friction: Numeric, v_n_in: Numeric) -> Numeric:
    r"""Maw's local contact angle ψ = 2(1−ν) v_T / (μ_f (2−ν) v_N,in) (2.4).

    Examples
    --------
    >>> round(float(maw_psi((1 - 0.27) / (2 - 0.27), 0.1, 0.11, 0.3)), 3)
    2.557
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        return 2.0 * as_float(ratio) * as_float(v_T) / (as_float(friction) * as_float(v_n_in))


@parameters
def tangential_regime(psi_in: Numeric, chi: Numeric) -> np.ndarray:
    r"""Maw's regime (§2) as codes: ψ_in ≤ 1 stick (micro-slip at the rim), 0;
    1 < ψ_in < 4χ−1 gross slip then stick, 1; ψ_in ≥ 4χ−1 gross slip throughout, 2.
    Names: ``TANGENTIAL_REGIME_NAMES[code]``.

    Examples
    --------
    >>> tangential_regime(np.array([0.5, 3.0, 6.0]), 1.4769).tolist()
    [0, 1, 2]
    """
    psi = as_float(psi_in)
    limit = 4.0 * as_float(chi) - 1.0
    return np.where(psi <= 1.0, STICK, np.where(psi < limit, SLIP_THEN_STICK, GROSS_SLIP))


@parameters
def rolling_friction_coefficient(rolling_length: Numeric, radius: Numeric) -> Numeric:
    r"""Rolling friction coefficient μ_r = λ_r / R (thesis (3.11)).

    Examples
    --------
    >>> float(rolling_friction_coefficient(1e-5, 5e-3))
    0.002
    """
    return as_float(rolling_length) / as_float(radius)


@parameters
def rolling_resistance_moment(
    rolling_coefficient: Numeric, normal_force: Numeric, radius: Numeric
) -> Numeric:
    r"""Rolling resistance moment M_r = μ_r R_n R [N·m] (thesis (3.11)).

    Examples
    --------
    >>> float(rolling_resistance_moment(0.002, 10.0, 5e-3))
    0.0001
    """
    return as_float(rolling_coefficient) * as_float(normal_force) * as_float(radius)


@parameters
def restitution_from_energy(energy_returned: Numeric, energy_stored: Numeric) -> Numeric:
    r"""Restitution from energies, e = √(W′/W) (thesis (3.22)).

    Examples
    --------
    >>> float(restitution_from_energy(0.81, 1.0))
    0.9
    """
    return np.sqrt(as_float(energy_returned) / as_float(energy_stored))
