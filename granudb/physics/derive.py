"""Every derived quantity and verdict for a table of collisions or scenarios, in one
vectorized pass (no per-row Python, no quadrature).

``derive()`` takes arrays (or scalars, broadcast together) of the pair's material
properties, the fluid's state, the particle size and the velocities, and returns a dict of
arrays under granudb's column names (their units and meanings are in
``granudb.vocabulary.DERIVED_TERMS``). A dry collision has ``viscosity_pa_s`` NaN: its
fluid quantities are NaN, its roughness verdict False (``roughness_regime`` "dry") and
rebound is expected. Where an
input makes a quantity undefined (no measured rebound) that quantity is NaN, element by
element; where a model is outside its range or lacks an input, a text state column names
why (``elastic_state``, ``lubricated_friction_state``, ``roughness_regime``) so no NaN
reaches a verdict silently. The steps live in ``granudb.physics.quantities``.

**The target.** Particle (1), target (2). The normal n points from the particle to the
target, the tangential axis t along the particle's incoming tangential motion; spins
are about n × t, positive where the particle's spin moves its contact point along +t.
The particle's ``v_n_in`` is along n (> 0) and its ``v_n_out`` along −n (≥ 0, away
from the target), as granudb stores them. The target's ``wall_v_n_in``/``wall_v_n_out`` are
along n (> 0 moving away from the particle), ``wall_v_t_*`` along t and
``wall_omega_*`` about the same axis n × t (so a positive target spin moves its contact
point along −t). All target velocities NaN: a flat wall (``wall_diameter_m`` NaN) or a
fixed sphere (finite), immovable (m₂ = ∞) and at rest; ``wall_v_n_in`` given: a free
sphere of the wall material (a missing tangential or spin input before impact is 0, a
missing one after impact makes the collision parameters that need it NaN).
Every collision parameter (e, β, Ψ_in, Ψ_out, μ_f) then comes from the relative
velocities v_N = (v₁ − v₂)·n and v_T = (v₁ − v₂)·t + ω₁R₁ + ω₂R₂ of the contact point;
Hertz, St, St_n, Re, x₁ and x₃ from m*, R* and v_N (Davis et al. 1986); Walton's (2.9)
with B = 1 + m*(R₁²/I₁ + R₂²/I₂) (``walton_factor``, 7/2 for solid spheres).
``incidence_angle_rad`` is ζ_in of the contact point's path, atan(|v_T,in|/v_N,in):
spin counts (the measured set-up angle is a different, stored column).

**Limits.** ``elastic_state`` compares p_max with 1.6 Y of the softer body (§11); the
quasi-static verdict is False where yield is exceeded (Hertz no longer holds).
``lubricated_friction_state``: (5.8) is "in_range", "above_limit" (above
min(``dry_friction``, ``limiting_shear_slope``), Bair & Winer 1979),
"no_pressure_coefficient" or "dry".

**Friction for Maw's regime** (``friction_coefficient_used``): ``dry_friction`` where
the collision is dry, and where σ > h_m (asperities touch, the paper's §4 argument) in a
liquid the pair's ``immersed_friction`` where one is known (NaN: ``dry_friction``). With
the default h_m = x₁/3 a roughness in Davis's "uncertain" band x₁/4 < σ ≤ x₁/3 is still
treated as a film, and ``roughness_regime`` says it is uncertain. Else the film's:
(5.8) when in range; the cap min(dry, γ_max) — a film at its limiting shear stress —
when (5.8) is above it. For a fluid without a pressure–viscosity coefficient (water in
the seed data) μ_f is not computed: water's viscosity *decreases* with pressure below
~150 MPa at ≤ 30 °C (Eisenberg & Kauzmann 1969, quoted by Joseph & Hunt §5), so neither
a borrowed coefficient nor (5.6)'s piezoviscous film applies, and C → 0 makes (5.6)'s
film vanish (the isoviscous limit of (5.8) is not finite). The same cap is then used as
an upper bound: the regime is "gross_slip" where the bound already gives it (a smaller
μ_f only slips more) and "undetermined" otherwise.

**Restitution.** ``dry_restitution`` and ``dry_friction`` are the pair's dry values, per
row (``granudb.scenario.dry_values`` resolves them with their sources; the defaults are
Joseph & Hunt's steel on Zerodur, borrowed). Past yield (``elastic_state``
"yield_exceeded") the dry e is bounded by Thornton's elastic–plastic restitution,
``restitution_ceiling`` = min(e_dry, e_Thornton(V_y/V)) (docs/physics.md §15) and
``restitution_model`` says "elastic_plastic"; else it is e_dry ("elastic").
``predicted_restitution`` = ``restitution_ceiling`` × exp(−35/St) with Legendre et al.'s
added-mass St of the pair's normal approach, 0 where rebound is not expected
(St_n ≤ ``critical_stokes``), ``restitution_ceiling`` for dry rows, NaN for an immersed
row without fluid density.

**Hertz's small strain.** ``contact_radius_ratio`` a/R* and ``approach_ratio`` δ/R*;
``hertz_strain_valid`` where a/R* ≤ 0.1 (``limits.HERTZ_STRAIN_LIMIT``, docs/physics.md
§16).
"""

from __future__ import annotations

from collections.abc import Mapping
from functools import partial
from typing import Any

import numpy as np

from granudb.physics import flow, limits, lubrication, pair, propagation_check, uncertainty
from granudb.physics import quantities as steps
from granudb.physics.numeric import Numeric, PhysicsInputError
from granudb.physics.row_chunks import run_in_chunks

#: Friction coefficient assumed where asperities touch or the collision is dry; the paper's
#: dry fits give 0.11 (steel) and 0.106 (glass) on Zerodur (§3).
DRY_FRICTION = 0.11
#: Joseph & Hunt's mean dry restitution, ē_dry = 0.97 ± 0.02 (§3).
DRY_RESTITUTION = 0.97


def _check(name: str, values: np.ndarray, ok: np.ndarray, rule: str) -> None:
    bad = ~ok
    if bad.any():
        index = int(np.flatnonzero(bad.ravel())[0])
        raise PhysicsInputError(
            name, f"{values.ravel()[index]:g}", rule, row=index + 1 if values.size > 1 else None
        )


#: Inputs of ``derive`` in the order they are broadcast, with their short step names.
_INPUTS = {
    "particle_density_kg_m3": "rho1",
    "particle_youngs_modulus_pa": "e1",
    "particle_poisson_ratio": "nu1",
    "particle_roughness_rms_m": "s1",
    "particle_shear_modulus_pa": "g1",
    "particle_yield_stress_pa": "y1",
    "wall_density_kg_m3": "rho2",
    "wall_youngs_modulus_pa": "e2",
    "wall_poisson_ratio": "nu2",
    "wall_roughness_rms_m": "s2",
    "wall_shear_modulus_pa": "g2",
    "wall_yield_stress_pa": "y2",
    "wall_diameter_m": "d2",
    "diameter_m": "d",
    "v_n_in_m_s": "vn",
    "v_t_in_m_s": "vt",
    "omega_in_rad_s": "w",
    "fluid_density_kg_m3": "rho_f",
    "viscosity_pa_s": "mu",
    "pressure_viscosity_pa_inv": "c_barus",
    "v_n_out_m_s": "vn_out",
    "v_t_out_m_s": "vt_out",
    "omega_out_rad_s": "w_out",
    "wall_v_n_in_m_s": "w_vn",
    "wall_v_t_in_m_s": "w_vt",
    "wall_omega_in_rad_s": "w_w",
    "wall_v_n_out_m_s": "w_vn_out",
    "wall_v_t_out_m_s": "w_vt_out",
    "wall_omega_out_rad_s": "w_w_out",
    "dry_restitution": "e_dry",
    "dry_friction": "mu_dry",
    "immersed_friction": "mu_wet",
}
_TARGET_VELOCITIES = ("w_vn", "w_vt", "w_w", "w_vn_out", "w_vt_out", "w_w_out")


def _validate(x: dict[str, np.ndarray]) -> None:
    """Refuse unphysical input in one line naming the field, the value and the rule."""
    _check("diameter_m", x["d"], x["d"] > 0, "must be > 0")
    _check(
        "v_n_in_m_s",
        x["vn"],
        np.isfinite(x["w_vn"]) | (x["vn"] > 0),  # a free target: the approach rule below
        "must be > 0 (the normal speed towards the wall)",
    )
    _check("v_t_in_m_s", x["vt"], x["vt"] >= 0, "must be ≥ 0 (the tangential axis points along it)")
    _check(
        "dry_restitution", x["e_dry"], (x["e_dry"] > 0) & (x["e_dry"] <= 1), "must be > 0 and ≤ 1"
    )
    _check("dry_friction", x["mu_dry"], x["mu_dry"] >= 0, "must be ≥ 0")
    wet = x["mu_wet"]
    _check("immersed_friction", wet, np.isnan(wet) | (wet >= 0), "must be ≥ 0 (NaN: the dry value)")
    for name in ("particle_youngs_modulus_pa", "wall_youngs_modulus_pa"):
        _check(name, x[_INPUTS[name]], x[_INPUTS[name]] > 0, "must be > 0")
    for name in ("particle_density_kg_m3", "wall_density_kg_m3"):
        _check(name, x[_INPUTS[name]], x[_INPUTS[name]] > 0, "must be > 0")
    for name in ("particle_poisson_ratio", "wall_poisson_ratio"):
        values = x[_INPUTS[name]]
        _check(name, values, (values > -1) & (values < 0.5), "must be > -1 and < 0.5")
    _check(
        "viscosity_pa_s", x["mu"], np.isnan(x["mu"]) | (x["mu"] > 0), "must be > 0 (NaN for dry)"
    )
    c = x["c_barus"]
    _check(
        "pressure_viscosity_pa_inv",
        c,
        np.isnan(c) | (c > 0),
        "must be > 0 (NaN where not known; C = 0 makes (5.6)'s film vanish and μ_f infinite)",
    )
    for name in ("particle_yield_stress_pa", "wall_yield_stress_pa"):
        values = x[_INPUTS[name]]
        _check(name, values, np.isnan(values) | (values > 0), "must be > 0 (NaN where not known)")
    moving = np.zeros(x["d"].shape, dtype=bool)
    for short in _TARGET_VELOCITIES:
        moving |= np.isfinite(x[short])
    _check(
        "wall_diameter_m",
        x["d2"],
        ~moving | np.isfinite(x["d2"]),
        "must be given when the target's velocities are (only a sphere can be a free target)",
    )
    _check(
        "wall_v_n_in_m_s",
        x["w_vn"],
        ~moving | np.isfinite(x["w_vn"]),
        "must be given for a free target (NaN with every target velocity NaN: a fixed target)",
    )
    approach = x["vn"] - np.where(np.isnan(x["w_vn"]), 0.0, x["w_vn"])
    _check(
        "wall_v_n_in_m_s",
        x["w_vn"],
        approach > 0,
        "must be below v_n_in_m_s (the particle must approach the target)",
    )


def derive(
    *,
    particle_density_kg_m3: Numeric,
    particle_youngs_modulus_pa: Numeric,
    particle_poisson_ratio: Numeric,
    particle_roughness_rms_m: Numeric,
    wall_density_kg_m3: Numeric,
    wall_youngs_modulus_pa: Numeric,
    wall_poisson_ratio: Numeric,
    wall_roughness_rms_m: Numeric,
    diameter_m: Numeric,
    v_n_in_m_s: Numeric,
    v_t_in_m_s: Numeric = 0.0,
    omega_in_rad_s: Numeric = 0.0,
    particle_shear_modulus_pa: Numeric = np.nan,
    wall_shear_modulus_pa: Numeric = np.nan,
    particle_yield_stress_pa: Numeric = np.nan,
    wall_yield_stress_pa: Numeric = np.nan,
    wall_diameter_m: Numeric = np.nan,
    fluid_density_kg_m3: Numeric = np.nan,
    viscosity_pa_s: Numeric = np.nan,
    pressure_viscosity_pa_inv: Numeric = np.nan,
    v_n_out_m_s: Numeric = np.nan,
    v_t_out_m_s: Numeric = np.nan,
    omega_out_rad_s: Numeric = np.nan,
    wall_v_n_in_m_s: Numeric = np.nan,
    wall_v_t_in_m_s: Numeric = np.nan,
    wall_omega_in_rad_s: Numeric = np.nan,
    wall_v_n_out_m_s: Numeric = np.nan,
    wall_v_t_out_m_s: Numeric = np.nan,
    wall_omega_out_rad_s: Numeric = np.nan,
    critical_stokes: float = flow.CRITICAL_STOKES_NUMBER,
    dry_friction: Numeric = DRY_FRICTION,
    gap_fraction: float = lubrication.GAP_FRACTION,
    dry_restitution: Numeric = DRY_RESTITUTION,
    immersed_friction: Numeric = np.nan,
    limiting_shear_slope: float = limits.LIMITING_SHEAR_SLOPE,
    threads: int | None = None,
    uncertainties: Mapping[str, Numeric] | None = None,
    correlated_materials: Numeric = False,
    one_speed: Numeric = False,
    monte_carlo: bool = True,
    monte_carlo_draws: int = propagation_check.DRAW_BUDGET,
) -> dict[str, np.ndarray]:
    """Derive every derived column (``granudb.vocabulary.DERIVED_TERMS``) for arrays of collisions.

    Inputs are SI and broadcast together. NaN shear modulus: derived from E and ν. NaN
    ``wall_diameter_m``: a flat wall (infinite radius and mass). NaN ``viscosity_pa_s``: a
    dry collision. NaN after-impact velocities: a scenario (per-collision parameters NaN).
    NaN yield stress: not known (``elastic_state`` "unknown" unless exceeded by the other).

    The conventions for a target sphere, the limits, the friction used for Maw's regime
    and the predicted restitution are in the module docstring.

    Raises ``PhysicsInputError`` on unphysical input (non-positive size, speed, modulus,
    yield stress or pressure–viscosity coefficient, ν outside (−1, 0.5), a target that
    recedes faster than the particle approaches, target velocities without a target
    diameter).

    Large tables are computed in blocks of ``granudb.physics.row_chunks.CHUNK_ROWS`` rows on
    ``threads`` threads (None: the calling thread only, which measured faster than two on
    two cores; n: a pool of n, at most the cores available); every row's result is the
    same whatever the blocks or threads.

    ``uncertainties``: standard uncertainties of inputs, keyed ``u_<input>``
    (``u_particle_youngs_modulus_pa``, ``u_viscosity_pa_s``, ``u_v_n_in_m_s``, … — the
    inputs in ``UNCERTAIN_INPUTS``), same unit, NaN where not given. With it (even
    empty) the result also has ``u_<column>`` of every continuous quantity
    (``granudb.vocabulary.UNCERTAINTY_TERMS``, in column order) and the verdict
    probabilities
    (``granudb.physics.uncertainty``: GUM first order); ``correlated_materials`` true
    where the particle and the wall are one material (their sources are then one),
    ``one_speed`` where v_n and v_t are one measured speed at a set angle (their
    uncertainties fully correlated). Each row's u is first order where
    ``granudb.physics.propagation_check``'s check allows, else its Monte Carlo; with
    ``monte_carlo`` False first order everywhere, and ``propagation_method`` names the
    quantities the check failed (the cost of the Monte Carlo is then not paid).
    ``monte_carlo_draws`` bounds the Monte Carlo's cost: the call's draws of the
    derivation over all its rows, each block of rows its rows' share, served in row order;
    a row beyond it keeps first order and its ``propagation_method`` says so.
    """
    given = locals()
    names = list(_INPUTS)
    u_given = _uncertainty_inputs(uncertainties)
    values = [given[name] for name in names] + list(u_given.values())
    if uncertainties is not None:
        values += [correlated_materials, one_speed]
    arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in values))
    x = dict(zip(_INPUTS.values(), arrays, strict=False))
    for index, short in enumerate(u_given):
        x[_U + short] = arrays[len(names) + index]
    if uncertainties is not None:
        x[_CORRELATED], x[_ONE_SPEED] = arrays[-2], arrays[-1]
    rows = max(int(arrays[0].size), 1) if arrays else 1
    compute = partial(
        _derive_block,
        uncertain=uncertainties is not None,
        monte_carlo=monte_carlo,
        draws_per_row=monte_carlo_draws / rows,
        limiting_shear_slope=limiting_shear_slope,
        gap_fraction=gap_fraction,
        critical_stokes=critical_stokes,
    )
    try:
        return run_in_chunks(compute, x, threads, writes_into=uncertainties is not None)
    except PhysicsInputError:
        _validate(x)  # the first bad row of the whole table, as one pass would name it
        raise


def _derive_block(
    x: dict[str, np.ndarray],
    into: dict[str, np.ndarray] | None = None,
    *,
    uncertain: bool,
    monte_carlo: bool,
    draws_per_row: float,
    limiting_shear_slope: float,
    gap_fraction: float,
    critical_stokes: float,
) -> dict[str, np.ndarray]:
    """Every derived column for broadcast inputs ``x`` (one block of rows), after
    ``_validate``. ``into``: the outputs' rows of this block, where the uncertainties and
    intervals are written directly (``row_chunks.run_in_chunks``' ``writes_into``)."""
    _validate(x)
    evaluate = partial(
        _evaluate,
        limiting_shear_slope=limiting_shear_slope,
        gap_fraction=gap_fraction,
        critical_stokes=critical_stokes,
    )
    columns: dict[str, np.ndarray]
    columns, (p, h, f, lub, tan) = evaluate(x, keep_steps=True)
    if into is not None:  # stored while still in cache, before the uncertainties' work
        for name, values in columns.items():
            into[name][...] = values
            columns[name] = into[name]
    if uncertain:
        u = {name[len(_U) :]: values for name, values in x.items() if name.startswith(_U)}
        correlated, one_speed = x[_CORRELATED] != 0, x[_ONE_SPEED] != 0
        scaled: dict[str, np.ndarray] = {}  # the sources' scaled u, for the check too
        first = uncertainty.propagate(
            x,
            u,
            (p, h, f, lub, tan),
            columns,
            critical_stokes,
            correlated,
            one_speed,
            into,
            scaled,
        )
        # first order where its check allows, else a Monte Carlo; intervals and method
        names = tuple(k[2:] for k in first if k.startswith("u_"))
        columns.update(
            propagation_check.check_and_resample(
                evaluate,
                x,
                u,
                columns,
                first,
                names,
                correlated,
                one_speed,
                critical_stokes,
                limits.friction_cap(x["mu_dry"], limiting_shear_slope),
                monte_carlo=monte_carlo,
                budget=draws_per_row * max(int(np.size(columns[names[0]])), 1),
                into=into,
                scaled=scaled,
            )
        )
    return columns


def _evaluate(
    x: dict[str, np.ndarray],
    *,
    limiting_shear_slope: float,
    gap_fraction: float,
    critical_stokes: float,
    keep_steps: bool = False,
) -> Any:
    """derive's columns for valid inputs ``x`` (and the steps' results if ``keep_steps``)."""
    caps = (x["mu_dry"], limiting_shear_slope)
    p = steps.pair_properties(x)
    h = steps.hertz(x, p)
    f = steps.fluid_numbers(x, p, gap_fraction)
    lub = steps.lubricated(x, p, h, f, caps)
    tan = steps.tangential(p, f, lub, caps, x["mu_wet"])
    col = steps.collision(p)
    columns = _columns(p, h, f, lub, tan, col, critical_stokes)
    return (columns, (p, h, f, lub, tan)) if keep_steps else columns


#: Prefix of an input's uncertainty among the block's arrays, and the correlation flag.
_U, _CORRELATED, _ONE_SPEED = "u:", "correlated", "one speed"
#: The inputs that may carry a standard uncertainty (``derive``'s ``uncertainties``).
UNCERTAIN_INPUTS = tuple(name for name, short in _INPUTS.items() if short in uncertainty.SOURCES)


def _uncertainty_inputs(uncertainties: Mapping[str, Numeric] | None) -> dict[str, Any]:
    """``u_<input>`` → the input's step name with its uncertainty; refuses an unknown
    name or a negative uncertainty."""
    out: dict[str, Any] = {}
    for key, value in (uncertainties or {}).items():
        name = key.removeprefix("u_")
        if not key.startswith("u_") or name not in UNCERTAIN_INPUTS:
            raise PhysicsInputError(
                key, "", f"is not an input uncertainty (u_ + one of {', '.join(UNCERTAIN_INPUTS)})"
            )
        array = np.asarray(value, dtype=float)
        # the smallest u first (no temporary); NaN ("not given") makes it NaN: look closer
        if array.size and not array.min() >= 0 and (array < 0).any():
            _check(key, array, np.isnan(array) | (array >= 0), "must be ≥ 0 (NaN: not given)")
        out[_INPUTS[name]] = array
    return out


def _columns(
    p: dict[str, np.ndarray],
    h: dict[str, np.ndarray],
    f: dict[str, np.ndarray],
    lub: dict[str, np.ndarray],
    tan: dict[str, np.ndarray],
    col: dict[str, np.ndarray],
    critical_stokes: float,
) -> dict[str, np.ndarray]:
    """The derived columns under granudb's names (``DERIVED_TERMS``)."""
    rebound = ~f["immersed"] | (f["st_n"] > critical_stokes)
    predicted = flow.predicted_restitution(f["st_am"], h["e_dry"], critical_stokes)
    predicted = np.where(f["immersed"] & ~rebound, 0.0, predicted)
    predicted = np.where(f["immersed"] & np.isnan(f["st_am"]), np.nan, predicted)
    return {
        "reduced_modulus_pa": p["e_star"],
        "reduced_shear_modulus_pa": p["g_star"],
        "effective_radius_m": p["r_eff"],
        "particle_mass_kg": p["m1"],
        "effective_mass_kg": p["m_eff"],
        "walton_factor": p["walton"],
        "impact_speed_m_s": p["speed"],
        "normal_speed_m_s": p["v_n"],
        "incidence_angle_rad": pair.contact_incidence_angle(p["u"], p["v_n"]),
        "reynolds_number": f["re"],
        "stokes_number": f["st"],
        "normal_stokes_number": f["st_n"],
        "added_mass_stokes_number": f["st_am"],
        "impact_load_n": h["load"],
        "contact_radius_m": h["a"],
        "max_pressure_pa": h["p_max"],
        "max_approach_m": h["delta"],
        "contact_time_s": h["t_c"],
        "wave_speed_m_s": h["c_wave"],
        "quasi_static_ratio": h["qs_ratio"],
        "quasi_static_valid": h["qs_valid"],
        "yield_speed_m_s": h["yield_speed"],
        "elastic_state": limits.names(limits.ELASTIC_STATES, h["elastic_state"]),
        "restitution_ceiling": h["e_dry"],
        "restitution_model": h["e_model"],
        "contact_radius_ratio": h["a_ratio"],
        "approach_ratio": h["delta_ratio"],
        "hertz_strain_valid": h["strain_valid"],
        "elastic_length_m": f["x1"],
        "min_gap_m": f["h_m"],
        "eta_hat_pa_inv": f["eta_hat"],
        "piezoviscous_length_m": f["x3"],
        "composite_roughness_m": f["sigma"],
        "film_parameter": f["film"],
        "roughness_exceeds_gap": f["rough"],
        "roughness_regime": limits.names(limits.ROUGHNESS_REGIMES, f["roughness_regime"]),
        "rebound_expected": rebound,
        "predicted_restitution": predicted,
        "tangential_speed_m_s": p["u"],
        "traction_film_m": lub["h_film"],
        "friction_integral": lub["integral"],
        "lubricated_friction": lub["mu_lub"],
        "lubricated_friction_state": limits.names(limits.FRICTION_STATES, lub["state"]),
        "shear_strain": lub["strain"],
        "friction_coefficient_used": tan["mu_used"],
        "maw_chi": tan["chi"],
        "maw_psi_in": tan["psi"],
        "tangential_regime": tan["regime"],
        "normal_restitution": col["e"],
        "rotational_restitution": col["beta"],
        "effective_incidence": col["psi_in"],
        "effective_rebound": col["psi_out"],
        "sliding_friction": col["mu_f"],
    }


def scalar_view(result: dict[str, np.ndarray], index: int = 0) -> dict[str, Any]:
    """One row of a ``derive`` result as plain Python values (for one scenario)."""
    row: dict[str, Any] = {}
    for name, values in result.items():
        value = np.asarray(values).ravel()[index]
        row[name] = value.item() if hasattr(value, "item") else value
    return row
