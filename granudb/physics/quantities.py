"""The steps of ``granudb.physics.derive.derive``, one concern each (all vectorized).

Each step takes the dict of broadcast input arrays (``x``) and what earlier steps
returned, and returns a dict of arrays; ``derive`` assembles the columns. Kept apart from
``derive`` so each function stays short and each concern can be read on its own.
"""

from __future__ import annotations

import numpy as np

from granudb.physics import contact, flow, impact, limits, lubrication, pair
from granudb.physics.numeric import hypot

Arrays = dict[str, np.ndarray]
#: (the dry friction per row, the limiting-shear slope γ_max)
Caps = tuple[np.ndarray | float, float]


def pair_properties(x: Arrays) -> Arrays:
    """Moduli, radii, masses, the Walton factor and the relative contact-point velocities.

    The target is free where ``wall_v_n_in`` is given (finite); otherwise it is a flat
    wall or a fixed sphere, immovable (m₂ = ∞) and at rest.
    """
    g1 = np.where(np.isnan(x["g1"]), contact.shear_modulus(x["e1"], x["nu1"]), x["g1"])
    g2 = np.where(np.isnan(x["g2"]), contact.shear_modulus(x["e2"], x["nu2"]), x["g2"])
    free = np.isfinite(x["w_vn"])
    r1 = x["d"] / 2.0
    r2 = np.where(np.isnan(x["d2"]), np.inf, x["d2"] / 2.0)
    m1 = contact.sphere_mass(x["rho1"], x["d"])
    any_free = bool(free.any())  # skip the target's terms for walls and fixed spheres
    m2 = np.where(free, contact.sphere_mass(x["rho2"], x["d2"]), np.inf) if any_free else np.inf
    m_eff = contact.effective_mass(m1, m2)
    r_spin = np.where(free, r2, 0.0) if any_free else 0.0  # an immovable target does not spin

    def before(name: str) -> np.ndarray | float:  # a free target's missing value: at rest
        if not any_free:
            return 0.0
        return np.where(free & ~np.isnan(x[name]), x[name], 0.0)

    def after(name: str) -> np.ndarray | float:  # a free target's missing value: unknown
        return np.where(free, x[name], 0.0) if any_free else 0.0

    v_n = pair.relative_normal_velocity(x["vn"], before("w_vn"))
    v_t_centre = x["vt"] - before("w_vt")
    u = pair.relative_tangential_velocity(
        x["vt"], x["w"], r1, before("w_vt"), before("w_w"), r_spin
    )
    u_out = pair.relative_tangential_velocity(
        x["vt_out"], x["w_out"], r1, after("w_vt_out"), after("w_w_out"), r_spin
    )
    return {
        "g1": g1,
        "g2": g2,
        "free": free,
        "radius": r1,
        "r_eff": contact.effective_radius(r1, r2),
        "m1": m1,
        "m_eff": m_eff,
        "walton": pair.walton_factor(m_eff, m1, m2),
        "e_star": contact.reduced_modulus(x["e1"], x["nu1"], x["e2"], x["nu2"]),
        "g_star": contact.reduced_shear_modulus(g1, x["nu1"], g2, x["nu2"]),
        "v_n": v_n,
        "speed": hypot(v_n, v_t_centre),
        "v_t_centre": v_t_centre,
        "u": u,
        # the particle's v_n_out is stored away from the target, the target's along n
        "v_n_out": x["vn_out"] + after("w_vn_out"),
        "u_out": u_out,
    }


def hertz(x: Arrays, p: Arrays) -> Arrays:
    """Hertz impact at the relative normal speed with m* and R*, and the yield verdict."""
    v_n, m_eff, r_eff, e_star = p["v_n"], p["m_eff"], p["r_eff"], p["e_star"]
    delta = contact.max_approach(m_eff, v_n, e_star, r_eff)
    load = contact.hertz_force(e_star, r_eff, delta)  # = contact.peak_impact_force
    a = contact.max_contact_radius(r_eff, load, e_star)
    p_max = contact.max_pressure(load, a)
    t_c = contact.contact_time_from_approach(delta, v_n)  # = contact.contact_time
    c_wave_1 = contact.wave_speed(x["e1"], x["rho1"])
    c_wave_2 = contact.wave_speed(x["e2"], x["rho2"])
    c_wave = np.minimum(c_wave_1, c_wave_2)
    ratio = contact.quasi_static_ratio(a, c_wave, t_c)
    y_soft = np.fmin(x["y1"], x["y2"])
    state = limits.elastic_state(p_max, x["y1"], x["y2"])
    yield_speed = limits.yield_speed_from_pressure(v_n, p_max, y_soft)
    a_ratio, delta_ratio = limits.hertz_strain(a, r_eff)
    plastic = state == limits.YIELD_EXCEEDED
    # past yield Thornton's (15.1) bounds the dry e (docs/physics.md §15); which e applies:
    # Thornton's only where it is below e_dry (above the hand-over speed,
    # ``limits.handover_speed``); past V_y but below it, e_dry still applies. Computed on
    # no row where none is past yield (most tables, every Monte Carlo draw of one).
    e_dry = np.array(x["e_dry"], dtype=float)
    model = np.zeros(np.shape(state), dtype=np.intp)
    if plastic.any():
        e_dry = np.where(
            plastic, limits.elastic_plastic_restitution(x["e_dry"], yield_speed, v_n), e_dry
        )
        model[plastic & (limits.thornton_restitution(yield_speed, v_n) < x["e_dry"])] = 1
    return {
        "load": load,
        "a": a,
        "p_max": p_max,
        "delta": delta,
        "t_c": t_c,
        "c_wave": c_wave,
        "c_wave_1": c_wave_1,  # the particle's and the wall's (which is slower: uncertainty)
        "c_wave_2": c_wave_2,
        "qs_ratio": ratio,
        "qs_valid": (ratio < contact.QUASI_STATIC_LIMIT) & (state != limits.YIELD_EXCEEDED),
        "yield_speed": yield_speed,
        "elastic_state": state,
        "a_ratio": a_ratio,
        "delta_ratio": delta_ratio,
        "strain_valid": a_ratio <= limits.HERTZ_STRAIN_LIMIT,
        "e_dry": e_dry,
        "e_model": limits.names(limits.RESTITUTION_MODELS, model),
    }


def fluid_numbers(x: Arrays, p: Arrays, gap_fraction: float) -> Arrays:
    """Re, St, St_n (Davis's pair form, m* and R*), x₁, h_m, x₃ and the roughness verdicts."""
    mu, r_eff = x["mu"], p["r_eff"]
    immersed = ~np.isnan(mu)
    # Every fluid number below has μ as a factor, so it is NaN exactly where the row is
    # dry (μ NaN): no masking needed.
    st_n = pair.pair_normal_stokes_number(p["m_eff"], p["v_n"], mu, r_eff)
    x1 = lubrication.davis_elastic_length(mu, p["v_n"], r_eff, p["e_star"])
    h_m = lubrication.ehd_min_gap(x1, gap_fraction)
    eta_hat = lubrication.chu_cameron_coefficient(x["c_barus"])
    sigma = contact.composite_roughness(x["s1"], x["s2"])
    with np.errstate(divide="ignore", invalid="ignore"):
        film = h_m / sigma  # NaN where dry (h_m is)
    return {
        "immersed": immersed,
        "re": flow.reynolds_number(x["rho_f"], r_eff, p["speed"], mu),
        "st": pair.pair_stokes_number(p["m_eff"], p["speed"], mu, r_eff),
        "st_n": st_n,
        # Legendre et al.'s added mass, on the pair's normal Stokes number
        "st_am": st_n * (1.0 + flow.ADDED_MASS_COEFFICIENT * x["rho_f"] / x["rho1"]),
        "x1": x1,
        "h_m": h_m,
        "eta_hat": eta_hat,
        "x3": lubrication.piezoviscous_length(eta_hat, mu, p["v_n"], r_eff),
        "sigma": sigma,
        "film": film,
        "rough": immersed & (sigma > h_m),
        "roughness_regime": limits.roughness_regime(sigma, x1),
    }


def lubricated(x: Arrays, p: Arrays, h: Arrays, f: Arrays, caps: Caps) -> Arrays:
    """Gohar's film, A(c) and (5.8) at the contact point's relative speed, with its state.

    (5.8) is only evaluated where the fluid has a pressure–viscosity coefficient; the
    state says why it is NaN or out of range (``limits.lubricated_friction_state``).
    """
    mu, eta_hat, r_eff, e_star = x["mu"], f["eta_hat"], p["r_eff"], p["e_star"]
    has_c = f["immersed"] & ~np.isnan(eta_hat)
    u_abs = np.abs(p["u"])
    h_film = lubrication.traction_film_thickness(r_eff, mu, u_abs, eta_hat, h["load"], e_star)
    integral = lubrication.friction_integral(eta_hat * h["p_max"])
    mu_lub = lubrication.lubricated_friction(
        mu, u_abs, h["load"], h_film, h["a"], eta_hat, h["p_max"], integral
    )
    nan = np.full(mu.shape, np.nan)
    mu_lub = np.where(has_c, mu_lub, nan)
    return {
        "u_abs": u_abs,
        "h_film": np.where(has_c, h_film, nan),
        "integral": np.where(has_c, integral, nan),
        "mu_lub": mu_lub,
        "strain": np.where(f["immersed"], lubrication.shear_strain(mu, u_abs, e_star, r_eff), nan),
        "state": limits.lubricated_friction_state(mu_lub, f["immersed"], has_c, *caps),
    }


def tangential(
    p: Arrays, f: Arrays, lub: Arrays, caps: Caps, immersed_friction: np.ndarray
) -> Arrays:
    """Maw's regime with the friction the physics supports (``derive`` documents the rule)."""
    dry, _ = caps
    # asperities touching in a liquid: the pair's immersed value where one is known
    touching = np.where(f["immersed"] & np.isfinite(immersed_friction), immersed_friction, dry)
    cap = limits.friction_cap(*caps)
    # A film only where σ is known to lie below h_m: a roughness not stated (σ NaN)
    # decides nothing, and the touching value is used (docs/physics.md §18).
    film = f["immersed"] & ~f["rough"] & ~np.isnan(f["sigma"])
    state = lub["state"]
    # No tangential motion: nothing slips, and (5.8) gives 0; Maw's ψ_in = 0 with the dry
    # value, as before issue 13 (a 0/0 here would read as gross slip).
    still = lub["u_abs"] == 0.0
    mu_used = np.where(
        ~film | still, touching, np.where(state == limits.IN_RANGE, lub["mu_lub"], cap)
    )
    ratio = impact.stiffness_ratio(p["g_star"], p["e_star"])
    chi = ratio * p["walton"]
    psi = impact.maw_psi(ratio, lub["u_abs"], mu_used, p["v_n"])
    code = impact.tangential_regime(psi, chi)
    # No coefficient: μ_f ≤ cap is all that is known, and a smaller μ_f only slips more;
    # the bound decides the regime only when it already gives gross slip.
    open_ended = (
        film & ~still & (state == limits.NO_PRESSURE_COEFFICIENT) & (code != impact.GROSS_SLIP)
    )
    return {
        "mu_used": mu_used,
        "chi": chi,
        "psi": psi,
        # one lookup from codes to names (object arrays are slow to build, twice slower)
        "regime": _REGIME_NAMES[np.where(open_ended, len(impact.TANGENTIAL_REGIME_NAMES), code)],
    }


#: Maw's regime where the friction is only bounded (no pressure–viscosity coefficient).
UNDETERMINED = "undetermined"
#: Maw's regimes (``impact.TANGENTIAL_REGIME_NAMES``, by code) and then ``UNDETERMINED``.
_REGIME_NAMES = np.asarray((*impact.TANGENTIAL_REGIME_NAMES, UNDETERMINED), dtype=object)


def collision(p: Arrays) -> Arrays:
    """e, β, Ψ_in, Ψ_out and μ_f from the relative contact-point velocities (§9)."""
    v_n, u, u_out = p["v_n"], p["u"], p["u_out"]
    beta = impact.rotational_restitution(u, u_out)  # NaN for a normal impact
    e = impact.normal_restitution(v_n, p["v_n_out"])
    psi_in = impact.effective_incidence(u, v_n)
    psi_out = impact.effective_rebound(u_out, v_n)
    return {
        "e": e,
        "beta": beta,
        "psi_in": psi_in,
        "psi_out": psi_out,
        "mu_f": pair.pair_sliding_friction(psi_in, psi_out, e, p["walton"]),
    }
