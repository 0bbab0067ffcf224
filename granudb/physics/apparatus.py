"""The pendulum apparatus of Joseph & Hunt's Appendix (docs/physics.md §7).

The sphere hangs on a string whose torsional stiffness must be small compared with the
contact's lateral stiffness, so the string cannot change the spin during the collision.
"""

from __future__ import annotations

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float


@parameters
def string_torsional_stiffness(density: Numeric, radius: Numeric, period: Numeric) -> Numeric:
    r"""String torsional stiffness from the sphere's torsional oscillation period τ,
    K_s = 4π² I₀/τ² = (32/15) π³ ρ R⁵ / τ² [N·m] (A 1), with I₀ = (2/5) m R².

    Note: the K_s printed in the paper's table 3 is 32 times this formula with
    R = 6.35 mm, as if R had been the diameter; granudb keeps the printed numbers and
    computes from the formula.

    Examples
    --------
    >>> round(float(string_torsional_stiffness(7780.0, 6.35e-3, 6.648)) * 1e9, 2)
    120.22
    """
    return (
        32.0 / 15.0 * np.pi**3 * as_float(density) * as_float(radius) ** 5 / as_float(period) ** 2
    )


@parameters
def lateral_contact_stiffness(
    contact_radius: Numeric, reduced_shear_modulus_pa: Numeric
) -> Numeric:
    r"""Lateral (tangential) stiffness of a Hertz contact, κ = 8 a G* [N/m] (Appendix).

    Examples
    --------
    >>> round(float(lateral_contact_stiffness(212e-6, 14.07e9)) / 1e6, 1)
    23.9
    """
    return 8.0 * as_float(contact_radius) * as_float(reduced_shear_modulus_pa)


@parameters
def time_scale_ratio(
    radius: Numeric, contact_stiffness: Numeric, string_stiffness: Numeric
) -> Numeric:
    r"""τ_string / τ_collision ≈ (1/R) √(κ_contact / K_s) [-] (A 2).

    Examples
    --------
    >>> round(float(time_scale_ratio(6.35e-3, 23.9e6, 1.193e-7)))
    2228974004
    """
    return np.sqrt(as_float(contact_stiffness) / as_float(string_stiffness)) / as_float(radius)


@parameters
def consistent_time_scale_ratio(
    radius: Numeric, contact_stiffness: Numeric, string_stiffness: Numeric
) -> Numeric:
    r"""Dimensionless ratio of the string's to the collision's time scale,
    √(κ I₀ / (m K_s)) = R √(0.4 κ / K_s) [-] (docs/physics.md §14), with I₀ = (2/5) m R².

    (A 2) as printed, (1/R)√(κ/K_s) (``time_scale_ratio``), has units of m⁻²; this is the
    consistent form: the collision's tangential time scale is √(m/κ) and the string's
    √(I₀/K_s).

    Examples
    --------
    >>> round(float(consistent_time_scale_ratio(6.35e-3, 23.9e6, 1.193e-7)))
    56844
    """
    return as_float(radius) * np.sqrt(
        0.4 * as_float(contact_stiffness) / as_float(string_stiffness)
    )
