"""The names of uncertainties and of verdict probabilities.

A value's standard uncertainty u (GUM, JCGM 100:2008 §2.3.1: one standard deviation, in
the value's own unit) is stored and returned under the value's name with a ``u_``
prefix: ``u_youngs_modulus_pa`` is u(E) in pascals, ``u_normal_stokes_number`` u(St_n).
The prefix keeps the unit suffix, so one unit table reads and formats both. Empty (None,
NaN) means "not given", never zero.

Every catalogue property may carry one (``--youngs-modulus "190 GPa ± 5 %"``); every
continuous derived quantity of ``granudb.physics.derive`` gets one when uncertainties are
given (``UNCERTAIN_DERIVED``), with the probability of each verdict
(``PROBABILITY_TERMS``). This module adds their terms to ``TERMS`` and their rule (≥ 0)
to ``RULES``, so schemas, listings and labels are generated from here.
"""

from __future__ import annotations

from granudb.vocabulary.catalog import FLUIDS, MATERIALS
from granudb.vocabulary.derived import DERIVED_TERMS
from granudb.vocabulary.rules import NON_NEGATIVE, RULES
from granudb.vocabulary.terms import (
    COLLISION_UNCERTAIN,
    PROPAGATION_METHOD,
    TERMS,
    Term,
    interval_columns,
    stored,
    uncertainty_column,
)

#: A fluid point's values that carry a standard uncertainty.
POINT_UNCERTAIN = [s.column for s in stored("fluid_points") if s.uncertain]


def _uncertainty_term(column: str, term: Term, role: str) -> Term:
    symbol = term.symbol or column
    return Term(
        f"u({term.title})",
        term.unit,
        f"Standard uncertainty u({symbol}) of {column}, same unit (one standard deviation; "
        "empty: not given).",
        role=role,
        symbol=f"u({symbol})",
    )


#: The stored uncertainty columns of the catalogue, by the property they belong to.
STORED_UNCERTAINTIES: dict[str, str] = {
    column: uncertainty_column(column)
    for column in (*MATERIALS.properties, *FLUIDS.properties, *POINT_UNCERTAIN)
}

#: Derived quantities that get a standard uncertainty (the continuous ones a scenario
#: has; a measured run's e, β and Ψ get theirs from its speeds': ``MEASURED_DERIVED``),
#: in presentation order.
UNCERTAIN_DERIVED = (
    "reduced_modulus_pa",
    "reduced_shear_modulus_pa",
    "effective_radius_m",
    "particle_mass_kg",
    "effective_mass_kg",
    "impact_speed_m_s",
    "normal_speed_m_s",
    "incidence_angle_rad",
    "reynolds_number",
    "stokes_number",
    "normal_stokes_number",
    "added_mass_stokes_number",
    "impact_load_n",
    "contact_radius_m",
    "max_pressure_pa",
    "max_approach_m",
    "contact_time_s",
    "wave_speed_m_s",
    "quasi_static_ratio",
    "yield_speed_m_s",
    "elastic_length_m",
    "min_gap_m",
    "eta_hat_pa_inv",
    "piezoviscous_length_m",
    "composite_roughness_m",
    "film_parameter",
    "predicted_restitution",
    "tangential_speed_m_s",
    "traction_film_m",
    "friction_integral",
    "lubricated_friction",
    "shear_strain",
    "friction_coefficient_used",
    "maw_chi",
    "maw_psi_in",
)

#: A run's parameters whose uncertainty comes from its measured speeds' stated ones
#: (``granudb.physics.uncertainty.ratio_uncertainty``), listed where a run states any.
MEASURED_DERIVED = (
    "normal_restitution",
    "rotational_restitution",
    "effective_incidence",
    "effective_rebound",
)

#: The probability of each verdict, from the propagated uncertainties
#: (``granudb.physics.uncertainty.verdict_probabilities`` states the model).
PROBABILITY_TERMS: dict[str, Term] = {
    "probability_asperity_contact": Term(
        "P(asperity contact)",
        None,
        "P(σ > h_m): probability that the asperities touch through the film, from u(Λ) "
        "(lognormal Λ); empty for a dry collision.",
        role="derived",
        symbol="P(σ > h_m)",
    ),
    "probability_rebound": Term(
        "P(rebound)",
        None,
        "P(St_n > St_c): probability of a rebound, from u(St_n) (lognormal St_n); 1 when dry.",
        role="derived",
        symbol="P(St_n > St_c)",
    ),
    "probability_yield": Term(
        "P(yield)",
        None,
        "P(p_max > 1.6 Y): probability that the softer body yields, from u(p_max) and u(Y) "
        "(lognormal ratio); empty where no Y is known.",
        role="derived",
        symbol="P(p_max > 1.6 Y)",
    ),
}


def _interval_terms(column: str, term: Term) -> dict[str, Term]:
    symbol = term.symbol or column
    low, high = interval_columns(column)
    return {
        name: Term(
            f"{end} end of {term.title}'s 95 % interval",
            term.unit,
            f"{end.capitalize()} end of the 95 % coverage interval of {column} (same unit; "
            "first order: value·exp(±1.96u/value), ±1.96u for a speed or angle; Monte "
            "Carlo: its 2.5 % or 97.5 % quantile; propagation_method says which; empty: no u).",
            role="derived",
            symbol=f"{symbol} {'≥' if end == 'low' else '≤'}",
        )
        for name, end in ((low, "low"), (high, "high"))
    }


#: The 95 % coverage interval's ends of each quantity in ``UNCERTAIN_DERIVED``.
INTERVAL_TERMS: dict[str, Term] = {
    name: value
    for column in UNCERTAIN_DERIVED
    for name, value in _interval_terms(column, DERIVED_TERMS[column]).items()
}

#: How a row's u, intervals and verdict probabilities were obtained (one field for all).
METHOD_TERMS: dict[str, Term] = {
    PROPAGATION_METHOD: Term(
        "Propagation method",
        None,
        "Which method gave this scenario's standard uncertainties, 95 % intervals and "
        "verdict probabilities: first order (GUM) where its check shows it adequate, else "
        "a Monte Carlo (JCGM 101) with the number of draws it took; first order, naming "
        "the quantities whose check failed, where a call's budget of draws "
        "(monte_carlo_draws) was spent on earlier rows or where stored runs are read (no "
        "draws); empty where no input states a u (docs/propagation.md).",
        role="derived",
        symbol="method of u",
    )
}

#: Every column ``derive`` adds when given uncertainties: u of each quantity in
#: ``UNCERTAIN_DERIVED``, the probabilities, each quantity's 95 % interval and the method.
UNCERTAINTY_TERMS: dict[str, Term] = {
    **{
        uncertainty_column(name): _uncertainty_term(name, DERIVED_TERMS[name], "derived")
        for name in UNCERTAIN_DERIVED
    },
    **PROBABILITY_TERMS,
    **INTERVAL_TERMS,
    **METHOD_TERMS,
}

#: A collision's measured columns and their stated uncertainties' columns
#: (``granudb.vocabulary.terms.COLLISION_UNCERTAINTIES``), by measured column.
MEASURED_UNCERTAINTIES: dict[str, str] = {c: uncertainty_column(c) for c in COLLISION_UNCERTAIN}

TERMS.update(
    {
        u: _uncertainty_term(column, TERMS[column], "stored")
        for column, u in (*STORED_UNCERTAINTIES.items(), *MEASURED_UNCERTAINTIES.items())
    }
)
TERMS.update(
    {
        uncertainty_column(name): _uncertainty_term(name, DERIVED_TERMS[name], "derived")
        for name in MEASURED_DERIVED
    }
)
TERMS.update(UNCERTAINTY_TERMS)  # ``term()`` finds them; derive's own list stays DERIVED_TERMS
RULES.update(
    {u: NON_NEGATIVE for u in (*STORED_UNCERTAINTIES.values(), *MEASURED_UNCERTAINTIES.values())}
)
