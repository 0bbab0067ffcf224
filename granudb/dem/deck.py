"""Helpers shared by the writers: number formatting, comments, limit checks with --clamp."""

from __future__ import annotations

import math
import textwrap
from collections.abc import Iterator
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from granudb.dem import damping
from granudb.dem.spec import TOLERANCES, DemModel, PairParameters, ParticleType, Value
from granudb.errors import ValidationError
from granudb.physics.impact import (
    GROSS_SLIP,
    maw_chi,
    maw_psi,
    stiffness_ratio,
    tangential_regime,
    walton_rebound,
)


def num(x: float) -> str:
    """A number as the codes read it: plain decimal or exponent, 10 significant digits."""
    return f"{x:.10g}"


#: Characters a comment must not carry into a deck: LAMMPS joins lines at a trailing ``&``
#: and inside triple quotes before it strips comments; a C++ line comment continues past a
#: trailing backslash; a control character may end a line anywhere.
_COMMENT_SAFE = str.maketrans({'"': "'", "\\": "/", **{chr(c): " " for c in range(32)}})


def comment(text: str, prefix: str = "# ", width: int = 96) -> list[str]:
    """``text`` as comment lines of at most ``width`` characters, with nothing in them a
    code could read as more than a comment (``_COMMENT_SAFE``).

    >>> comment('dataset "x" & more &')
    ["# dataset 'x' & more and"]
    """
    lines: list[str] = []
    text = "\n".join(line.translate(_COMMENT_SAFE) for line in text.split("\n"))
    for paragraph in text.split("\n"):
        wrapped = textwrap.wrap(paragraph, width - len(prefix), break_on_hyphens=False) or [""]
        # LAMMPS continues a line whose last printable character is "&", comment or not.
        lines.extend(prefix + (w[:-1] + "and" if w.endswith("&") else w) for w in wrapped)
    return lines


def describe(value: Value) -> str:
    """A value as its comment says it: the number, where it came from, and its interval
    where one is stated."""
    interval = value.stated_interval()
    return f"{num(value.value)} ({value.provenance}{'; ' + interval if interval else ''})"


def pair_label(pair: PairParameters) -> str:
    return f"{pair.type_i}/{pair.type_j}"


@dataclass
class Limited:
    """A value after a code's limit check: possibly clamped, with the note saying so."""

    value: float
    note: str | None = None


def check(
    code: str,
    field: str,
    value: float,
    ok: bool,
    rule: str,
    nearest: float,
    clamp: bool,
) -> Limited:
    """Pass ``value`` if ``ok``; else clamp to ``nearest`` (with a note) or refuse in one line.

    The refusal names the code and its rule, so a user knows which code cannot take the
    number and what ``--clamp`` would write instead.
    """
    if ok:
        return Limited(value)
    if clamp:
        return Limited(nearest, f"CLAMPED from {num(value)} to {num(nearest)}: {code} {rule}")
    raise ValidationError(
        field, f"{value:.4g}", f"{code} {rule}; use --clamp to write {num(nearest)} with a comment"
    )


def check_poisson(code: str, model: DemModel, low: float, clamp: bool) -> dict[str, Limited]:
    """ν in [low, 0.5] for every type (elastic solids have ν ≤ 0.5; some codes refuse ν < 0)."""
    out: dict[str, Limited] = {}
    for t in model.types:
        nu = t.poisson_ratio
        out[t.name] = check(
            code,
            f"poisson_ratio {t.name}",
            nu,
            low <= nu <= 0.5,
            f"requires {low:g} <= poissonsRatio <= 0.5",
            min(max(nu, low), 0.5),
            clamp,
        )
    return out


def type_lines(model: DemModel, prefix: str = "# ") -> list[str]:
    lines = []
    for i, t in enumerate(model.types, start=1):
        what = "flat wall" if t.is_wall else f"sphere, d = {num(t.diameter_m or 0.0)} m"
        lines.append(
            f"{prefix}type {i} = {t.name} ({what}): E = {num(t.youngs_modulus_pa)} Pa, "
            f"nu = {num(t.poisson_ratio)}, rho = {num(t.density_kg_m3)} kg/m^3"
        )
    return lines


def ordered_pairs(model: DemModel) -> Iterator[tuple[ParticleType, ParticleType, PairParameters]]:
    """Every i ≤ j pair that can touch, in type order."""
    for i, a in enumerate(model.types):
        for b in model.types[i:]:
            pair = model.pair(a.name, b.name)
            if pair is not None:
                yield a, b, pair


def wet_note(pair: PairParameters, speed: float) -> str | None:
    """The e(St) law of an immersed pair and the speeds over which the constant e written
    (the law's value at ``speed``, the characteristic speed) stays within e's tolerance."""
    if pair.wet is None:
        return None
    w = pair.wet
    e = pair.restitution.value
    tolerance = TOLERANCES["restitution"]
    st = w.stokes_at(e)
    low, high = w.constant_range(e, tolerance)
    top = "any higher speed" if math.isinf(high) else f"{num(round(speed * high / st, 4))} m/s"
    st_top = "infinity" if math.isinf(high) else f"{high:.4g}"
    return (
        f"immersed: e(St_am) = {num(w.max_restitution)} exp(-{num(w.coefficient)}/St_am), "
        f"mu_fluid = {num(w.fluid_viscosity_pa_s)} Pa s ({w.provenance}); the e written is the "
        f"value at St_am = {st:.4g} (V = {num(speed)} m/s). It stays within "
        f"{tolerance:.0%} of e(St) for St_am {low:.4g} to {st_top}, i.e. normal impact speeds "
        f"{num(round(speed * low / st, 4))} m/s to {top}; outside that range this code gives "
        "the constant, not e(St)"
    )


#: The fewest time steps per contact a deck's values are stated for. Measured in the three
#: packaged codes (steel and glass on Zerodur, dry and in 78 % glycerol): at t_c/50, e within
#: 0.2 % and the sliding mu_f within 2.3 % of their targets; at t_c/20, mu_f 3.4 % off in Yade
#: (beyond ``TOLERANCES["friction"]``). ``dem verify`` runs at t_c/200.
MIN_STEPS_PER_CONTACT = 50


def time_step_bound(model: DemModel) -> tuple[float, PairParameters, float]:
    """(largest time step the deck's values hold for, the pair with the shortest contact,
    its t_c) at the characteristic speed: t_c/``MIN_STEPS_PER_CONTACT``, rounded down to
    the 3 digits the deck states."""
    pair = min(model.pairs, key=lambda p: model.contact(p).contact_time_s)
    t_c = model.contact(pair).contact_time_s
    bound = t_c / MIN_STEPS_PER_CONTACT
    scale = 10.0 ** (math.floor(math.log10(bound)) - 2)  # 3 significant digits, rounded down
    return math.floor(bound / scale) * scale, pair, t_c


def time_step_sentence(model: DemModel) -> str:
    """What a deck says about the time step (``time_step_bound``)."""
    dt, pair, t_c = time_step_bound(model)
    v = model.characteristic_velocity_m_s
    return (
        f"Time step: dt <= {dt:.3g} s, t_c/{MIN_STEPS_PER_CONTACT} of the shortest contact "
        f"({pair_label(pair)}: t_c = {t_c:.4g} s at {num(v)} m/s). t_c shrinks as V^-1/5: for "
        f"faster impacts scale dt by ({num(v)}/V)^(1/5). At t_c/{MIN_STEPS_PER_CONTACT} the "
        "three codes gave e within 0.2 % and the sliding mu_f within 2.3 % of the values "
        "below; at t_c/20 mu_f missed by 3.4 % (dem verify runs at t_c/200)."
    )


def header(code: str, version: str, model: DemModel) -> list[str]:
    v = model.characteristic_velocity_m_s
    lines = [
        f"granudb DEM export for {code} ({version}), SI units (m, kg, s, Pa).",
        f"Characteristic impact speed {num(v)} m/s. Every number below says where it came from.",
    ]
    if model.parameter_set != "central":
        lines.append(
            f"Parameter set: {model.parameter_set.upper()}, for sensitivity runs: every value "
            f"at the {model.parameter_set} end of its stated interval (a fit's 95 % interval, or "
            "± 2u from a stated standard uncertainty u); a value without an interval keeps its "
            "central value and says so. Wet restitutions follow from the dry e of the set."
        )
    out = [line for text in lines for line in comment(text)]
    return out + type_lines(model)


def rebound_limit(code: str, stiffness: str) -> str:
    """Why ``code`` cannot reproduce a measured β: its tangential stiffness (``stiffness``)
    is not a per-pair input. Written in its deck, and ``dem verify``'s "stated limit"."""
    return (
        f"{code}'s tangential stiffness is {stiffness}, not a per-pair input, so a measured "
        "beta cannot be set: Psi_out on the sticking side of Walton's relation is the Mindlin "
        "contact's"
    )


def rebound_lines(model: DemModel, limit: str) -> list[str]:
    """The deck's statement of ``limit`` for the pairs that have a measured β."""
    measured = [(p, p.rotational_restitution) for p in model.pairs]
    said = ", ".join(
        f"{pair_label(p)} {describe(beta)}" for p, beta in measured if beta is not None
    )
    if not said:
        return []
    return comment(f"beta NOT reproduced ({said}): {limit}")


#: The impact angle (from the normal) at which a μ_f input gives the target μ_f on the
#: sliding branch: the oblique angle ``dem verify`` checks it at.
SLIDING_ANGLE_DEG = 60.0
#: Where a deck says what the effective μ_f becomes away from that angle.
STATED_ANGLES_DEG = (45.0, 80.0)
#: How far below μ_f the effective μ_f at that angle may stay when no input up to
#: ``damping.FRICTION_INPUT_LIMIT`` times μ_f reaches it, before the export refuses (a third
#: of ``dem verify``'s tolerance on μ_f).
FRICTION_SHORTFALL = TOLERANCES["friction"] / 3.0


@dataclass
class FrictionLaw:
    """How a code's tangential spring builds up (``damping.sliding_friction``): its name
    for the deck, whether it is incremental (Yade) or total (LIGGGHTS, LAMMPS), and the
    loss at ``SLIDING_ANGLE_DEG`` below which the plain μ_f is written (0: always corrected)."""

    name: str
    incremental: bool
    correct_above: float = 0.0


def slides_throughout(model: DemModel, pair: PairParameters, angle_deg: float) -> bool:
    """Whether an impact at ``angle_deg`` from the normal is on Walton's sliding branch for
    the pair's μ_f (Maw's regime, as ``dem verify`` classifies its runs)."""
    scales = model.contact(pair)
    ratio = stiffness_ratio(scales.reduced_shear_modulus_pa, scales.reduced_modulus_pa)
    psi = maw_psi(ratio, math.tan(math.radians(angle_deg)), pair.friction.value, 1.0)
    return int(tangential_regime(psi, maw_chi(ratio))) == GROSS_SLIP


def friction_input(
    code: str,
    law: FrictionLaw,
    model: DemModel,
    pair: PairParameters,
    damping_c: float,
    spring_ratio: float,
    clamp: bool = False,
) -> tuple[float, str | None]:
    """μ_f input for ``pair`` and the sentence saying why: the input whose effective μ_f
    on the sliding branch at ``SLIDING_ANGLE_DEG`` is the pair's μ_f, on the clamped law
    with damping C = ``damping_c`` and k_t/k_n = ``spring_ratio``
    (``damping.friction_for_sliding``). The plain μ_f (no sentence) where its loss is at
    most ``law.correct_above`` (and, with a sentence, where that impact does not slide
    throughout, so μ_f does not decide it); where no input up to
    ``damping.FRICTION_INPUT_LIMIT`` times μ_f reaches it, refused, or with ``clamp``
    written at that limit and said so."""
    mu = pair.friction.value
    if not slides_throughout(model, pair, SLIDING_ANGLE_DEG):
        return mu, (
            f"{pair_label(pair)}: mu_f written as it is: an impact at {SLIDING_ANGLE_DEG:g} deg "
            "does not slide throughout with this mu_f (Maw's regime), so the loss of friction "
            "at first touch is not corrected"
        )
    c, ratio = round(damping_c, 12), round(spring_ratio, 12)
    psis = [math.tan(math.radians(a)) for a in (SLIDING_ANGLE_DEG, *STATED_ANGLES_DEG)]
    if law.correct_above > 0.0:
        plain = damping.sliding_friction(
            mu, c, ratio, psis[0], step=2e-3, incremental=law.incremental
        )
        if abs(float(plain) / mu - 1.0) <= law.correct_above:
            return mu, None
    mu_in = damping.friction_for_sliding(
        round(mu, 12), c, ratio, round(psis[0], 12), incremental=law.incremental
    )
    effective = [
        float(m)
        for m in damping.sliding_friction(
            mu_in, c, ratio, psis, step=2e-3, incremental=law.incremental
        )
    ]
    limited = check(
        code,
        f"friction {pair_label(pair)}",
        mu,
        effective[0] >= mu * (1.0 - FRICTION_SHORTFALL),
        f"{law.name} sticks so long at first touch (damping C = {c:.3g}) that no mu_f input "
        f"up to {damping.FRICTION_INPUT_LIMIT:g} times it slides with it at "
        f"{SLIDING_ANGLE_DEG:g} deg (at most {effective[0]:.4g})",
        effective[0],
        clamp,
    )
    stated = " and ".join(
        f"{m:.4g} at {a:g} deg" for a, m in zip(STATED_ANGLES_DEG, effective[1:], strict=True)
    )
    note = (
        f"{pair_label(pair)}: mu_f input {num(mu_in)} so that the effective mu_f on the "
        f"sliding branch at {SLIDING_ANGLE_DEG:g} deg is {num(limited.value)}: {code}'s "
        f"contact sticks at first touch while its damped normal force jumps "
        f"(granudb.dem.damping.sliding_friction); the effective mu_f is {stated}"
    )
    return mu_in, note + (f". {limited.note}" if limited.note else "")


#: The impact angles (from the normal, degrees) on which a deck's Ψ_out claim is computed.
REBOUND_ANGLES_DEG = tuple(float(a) for a in range(1, 90))


@dataclass(frozen=True)
class ReboundRange:
    """Where a deck's contact gives Ψ_out within ``TOLERANCES["rebound"]`` of Walton's
    relation with the pair's β, μ_f and e: every impact angle from ``lowest_deg`` up (to
    89°), computed on the written inputs (``damping.sliding_friction``); below it the
    largest deviation, ``worst_beta`` (the effective β = −Ψ_out/Ψ_in) at ``worst_deg``."""

    lowest_deg: float
    worst_deg: float
    worst_beta: float
    worst_error: float

    def holds_at(self, angle_deg: float) -> bool:
        return angle_deg >= self.lowest_deg

    #: (angle, effective β) at ``sticking_angle``, where ``dem verify`` checks the claim.
    checked: tuple[float, float] | None = None

    def sentence(self, pair: PairParameters) -> str:
        beta = pair.rotational_restitution
        said = (
            f"Psi_out within {TOLERANCES['rebound']:.0%} of Walton's relation with beta, "
            f"mu_f and e for impact angles from {self.lowest_deg:g} deg (from the normal) up"
        )
        if self.lowest_deg <= REBOUND_ANGLES_DEG[0] or beta is None:
            return said
        return (
            f"{said}; at smaller angles the contact slips near its end under mu_f (its normal "
            f"force vanishes before the tangential spring has unloaded), so the effective beta "
            f"is not {num(beta.value)}: "
            + (
                f"{self.checked[1]:.3f} at {self.checked[0]:g} deg (mid sticking branch), "
                if self.checked is not None and not self.holds_at(self.checked[0])
                else ""
            )
            + f"up to {self.worst_beta:.3f} at {self.worst_deg:g} deg "
            f"(Psi_out {self.worst_error:+.0%} from Walton's), computed on these inputs "
            "(granudb.dem.damping.sliding_friction). Outside that range dem verify reports "
            "this limit instead of judging Psi_out"
        )


def sticking_angle(pair: PairParameters | None) -> float | None:
    """For a pair with a measured β, the impact angle (from the normal, 0.1° steps) in the
    middle of Walton's sticking branch, Ψ_in half the corner's μ_f(1+e)(1+1/K²)/(1+β):
    where ``dem verify`` tests a deck's β claim (issue 33), besides 30° and 60°; None
    without β."""
    beta = None if pair is None else pair.rotational_restitution
    if pair is None or beta is None:
        return None
    corner = (
        pair.friction.value
        * (1.0 + pair.restitution.value)
        * damping.CONTACT_POINT_FACTOR
        / (1.0 + beta.value)
    )
    return round(math.degrees(math.atan(corner / 2.0)), 1)


def rebound_range(
    pair: PairParameters,
    damping_c: float,
    spring_ratio: float,
    friction_in: float,
    incremental: bool,
) -> ReboundRange | None:
    """The ``ReboundRange`` of a pair with a measured β on a contact with damping C, k_t/k_n
    and μ_f input as written; None without β."""
    beta = pair.rotational_restitution
    if beta is None:
        return None
    found = _rebound_range(
        round(beta.value, 12), round(pair.friction.value, 12),
        round(pair.restitution.value, 12), round(damping_c, 12), round(spring_ratio, 12),
        round(friction_in, 12), incremental,
    )  # fmt: skip
    angle = sticking_angle(pair)
    if angle is None:
        return found
    psi_out = contact_rebound(pair, damping_c, spring_ratio, friction_in, incremental, angle)
    return replace(found, checked=(angle, -psi_out / math.tan(math.radians(angle))))


def contact_rebound(
    pair: PairParameters,
    damping_c: float,
    spring_ratio: float,
    friction_in: float,
    incremental: bool,
    angle_deg: float,
) -> float:
    """Ψ_out of the written contact (damping C, k_t/k_n, μ_f input) at ``angle_deg``:
    what a deck states its code gives where Walton's relation does not hold."""
    psi = math.tan(math.radians(angle_deg))
    effective = float(
        damping.sliding_friction(
            friction_in, damping_c, spring_ratio, psi, step=2e-3, incremental=incremental
        )
    )
    return psi - effective * damping.CONTACT_POINT_FACTOR * (1.0 + pair.restitution.value)


@lru_cache(maxsize=128)
def _rebound_range(
    beta: float, mu: float, e: float, c: float, ratio: float, mu_in: float, incremental: bool
) -> ReboundRange:
    angles = np.array(REBOUND_ANGLES_DEG)
    psi = np.tan(np.radians(angles))
    effective = damping.sliding_friction(mu_in, c, ratio, psi, step=2e-3, incremental=incremental)
    psi_out = psi - effective * damping.CONTACT_POINT_FACTOR * (1.0 + e)
    walton = np.asarray(walton_rebound(psi, beta, mu, e), dtype=float)
    error = psi_out / walton - 1.0
    bad = np.nonzero(~(np.abs(error) <= TOLERANCES["rebound"]))[0]
    if bad.size == 0:
        return ReboundRange(float(angles[0]), float(angles[0]), beta, 0.0)
    last = int(bad[-1])
    worst = int(np.argmax(np.abs(error[: last + 1])))
    lowest = float(angles[last + 1]) if last + 1 < len(angles) else 90.0
    return ReboundRange(
        lowest, float(angles[worst]), float(-psi_out[worst] / psi[worst]), float(error[worst])
    )
