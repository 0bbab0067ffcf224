"""LIGGGHTS 3.8.0 input fragment: ``fix property/global`` material and pair matrices.

Walls are atom types too in LIGGGHTS (``fix wall/gran ... type N``), so every matrix is
N×N over all types. Limits are those of the installed 3.8.0 (strings of libliggghts and
src/global_properties.cpp): 0.05 < coefficientRestitution ≤ 1, 0 ≤ poissonsRatio ≤ 0.5,
youngsModulus ≥ 5e6 Pa in SI unless ``soft_particles yes`` and ≤ 1e9 Pa unless
``hard_particles yes`` (both commands are written when needed, with the reason).

Damping: ``model hertz`` turns e into γ_n = 2√(5/6)β√(S_n m*), which gives back e exactly
on an unclamped Hertz contact (granudb.dem.damping). The export sets ``limitForce on``
(no attractive normal force: LIGGGHTS caps the tangential force at μ_f |F_n|, and an
attractive F_n at the end of a strongly damped wet contact added friction, +67 % on glass
in 78 % glycerol) and ``tangential_damping off`` (LIGGGHTS adds the tangential dashpot
outside the Coulomb cap while the contact sticks, which with a wet pair's damping pushed
the tangential force past μ_f F_n). With the clamp the coefficient written is the e whose
unclamped damping is the clamped law's (``damping.liggghts_hertz_input``), not the target.

Friction: with a wet pair's damping the normal force jumps at first touch while
``tangential history`` (a total spring, F_t = −8 G* a u) builds up, so the contact sticks
for a moment and slides with less than μ_f (−3.0 % at 60° for glass in 78 % glycerol).
Where that loss exceeds 0.1 % the coefficientFriction written is the input that gives μ_f
at 60° (``deck.friction_input``; measured +0.11 %), and the comment states 45° and 80°.

Wet pairs: LIGGGHTS has ``model hooke ... viscous on`` (FluidViscosity, CriticalStokes,
MaximumRestitution). In 3.8.0 (src/normal_model_hooke.h) it computes St from the
*instantaneous* normal velocity and uses ln e_max + St_c/St (sign reversed) as ln e, so
the damping becomes critical as the sphere stops: a glass sphere at 0.3 m/s in 48 mPa s
rebounds with e ≈ 0 instead of e_max exp(−St_c/St) = 0.20 (tried in the packaged
binary). granudb therefore writes e at the stated Stokes number and the e(St) law as a
comment, never the viscous model.
"""

from __future__ import annotations

from granudb.dem import damping, deck
from granudb.dem.spec import DemModel, PairParameters, ParticleType

CODE = "LIGGGHTS"
VERSION = "3.8.0, Debian package liggghts"

#: Why Ψ_out at 30° may miss Walton's relation with a measured β (``dem verify``).
REBOUND_LIMIT = deck.rebound_limit(CODE, "8 G* a from the materials' E and nu")
RESTITUTION_FLOOR = 0.05
SOFT_LIMIT_PA = 5e6
HARD_LIMIT_PA = 1e9
WALL_PLACEHOLDER = "placeholder: walls never touch each other"


def pair_style(model: DemModel) -> str:
    """The model string to use in ``pair_style gran`` and ``fix wall/gran``."""
    rolling = any(p.rolling_friction is not None for p in model.pairs)
    return "model hertz tangential history" + (" rolling_friction cdt" if rolling else "")


#: The contact settings every export needs (see the module docstring): after the models in
#: ``pair_style gran``, after the wall's geometry in ``fix wall/gran``.
SETTINGS = "tangential_damping off limitForce on"

#: The communication setting granular pairs need (ghost atoms' velocities), written by the
#: fragment itself.
COMM = "communicate single vel yes"

#: ``tangential history``: a total spring F_t = −8 G* a u, u cut back at the Coulomb cap
#: μ_f |F_n| (src/tangential_model_history.h); corrected where the loss exceeds 0.1 %.
FRICTION_LAW = deck.FrictionLaw("tangential history", incremental=False, correct_above=1e-3)


def friction_input(
    model: DemModel, pair: PairParameters, restitution_in: float, clamp: bool
) -> deck.Limited:
    """The coefficientFriction to write (``deck.friction_input``): LIGGGHTS's damping C is
    ``damping.hertz_damping`` of the coefficientRestitution written, k_t/k_n is Mindlin's
    8 G*/((4/3) E*)."""
    scales = model.contact(pair)
    mu_in, note = deck.friction_input(
        CODE,
        FRICTION_LAW,
        model,
        pair,
        damping.hertz_damping(restitution_in),
        scales.mindlin_stiffness / scales.hertz_stiffness,
        clamp,
    )
    return deck.Limited(mu_in, note)


def restitution_input(pair: PairParameters, clamp: bool) -> deck.Limited:
    """The coefficientRestitution to write (``damping.liggghts_hertz_input`` of the target),
    within LIGGGHTS's sanity check (an input above 0.05, which with ``limitForce on`` is a
    target above ``damping.liggghts_floor()``)."""
    e = pair.restitution.value
    floor = damping.liggghts_floor(RESTITUTION_FLOOR)
    limited = deck.check(
        CODE,
        f"restitution {deck.pair_label(pair)}",
        e,
        e > floor,
        f"refuses e <= {RESTITUTION_FLOOR:g} (its sanity check: 0.05 < coefficientRestitution "
        f"<= 1), which with limitForce on is e <= {floor:.4f}",
        damping.liggghts_floor(RESTITUTION_FLOOR + 1e-4),
        clamp,
    )
    return deck.Limited(damping.liggghts_hertz_input(limited.value), limited.note)


def write(model: DemModel, *, clamp: bool = False) -> str:
    """The fragment to include after ``create_box`` and before ``pair_style gran``."""
    poisson = deck.check_poisson(CODE, model, 0.0, clamp)
    restitution = {
        frozenset((a.name, b.name)): restitution_input(p, clamp)
        for a, b, p in deck.ordered_pairs(model)
    }
    out = deck.header(CODE, VERSION, model)
    out += deck.comment(host_settings(model))
    out += deck.rebound_lines(model, REBOUND_LIMIT)
    moduli = [t.youngs_modulus_pa for t in model.types]
    if max(moduli) > HARD_LIMIT_PA:
        out += deck.comment(f"some E > {HARD_LIMIT_PA:g} Pa: LIGGGHTS's SI sanity check needs this")
        out.append("hard_particles yes")
    if min(moduli) < SOFT_LIMIT_PA:
        out += deck.comment(f"some E < {SOFT_LIMIT_PA:g} Pa: LIGGGHTS's SI sanity check needs this")
        out.append("soft_particles yes")
    out += _per_type(
        model, "youngsModulus", {t.name: deck.Limited(t.youngs_modulus_pa) for t in model.types}
    )
    out += _per_type(model, "poissonsRatio", poisson)
    out += _matrix(model, "coefficientRestitution", restitution, "restitution")
    friction = {
        p.key: friction_input(model, p, restitution[p.key].value, clamp) for p in model.pairs
    }
    out += _matrix(model, "coefficientFriction", friction, "friction")
    if any(p.rolling_friction is not None for p in model.pairs):
        rolling = {
            p.key: deck.Limited(p.rolling_friction.value if p.rolling_friction else 0.0)
            for p in model.pairs
        }
        out += _matrix(model, "coefficientRollingFriction", rolling, "rolling_friction")
    out += [""] + deck.comment(
        f"The contact model these values are for: {SETTINGS} (module docstring of "
        "granudb.dem.liggghts); do not redefine pair_style after this file."
    )
    out += [COMM, f"pair_style gran {pair_style(model)} {SETTINGS}", "pair_coeff * *"]
    for wall in model.walls:
        out += deck.comment(
            f"wall {wall.name} (type {model.index(wall.name)}): set its geometry before "
            f'including this file, e.g. variable {wall_variable(wall)} string "zplane 0.0"'
        )
        out.append(
            f"fix granudb_wall_{wall.name} all wall/gran {pair_style(model)} primitive type "
            f"{model.index(wall.name)} ${{{wall_variable(wall)}}} {SETTINGS}"
        )
    return "\n".join(out) + "\n"


def wall_variable(wall: ParticleType) -> str:
    """Name of the string variable holding a wall's geometry (e.g. ``zplane 0.0``)."""
    return f"granudb_wall_{wall.name}"


def host_settings(model: DemModel) -> str:
    """What the host input needs around this fragment (``dem verify`` runs with exactly
    this): the fragment writes the pair style and the wall fixes itself, with
    ``limitForce on`` and ``tangential_damping off``, which the values depend on."""
    walls = ", ".join(f"{wall_variable(w)}" for w in model.walls)
    return (
        "Include after create_box (units si, atom_style granular) and before the run. This "
        f"fragment writes {COMM}, the pair style, pair_coeff * * and "
        f"the wall fixes itself with the settings the values depend on ({SETTINGS}): without "
        "limitForce on the coefficientRestitution written gives a lower e, without "
        "tangential_damping off a higher friction. Do not write another pair_style or "
        "wall/gran for these types. "
        + (
            f"Set the string variable{'s' if len(model.walls) > 1 else ''} {walls} (a "
            "wall/gran geometry, e.g. zplane 0.0) before including it: LIGGGHTS stops on an "
            "unset variable. "
            if model.walls
            else ""
        )
        + deck.time_step_sentence(model)
    )


def _per_type(model: DemModel, prop: str, values: dict[str, deck.Limited]) -> list[str]:
    lines = [""]
    for t in model.types:
        v = values[t.name]
        source = "material property of the type" if prop == "youngsModulus" else "material"
        lines += deck.comment(f"{t.name}: {prop} = {deck.num(v.value)} ({source})")
        if v.note:
            lines += deck.comment(v.note)
    row = " ".join(deck.num(values[t.name].value) for t in model.types)
    lines.append(f"fix granudb_{prop} all property/global {prop} peratomtype {row}")
    return lines


def _matrix(
    model: DemModel, prop: str, values: dict[frozenset[str], deck.Limited], attribute: str
) -> list[str]:
    """A full N×N ``peratomtypepair`` matrix (symmetric), each entry commented above it."""
    n = len(model.types)
    lines = [""]
    for a, b, pair in deck.ordered_pairs(model):
        value: deck.Value | None = getattr(pair, attribute)
        limited = values[pair.key]
        shown = (
            deck.describe(value) if value is not None else "not known: 0 (no rolling resistance)"
        )
        lines += deck.comment(
            f"{model.index(a.name)}-{model.index(b.name)} {a.name}/{b.name}: {prop} = {shown}"
        )
        if limited.note:
            lines += deck.comment(limited.note)
        if attribute == "restitution":
            lines += deck.comment(
                f"written {deck.num(limited.value)}: with limitForce on, LIGGGHTS's hertz "
                f"damping of this input gives e = {deck.num(pair.restitution.value)} "
                "(granudb.dem.damping)"
            )
        if attribute == "restitution" and (
            note := deck.wet_note(pair, model.characteristic_velocity_m_s)
        ):
            lines += deck.comment(
                note + "; LIGGGHTS 3.8.0's 'viscous on' is not used (see the granudb.dem.liggghts "
                "docstring: it does not reproduce e(St))"
            )
    rows = []
    for a in model.types:
        row = []
        for b in model.types:
            between = model.pair(a.name, b.name)
            if between is None:
                row.append(deck.num(0.5 if attribute == "restitution" else 0.0))
            else:
                row.append(deck.num(values[between.key].value))
        rows.append(" ".join(row))
    if any(model.pair(a.name, b.name) is None for a in model.types for b in model.types):
        lines += deck.comment(f"wall/wall entries: {WALL_PLACEHOLDER}")
    lines.append(f"fix granudb_{prop} all property/global {prop} peratomtypepair {n} &")
    lines += [f"    {r} &" for r in rows[:-1]] + [f"    {rows[-1]}"]
    return lines
