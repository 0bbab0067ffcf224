"""Where the models stop: yield (docs/physics.md §11), the bounds of the lubricated friction
(5.8) (§12) and the uncertain band of the EHD gap (§12).

Each verdict is a small set of named states (text), never a NaN a reader could mistake
for "safe": an unknown yield stress gives ``"unknown"``, not ``"elastic"``.
"""

from __future__ import annotations

import numpy as np

from granudb.physics.arguments import parameters
from granudb.physics.numeric import Numeric, as_float

#: Yield starts below the surface when p_max = 1.6 Y (Y in tension of the softer body;
#: Johnson 1985, *Contact Mechanics*, §11.4 and §6.2).
YIELD_PRESSURE_FACTOR = 1.6
#: ρ_p V_y² / Y = YIELD_SPEED_CONSTANT (Y/E*)⁴ with the constant π⁴ 1.6⁵ / 40 = 25.5352…,
#: from (5.5) with p_max = 1.6 Y (docs/physics.md §11).
YIELD_SPEED_CONSTANT = np.pi**4 * YIELD_PRESSURE_FACTOR**5 / 40.0

ELASTIC_STATES = ("elastic", "yield_exceeded", "unknown")
ELASTIC, YIELD_EXCEEDED, YIELD_UNKNOWN = 0, 1, 2
#: Which dry e applies: e_dry, or Thornton's (15.1) past yield where it is lower.
RESTITUTION_MODELS = ("elastic", "elastic_plastic")

#: Upper end of the limiting-shear slope γ in τ_L = τ_L0 + γ p, "about 0.05–0.1 for
#: traction fluids" (Bair & Winer 1979, "A rheological model for elastohydrodynamic
#: contacts based on primary laboratory data", J. Lubr. Technol. 101(3), 258–264,
#: doi:10.1115/1.3453342). A film at its limiting shear stress carries at most
#: τ_L/p ≈ γ of the pressure, so a lubricated μ_f above γ_max is outside the model.
LIMITING_SHEAR_SLOPE = 0.1

#: States of the lubricated friction (5.8), see ``lubricated_friction_state``.
FRICTION_STATES = ("in_range", "above_limit", "no_pressure_coefficient", "dry")
IN_RANGE, ABOVE_LIMIT, NO_PRESSURE_COEFFICIENT, DRY = 0, 1, 2, 3

#: Davis et al. (1986) give the EHD gap of a normal approach as h_m = x₁/4 … x₁/3.
GAP_BAND = (0.25, 1.0 / 3.0)
#: "not_stated": a liquid, but a material's roughness σ is not stated (NaN): not decided.
ROUGHNESS_REGIMES = ("film", "uncertain", "asperity_contact", "dry", "not_stated")


@parameters(particle_density="particle density ρ_p [kg/m³] (a sphere on a flat wall)")
def yield_speed(
    particle_density: Numeric, yield_stress: Numeric, reduced_modulus_pa: Numeric
) -> Numeric:
    r"""Normal impact speed at the onset of yield, from ρ_p V_y²/Y = (π⁴ 1.6⁵/40)(Y/E*)⁴
    [m/s] (docs/physics.md §11: (5.5) with p_max = 1.6 Y, Johnson 1985 §11.4).

    Examples
    --------
    >>> round(float(YIELD_SPEED_CONSTANT), 4)
    25.5352

    Steel with an assumed Y = 1 GPa on Zerodur (E* = 65.64 GPa):

    >>> round(float(yield_speed(7780.0, 1.0e9, 65.64e9)), 4)
    0.4205
    """
    y = as_float(yield_stress)
    return np.sqrt(
        YIELD_SPEED_CONSTANT
        * (y / as_float(reduced_modulus_pa)) ** 4
        * y
        / as_float(particle_density)
    )


@parameters(normal_speed="normal speed V at which p_max was computed [m/s]")
def yield_speed_from_pressure(
    normal_speed: Numeric, max_pressure_pa: Numeric, yield_stress: Numeric
) -> Numeric:
    r"""V_y = V (1.6 Y / p_max)^{5/2} [m/s], for any pair (p_max ∝ V^{2/5} in Hertz impact).

    Equals ``yield_speed`` for a sphere on a flat wall; for two spheres it uses the
    p_max computed with m* and R*. ``normal_speed`` V [m/s] is the speed p_max was
    computed at, ``max_pressure_pa`` [Pa], ``yield_stress`` Y [Pa].

    Examples
    --------
    >>> from granudb.physics.contact import max_pressure_from_impact
    >>> p = max_pressure_from_impact(7780.0, 0.3, 65.64e9)
    >>> round(float(yield_speed_from_pressure(0.3, p, 1.0e9)), 4)
    0.4205
    """
    q = YIELD_PRESSURE_FACTOR * as_float(yield_stress) / as_float(max_pressure_pa)
    return as_float(normal_speed) * (q * q * np.sqrt(q))  # q^{5/2}; a power costs ~10× more


@parameters
def elastic_state(
    max_pressure_pa: Numeric, particle_yield_stress: Numeric, wall_yield_stress: Numeric
) -> np.ndarray:
    r"""Elastic state of the impact as a code into ``ELASTIC_STATES``: ``"elastic"``,
    ``"yield_exceeded"`` or ``"unknown"`` (``names`` turns codes into text).

    Yield starts when p_max > 1.6 Y of the softer body (Johnson 1985 §11.4). NaN means
    a yield stress is not known. Exceeded when p_max exceeds 1.6 × any known Y (the softer
    body yields no later); elastic only when both Y are known and neither is reached;
    otherwise unknown — never read as safe.

    Examples
    --------
    >>> code = elastic_state(np.array([1e9, 4e9, 1e9]), 1.0e9, np.array([2e9, np.nan, np.nan]))
    >>> names(ELASTIC_STATES, code).tolist()
    ['elastic', 'yield_exceeded', 'unknown']
    """
    limit = YIELD_PRESSURE_FACTOR * np.fmin(
        as_float(particle_yield_stress), as_float(wall_yield_stress)
    )
    p = as_float(max_pressure_pa)
    both = np.isfinite(as_float(particle_yield_stress)) & np.isfinite(as_float(wall_yield_stress))
    exceeded = np.isfinite(limit) & (p > limit)
    return np.where(exceeded, YIELD_EXCEEDED, np.where(both, ELASTIC, YIELD_UNKNOWN))


#: Largest a/R at which granudb calls Hertz's small-strain theory valid (docs/physics.md
#: §16). Hertz assumes the contact small against the radii (a ≪ R, Johnson 1985 §4.2);
#: at a/R = 0.1 the approach is δ/R = (a/R)² = 0.01, strains of about a percent, and the
#: error of the theory a few percent. Beyond it a number is outside the theory's range.
HERTZ_STRAIN_LIMIT = 0.1


@parameters(normal_speed="normal impact speed V [m/s]")
def thornton_restitution(yield_speed: Numeric, normal_speed: Numeric) -> Numeric:
    r"""Restitution of an elastic–perfectly plastic impact above the yield speed V_y,
    Thornton (1997), docs/physics.md eq. (15.1), with r = V_y / V [-]:

    e = (6√3/5)^{1/2} [1 − r²/6]^{1/2} {r / [r + 2√(6/5 − r²/5)]}^{1/4}

    (Thornton, C. 1997, "Coefficient of restitution for collinear collisions of
    elastic-perfectly plastic spheres", J. Appl. Mech. 64, 383–386.) It is 1 at V = V_y,
    decreases with V and tends to 1.185 (V_y/V)^{1/4} for V ≫ V_y, the power law of
    Johnson (1985) §11.5. Below V_y (r ≥ 1) the impact is elastic: 1 here, and the
    caller's dry e is the ceiling (``elastic_plastic_restitution``). NaN V_y gives NaN.

    Examples
    --------
    Hard steel on aluminium at 11 × V_y (the issue's figure, about 0.64):

    >>> round(float(thornton_restitution(0.3 / 11, 0.3)), 3)
    0.644
    >>> float(thornton_restitution(0.3, 0.3))
    1.0
    """
    r = np.minimum(as_float(yield_speed) / as_float(normal_speed), 1.0)
    with np.errstate(invalid="ignore"):
        return (
            np.sqrt(6.0 * np.sqrt(3.0) / 5.0)
            * np.sqrt(1.0 - r * r / 6.0)
            * (r / (r + 2.0 * np.sqrt(6.0 / 5.0 - r * r / 5.0))) ** 0.25
        )


@parameters(
    normal_speed="normal impact speed V [m/s]",
    yield_speed="normal impact speed at the onset of yield V_y [m/s]; NaN where not known",
)
def elastic_plastic_restitution(
    dry_restitution: Numeric, yield_speed: Numeric, normal_speed: Numeric
) -> Numeric:
    r"""The dry restitution with yield: min(e_dry, e_Thornton(V_y/V)) [-] (docs/physics.md
    §15). The pair's measured (or borrowed) e_dry is the elastic ceiling; past V_y
    Thornton's (15.1) takes over where it is lower. NaN V_y (yield not known): e_dry.

    Examples
    --------
    >>> [round(float(e), 3) for e in elastic_plastic_restitution(
    ...     0.97, np.array([1.0, 0.3 / 11, np.nan]), 0.3)]
    [0.97, 0.644, 0.97]
    """
    plastic = thornton_restitution(yield_speed, normal_speed)
    return np.fmin(as_float(dry_restitution), plastic)


@parameters(
    yield_speed="normal impact speed at the onset of yield V_y [m/s]; NaN where not known",
)
def handover_speed(dry_restitution: Numeric, yield_speed: Numeric) -> Numeric:
    r"""The normal speed V_h [m/s] above which Thornton's (15.1) e falls below e_dry, so
    that ``elastic_plastic_restitution`` = min(e_dry, e_T(V_y/V)) is Thornton's e: below
    V_h (past V_y or not) e_dry applies, above it Thornton's e (docs/physics.md §15).
    e_T decreases with V from 1 at V_y, so V_h ≥ V_y (= V_y for e_dry ≥ 1); NaN V_y or
    e_dry gives NaN. Solved by bisection on r = V_y/V (e_T rises with r).

    Examples
    --------
    >>> e_t = float(thornton_restitution(1.0, 11.0))  # 0.644 at 11 V_y
    >>> round(float(handover_speed(e_t, 1.0)), 6)
    11.0
    >>> float(handover_speed(1.0, 0.02))
    0.02
    """
    e_dry, v_y = np.broadcast_arrays(as_float(dry_restitution), as_float(yield_speed))
    low, high = np.zeros(e_dry.shape), np.ones(e_dry.shape)  # r where e_T < e_dry, ≥ e_dry
    for _ in range(60):  # each halves the bracket: 2⁻⁶⁰ of r
        middle = 0.5 * (low + high)
        below = thornton_restitution(middle, 1.0) < e_dry
        low, high = np.where(below, middle, low), np.where(below, high, middle)
    with np.errstate(divide="ignore", invalid="ignore"):
        speed = np.where(e_dry >= 1.0, v_y, v_y / high)
    speed = np.where(np.isnan(e_dry) | np.isnan(v_y), np.nan, speed)
    return speed if speed.ndim else float(speed)


@parameters
def hertz_strain(contact_radius: Numeric, effective_radius: Numeric) -> tuple[Numeric, Numeric]:
    r"""Hertz's small-strain measures a/R* and δ/R* = (a/R*)² [-] (docs/physics.md §16;
    Hertz: δ = a²/R*, Johnson 1985 §4.2).

    Examples
    --------
    >>> [round(float(x), 2) for x in hertz_strain(2.794e-3, 6.35e-3)]
    [0.44, 0.19]
    """
    ratio = as_float(contact_radius) / as_float(effective_radius)
    return ratio, ratio * ratio


@parameters(friction="lubricated friction μ_f from (5.8) [-]")
def lubricated_friction_state(
    friction: Numeric,
    immersed: Numeric,
    has_pressure_coefficient: Numeric,
    dry_friction: Numeric = 0.11,
    limiting_shear_slope: Numeric = LIMITING_SHEAR_SLOPE,
) -> np.ndarray:
    r"""State of a lubricated μ_f from (5.8) as a code into ``FRICTION_STATES`` (§12).

    ``"dry"`` no liquid; ``"no_pressure_coefficient"`` the fluid has no Barus coefficient,
    so (5.6) and (5.8) cannot be evaluated; ``"above_limit"`` μ_f exceeds the dry value
    or the limiting-shear cap γ_max (Bair & Winer 1979): the model is outside its range,
    not a prediction; ``"in_range"`` otherwise.

    Examples
    --------
    >>> code = lubricated_friction_state(np.array([0.02, 169.0, np.nan, np.nan]),
    ...                                  np.array([True, True, True, False]),
    ...                                  np.array([True, True, False, False]))
    >>> names(FRICTION_STATES, code).tolist()
    ['in_range', 'above_limit', 'no_pressure_coefficient', 'dry']
    """
    cap = friction_cap(dry_friction, limiting_shear_slope)
    mu = as_float(friction)
    immersed = np.asarray(immersed, dtype=bool)
    known = np.asarray(has_pressure_coefficient, dtype=bool)
    return np.where(
        ~immersed,
        DRY,
        np.where(~known, NO_PRESSURE_COEFFICIENT, np.where(mu <= cap, IN_RANGE, ABOVE_LIMIT)),
    )


@parameters
def friction_cap(
    dry_friction: Numeric = 0.11, limiting_shear_slope: Numeric = LIMITING_SHEAR_SLOPE
) -> Numeric:
    r"""The largest lubricated μ_f the film model may give: min(μ_dry, γ_max) [-] (§12).

    Examples
    --------
    >>> float(friction_cap(0.11))
    0.1
    """
    return np.minimum(as_float(dry_friction), as_float(limiting_shear_slope))


@parameters
def roughness_regime(roughness: Numeric, elastic_length: Numeric) -> np.ndarray:
    r"""Three-state roughness verdict from Davis's band h_m = x₁/4 … x₁/3 (§4, §12), as a
    code into ``ROUGHNESS_REGIMES``.

    ``"asperity_contact"`` σ > x₁/3 (above the largest gap), ``"uncertain"``
    x₁/4 < σ ≤ x₁/3, ``"film"`` σ ≤ x₁/4; ``"dry"`` where x₁ is NaN (no liquid);
    ``"not_stated"`` where σ is NaN in a liquid (a roughness no source states: neither
    film nor contact is decided). ``roughness`` σ [m], ``elastic_length`` x₁ [m].

    Examples
    --------
    >>> code = roughness_regime(np.array([10e-9, 30e-9, 40e-9, 1e-9, np.nan]),
    ...                         np.array([100e-9, 100e-9, 100e-9, np.nan, 100e-9]))
    >>> names(ROUGHNESS_REGIMES, code).tolist()
    ['film', 'uncertain', 'asperity_contact', 'dry', 'not_stated']
    """
    sigma = as_float(roughness)
    x1 = as_float(elastic_length)
    low, high = GAP_BAND
    code = np.where(
        np.isnan(x1),
        3,
        np.where(
            np.isnan(sigma), 4, np.where(sigma > high * x1, 2, np.where(sigma > low * x1, 1, 0))
        ),
    )
    return code


@parameters
def names(states: tuple[str, ...], code: Numeric) -> np.ndarray:
    """Text states from the integer codes the verdict functions return (object array).

    Examples
    --------
    >>> names(ELASTIC_STATES, np.array([0, 2])).tolist()
    ['elastic', 'unknown']
    """
    named: np.ndarray = np.asarray(states, dtype=object)[np.asarray(code)]
    return named
