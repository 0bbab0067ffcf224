"""MercuryDPM C++ snippet (export only: no Debian package, not verified by a run).

Uses the documented species API: ``LinearViscoelasticSlidingFrictionSpecies`` (or
``LinearViscoelasticFrictionSpecies`` when a rolling coefficient is known),
``setDensity``, ``setCollisionTimeAndRestitutionCoefficient(tc, e, mass)`` whose ``mass``
is 2/(1/m₁+1/m₂) = 2m* (MercuryDPM source doc), ``setSlidingStiffness(2/7 k)``,
``setSlidingDissipation(2/7 γ)``, ``setSlidingFrictionCoefficient``,
``setRollingFrictionCoefficient`` and ``speciesHandler.getMixedObject(s1, s2)`` for pairs.
A linear spring–dashpot reproduces e exactly at any speed; its stiffness is set from the
Hertz contact time t_c ≈ 2.87(m*²/(R*E*²V))^{1/5} at the characteristic speed (Johnson
§11.4, docs/physics.md §13), so collisions last as long as Hertz's at that speed.
"""

from __future__ import annotations

from granudb.dem import deck
from granudb.dem.spec import DemModel

CODE = "MercuryDPM"
VERSION = "species API of MercuryDPM 0.x/1.0 (export only, not run)"
API_NAMES = (
    "speciesHandler.copyAndAddObject",
    "speciesHandler.getMixedObject",
    "setDensity",
    "setCollisionTimeAndRestitutionCoefficient",
    "setSlidingStiffness",
    "setSlidingDissipation",
    "setSlidingFrictionCoefficient",
    "setRollingFrictionCoefficient",
)


def write(model: DemModel, *, clamp: bool = False) -> str:
    """C++ statements for ``setupInitialConditions()`` of a DPMBase subclass."""
    deck.check_poisson(CODE, model, -1.0, clamp)
    rolling = any(p.rolling_friction is not None for p in model.pairs)
    species = (
        "LinearViscoelasticFrictionSpecies"
        if rolling
        else ("LinearViscoelasticSlidingFrictionSpecies")
    )
    out = deck.header(
        CODE,
        VERSION,
        model,
    )
    out = [line.replace("# ", "// ", 1) for line in out]
    out.append(f"// species class: {species}; walls get a species too (density unused).")
    out += deck.comment(
        deck.time_step_sentence(model) + " MercuryDPM is not run by dem verify (no package): "
        "set setTimeStep() at or below this bound.",
        "// ",
    )
    for t in model.types:
        out.append(f"auto* {t.name} = speciesHandler.copyAndAddObject({species}());")
        out.append(
            f"{t.name}->setDensity({deck.num(t.density_kg_m3)});  // {t.name} material value"
        )
    for a, b, pair in deck.ordered_pairs(model):
        scales = model.contact(pair)
        e = deck.check(
            CODE,
            f"restitution {deck.pair_label(pair)}",
            pair.restitution.value,
            0.0 < pair.restitution.value <= 1.0,
            "requires 0 < e <= 1",
            1.0,
            clamp,
        )
        var = f"{a.name}_{b.name}"
        target = (
            f"{a.name}"
            if a.name == b.name
            else (f"speciesHandler.getMixedObject({a.name}, {b.name})")
        )
        notes = [
            f"{deck.pair_label(pair)}: e = {deck.describe(pair.restitution)}",
            f"mu_f = {deck.describe(pair.friction)}",
            f"t_c = {deck.num(scales.contact_time_s)} s: Hertz contact time at "
            f"{deck.num(model.characteristic_velocity_m_s)} m/s "
            f"(E* = {deck.num(scales.reduced_modulus_pa)} Pa, "
            f"R* = {deck.num(scales.radius_m)} m, m* = {deck.num(scales.mass_kg)} kg); "
            "mass argument 2m*",
        ]
        if e.note:
            notes.append(e.note)
        if (note := deck.wet_note(pair, model.characteristic_velocity_m_s)) is not None:
            notes.append(note)
        out += [line for n in notes for line in deck.comment(n, "// ")]
        out.append(f"auto* {var} = {target};")
        out.append(
            f"{var}->setCollisionTimeAndRestitutionCoefficient({deck.num(scales.contact_time_s)}, "
            f"{deck.num(e.value)}, {deck.num(2.0 * scales.mass_kg)});"
        )
        out.append(f"{var}->setSlidingStiffness(2.0 / 7.0 * {var}->getStiffness());")
        out.append(f"{var}->setSlidingDissipation(2.0 / 7.0 * {var}->getDissipation());")
        out.append(f"{var}->setSlidingFrictionCoefficient({deck.num(pair.friction.value)});")
        if rolling:
            mu_r = pair.rolling_friction.value if pair.rolling_friction else 0.0
            source = (
                deck.describe(pair.rolling_friction) if pair.rolling_friction else "not known: 0"
            )
            out.append(f"{var}->setRollingFrictionCoefficient({deck.num(mu_r)});  // {source}")
    return "\n".join(out) + "\n"
