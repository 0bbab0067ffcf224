"""The regime verdicts in words, for the terminal (``granudb pair``) and the reports alike.

Every verdict reads the named states of ``granudb.physics.derive`` (``roughness_regime``,
``lubricated_friction_state``, ``tangential_regime``, ``elastic_state``), never a bare NaN:
a number that is missing is said in words (``_number``), so no "nan" reaches a sentence.
The roughness words are the ones of the derived-quantities table (``film_parameter``) and
of the regime map (``ROUGHNESS_WORDS``): asperity contact Λ < 1, uncertain 1 ≤ Λ < 4/3
(Davis et al.'s band h_m = x₁/4 … x₁/3), film Λ ≥ 4/3, with h_m = x₁/3.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from granudb.physics import flow, limits
from granudb.physics.uncertainty import LIKELY, UNLIKELY, certainty
from granudb.reporting.format import display, engineering, is_number
from granudb.scenario.dry_values import BORROWED_VALUES

GAP_DEFINITION = "h_m = x₁/3, the EHD minimum gap of the normal approach (Joseph & Hunt §1, §4)"
#: The three roughness states in words, shared by verdicts, tables and the regime map.
ROUGHNESS_WORDS = {
    "asperity_contact": "asperity contact (σ > x₁/3, Λ < 1)",
    "uncertain": "uncertain (x₁/4 < σ ≤ x₁/3, 1 ≤ Λ < 4/3)",
    "film": "film (σ ≤ x₁/4, Λ ≥ 4/3)",
    "dry": "dry (no liquid)",
    "not_stated": "not determined (a material's roughness is not stated)",
}
PREDICTION_FORM = (
    f"e = e_dry exp(−{flow.LEGENDRE_BETA:g}/St) (Legendre, Zenit, Daniel & Guiraud 2006), "
    f"St = (ρ_p + ρ_f/2) 2R* v_N,in / (9μ) the added-mass Stokes number of the pair's normal "
    f"approach; 0 where St_n ≤ St_c"
)
#: Where the elastic–plastic restitution comes from (docs/physics.md §15).
THORNTON = (
    "Thornton (1997), J. Appl. Mech. 64, 383: e = min(e_dry, e_T(V_y/V)), elastic–perfectly "
    "plastic spheres"
)
BRITTLE_NOTE = (
    "{names} {verb} stored as brittle: brittle bodies do not yield, they fail by Hertzian "
    "cone cracks, which granudb does not predict (a note, not a number)."
)
#: Without stored dry values: Joseph & Hunt's steel on Zerodur (``analysis.dry_values``).
BORROWED_DRY = BORROWED_VALUES.record()


_SYMBOLS = {"dry_restitution": "e_dry", "dry_friction": "μ_dry", "immersed_friction": "μ"}


def dry_words(dry: Mapping[str, Any], key: str) -> str:
    """A pair's value with its source, "e_dry = 0.97 (measured for steel on Zerodur
    (joseph-hunt-2004, §3, figure 4))", for ``key`` "dry_restitution", "dry_friction" or
    "immersed_friction"."""
    return f"{_SYMBOLS[key]} = {dry[key]:.3g} ({dry[f'{key}_source']})"


@dataclass(frozen=True)
class Verdict:
    key: str
    name: str
    text: str
    raised: bool = False  # a warning the reader must not miss


def in_words(value: Any, unit: str = "", missing: str = "not known") -> str:
    """A number for a sentence (3 significant digits, engineering prefix with a unit), or
    the words ``missing`` when it is NaN or absent."""
    if not is_number(value):
        return missing
    return engineering(float(value), unit, 3) if unit else f"{float(value):.3g}"


def friction_cap(dry_friction: float = BORROWED_VALUES.friction) -> float:
    return float(limits.friction_cap(dry_friction, limits.LIMITING_SHEAR_SLOPE))


def verdicts(
    derived: Mapping[str, Any],
    critical_stokes: float = 10.0,
    immersed: bool = True,
    materials: Sequence[Mapping[str, Any]] = (),
    fluid_name: str | None = None,
    dry: Mapping[str, Any] | None = None,
) -> list[Verdict]:
    """Rebound and predicted restitution, roughness against gap, the lubricated friction,
    Maw's tangential regime, Hertz validity (quasi-static, small strain) and yield.
    ``materials`` (particle, wall records) name the bodies whose yield stress is not known
    or that are brittle; ``fluid_name`` the fluid; ``dry`` the pair's dry values with their
    sources (``DryValues.record()``; None: the borrowed ones, said so). Where the inputs
    carry uncertainties, the rebound, roughness and yield verdicts say their probability
    (``with_probability``)."""
    dry = dry or BORROWED_DRY
    said = [
        rebound_verdict(derived, critical_stokes, immersed, dry),
        restitution_verdict(derived, critical_stokes, immersed, dry),
        roughness_verdict(derived, immersed, materials),
        friction_verdict(derived, immersed, fluid_name, dry),
        tangential_verdict(derived),
        quasi_static_verdict(derived),
        strain_verdict(derived),
        yield_verdict(derived, materials, dry),
    ]
    return [with_probability(verdict, derived) for verdict in said]


# --- Verdicts with their probability (issue 27) ------------------------------------------

#: Each verdict's probability column, the event in symbols and the uncertainty that
#: makes it more than 0 or 1 (``granudb.physics.uncertainty.verdict_probabilities``).
PROBABILITIES = {
    "rebound_expected": ("probability_rebound", "St_n > St_c", "u_normal_stokes_number"),
    "roughness_regime": ("probability_asperity_contact", "σ > h_m", "u_film_parameter"),
    "elastic_state": ("probability_yield", "p_max > 1.6 Y", "u_max_pressure_pa"),
}
LIKELY_RULE = (
    f"likely where P ≥ {LIKELY:g} or P ≤ {UNLIKELY:g}, else uncertain; P from the propagated "
    "standard uncertainties, lognormal (docs/physics.md, Uncertainty)"
)


def with_probability(verdict: Verdict, derived: Mapping[str, Any]) -> Verdict:
    """``verdict`` with "P(σ > h_m) = 0.46: uncertain." appended where its number carries
    an uncertainty (``u_…`` > 0, or a probability strictly between 0 and 1), by the rule
    ``LIKELY_RULE``; an uncertain verdict is raised. Else unchanged."""
    if verdict.key not in PROBABILITIES:
        return verdict
    column, event, spread = PROBABILITIES[verdict.key]
    probability, u = derived.get(column), derived.get(spread)
    spread_given = is_number(u) and u > 0
    if not is_number(probability) or (not spread_given and probability in (0.0, 1.0)):
        return verdict
    word = certainty(float(probability))
    text = f"{verdict.text} P({event}) = {float(probability):.2f}: {word}."
    return Verdict(verdict.key, verdict.name, text, verdict.raised or word == "uncertain")


def rebound_verdict(
    derived: Mapping[str, Any],
    critical_stokes: float,
    immersed: bool,
    dry: Mapping[str, Any] = BORROWED_DRY,
) -> Verdict:
    st_n = derived.get("normal_stokes_number")
    if not immersed:
        text = (
            "expected: a dry collision rebounds (restitution set by the solids, "
            f"{dry_words(dry, 'dry_restitution')})."
        )
        return Verdict("rebound_expected", "Rebound", text)
    if not is_number(st_n):
        return Verdict(
            "rebound_expected",
            "Rebound",
            "not decided: the normal Stokes number could not be computed.",
            raised=True,
        )
    if derived.get("rebound_expected"):
        text = f"expected: normal Stokes number St_n = {st_n:.3g} > St_c = {critical_stokes:g}."
        return Verdict("rebound_expected", "Rebound", text)
    return Verdict(
        "rebound_expected",
        "Rebound",
        f"not expected: normal Stokes number St_n = {st_n:.3g} ≤ St_c = "
        f"{critical_stokes:g}; the fluid absorbs the impact.",
        raised=True,
    )


def restitution_applies(derived: Mapping[str, Any], dry: Mapping[str, Any]) -> str:
    """Which dry e the prediction uses, read from the record (``restitution_model``, the
    one rule of ``physics.quantities``): e_dry below yield and, past it, below the
    hand-over speed V_h where Thornton's e falls to e_dry; Thornton's e above V_h. The
    words every verdict about it uses."""
    e_dry = dry_words(dry, "dry_restitution")
    v_y, v_n = derived.get("yield_speed_m_s"), derived.get("normal_speed_m_s")
    if derived.get("elastic_state") != "yield_exceeded" or not is_number(v_y):
        return e_dry
    v_h = in_words(float(limits.handover_speed(dry["dry_restitution"], v_y)), "m/s")
    where = f"v_N,in = {in_words(v_n, 'm/s')}, V_y = {in_words(v_y, 'm/s')}, V_h = {v_h}"
    if derived.get("restitution_model") == "elastic_plastic":
        return (
            f"Thornton's elastic–plastic e = {in_words(derived.get('restitution_ceiling'))}, "
            f"which applies above the hand-over speed V_h where it falls below {e_dry} "
            f"({where}; {THORNTON})"
        )
    return (
        f"{e_dry}, which applies: past the onset of yield but below the hand-over speed "
        f"V_h, above which Thornton's elastic–plastic e would fall below it ({where}; "
        f"{THORNTON})"
    )


def _ceiling(derived: Mapping[str, Any], dry: Mapping[str, Any]) -> str:
    """The dry e the prediction starts from, with its source (``restitution_applies``)."""
    return restitution_applies(derived, dry)


def restitution_verdict(
    derived: Mapping[str, Any],
    critical_stokes: float,
    immersed: bool,
    dry: Mapping[str, Any] = BORROWED_DRY,
) -> Verdict:
    """The predicted restitution with its form, Stokes number and dry e named, each with
    its source (docs/physics.md §10, §18, §15)."""
    e_pred = derived.get("predicted_restitution")
    st = derived.get("added_mass_stokes_number")
    name = "Predicted restitution"
    plastic = derived.get("restitution_model") == "elastic_plastic"
    if not immersed:
        return Verdict(
            "predicted_restitution",
            name,
            f"e = {in_words(e_pred)}: dry, {_ceiling(derived, dry)}.",
            raised=plastic,
        )
    if not is_number(e_pred):
        return Verdict(
            "predicted_restitution",
            name,
            "not computed: the fluid's density or the Stokes number is not known.",
            raised=True,
        )
    if not derived.get("rebound_expected"):
        text = (
            f"e = 0: no rebound expected (St_n ≤ St_c = {critical_stokes:g}). "
            f"Form: {PREDICTION_FORM}."
        )
        return Verdict("predicted_restitution", name, text)
    text = (
        f"e ≈ {e_pred:.2f} at the added-mass Stokes number St = {in_words(st)}. "
        f"Form: {PREDICTION_FORM}, with {_ceiling(derived, dry)}. A prediction where "
        "nothing is measured, not a fit."
    )
    return Verdict("predicted_restitution", name, text, raised=plastic)


def unstated_roughness(materials: Sequence[Mapping[str, Any]]) -> list[str]:
    """The names of the materials (particle, wall records) whose roughness is not stated."""
    names = [m.get("name") for m in materials if m.get("roughness_rms_m") is None]
    return list(dict.fromkeys(str(n) for n in names if n))


def roughness_verdict(
    derived: Mapping[str, Any],
    immersed: bool = True,
    materials: Sequence[Mapping[str, Any]] = (),
) -> Verdict:
    """σ against Davis's band of the gap, h_m = x₁/4 … x₁/3, with Λ (docs/physics.md §4, §12);
    "not determined" where a material's roughness is not stated (``materials``: the
    particle and wall records, which name it; §18)."""
    regime = str(derived.get("roughness_regime") or "")
    sigma, x1, film = (
        derived.get(k) for k in ("composite_roughness_m", "elastic_length_m", "film_parameter")
    )
    if not immersed or regime == "dry" or not is_number(x1):
        return Verdict(
            "roughness_regime",
            "Roughness against gap",
            "no fluid film: a dry contact, asperities touch (friction dry).",
        )
    unstated = unstated_roughness(materials)
    if regime == "not_stated" or unstated or not is_number(sigma):
        whose = " and ".join(unstated) or "a material"
        return Verdict(
            "roughness_regime",
            "Roughness against gap",
            f"not determined: roughness of {whose} not stated. The EHD gap is h_m = "
            f"x₁/4 … x₁/3 = {in_words(x1 / 4, 'm')} … {in_words(x1 / 3, 'm')} (Davis et al. "
            "1986); without σ neither a film nor asperity contact follows, so granudb "
            "does not assume a film: Maw's regime uses the friction where asperities touch.",
            raised=True,
        )
    if regime not in ROUGHNESS_WORDS:  # an older frame without the three-state column
        regime = "asperity_contact" if derived.get("roughness_exceeds_gap") else "film"
    numbers = (
        f"σ = {in_words(sigma, 'm')} (composite RMS); the EHD gap is h_m = x₁/4 … x₁/3 = "
        f"{in_words(x1 / 4, 'm')} … {in_words(x1 / 3, 'm')} (Davis et al. 1986); "
        f"Λ = h_m/σ = {in_words(film)} with {GAP_DEFINITION}"
    )
    if regime == "asperity_contact":
        return Verdict(
            "roughness_regime",
            "Roughness exceeds the gap: asperity contact",
            f"{numbers}. σ exceeds even the largest gap. Asperities touch through the film: "
            "expect dry-like friction (glass on Zerodur in glycerol: μ_f ≈ 0.15).",
            raised=True,
        )
    if regime == "uncertain":
        return Verdict(
            "roughness_regime",
            "Roughness within the gap's uncertainty: uncertain",
            f"{numbers}. σ lies within the uncertainty of the gap itself: asperities may or "
            "may not touch. granudb treats the contact as a film for Maw's regime; friction "
            "may be anywhere from the film's to the dry value.",
            raised=True,
        )
    return Verdict(
        "roughness_regime",
        "Roughness within the gap: film",
        f"{numbers}. σ is below even the smallest gap: the film separates the surfaces; "
        "friction comes from shearing the film and is low (steel on Zerodur: μ_f ≈ 0.02).",
    )


def friction_verdict(
    derived: Mapping[str, Any],
    immersed: bool,
    fluid_name: str | None = None,
    dry: Mapping[str, Any] = BORROWED_DRY,
) -> Verdict:
    """The lubricated friction (5.8) and whether it is used (docs/physics.md §12), with
    the pair's dry friction and its source (§18)."""
    state = str(derived.get("lubricated_friction_state") or ("dry" if not immersed else ""))
    mu = derived.get("lubricated_friction")
    cap = friction_cap(dry["dry_friction"])
    mu_dry = dry_words(dry, "dry_friction")
    touching = dry_words(dry, "immersed_friction")
    bound = (
        f"min({mu_dry}, limiting-shear slope γ_max = "
        f"{limits.LIMITING_SHEAR_SLOPE:g}, Bair & Winer 1979) = {cap:g}"
    )
    name = "Lubricated friction (5.8)"
    regime = derived.get("roughness_regime")
    # a roughness not stated shows no film, so the touching value is used (§4, §18)
    asperities = regime in ("asperity_contact", "not_stated")
    why = (
        "the roughness is not stated (no film is assumed)"
        if regime == "not_stated"
        else "asperities touch here"
    )
    if state == "dry" or not immersed:
        return Verdict(
            "lubricated_friction_state",
            name,
            f"dry contact: the dry value is used, {mu_dry}.",
        )
    if state == "no_pressure_coefficient":
        fluid = fluid_name or "the fluid"
        return Verdict(
            "lubricated_friction_state",
            name,
            f"not computed: {fluid} has no pressure–viscosity coefficient C in the database. "
            "Water's viscosity decreases with pressure below ~150 MPa at ≤ 30 °C (Joseph & "
            "Hunt §5), so neither a borrowed C nor the piezoviscous film (5.6) applies. "
            f"Decided: μ_f is only bounded, μ_f ≤ {bound}, and that bound is used for Maw's "
            "regime only where it already settles it."
            + (f" {why.capitalize()}, so {touching} is used." if asperities else ""),
            raised=True,
        )
    if state == "above_limit":
        return Verdict(
            "lubricated_friction_state",
            name,
            f"outside the model's range, not used: (5.8) evaluates to {in_words(mu)}, above "
            f"{bound}; a film cannot carry more shear than its limiting shear stress, so "
            "this is not a prediction. "
            + (
                f"{why.capitalize()}, so {touching} is used for Maw's regime."
                if asperities
                else f"Maw's regime uses the cap μ_f = {cap:g} (a film at its limiting shear)."
            ),
            raised=True,
        )
    if state == "in_range":
        use = f"not used: {why}, so {touching} is used." if asperities else "used for Maw's regime."
        return Verdict(
            "lubricated_friction_state",
            name,
            f"μ_f = {in_words(mu)}, within the model's range (≤ {bound}); {use}",
        )
    return Verdict("lubricated_friction_state", name, "not computed.", raised=True)


_REGIME_WORDS = {
    "stick": "stick — the contact point sticks, micro-slip only at the rim (ψ_in ≤ 1)",
    "slip_then_stick": "slip, then stick (1 < ψ_in < 4χ − 1)",
    "gross_slip": "gross slip throughout the contact (ψ_in ≥ 4χ − 1)",
}


def _friction_basis(derived: Mapping[str, Any]) -> str:
    regime, state = derived.get("roughness_regime"), derived.get("lubricated_friction_state")
    if regime == "asperity_contact" and state != "dry":
        return "the pair's with asperities touching in a liquid"
    if regime == "not_stated" and state != "dry":
        return "the pair's with asperities touching (roughness not stated: no film assumed)"
    if regime in ("dry", "asperity_contact") or state == "dry":
        return "the dry value"
    if state == "in_range":
        return "the film's (5.8)" + (", roughness uncertain" if regime == "uncertain" else "")
    if state == "above_limit":
        return "the cap: (5.8) is outside its range"
    return "an upper bound only"


def tangential_verdict(derived: Mapping[str, Any]) -> Verdict:
    """Maw's regime, with "undetermined" explained (μ_f only bounded)."""
    regime = str(derived.get("tangential_regime"))
    psi, chi, mu = (derived.get(k) for k in ("maw_psi_in", "maw_chi", "friction_coefficient_used"))
    name = "Tangential regime (Maw)"
    if not is_number(psi) or psi == 0:
        return Verdict("tangential_regime", name, "stick. No tangential motion (normal impact).")
    numbers = (
        f"ψ_in = {in_words(psi)}, χ = {in_words(chi)}, with μ_f = {in_words(mu)} "
        f"({_friction_basis(derived)})"
    )
    if regime == "undetermined":
        at_bound = "stick (ψ_in ≤ 1)" if psi <= 1 else "slip, then stick (1 < ψ_in < 4χ − 1)"
        return Verdict(
            "tangential_regime",
            name,
            "undetermined: without a pressure–viscosity coefficient μ_f is known only to be "
            f"≤ {in_words(mu)}. At that bound ψ_in = {in_words(psi)} and χ = {in_words(chi)} give "
            f"{at_bound}; a smaller μ_f gives a larger ψ_in and more slip, so the regime lies "
            "between that and gross slip.",
            raised=True,
        )
    words = _REGIME_WORDS.get(regime, regime)
    return Verdict("tangential_regime", name, f"{words}. {numbers}.")


def quasi_static_verdict(derived: Mapping[str, Any]) -> Verdict:
    ratio = derived.get("quasi_static_ratio")
    name = "Hertz quasi-static"
    words = f"contact radius / wavelength = {in_words(ratio)}"
    if derived.get("quasi_static_valid"):
        return Verdict("quasi_static_valid", name, f"valid: {words} ≪ 1.")
    if derived.get("elastic_state") == "yield_exceeded" and is_number(ratio) and ratio < 0.1:
        return Verdict(
            "quasi_static_valid",
            name,
            f"not valid: yield is exceeded (see Yield), although {words} ≪ 1.",
            raised=True,
        )
    return Verdict(
        "quasi_static_valid",
        name,
        f"questionable: {words}; elastic waves carry energy away.",
        raised=True,
    )


def strain_verdict(derived: Mapping[str, Any]) -> Verdict:
    """Hertz's small strain: a/R* and δ/R* against a/R* ≤ 0.1 (docs/physics.md §16)."""
    a_ratio, d_ratio = derived.get("contact_radius_ratio"), derived.get("approach_ratio")
    name = "Hertz small strain"
    words = (
        f"a/R* = {in_words(a_ratio)}, δ/R* = {in_words(d_ratio)} (threshold a/R* ≤ "
        f"{limits.HERTZ_STRAIN_LIMIT:g}: Hertz assumes a ≪ R, Johnson 1985 §4.2)"
    )
    if not is_number(a_ratio):
        return Verdict("hertz_strain_valid", name, f"not computed: {words}.", raised=True)
    if derived.get("hertz_strain_valid"):
        return Verdict("hertz_strain_valid", name, f"valid: {words}.")
    return Verdict(
        "hertz_strain_valid",
        "Hertz not valid",
        f"Hertz not valid: {words}. The contact is too large for small-strain theory; "
        "the Hertz load, contact time, pressure and everything built on them are outside "
        "their range.",
        raised=True,
    )


def _yield_known(materials: Sequence[Mapping[str, Any]]) -> tuple[list[str], list[str]]:
    known = [
        f"{m['name']} (Y = {display(m['yield_stress_pa'], 'youngs_modulus_pa')})"
        for m in materials
        if is_number(m.get("yield_stress_pa"))
    ]
    unknown = [str(m["name"]) for m in materials if not is_number(m.get("yield_stress_pa"))]
    return known, unknown


def yield_verdict(
    derived: Mapping[str, Any],
    materials: Sequence[Mapping[str, Any]] = (),
    dry: Mapping[str, Any] = BORROWED_DRY,
) -> Verdict:
    """Onset of yield, p_max = 1.6 Y of the softer body (docs/physics.md §11)."""
    state = str(derived.get("elastic_state") or "unknown")
    p_max, v_y, v_n = (
        derived.get(k) for k in ("max_pressure_pa", "yield_speed_m_s", "normal_speed_m_s")
    )
    known, unknown = _yield_known(materials)
    name = "Yield"
    pressure = f"p_max = {in_words(p_max, 'Pa')}"
    if state == "yield_exceeded":
        return Verdict(
            "elastic_state",
            "Above the onset of yield",
            f"above the onset of yield (V_y = {in_words(v_y, 'm/s')}; v_N,in = "
            f"{in_words(v_n, 'm/s')}): {pressure} > 1.6 Y of "
            f"{', '.join(known) or 'the softer body'} (Johnson 1985 §11.4). Hertz's elastic "
            "relations (2.1), (2.2), (5.5) and the lubricated friction built on them are "
            "outside their range here; the predicted restitution uses "
            f"{restitution_applies(derived, dry)}.",
            raised=True,
        )
    if state == "elastic":
        return Verdict(
            "elastic_state",
            name,
            f"elastic: {pressure} < 1.6 Y of the softer body ({', '.join(known) or 'both'}); yield "
            f"would begin at V_y = {in_words(v_y, 'm/s')} (Johnson 1985 §11.4).",
        )
    who = " and ".join(unknown) if unknown else "a body of the pair"
    partial = (
        f" Known: {', '.join(known)}, not reached (V_y = {in_words(v_y, 'm/s')} for it)."
        if known
        else ""
    )
    brittle = [str(m["name"]) for m in materials if m.get("brittleness") == "brittle"]
    note = ""
    if brittle:
        verb = "is" if len(brittle) == 1 else "are"
        note = " " + BRITTLE_NOTE.format(names=" and ".join(brittle), verb=verb)
    return Verdict(
        "elastic_state",
        name,
        f"unknown: yield stress not known for {who}, so the onset of yield is not checked "
        f"({pressure}).{partial}{note}",
    )
