"""LIGGGHTS 3.8.0 input fragment: ``fix property/global`` material and pair matrices.

Walls are atom types too in LIGGGHTS (``fix wall/gran ... type N``), so every matrix is
N×N over all types. Limits are those of the installed 3.8.0 (strings of libliggghts and
src/global_properties.cpp): 0.05 < coefficientRestitution ≤ 1, 0 ≤ poissonsRatio ≤ 0.5,
youngsModulus ≥ 5e6 Pa in SI unless ``soft_particles yes`` and ≤ 1e9 Pa unless
``hard_particles yes`` (both commands are written when needed, with the reason).

Damping: ``model hertz`` turns e into γ_n = 2√(5/6)β√(S_n m*), which gives back e exactly
on a Hertz contact (granudb.dem.damping), so the coefficient written is the target e.

Wet pairs: LIGGGHTS has ``model hooke ... viscous on`` (FluidViscosity, CriticalStokes,
MaximumRestitution). In 3.8.0 (src/normal_model_hooke.h) it computes St from the
*instantaneous* normal velocity and uses ln e_max + St_c/St (sign reversed) as ln e, so
the damping becomes critical as the sphere stops: a glass sphere at 0.3 m/s in 48 mPa s
rebounds with e ≈ 0 instead of e_max exp(−St_c/St) = 0.20 (tried in the packaged
binary). granudb therefore writes e at the stated Stokes number and the e(St) law as a
comment, never the viscous model.
"""

from __future__ import annotations

from granudb.dem import deck
from granudb.dem.spec import DemModel, PairParameters

CODE = "LIGGGHTS"
VERSION = "3.8.0, Debian package liggghts"
RESTITUTION_FLOOR = 0.05
SOFT_LIMIT_PA = 5e6
HARD_LIMIT_PA = 1e9
WALL_PLACEHOLDER = "placeholder: walls never touch each other"


def pair_style(model: DemModel) -> str:
    """The model string to use in ``pair_style gran`` and ``fix wall/gran``."""
    rolling = any(p.rolling_friction is not None for p in model.pairs)
    return "model hertz tangential history" + (" rolling_friction cdt" if rolling else "")


def restitution_input(pair: PairParameters, clamp: bool) -> deck.Limited:
    """The coefficientRestitution to write: the target, within LIGGGHTS's sanity check."""
    e = pair.restitution.value
    return deck.check(
        CODE,
        f"restitution {deck.pair_label(pair)}",
        e,
        e > RESTITUTION_FLOOR,
        f"refuses e <= {RESTITUTION_FLOOR:g} "
        "(its sanity deck.check: 0.05 < coefficientRestitution <= 1)",
        0.0501,
        clamp,
    )


def write(model: DemModel, *, clamp: bool = False) -> str:
    """The fragment to include after ``create_box`` and before ``pair_style gran``."""
    poisson = deck.check_poisson(CODE, model, 0.0, clamp)
    restitution = {
        frozenset((a.name, b.name)): restitution_input(p, clamp)
        for a, b, p in deck.ordered_pairs(model)
    }
    out = deck.header(CODE, VERSION, model)
    out += deck.comment(
        f"Use with: pair_style gran {pair_style(model)} ; pair_coeff * * ; walls as "
        f"fix ID all wall/gran {pair_style(model)} ... type N (N = the wall's type)."
    )
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
    friction = {p.key: deck.Limited(p.friction.value) for p in model.pairs}
    out += _matrix(model, "coefficientFriction", friction, "friction")
    if any(p.rolling_friction is not None for p in model.pairs):
        rolling = {
            p.key: deck.Limited(p.rolling_friction.value if p.rolling_friction else 0.0)
            for p in model.pairs
        }
        out += _matrix(model, "coefficientRollingFriction", rolling, "rolling_friction")
    return "\n".join(out) + "\n"


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
        value: object = getattr(pair, attribute)
        limited = values[pair.key]
        shown = (
            deck.describe(value) if value is not None else "not known: 0 (no rolling resistance)"
        )
        lines += deck.comment(
            f"{model.index(a.name)}-{model.index(b.name)} {a.name}/{b.name}: {prop} = {shown}"
        )
        if limited.note:
            lines += deck.comment(limited.note)
        if attribute == "restitution" and (note := deck.wet_note(pair)):
            lines += deck.comment(
                note + "; LIGGGHTS 3.8.0's 'viscous on' is not used (see the granudb.dem.liggghts "
                "docstring: it does not reproduce e(St))"
            )
    rows = []
    for a in model.types:
        row = []
        for b in model.types:
            pair = model.pair(a.name, b.name)
            if pair is None:
                row.append(deck.num(0.5 if attribute == "restitution" else 0.0))
            else:
                row.append(deck.num(values[pair.key].value))
        rows.append(" ".join(row))
    if any(model.pair(a.name, b.name) is None for a in model.types for b in model.types):
        lines += deck.comment(f"wall/wall entries: {WALL_PLACEHOLDER}")
    lines.append(f"fix granudb_{prop} all property/global {prop} peratomtypepair {n} &")
    lines += [f"    {r} &" for r in rows[:-1]] + [f"    {rows[-1]}"]
    return lines
