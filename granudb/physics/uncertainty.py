"""Standard uncertainties of every derived quantity, and the probability of each verdict.

**Propagation** (GUM, JCGM 100:2008 §5.1, first order). Each input x_k with a standard
uncertainty u(x_k) is a *source*. Every derived quantity Q of ``granudb.physics.derive``
is a product of powers of the pair's properties, the fluid's and the speeds (Hertz, the
Stokes and Reynolds numbers, x₁, h_m, x₃, (5.6), (5.8), Maw's ψ), so its logarithmic
sensitivity to each source, s_k = ∂ln Q/∂x_k, follows exactly from the exponents and
from the chain rule through E*, G*, R*, m*, V, σ and A(c) (``friction_integral_log_slope``
gives A's slope). Then

    u(Q)/|Q| = √(Σ_k (s_k u(x_k))²)

with sources that are the same quantity merged before squaring: where the particle and
the wall are the same material (``correlated``), their E, ν, ρ, σ and Y come from one
source and are fully correlated (r = 1, GUM (16)), so u(E*) is then u(E)/E and not
u(E)/(E√2); and where v_n and v_t are one measured speed at a set angle (``one_speed``,
as ``granudb.pair`` takes them). The merging is done once on the base quantities and
holds for all built from them, as the propagation is linear. Inputs without an
uncertainty (None, NaN) contribute nothing. No per-row Python: each sensitivity is a
scalar or an array over the rows, and E* is one source (its u from E and ν of both
bodies) for everything but G*, c and what is built on them, which take E and ν
themselves (``expand_e_star``). The incidence angle, not a product of powers, is
propagated absolutely in the same way.

Temperature enters through the viscosity: the caller gives u(μ) including
|∂μ/∂T| u(T) from the fluid model (``granudb.scenario.fluid_state``). The per-collision
parameters e, β, Ψ_in and Ψ_out of a measured run are ratios of measured speeds: their u
is ``ratio_uncertainty``'s (with ``contact_speed_uncertainty``), not a sensitivity here;
μ_f of (2.9) gets none yet.

How it is summed (``propagate``): each quantity's Σ (s_k u_k)² is formed once, a constant
s_k² times the u_k² computed once per block (a zero s_k, like R*'s in p_max, adds
nothing); a quantity whose sensitivities are a factor times a sum of others' with no
source in common (St = m*/R*² · V/μ, Re, Λ = x₁/σ, (5.9)'s A, e's prediction from
St_am, ζ) takes Σ coefficient² × their variances instead, which is the same sum
regrouped. tests/physics/test_uncertainty.py checks every column against the plain sum,
source by source, to 1e-12. A u_k² is computed only for a source some constant s_k
reaches (on ``benchmarks/derive_speed.py``'s scenarios 8 of the 15 given sources are
reached only through sensitivities that vary by row), and each input's u is looked at
once for its scaled source and whether it is stated in part. The u columns are written
straight into the output's rows (``into``), the verdict probabilities copied there while
still in cache (``granudb.physics.row_chunks``). On that benchmark first order's u and
probabilities cost about 0.9 of the plain derive's CPU, most of it the variances (about
250 numpy passes and 33 square roots a block of rows).

The first-order result is checked against Monte Carlo propagation (JCGM 101:2008) in
tests/physics/test_uncertainty.py: within 10 % for input uncertainties up to 5 %; at
30 % the curvature makes them part: u(St) of a 30 % viscosity (St ∝ 1/μ) is more than
10 % below the Monte Carlo spread. ``derive`` therefore does not take these u as they
are: ``granudb.physics.propagation_check`` checks them per row and quantity, gives the
95 % intervals, and replaces by a Monte Carlo the ones its check refuses
(docs/propagation.md).

**Verdict probabilities** (``verdict_probabilities``): a verdict compares a positive
quantity with a threshold, q = Q/Q_c > 1. q is taken as lognormal with ln q's standard
deviation s = u_rel(q), the first-order relative uncertainty of the ratio (its
sensitivities to shared sources subtracted, so a source common to both cancels), and

    P(q > 1) = Φ(ln q / s)

(s = 0: 1 if q > 1 else 0). A probability is "likely" (either way) when P ≥ 0.9 or
P ≤ 0.1, else "uncertain" (``LIKELY``, ``certainty``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from granudb.physics import flow, lubrication

Arrays = dict[str, np.ndarray]
#: Sensitivities of one quantity: source → ∂ln Q/∂(the source's scaled variable).
Sens = dict[str, Any]

#: The inputs of ``derive`` that may carry an uncertainty, by their step names, and
#: whether the source is scaled relatively (u/|x|; power-law factors) or absolutely
#: (u; Poisson ratios, roughness and velocities, which may be 0; v_n's is made relative
#: to the approach speed v_N > 0 in ``propagate``).
SOURCES: dict[str, bool] = {
    "rho1": True,
    "e1": True,
    "nu1": False,
    "s1": False,
    "y1": True,
    "rho2": True,
    "e2": True,
    "nu2": False,
    "s2": False,
    "y2": True,
    "d": True,
    "vn": False,
    "vt": False,
    "rho_f": True,
    "mu": True,
    "c_barus": True,
}
#: The wall's source of each of the particle's: the same source when both are one material.
_PARTNERS = {"rho1": "rho2", "e1": "e2", "nu1": "nu2", "s1": "s2", "y1": "y2"}
#: Probabilities at or beyond which a verdict is "likely" (either way).
LIKELY, UNLIKELY = 0.9, 0.1


def _lin(*terms: tuple[Any, Sens]) -> Sens:
    """Σ coefficient × sensitivities (the log of a product of powers)."""
    given = [(coefficient, sens) for coefficient, sens in terms if sens]
    if len(given) == 1 and type(given[0][0]) is int and given[0][0] == 1:
        return given[0][1]  # the same sensitivities: their norm is computed once
    out: Sens = {}
    for coefficient, sens in given:
        unit = type(coefficient) is int and coefficient in (1, -1)
        for source, value in sens.items():
            held = out.get(source)
            if unit and held is not None:  # one pass: add or subtract, no product first
                out[source] = held + value if coefficient == 1 else held - value
            elif unit and coefficient == 1:
                out[source] = value
            else:
                product = coefficient * value
                out[source] = product if held is None else held + product
    return out


def _scale(factor: Any, sens: Sens) -> Sens:
    return {source: factor * value for source, value in sens.items()}


def scaled_sources(x: Arrays, u: Arrays) -> Arrays:
    """Each given source's scaled uncertainty: u/|x| (relative) or u (absolute); NaN or
    missing u is "not given" and left out. A u stated as 0 (known exactly) is kept: the
    quantities it reaches then have u = 0, where one it does not reach has none (NaN,
    "not stated", never 0; ``propagate``).

    >>> scaled_sources({"e1": np.array([200e9])}, {"e1": np.array([10e9])})["e1"]
    array([0.05])
    >>> scaled_sources({"e1": np.array([200e9])}, {"e1": np.array([0.0])})["e1"]
    array([0.])
    >>> scaled_sources({"e1": np.array([200e9])}, {"e1": np.array([np.nan])})
    {}
    """
    return _scaled_and_partial(x, u)[0]


def _scaled_and_partial(x: Arrays, u: Arrays) -> tuple[Arrays, Arrays]:
    """``scaled_sources``, and each given source stated for some rows only: 1.0 where
    stated, 0.0 where not (one look at each u for both)."""
    out: Arrays = {}
    partial: Arrays = {}
    with np.errstate(divide="ignore", invalid="ignore"):
        for source, relative in SOURCES.items():
            given = u.get(source)
            if given is None:
                continue
            value = np.asarray(given, dtype=float)
            missing = np.isnan(value)  # u ≥ 0 (``derive`` checks); NaN: not given
            if missing.any():
                if missing.all():
                    continue
                partial[source] = (~missing).astype(float)
                value = np.nan_to_num(value, nan=0.0)
            out[source] = value / np.abs(x[source]) if relative else value
    return out, partial


def relative_uncertainty(
    sens: Sens,
    scaled: Arrays,
    correlated: Any = None,
    one_speed: Any = None,
    speed_factor: Any = 1.0,
) -> np.ndarray | float:
    """u(Q)/|Q| = √(Σ (s_k u_k)²), with the terms of two inputs that are one source added
    before squaring (r = 1): the particle's and the wall's property where ``correlated``
    (one material on both sides), v_n and v_t where ``one_speed`` (one measured speed
    at a set angle, as ``granudb.pair`` takes it; ``speed_factor`` is v_t's scaled u
    over v_n's).

    >>> float(relative_uncertainty({"e1": 0.5, "e2": 0.5}, {"e1": 0.1, "e2": 0.1}))
    0.07071067811865477
    >>> float(relative_uncertainty({"e1": 0.5, "e2": 0.5}, {"e1": 0.1, "e2": 0.1}, True))
    0.1
    """
    return _norm(_merged(sens, scaled, correlated, one_speed, speed_factor), scaled)


def _norm(sens: Sens, scaled: Arrays, squares: Arrays | None = None) -> np.ndarray | float:
    """√(Σ (s_k u_k)²) over the given sources (after ``_merged``); ``squares``, the
    u_k² if already computed, save a multiplication for each constant s_k."""
    total = _variance(sens, scaled, squares)
    return np.nan if total is None else np.sqrt(total)


def _variance(sens: Sens, scaled: Arrays, squares: Arrays | None = None) -> Any:
    """Σ (s_k u_k)² (``_norm`` squared; None without a given source). The result may be
    one of ``squares`` itself (a single source of unit weight): read it, never write it."""
    total: Any = None
    owned = False  # total is a fresh array of this call's, summed into in place
    for source, value in sens.items():
        given = scaled.get(source)
        if given is None:
            continue
        if squares is not None and not isinstance(value, np.ndarray):
            weight = value * value
            if weight == 0:  # a sensitivity that cancels (e.g. R* in p_max) adds nothing
                continue
            term = squares[source] if weight == 1 else weight * squares[source]
            fresh = weight != 1
        else:
            term = value * given
            if isinstance(term, np.ndarray):
                np.multiply(term, term, out=term)
            else:
                term = term * term
            fresh = True
        if total is None:
            total, owned = term, fresh and isinstance(term, np.ndarray)
        elif owned and total.shape == np.shape(term):
            total += term
        else:
            total = total + term
            owned = isinstance(total, np.ndarray)
    return total


def _merged(sens: Sens, scaled: Arrays, correlated: Any, one_speed: Any, speed_factor: Any) -> Sens:
    """``sens`` with each pair of inputs that are one source (see ``relative_uncertainty``)
    put on the first's scaled uncertainty: the wall's onto the particle's (one material:
    the same u/x), v_t's onto v_n's times ``speed_factor`` (one speed: the same
    relative u). Done once on the base quantities, it holds for all that are built from
    them (the propagation is linear)."""
    out = {name: value for name, value in sens.items() if name in scaled}
    if correlated is None and one_speed is None:
        return out  # no two inputs are one source
    pairs = [(first, second, correlated, 1.0) for first, second in _PARTNERS.items()]
    pairs.append(("vn", "vt", one_speed, speed_factor))
    for first, second, flag, factor in pairs:
        if second not in out or flag is None or (flag is not True and not np.any(flag)):
            continue
        moved = out[second] * factor
        if flag is True or np.all(flag):
            out[first] = out.get(first, 0.0) + moved
            del out[second]
        else:
            out[first] = out.get(first, 0.0) + np.where(flag, moved, 0.0)
            out[second] = np.where(flag, 0.0, out[second])
    return out


def _flag(flag: Any) -> Any:
    """A correlation flag as None (no row), True (every row) or the array (some rows)."""
    if flag is None:
        return None
    flag = np.asarray(flag)
    if not flag.any():
        return None
    return True if flag.all() else flag


def _indicator(condition: np.ndarray) -> np.ndarray:
    return condition.astype(float)


def sensitivities(
    x: Arrays,
    steps: tuple[Arrays, Arrays, Arrays, Arrays],
    scaled: Arrays,
    correlated: Any = None,
    one_speed: Any = None,
) -> dict[str, Sens]:
    """∂ln Q/∂(scaled source) of every propagated quantity, by ``derive``'s column name
    (``incidence_angle_rad``'s are of the angle itself, absolute), from the inputs ``x``
    and the steps' results (``granudb.physics.quantities``): only the given sources
    (``scaled``), with inputs that are one source merged (``_merged``)."""
    p, h, f, lub = steps
    wall_only = not np.asarray(p["free"]).any() and bool(np.isnan(x["d2"]).all())

    correlated, one_speed = _flag(correlated), _flag(one_speed)  # tested once, not per base
    speed_factor: Any = 1.0
    if one_speed is not None:
        with np.errstate(divide="ignore", invalid="ignore"):
            # v_n's u is scaled by v_N (relative), v_t's is absolute: one speed's ratio
            speed_factor = x["vt"] * p["v_n"] / x["vn"]

    def base(sens: Sens) -> Sens:
        return _merged(sens, scaled, correlated, one_speed, speed_factor)

    e_star, g_star = p["e_star"], p["g_star"]
    nu1, nu2 = x["nu1"], x["nu2"]
    with np.errstate(divide="ignore", invalid="ignore"):
        e_w1, e_w2 = e_star * (1 - nu1**2) / x["e1"], e_star * (1 - nu2**2) / x["e2"]
        s_e = {"e1": e_w1, "e2": e_w2, "nu1": 2 * nu1 * e_star / x["e1"],
               "nu2": 2 * nu2 * e_star / x["e2"]}  # fmt: skip
        # G = E/(2(1+ν)) where not given: its E and ν enter G*
        g_sens: Sens = {}
        for side, g_name, nu in (("1", "g1", nu1), ("2", "g2", nu2)):
            weight = g_star * (2 - nu) / p[g_name]
            missing = np.isnan(x[g_name])
            if not missing.all():  # G given in some rows: E and ν enter only where not
                weight = weight * _indicator(missing)
            g_sens = _lin(
                (1.0, g_sens),
                (1.0, {f"e{side}": weight, f"nu{side}": g_star / p[g_name] - weight / (1 + nu)}),
            )
        s_r = {"d": 1.0} if wall_only else {"d": p["r_eff"] / p["radius"]}
        s_m1 = {"rho1": 1.0, "d": 3.0}
        # 1/m* = 1/m₁ + 1/m₂: d ln m* = (m*/m₁) d ln m₁ + (1 − m*/m₁) d ln m₂ (wall: m* = m₁)
        k1 = p["m_eff"] / p["m1"]
        s_m = s_m1 if wall_only else {"rho1": k1, "d": 3.0 * k1, "rho2": 1.0 - k1}
        v_n, speed = p["v_n"], p["speed"]
        vt_centre = p["v_t_centre"]
        s_vn = {"vn": 1.0}  # v_n's u is relative to v_N (``propagate``)
        s_v = {"vn": (v_n / speed) ** 2, "vt": vt_centre / speed**2}
        tangential = p["u"]
        inverse = np.asarray(1.0 / tangential)
        inverse[tangential == 0.0] = 0.0
        s_u = {"vt": inverse}
        sigma_squared = f["sigma"] ** 2
        s_sigma = {"s1": x["s1"] / sigma_squared, "s2": x["s2"] / sigma_squared}
        k_am = flow.ADDED_MASS_COEFFICIENT * x["rho_f"] / x["rho1"]
        k_am = k_am / (1.0 + k_am)
    mu, rho_f, c, rho1 = (base({k: 1.0}) for k in ("mu", "rho_f", "c_barus", "rho1"))
    s_e, g_sens, s_r, s_m1, s_m, s_vn, s_v, s_u, s_sigma = (
        base(sens) for sens in (s_e, g_sens, s_r, s_m1, s_m, s_vn, s_v, s_u, s_sigma)
    )
    # E, ν of both bodies enter everything but G*, c and what is built on them through
    # E* alone: E* is one source for those (its u from the four), expanded where needed.
    e_sources = s_e
    if s_e:
        scaled[E_STAR] = np.asarray(_norm(s_e, scaled))
        s_e = {E_STAR: 1.0}

    s: dict[str, Sens] = {
        "reduced_modulus_pa": s_e,
        "reduced_shear_modulus_pa": g_sens,
        "effective_radius_m": s_r,
        "particle_mass_kg": s_m1,
        "effective_mass_kg": s_m,
        "impact_speed_m_s": s_v,
        "normal_speed_m_s": s_vn,
    }
    # Quantities whose u comes from others': Q's sensitivities are factor × Σ coefficient
    # × parts; where the parts have no source in common (checked in ``propagate``) the
    # variance is Σ coefficient² × the parts' variances, computed once for all.
    sums: dict[str, tuple[Any, tuple[tuple[Any, Sens], ...]]] = {}
    sums["reynolds_number"] = (None, ((1, rho_f), (1, s_r), (1, s_v), (-1, mu)))
    inertia = _lin((1, s_m), (-2, s_r))  # m*/R*²
    sums["stokes_number"] = (None, ((1, inertia), (1, s_v), (-1, mu)))
    sums["normal_stokes_number"] = (None, ((1, inertia), (1, s_vn), (-1, mu)))
    s["normal_stokes_number"] = _lin((1, s_m), (1, s_vn), (-1, mu), (-2, s_r))
    s["added_mass_stokes_number"] = _lin(
        (1, s["normal_stokes_number"]), (k_am, rho_f), (-k_am, rho1)
    )
    delta = _lin((0.4, s_m), (0.8, s_vn), (-0.4, s_e), (-0.2, s_r))
    load = _lin((1, s_e), (0.5, s_r), (1.5, delta))
    radius = _lin((1 / 3, s_r), (1 / 3, load), (-1 / 3, s_e))
    pressure = _lin((1, load), (-2, radius))
    time = _lin((1, delta), (-1, s_vn))
    slower = _indicator(h["c_wave_1"] <= h["c_wave_2"])
    wave = base({"e1": 0.5 * slower, "rho1": -0.5 * slower,
                 "e2": 0.5 * (1 - slower), "rho2": -0.5 * (1 - slower)})  # fmt: skip
    soft = _indicator(~(x["y2"] < x["y1"]))  # fmin: the particle's unless the wall's is lower
    s_y = base({"y1": soft, "y2": 1 - soft})
    s.update(
        {
            "impact_load_n": load,
            "contact_radius_m": radius,
            "max_pressure_pa": pressure,
            "max_approach_m": delta,
            "contact_time_s": time,
            "wave_speed_m_s": wave,
            "quasi_static_ratio": _lin(
                (1, expand_e_star(_lin((1, radius), (-1, time)), e_sources)), (-1, wave)
            ),
            "yield_speed_m_s": _lin((1, s_vn), (2.5, s_y), (-2.5, pressure)),
        }
    )
    x1 = _lin((0.4, mu), (0.4, s_vn), (0.6, s_r), (-0.4, s_e))
    s.update(
        {
            "elastic_length_m": x1,
            "min_gap_m": x1,
            "eta_hat_pa_inv": c,
            "piezoviscous_length_m": _lin((0.5, c), (0.5, mu), (0.5, s_vn), (0.5, s_r)),
            "composite_roughness_m": s_sigma,
        }
    )
    sums["film_parameter"] = (None, ((1, x1), (-1, s_sigma)))
    with np.errstate(divide="ignore", invalid="ignore"):
        recovery = 35.0 / f["st_am"]  # d ln e_pred / d ln St_am of e_dry exp(−35/St_am)
    sums["predicted_restitution"] = (recovery, ((1, s["added_mass_stokes_number"]),))
    film = _lin(
        (2 / 7, s_r), (5 / 7, mu), (5 / 7, s_u), (5 / 7, c), (-1 / 21, load),
        (1 / 21, s_e), (2 / 21, s_r)
    )  # fmt: skip
    slope = lubrication.friction_integral_log_slope(f["eta_hat"] * h["p_max"], lub["integral"])
    integral = _scale(slope, _lin((1, c), (1, pressure)))
    sums["friction_integral"] = (slope, ((1, c), (1, pressure)))
    friction = _lin((1, mu), (1, s_u), (2, radius), (1, integral), (-1, load), (-1, film))
    stiffness = _lin((1, g_sens), (-1, e_sources))
    s.update(
        {
            "tangential_speed_m_s": s_u,
            "traction_film_m": film,
            "lubricated_friction": friction,
            "shear_strain": _lin((2 / 7, mu), (2 / 7, s_u), (-2 / 7, s_e), (-2 / 7, s_r)),
            "maw_chi": stiffness,
        }
    )
    angle_factor = v_n * tangential / (v_n**2 + tangential**2)  # dζ = that × (dln U − dln v_N)
    sums["incidence_angle_rad"] = (angle_factor, ((1, s_u), (-1, s_vn)))
    s["_sums"] = sums  # not a column: the quantities above
    s["_yield_ratio"] = _lin((1, pressure), (-1, s_y))  # not a column: P(yield)'s ratio
    s["_e_star_sources"] = e_sources  # not a column: E*'s own sources, for ``propagate``
    return s


#: The name of E* as one source (``sensitivities``).
E_STAR = "E*"


def expand_e_star(sens: Sens, e_sources: Sens) -> Sens:
    """``sens`` with E* as a source replaced by E* 's own sources (E and ν of both
    bodies), for a quantity that also depends on them otherwise (c, G*)."""
    gamma = sens.get(E_STAR)
    if gamma is None:
        return sens
    rest = {name: value for name, value in sens.items() if name != E_STAR}
    return _lin((1, rest), (gamma, e_sources))


def propagate(
    x: Arrays,
    u: Arrays,
    steps: tuple[Arrays, Arrays, Arrays, Arrays, Arrays],
    columns: Arrays,
    critical_stokes: float,
    correlated: np.ndarray | None = None,
    one_speed: np.ndarray | None = None,
    into: Arrays | None = None,
    scaled: Arrays | None = None,
) -> Arrays:
    """``u_<column>`` of every propagated column of ``columns`` (``derive``'s, in its
    order) and the verdict probabilities, from the inputs' uncertainties ``u`` (step
    names, see ``SOURCES``); ``steps`` are the results of ``granudb.physics.quantities``'
    pair_properties, hertz, fluid_numbers, lubricated and tangential. ``into``: arrays
    to write ``u_<column>`` into, where given (returned as the values); ``scaled``, if
    given, receives each given source's scaled u (``scaled_sources``; v_n's relative to
    v_N), 0 where not stated."""
    p, h, f, lub, tan = steps
    given, partial = _scaled_and_partial(x, u)
    if "vn" in given:
        given["vn"] = given["vn"] / p["v_n"]  # relative to the approach speed v_N > 0
    if scaled is not None:
        scaled.update(given)
    scaled = given
    sens = sensitivities(x, (p, h, f, lub), scaled, correlated, one_speed)
    sums = sens.pop("_sums")
    lubricated = (tan["mu_used"] == lub["mu_lub"]) & np.isfinite(lub["mu_lub"])
    relative = _relatives(sens, sums, scaled, columns, lubricated)
    # A source stated for some rows only (a table of runs): a row none of whose reaching
    # sources is stated has no u (NaN), not the 0 its unstated rows' zeros would give.
    if partial:
        stated: dict[str, np.ndarray | float] = {
            k: partial.get(k, 1.0) for k in scaled if k != E_STAR
        }
        if E_STAR in scaled:
            stated[E_STAR] = _reach(sens["_e_star_sources"], stated)
        for name in relative:
            if name in sums:
                reach = _any_of([_reach(part, stated) for _, part in sums[name][1]])
            elif name == "maw_psi_in":
                reach = _any_of([_reach(sens[k], stated) for k in (
                    "maw_chi", "tangential_speed_m_s", "normal_speed_m_s", "lubricated_friction"
                )])  # fmt: skip
            else:
                reach = _reach(sens["lubricated_friction" if name ==
                                    "friction_coefficient_used" else name], stated)  # fmt: skip
            relative[name] = np.where(reach > 0, relative[name], np.nan)
    out: Arrays = {}
    into = into or {}
    for name in (name for name in columns if name in relative):
        key = f"u_{name}"
        if name == "incidence_angle_rad":  # absolute already; NaN where the angle is
            out[key] = np.add(relative[name], 0.0 * columns[name], out=into.get(key))
        else:
            u_q = np.multiply(columns[name], relative[name], out=into.get(key))
            out[key] = np.abs(u_q, out=u_q) if isinstance(u_q, np.ndarray) else abs(u_q)
    # Outside an immersed rebound e is e_dry (dry) or 0 by the St_c rule: neither has a
    # propagated u (e_dry's own is not an input here), so none is stated.
    rebound = np.isfinite(f["st_am"]) & (columns["predicted_restitution"] > 0) & f["immersed"]
    u_e = out["u_predicted_restitution"]
    if isinstance(u_e, np.ndarray) and u_e.ndim:
        np.putmask(u_e, ~rebound, np.nan)
    else:
        out["u_predicted_restitution"] = np.where(rebound, u_e, np.nan)
    probabilities = verdict_probabilities(
        film=columns["film_parameter"],
        u_film=relative["film_parameter"],
        normal_stokes=columns["normal_stokes_number"],
        u_normal_stokes=relative["normal_stokes_number"],
        critical_stokes=critical_stokes,
        yield_ratio=h["p_max"] / (1.6 * np.fmin(x["y1"], x["y2"])),
        u_yield_ratio=relative["_yield_ratio"],
        immersed=f["immersed"],
    )
    for name, values in probabilities.items():  # into ``into`` while still in cache
        out[name] = values if into.get(name) is None else _copied(values, into[name])
    return out


def _copied(values: np.ndarray, target: np.ndarray) -> np.ndarray:
    """``target`` with ``values`` copied in."""
    target[...] = values
    return target


def ratio_uncertainty(ratio: Any, denominator: Any, u_numerator: Any, u_denominator: Any) -> Any:
    r"""u(q) of a ratio q = a/b of two independently measured values (GUM, JCGM 100:2008
    eq. (10), first order): u(q) = √(u(a)² + q² u(b)²) / |b|.

    A missing uncertainty (NaN) counts as zero where the other is given; with neither
    given, u(q) is NaN (not stated, never zero). This is how a run's e = v_n,out/v_N,in,
    Ψ_in = v_T,in/v_N,in, Ψ_out = v_T,out/v_N,in and β = −v_T,out/v_T,in (Joseph & Hunt
    2004, (2.5), (2.8)) get their uncertainty from the measured speeds' (docs/physics.md,
    "Measurement uncertainty of runs").

    Parameters
    ----------
    ratio : q = a/b [any unit]
    denominator : b [unit of b]
    u_numerator : u(a), standard uncertainty of a [unit of a]
    u_denominator : u(b), standard uncertainty of b [unit of b]

    Examples
    --------
    >>> round(float(ratio_uncertainty(0.97, 0.3, 0.009, 0.009)), 5)  # u = 9 mm/s on each speed
    0.04179
    >>> float(ratio_uncertainty(0.97, 0.3, np.nan, np.nan))
    nan
    """
    ua, ub = np.asarray(u_numerator, dtype=float), np.asarray(u_denominator, dtype=float)
    q, b = np.asarray(ratio, dtype=float), np.asarray(denominator, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.hypot(np.nan_to_num(ua), q * np.nan_to_num(ub)) / np.abs(b)
    return np.where(np.isnan(ua) & np.isnan(ub), np.nan, u)


def contact_speed_uncertainty(
    u_v_t: Any, omega: Any, u_omega: Any, radius: Any, u_radius: Any
) -> Any:
    r"""u(v_T) of the contact point's tangential velocity v_T = v_t + ωR (Joseph & Hunt 2004
    §2) from independent u(v_t), u(ω), u(R) (GUM eq. (10)): √(u(v_t)² + (R u(ω))² +
    (ω u(R))²); NaN where none is given, a missing one counting as zero otherwise. A spin
    not measured (ω NaN) contributes nothing.

    Parameters
    ----------
    u_v_t : u(v_t) of the centre's tangential velocity [m/s]
    omega : spin ω [rad/s]
    u_omega : u(ω) [rad/s]
    radius : R = d/2 [m]
    u_radius : u(R) = u(d)/2 [m]

    Examples
    --------
    >>> round(float(contact_speed_uncertainty(0.003, 10.0, 0.5, 6.35e-3, 5e-6)), 6)
    0.004368
    """
    parts = (u_v_t, np.asarray(radius, dtype=float) * u_omega,
             np.nan_to_num(np.asarray(omega, dtype=float)) * u_radius)  # fmt: skip
    given = np.zeros(np.broadcast(*parts).shape, dtype=bool)
    total = np.zeros(given.shape)
    for part in parts:
        part = np.asarray(part, dtype=float)
        given |= ~np.isnan(part)
        total = total + np.nan_to_num(part) ** 2
    return np.where(given, np.sqrt(total), np.nan)


def _sum_norm(factor: Any, parts: tuple[Any, ...], scaled: Arrays, variance: Any) -> Any:
    """u(Q)/|Q| of sensitivities factor × Σ coefficient × part (``sensitivities``' sums):
    from the parts' variances where no two parts share a given source, else from the
    combined sensitivities; ``variance`` gives (and caches) a part's."""
    keys = [scaled.keys() & part.keys() for _, part in parts]
    if sum(map(len, keys)) == len(set().union(*keys)):  # no source in two parts
        total: Any = None
        owned = False  # total is this call's own array (the parts' are cached: read only)
        for coefficient, part in parts:
            term = variance(part)
            if term is None:  # no given source in this part
                continue
            weight = coefficient * coefficient
            if total is None:
                total, owned = (term, False) if weight == 1 else (weight * term, True)
            elif owned and isinstance(total, np.ndarray) and total.shape == np.shape(term):
                total += term if weight == 1 else weight * term
            else:
                total, owned = total + (term if weight == 1 else weight * term), True
    else:
        total = variance(_lin(*parts))
    if total is None:  # no given source: not stated (never 0), whatever the factor
        return np.nan
    norm = np.sqrt(total)
    return norm if factor is None else norm * np.abs(factor)


def normal_cdf(z: np.ndarray | float) -> np.ndarray:
    """Φ(z), the standard normal distribution function, vectorized; ±inf give 1 and 0.

    Abramowitz & Stegun 7.1.26 for erf (|error| ≤ 1.5e-7), in pure numpy.

    >>> [round(float(normal_cdf(z)), 4) for z in (-1.0, 0.0, 1.96)]
    [0.1587, 0.5, 0.975]
    """
    z = np.asarray(z, dtype=float)
    if z.ndim == 0:
        return normal_cdf(z.reshape(1)).reshape(())
    t_arg = np.abs(z)
    t_arg *= 1.0 / np.sqrt(2.0)
    t = 0.3275911 * t_arg
    t += 1.0
    np.divide(1.0, t, out=t)
    poly = 1.061405429 * t
    for coefficient in (-1.453152027, 1.421413741, -0.284496736, 0.254829592):
        poly += coefficient
        poly *= t
    np.multiply(t_arg, t_arg, out=t_arg)
    np.negative(t_arg, out=t_arg)
    with np.errstate(over="ignore", under="ignore"):
        np.exp(t_arg, out=t_arg)
    poly *= t_arg
    poly *= 0.5  # Φ(−|z|) = erfc(|z|/√2)/2
    # z > 0: 1 − Φ(−z); NaN stays NaN (the polynomial of NaN is NaN)
    probability: np.ndarray = np.where(z > 0, 1.0 - poly, poly)
    return probability


def exceedance(ratio: Any, u_relative: Any) -> np.ndarray:
    """P(q > 1) for a lognormal q with median ``ratio`` and ln-sd ``u_relative`` (the
    module docstring's rule); NaN where ``ratio`` is NaN.

    >>> round(float(exceedance(1.0, 0.1)), 3), float(exceedance(2.0, 0.0))
    (0.5, 1.0)
    """
    ratio = np.asarray(ratio, dtype=float)
    s = np.asarray(u_relative, dtype=float)
    if np.isnan(ratio).all():  # no verdict in any row (no yield stress, dry)
        return np.full(np.broadcast(ratio, s).shape, np.nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.log(ratio) / s  # s = 0: ±inf, whose Φ is the step 1 if q > 1 else 0
    out = normal_cdf(z)
    undefined = np.isnan(out)  # a NaN ratio; or no u (NaN), or s = 0 at q = 1: the step
    if undefined.any():
        step = undefined & ~(s > 0) & ~np.isnan(ratio)
        out[step] = np.broadcast_to(ratio > 1.0, out.shape)[step]
    return out


def verdict_probabilities(
    *,
    film: np.ndarray,
    u_film: Any,
    normal_stokes: np.ndarray,
    u_normal_stokes: Any,
    critical_stokes: float,
    yield_ratio: np.ndarray,
    u_yield_ratio: Any,
    immersed: np.ndarray,
) -> Arrays:
    """P(σ > h_m) = P(Λ < 1), P(St_n > St_c) and P(p_max > 1.6 Y) by the module's rule
    (relative uncertainties ``u_*``): NaN where the verdict has no number (dry, no Y);
    a dry collision rebounds (1).

    >>> out = verdict_probabilities(film=np.array([1.0]), u_film=0.2,
    ...     normal_stokes=np.array([100.0]), u_normal_stokes=0.0, critical_stokes=10.0,
    ...     yield_ratio=np.array([np.nan]), u_yield_ratio=0.0, immersed=np.array([True]))
    >>> [round(float(v[0]), 2) if v[0] == v[0] else None for v in out.values()]
    [0.5, 1.0, None]
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        contact = exceedance(film, u_film)
    np.subtract(1.0, contact, out=contact)
    rebound = exceedance(normal_stokes / critical_stokes, u_normal_stokes)
    if not immersed.all():  # dry rows: no contact verdict, rebound certain
        contact = np.where(immersed, contact, np.nan)
        rebound = np.where(immersed, rebound, 1.0)
    return {
        "probability_asperity_contact": contact,
        "probability_rebound": rebound,
        "probability_yield": exceedance(yield_ratio, u_yield_ratio),
    }


def certainty(probability: float) -> str:
    """ "likely" where P ≥ ``LIKELY`` or P ≤ 1 − ``LIKELY`` (either way), else "uncertain".

    >>> certainty(0.95), certainty(0.05), certainty(0.46)
    ('likely', 'likely', 'uncertain')
    """
    return "likely" if probability >= LIKELY or probability <= UNLIKELY else "uncertain"


def _reach(sens: Sens, stated: dict[str, np.ndarray | float]) -> Any:
    """1.0 in the rows where a source of ``sens`` is stated (``stated``: 1.0/0.0 by row,
    or 1.0 for every row), else 0.0: whether a stated input reaches the quantity at all,
    whatever its sensitivity's value."""
    return _any_of([stated[k] for k in sens if k in stated])


def _any_of(masks: list[Any]) -> Any:
    """The largest of 1.0/0.0 masks (scalars or arrays), row by row; 0.0 for none."""
    out: Any = 0.0
    for mask in masks:
        out = np.maximum(out, mask)
    return out


class _Squares(dict):  # type: ignore[type-arg]
    """u_k² of the scaled sources, each computed when first asked for (a source whose
    sensitivities are all arrays never needs its own)."""

    def __init__(self, scaled: Arrays) -> None:
        super().__init__()
        self.scaled = scaled

    def __missing__(self, source: str) -> np.ndarray:
        value = self.scaled[source]
        square: np.ndarray = value * value
        self[source] = square
        return square


def _relatives(
    sens: dict[str, Sens],
    sums: dict[str, Any],
    scaled: Arrays,
    columns: Arrays,
    lubricated: np.ndarray,
) -> dict[str, Any]:
    """u(Q)/|Q| of every propagated column from the sensitivities and the sources'
    scaled uncertainties (NaN where no given source reaches Q): ``propagate``'s sum."""
    squares = _Squares(scaled)
    variances: dict[int, Any] = {}  # each set of sensitivities once (x₁ and h_m share one)
    norms: dict[int, Any] = {}

    def variance(value: Sens) -> Any:
        if id(value) not in variances:
            variances[id(value)] = _variance(value, scaled, squares)
        return variances[id(value)]

    relative: dict[str, Any] = {}
    for name, value in sens.items():
        if name not in sums and (name in columns or name == "_yield_ratio"):
            if id(value) not in norms:
                total = variance(value)
                norms[id(value)] = np.nan if total is None else np.sqrt(total)
            relative[name] = norms[id(value)]
    for name, (factor, parts) in sums.items():
        relative[name] = _sum_norm(factor, parts, scaled, variance)
    # the dry or immersed μ used otherwise is a stored value: its u is not propagated here
    relative["friction_coefficient_used"] = np.where(
        lubricated, relative["lubricated_friction"], np.nan
    )
    if lubricated.all():
        friction = sens["lubricated_friction"]
    else:
        friction = _scale(lubricated.astype(float), sens["lubricated_friction"])
    friction = expand_e_star(friction, sens["_e_star_sources"])
    relative["maw_psi_in"] = _norm(
        _lin((1, sens["maw_chi"]), (1, sens["tangential_speed_m_s"]),
             (-1, sens["normal_speed_m_s"]), (-1, friction)),
        scaled, squares,
    )  # fmt: skip
    return relative
