"""From a target e to the damping input each code needs (docs/physics.md §13).

All three runnable codes use the same contact law for a Hertz contact: an elastic force
K δ^{3/2} with K = (4/3) E* √R* (docs/physics.md §13) and a dashpot whose coefficient grows as
δ^{1/4}, so that in the units of the contact

    m* δ̈ = −K δ^{3/2} − C √(m* K) δ^{1/4} δ̇ .                               (1)

Scaling δ by (m* V²/K)^{2/5} and t by that length over V removes m*, K and V: the
restitution coefficient depends on the dimensionless damping C alone, which is why this
law gives an e independent of the impact speed (Tsuji, Tanaka & Ishida 1992, Powder
Technol. 71). What differs between codes is how they turn the e a user types into C:

- LIGGGHTS ``model hertz``: γ_n = 2√(5/6) β √(S_n m*), S_n = 2E*√(R*δ), β the linear
  spring–dashpot ratio ln e/√(π²+ln²e) (docs/physics.md §13), i.e. C = √5 |ln e|/√(π²+ln²e).
  Integrating (1) gives back e to 1e-6 (tests/dem/test_damping.py) without a clamp.
- LAMMPS ``damping tsuji``: C = α(e), Tsuji's polynomial fit (LAMMPS pair_granular doc).
  It is not the inverse of (1): typed 0.97 gives 0.979, typed 0.5 gives 0.616 (LAMMPS
  issues #2812, #3025). granudb writes the e_in whose α(e_in) is the C that (1) needs.
- Yade ``MindlinPhys``: c_n = 2 β_n √(m* k_n) with the tangent stiffness k_n = S_n, i.e.
  C = √6 β_n; its force is clamped at zero (no attraction at the end of the contact), so
  (1) is integrated with the clamp and β_n = C/√6 is written.

Every export clamps the normal force at zero (LIGGGHTS ``limitForce on``, LAMMPS
``limit_damping``, Yade always): the Coulomb cap of all three codes is μ_f times the
normal force, and with the large damping of a wet pair the unclamped force turns
attractive at the end of the contact, where LIGGGHTS and LAMMPS cap the tangential force
at μ_f |F_n| — friction the measured μ_f never had. So the C written for every code is
the clamped law's (``clamped_hertz_damping``), turned into each code's input.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np

from granudb.errors import ValidationError
from granudb.lazy import scipy_optimize

#: Tsuji et al. (1992) polynomial α(e) as implemented by LAMMPS ``damping tsuji``.
TSUJI_POLYNOMIAL = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)


def linear_damping_ratio(restitution: float) -> float:
    """ζ = −ln e / √(π² + ln² e), the linear spring–dashpot ratio (docs/physics.md §13)."""
    log_e = math.log(restitution)
    return -log_e / math.sqrt(math.pi**2 + log_e**2)


def hertz_restitution(
    damping: float, *, clamp_attraction: bool = False, step: float = 1e-3
) -> float:
    """e of law (1) for dimensionless damping C, by fourth-order Runge–Kutta.

    ``clamp_attraction`` sets the total force to max(0, ·) as Yade does, so the contact
    ends when the force (not the overlap) reaches zero (Thornton et al. 2013).
    """

    def accel(x: float, v: float) -> float:
        xp = max(x, 0.0)
        a = -(xp**1.5) - damping * xp**0.25 * v
        return min(a, 0.0) if clamp_attraction else a

    x, v, t = 0.0, 1.0, 0.0
    while t < 200.0:
        k1x, k1v = v, accel(x, v)
        k2x, k2v = v + 0.5 * step * k1v, accel(x + 0.5 * step * k1x, v + 0.5 * step * k1v)
        k3x, k3v = v + 0.5 * step * k2v, accel(x + 0.5 * step * k2x, v + 0.5 * step * k2v)
        k4x, k4v = v + step * k3v, accel(x + step * k3x, v + step * k3v)
        x_new = x + step / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v_new = v + step / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)
        t += step
        if x_new <= 0.0 and t > step:
            frac = x / (x - x_new)
            return -(v + frac * (v_new - v))
        if (
            v_new >= 0.0
            and v < 0.0
            and x_new > 0.0
            and clamp_attraction
            and accel(x_new, v_new) == 0
        ):
            return 0.0  # overdamped with the clamp: the sphere stays in contact
        x, v = x_new, v_new
    return 0.0


def hertz_damping(restitution: float) -> float:
    """C of law (1) for a target e without clamping: √5 |ln e| / √(π² + ln² e).

    The 2√(5/6) prefactor of LIGGGHTS's Hertz damping times √(3/2) from S_n = (3/2)K√δ;
    tests/dem/test_damping.py integrates (1) to check it gives e back.
    """
    return math.sqrt(5.0) * linear_damping_ratio(restitution)


#: The most damping :func:`clamped_hertz_damping` searches: e of the clamped law (1) at this
#: C is below 1e-4, far under any code's floor (Yade's 0.01 is reached at C ≈ 12).
CLAMPED_DAMPING_MAX = 100.0


@lru_cache(maxsize=256)
def clamped_hertz_damping(restitution: float) -> float:
    """C of law (1) with the force clamped at zero (every export clamps it), by Brent's
    method on the integration: the clamp only removes attraction, so C is at least the
    unclamped C; the upper end of the bracket starts at 3 times it plus 1 and doubles
    (up to ``CLAMPED_DAMPING_MAX``) until it gives less than ``restitution`` (e ≤ 0.02
    needs more than the first guess)."""
    if restitution >= 1.0:
        return 0.0
    if not restitution > 0.0:
        raise ValidationError("restitution", f"{restitution:.4g}", "must be > 0 (and <= 1)")

    def miss(c: float) -> float:
        return hertz_restitution(c, clamp_attraction=True, step=2e-3) - restitution

    low = hertz_damping(restitution)
    high = 3.0 * low + 1.0
    while miss(high) > 0.0:
        if high >= CLAMPED_DAMPING_MAX:
            raise ValidationError(
                "restitution",
                f"{restitution:.4g}",
                f"the clamped Hertz law needs damping C > {CLAMPED_DAMPING_MAX:g} for it "
                "(granudb.dem.damping)",
            )
        low, high = high, min(2.0 * high, CLAMPED_DAMPING_MAX)
    return float(scipy_optimize.brentq(miss, low, high, xtol=1e-12))


def liggghts_floor(input_floor: float) -> float:
    """The smallest e LIGGGHTS's ``model hertz limitForce on`` gives from an input of
    ``input_floor`` (its sanity check refuses inputs at or below 0.05)."""
    return hertz_restitution(hertz_damping(input_floor), clamp_attraction=True)


def tsuji_alpha(restitution: float) -> float:
    """LAMMPS's α(e) = 1.2728 − 4.2783e + … + 4.8218e⁶ (pair_style granular doc, tsuji)."""
    return sum(c * restitution**k for k, c in enumerate(TSUJI_POLYNOMIAL))


#: The most damping LAMMPS's tsuji can give (α at e = 0) and the least (α at e = 1).
TSUJI_ALPHA_MAX = tsuji_alpha(0.0)
TSUJI_ALPHA_MIN = tsuji_alpha(1.0)


def lammps_tsuji_range() -> tuple[float, float]:
    """Targets e that LAMMPS tsuji damping can reproduce on a Hertz contact whose force is
    clamped at zero (``limit_damping``)."""
    return (
        hertz_restitution(TSUJI_ALPHA_MAX, clamp_attraction=True),
        hertz_restitution(TSUJI_ALPHA_MIN, clamp_attraction=True),
    )


def liggghts_hertz_input(restitution: float) -> float:
    """The coefficientRestitution to write for ``model hertz limitForce on`` so that
    LIGGGHTS gives ``restitution``: LIGGGHTS turns its input into C by
    :func:`hertz_damping` (an unclamped law), and the clamped law needs
    ``clamped_hertz_damping(restitution)``."""
    return restitution_for_hertz_damping(clamped_hertz_damping(round(restitution, 12)))


def restitution_for_hertz_damping(damping: float) -> float:
    """Inverse of :func:`hertz_damping`: e = exp(−π s/√(1−s²)), s = C/√5."""
    s = damping / math.sqrt(5.0)
    if s >= 1.0:
        return 0.0
    return math.exp(-math.pi * s / math.sqrt(1.0 - s * s))


def lammps_tsuji_input(restitution: float, label: str) -> float:
    """The e to type after ``hertz k_n ... damping tsuji ... limit_damping`` so LAMMPS
    gives ``restitution``.

    Solves α(e_in) = C(e) of the clamped law by bisection (α decreases monotonically on
    [0, 1]).
    """
    low, high = lammps_tsuji_range()
    if not low <= restitution <= high:
        raise ValidationError(
            f"restitution {label}",
            f"{restitution:.4g}",
            f"LAMMPS damping tsuji reaches only {low:.4f} <= e <= {high:.5f} on a Hertz "
            f"contact (alpha(e) is between {TSUJI_ALPHA_MIN:.4g} and {TSUJI_ALPHA_MAX:.4g}); "
            "use --clamp to write the nearest",
        )
    target = clamped_hertz_damping(round(restitution, 12))
    lo, hi = 0.0, 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if tsuji_alpha(mid) > target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def yade_betan(restitution: float) -> float:
    """β_n for Yade's MindlinPhys so that its clamped Hertz law gives ``restitution``."""
    return clamped_hertz_damping(round(restitution, 12)) / math.sqrt(6.0)


#: 1 + 1/K² for a solid sphere (K² = 2/5): how much a tangential force at the contact point
#: accelerates the contact point, relative to the centre (Walton; docs/physics.md §5).
CONTACT_POINT_FACTOR = 3.5


def stick_rebound(stiffness_ratio: Any, damping: float, *, step: float = 4e-3) -> Any:
    """β = −v_t,out/v_t,in of a contact that never slides, on the clamped law (1) with an
    incremental Mindlin tangential spring dF_t = −k_t a du (LAMMPS ``mindlin``):

        u̇' = 3.5 F_t,   Ḟ_t = −ρ √δ u̇ ,   ρ = k_t / k_n,

    in the units of (1) (m* = 1, K = 1); ``stiffness_ratio`` may be an array (the normal
    motion does not depend on it). Fourth-order Runge–Kutta to the end of contact.
    """
    rho = np.asarray(stiffness_ratio, dtype=float)

    def rates(x: float, v: float, force: Any, w: Any) -> tuple[float, float, Any, Any]:
        xp = max(x, 0.0)
        a = min(-(xp**1.5) - damping * xp**0.25 * v, 0.0)
        return v, a, -rho * math.sqrt(xp) * w, CONTACT_POINT_FACTOR * force

    x, v, force, w, t = 0.0, 1.0, np.zeros_like(rho), np.ones_like(rho), 0.0
    h = step
    while t < 200.0:
        k1 = rates(x, v, force, w)
        k2 = rates(*(a + 0.5 * h * b for a, b in zip((x, v, force, w), k1, strict=True)))
        k3 = rates(*(a + 0.5 * h * b for a, b in zip((x, v, force, w), k2, strict=True)))
        k4 = rates(*(a + h * b for a, b in zip((x, v, force, w), k3, strict=True)))
        x_new, v, force, w_new = (
            a + h / 6.0 * (b + 2 * c + 2 * d + e)
            for a, b, c, d, e in zip((x, v, force, w), k1, k2, k3, k4, strict=True)
        )
        t += h
        if x_new <= 0.0:  # the end of contact, between the two steps
            return -(w + x / (x - x_new) * (w_new - w))
        x, w = x_new, w_new
    return -w


@lru_cache(maxsize=256)
def stiffness_ratio_for_rebound(rebound: float, damping: float, mindlin_ratio: float) -> float:
    """ρ = k_t/k_n whose never-sliding contact rebounds with ``rebound`` (Walton's β):
    the root of :func:`stick_rebound` nearest below ``mindlin_ratio`` (Mindlin's own
    8G*/(4/3 E*)), from a grid of ρ refined twice around the crossing."""
    if not -1.0 < rebound < 1.0:
        raise ValidationError("rotational_restitution", rebound, "must be in (-1, 1)")
    low, high = 0.02, mindlin_ratio
    for _ in range(3):
        grid = np.linspace(low, high, 41)
        sign = np.sign(stick_rebound(grid, damping) - rebound)
        crossings = np.nonzero(sign[:-1] != sign[1:])[0]
        if crossings.size == 0:
            raise ValidationError(
                "rotational_restitution",
                rebound,
                "no tangential stiffness up to Mindlin's gives it on a contact that sticks",
            )
        k = crossings[-1]
        low, high = grid[k], grid[k + 1]
    values = stick_rebound(np.array([low, high]), damping) - rebound
    return float(low - values[0] * (high - low) / (values[1] - values[0]))


def sliding_friction(
    friction: Any,
    damping: float,
    stiffness_ratio: float,
    psi_in: Any,
    *,
    step: float = 1e-3,
    incremental: bool = True,
) -> Any:
    """The effective μ_f = (Ψ_in − Ψ_out)/((1 + e)·3.5) of an oblique impact on the clamped
    law (1) with an incremental Mindlin spring capped at ``friction`` times the normal force
    (Yade's ``Law2_ScGeom_MindlinPhys_Mindlin`` with ``betas`` 0): in the units of (1),

        Ḟ_t = −ρ √δ w  with |F_t| ≤ μ_f F_n,   ẇ = 3.5 F_t,   w(0) = Ψ_in .

    Below the input μ_f because the contact first sticks: the damped normal force jumps
    at first touch (C δ^{1/4} δ̇) while the spring builds as ∫√δ w dt, so for a moment
    |F_t| < μ_f F_n. ``friction`` and ``psi_in`` may be arrays (broadcast together; the
    normal motion depends on neither).

    With ``incremental`` false the spring is the total one of LIGGGHTS ``tangential
    history`` and LAMMPS ``tangential mindlin``: F_t = −ρ √δ u with u = ∫w dt, and where
    the cap is reached u is cut back to |F_t|/(ρ √δ).
    """
    mu = np.asarray(friction, dtype=float)

    def accel(x: float, v: float) -> float:
        xp = max(x, 0.0)
        return min(-(xp**1.5) - damping * xp**0.25 * v, 0.0)

    x, v, h, t = 0.0, 1.0, step, 0.0
    force = np.zeros(np.broadcast(mu, psi_in).shape)
    w, impulse = force + psi_in, 0.0
    shift = np.zeros_like(force)  # the total spring's u
    while t < 200.0:
        k1x, k1v = v, accel(x, v)
        k2x, k2v = v + 0.5 * h * k1v, accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v)
        k3x, k3v = v + 0.5 * h * k2v, accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v)
        k4x, k4v = v + h * k3v, accel(x + h * k3x, v + h * k3v)
        x += h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)
        t += h
        if x <= 0.0:  # the end of contact
            break
        normal = -accel(x, v)
        cap = mu * normal
        if incremental:
            force = np.clip(force - stiffness_ratio * math.sqrt(x) * w * h, -cap, cap)
        else:
            shift = shift + w * h
            force = np.clip(-stiffness_ratio * math.sqrt(x) * shift, -cap, cap)
            shift = -force / (stiffness_ratio * math.sqrt(x))
        w = w + CONTACT_POINT_FACTOR * force * h
        impulse += normal * h
    return (psi_in - w) / (CONTACT_POINT_FACTOR * impulse)


#: The largest μ_f input :func:`friction_for_sliding` writes, as a multiple of the target.
FRICTION_INPUT_LIMIT = 1.3


@lru_cache(maxsize=256)
def friction_for_sliding(
    friction: float,
    damping: float,
    stiffness_ratio: float,
    psi_in: float,
    *,
    incremental: bool = True,
) -> float:
    """The μ_f input whose effective μ_f (:func:`sliding_friction`) at ``psi_in`` is
    ``friction``: the effective μ_f grows monotonically with the input, so it is
    interpolated on a grid of inputs from ``friction`` to ``FRICTION_INPUT_LIMIT`` times
    it; where even the top of the grid falls short, the top (the caller checks what it
    gives). ``incremental`` as in :func:`sliding_friction`."""
    grid = friction * np.linspace(1.0, FRICTION_INPUT_LIMIT, 16)
    achieved = sliding_friction(
        grid, damping, stiffness_ratio, psi_in, step=2e-3, incremental=incremental
    )
    return float(np.interp(friction, achieved, grid))
