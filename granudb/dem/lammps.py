"""LAMMPS input fragment: ``pair_style granular`` with every pair written explicitly.

Checked against the Debian package lammps 20220106 (``LAMMPS (29 Sep 2021 - Update 2)``,
src/GRANULAR/pair_granular.cpp and fix_wall_gran.cpp of that release):

- ``hertz/material E η ν`` takes ONE E and ν and forms E_eff = E/(2(1−ν²)) as if both
  bodies were that material, and ``fix wall/gran`` converts E differently again (LAMMPS
  issue #4141). granudb therefore writes ``hertz k_n`` with k_n = (4/3)E* of the pair
  and ``tangential mindlin k_t`` with k_t = 8G* (docs/physics.md §13): force k_n √R* δ^{3/2},
  tangential stiffness k_t a, identical for pairs and walls, no conversion in the code.
- ``damping tsuji`` reads the η slot as e but maps it with a fitted polynomial that does
  not reproduce e on a Hertz contact; the e written is corrected (granudb.dem.damping), so
  it differs from the target and the comment gives both.
- ``limit_damping`` clamps the normal force at zero: LAMMPS caps the tangential force at
  μ_f |F_n|, and the attractive F_n at the end of a strongly damped (wet) contact otherwise
  adds friction the measured μ_f never had. The tangential damping ratio x_γ,t is 0: with
  a wet pair's normal damping, the tangential dashpot (x_γ,t times it) decided Ψ_out
  instead of μ_f (−29 % on glass in 78 % glycerol at 60°).
- μ_f: with a wet pair's damping the normal force jumps at first touch while the
  ``mindlin`` spring (total: F_t = −k_t a u) builds up, so the contact sticks for a moment
  and slides with less than μ_f (−3.0 % at 60° for glass in 78 % glycerol). Where that
  loss exceeds 0.1 % the μ_f written is the input that gives μ_f at 60° with this k_t
  (``deck.friction_input``; measured +0.12 %), and the comment states 45° and 80°.
- Unset pairs are mixed (geometric means, E* formula): every particle pair is written.
- Walls are not atom types: each (particle type, wall) pair is a ``fix wall/gran granular``
  on a group of that type, with the wall's geometry from a string variable the user sets.
"""

from __future__ import annotations

import math

from granudb.dem import damping, deck
from granudb.dem.spec import DemModel, PairParameters, ParticleType
from granudb.physics.contact import max_approach

CODE = "LAMMPS"
VERSION = "29 Sep 2021 - Update 2, Debian package lammps 20220106"


#: The check of the stated time step: LAMMPS halts naming this fix when dt is above it.
TIME_STEP_VARIABLE = "granudb_time_step_ok"
TIME_STEP_FIX = "granudb_time_step_above_the_decks_bound"

#: The communication setting granular pairs need, written by the fragment itself.
COMM = "comm_modify vel yes"


def type_number(model: DemModel, name: str) -> int:
    """LAMMPS atom type of a particle type: particles only, in model order (walls excluded)."""
    return [t.name for t in model.particles].index(name) + 1


def group_name(t: ParticleType) -> str:
    return f"granudb_{t.name}"


def wall_variable(wall: ParticleType) -> str:
    """Name of the string variable holding a wall's geometry (e.g. ``zplane 0.0 NULL``)."""
    return f"granudb_wall_{wall.name}"


def tsuji_input(pair: PairParameters, clamp: bool) -> deck.Limited:
    """The e for ``damping tsuji`` that makes LAMMPS give the target e (or a refusal)."""
    e = pair.restitution.value
    low, high = damping.lammps_tsuji_range()
    limited = deck.check(
        CODE,
        f"restitution {deck.pair_label(pair)}",
        e,
        low <= e <= high,
        f"damping tsuji reaches only {low:.4f} <= e <= {high:.5f} on a Hertz contact "
        f"(its alpha(e) polynomial spans {damping.TSUJI_ALPHA_MIN:.4g}.."
        f"{damping.TSUJI_ALPHA_MAX:.4g})",
        min(max(e, low), high),
        clamp,
    )
    return deck.Limited(
        damping.lammps_tsuji_input(limited.value, deck.pair_label(pair)), limited.note
    )


def tangential_stiffness(model: DemModel, pair: PairParameters) -> tuple[float, str]:
    """k_t for ``tangential mindlin`` and the sentence saying why: Mindlin's 8 G*, or where
    the pair has a measured β the k_t whose never-sliding contact rebounds with it
    (``damping.stiffness_ratio_for_rebound`` on this pair's clamped damping), so that
    Ψ_out follows Walton's relation with β and μ_f."""
    scales = model.contact(pair)
    mindlin = scales.mindlin_stiffness
    beta = pair.rotational_restitution
    if beta is None:
        return mindlin, (
            f"k_t = 8 G* = {deck.num(mindlin)} Pa (Mindlin; no measured beta for this pair, "
            "granudb docs/physics.md section 13)"
        )
    c = damping.clamped_hertz_damping(round(pair.restitution.value, 12))
    ratio = damping.stiffness_ratio_for_rebound(
        round(beta.value, 12), round(c, 12), mindlin / scales.hertz_stiffness
    )
    k_t = ratio * scales.hertz_stiffness
    return k_t, (
        f"k_t = {ratio:.4f} k_n = {deck.num(k_t)} Pa ({k_t / mindlin:.3f} of Mindlin's 8 G*): a "
        f"contact that never slides rebounds with beta = {deck.describe(beta)} "
        "(granudb.dem.damping)"
    )


#: ``tangential mindlin``: a total spring F_t = −k_t a u, u cut back at the Coulomb cap
#: μ_f |F_n| (pair_granular.cpp); corrected where the loss exceeds 0.1 %.
FRICTION_LAW = deck.FrictionLaw("tangential mindlin", incremental=False, correct_above=1e-3)


def _inputs(
    model: DemModel, pair: PairParameters, clamp: bool
) -> tuple[deck.Limited, float, str, float, str | None]:
    """(tsuji input, k_t and its note, μ_f input and its note) of one pair: the μ_f written
    is ``deck.friction_input`` with LAMMPS's damping α(e_in) and this k_t."""
    scales = model.contact(pair)
    e_in = tsuji_input(pair, clamp)
    k_t, k_t_note = tangential_stiffness(model, pair)
    mu_in, mu_note = deck.friction_input(
        CODE,
        FRICTION_LAW,
        model,
        pair,
        damping.tsuji_alpha(e_in.value),
        k_t / scales.hertz_stiffness,
        clamp,
    )
    return e_in, k_t, k_t_note, mu_in, mu_note


def rebound_range(
    model: DemModel, pair: PairParameters, clamp: bool = False
) -> deck.ReboundRange | None:
    """The impact angles over which this deck's Ψ_out follows Walton's relation with the
    pair's β (``deck.rebound_range`` on the written inputs); None without β."""
    e_in, k_t, _, mu_in, _ = _inputs(model, pair, clamp)
    ratio = k_t / model.contact(pair).hertz_stiffness
    return deck.rebound_range(pair, damping.tsuji_alpha(e_in.value), ratio, mu_in, False)


def stated_rebound(
    model: DemModel, pair: PairParameters, angle_deg: float, clamp: bool = False
) -> float:
    """Ψ_out this deck's contact gives at ``angle_deg`` (``deck.contact_rebound`` on the
    written inputs), where its ``rebound_range`` says Walton's relation does not hold."""
    e_in, k_t, _, mu_in, _ = _inputs(model, pair, clamp)
    ratio = k_t / model.contact(pair).hertz_stiffness
    c = damping.tsuji_alpha(e_in.value)
    return deck.contact_rebound(pair, c, ratio, mu_in, False, angle_deg)


def coefficients(model: DemModel, pair: PairParameters, clamp: bool) -> tuple[str, list[str]]:
    """The granular model arguments of one pair and the comment lines explaining them."""
    scales = model.contact(pair)
    e_in, k_t, k_t_note, mu_in, mu_note = _inputs(model, pair, clamp)
    args = (
        f"hertz {deck.num(scales.hertz_stiffness)} {deck.num(e_in.value)} "
        f"tangential mindlin {deck.num(k_t)} 0.0 "
        f"{deck.num(mu_in)} "
        "damping tsuji limit_damping"
    )
    notes = [
        f"{deck.pair_label(pair)}: e = {deck.describe(pair.restitution)}",
        f"  mu_f = {deck.describe(pair.friction)}",
        *([f"  {mu_note}"] if mu_note else []),
        f"  k_n = 4/3 E* = {deck.num(scales.hertz_stiffness)} Pa (E* = "
        f"{deck.num(scales.reduced_modulus_pa)} Pa, granudb docs/physics.md section 13)",
        f"  {k_t_note}",
        *(
            [f"  {found.sentence(pair)}"]
            if (found := rebound_range(model, pair, clamp)) is not None
            else []
        ),
        f"  tsuji input {deck.num(e_in.value)} so that LAMMPS's alpha(e) gives e = "
        f"{deck.num(pair.restitution.value)} on this Hertz contact with limit_damping "
        "(granudb.dem.damping); no tangential damping (x_gamma,t = 0)",
    ]
    if e_in.note:
        notes.append("  " + e_in.note)
    if (note := deck.wet_note(pair, model.characteristic_velocity_m_s)) is not None:
        notes.append("  " + note)
    if pair.rolling_friction is not None:
        a, b = model.type(pair.type_i), model.type(pair.type_j)
        delta = float(
            max_approach(
                scales.mass_kg,
                model.characteristic_velocity_m_s,
                scales.reduced_modulus_pa,
                scales.radius_m,
            )
        )
        k_roll = scales.mindlin_stiffness * math.sqrt(scales.radius_m * delta)
        args += f" rolling sds {deck.num(k_roll)} 0.0 {deck.num(pair.rolling_friction.value)}"
        notes.append(
            f"  rolling mu_r = {deck.describe(pair.rolling_friction)}; k_roll = 8 G* a_max at the "
            f"characteristic speed ({a.name}/{b.name}), no rolling damping"
        )
    return args, notes


def write(model: DemModel, *, clamp: bool = False) -> str:
    """The fragment to include once the atoms exist (after ``create_atoms`` or
    ``read_data``; atom_style sphere, units si): its wall fixes act on groups made by atom
    type, and a LAMMPS group holds the atoms that exist when it is made."""
    deck.check_poisson(CODE, model, -1.0, clamp)
    out = deck.header(CODE, VERSION, model)
    out += deck.comment(
        "LAMMPS atom types are the particle types only: "
        + ", ".join(f"{type_number(model, t.name)} = {t.name}" for t in model.particles)
        + ". Needs atom_style sphere (the fragment sets comm_modify vel yes). Include this file "
        "after the "
        "atoms exist (after create_atoms or read_data), never straight after create_box: "
        "its groups are made by type, and a LAMMPS group holds only the atoms that exist "
        "when it is made, so the wall fixes would act on nothing. The fragment writes "
        "pair_style granular and every pair_coeff and wall/gran fix itself, with the options "
        "the values depend on (hertz k_n, tangential mindlin k_t, damping tsuji, "
        "limit_damping): do not redefine pair_style or pair_coeff after it. "
        + deck.time_step_sentence(model)
    )
    out += ["", *deck.comment("granular pairs need the ghost atoms' velocities:"), COMM]
    out += ["", "pair_style granular"]
    particles = model.particles
    for i, a in enumerate(particles):
        for b in particles[i:]:
            pair = model.pair(a.name, b.name)
            assert pair is not None  # DemModel guarantees every particle pair
            args, notes = coefficients(model, pair, clamp)
            out += [""] + [line for n in notes for line in deck.comment(n)]
            out.append(
                f"pair_coeff {type_number(model, a.name)} {type_number(model, b.name)} {args}"
            )
    for t in particles:
        out.append(f"group {group_name(t)} type {type_number(model, t.name)}")
    for wall in model.walls:
        out += [""] + deck.comment(
            f"wall {wall.name}: set its geometry before including this file, e.g. "
            f'variable {wall_variable(wall)} string "zplane 0.0 NULL"'
        )
        for t in particles:
            pair = model.pair(t.name, wall.name)
            assert pair is not None
            args, notes = coefficients(model, pair, clamp)
            out += [line for n in notes for line in deck.comment(n)]
            out.append(
                f"fix granudb_{wall.name}_{t.name} {group_name(t)} wall/gran granular {args} "
                f"${{{wall_variable(wall)}}}"
            )
    dt, _, _ = deck.time_step_bound(model)
    out += [""] + deck.comment(
        f"The time step bound stated above: LAMMPS stops (fix halt) when dt > {deck.num(dt)} s."
    )
    out += [
        f'variable {TIME_STEP_VARIABLE} equal "dt <= {deck.num(dt)}"',
        f"fix {TIME_STEP_FIX} all halt 10 v_{TIME_STEP_VARIABLE} == 0 error hard message yes",
    ]
    return "\n".join(out) + "\n"
