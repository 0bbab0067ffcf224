"""Yade 2023.02a Python fragment: FrictMat per type, Hertz–Mindlin with per-pair MatchMakers.

Checked in the installed yade (``Ip2_FrictMat_FrictMat_MindlinPhys.__doc__`` and runs):

- ``en=`` converts e with Thornton et al. (2013) (B6), which in 2023.02a gives 0.9648 for
  0.97 on a sphere–wall impact; granudb writes ``betan=`` instead, computed by integrating
  Yade's own law (c_n = 2β_n√(m* k_n), force clamped at zero; granudb.dem.damping).
  ``betas`` (tangential damping) defaults to ``betan``; granudb writes ``betas`` 0:
  Yade adds the tangential dashpot outside the Coulomb cap while a contact sticks, and
  with a wet pair's β_n that force exceeded μ_f F_n (μ_f +155 % on glass in 78 %
  glycerol at 60°).
- Friction is a per-pair ``frictAngle`` MatchMaker (tan φ = μ_in); without it Yade takes
  the smaller of the two materials' angles (a mixing rule). μ_in is not μ_f: Yade's
  incremental Mindlin spring sticks at first touch, while the damped normal force jumps
  (C δ^{1/4} δ̇) and the spring builds as ∫k_s du, so the friction impulse falls short of
  μ_in times the normal one — by 4.1 % on glass in 78 % glycerol at 60° (μ_f 0.15, e 0.27),
  below 0.01 % dry. μ_in is the input whose effective μ_f on the sliding branch at
  ``deck.SLIDING_ANGLE_DEG`` is μ_f (``damping.friction_for_sliding``, which reproduces Yade's
  0.1433 for that case to 0.1 %); the deficit shrinks as the impact grows more oblique, so
  the fragment states the effective μ_f at 45° and 80° too.
- ``Ig2_Wall_Sphere_ScGeom`` gives the wall the sphere's radius (refR1 = refR2 = R), so
  MindlinPhys uses R/2 for a wall contact: k_n is 1/√2 of Hertz's and the contact lasts
  2^{1/5} ≈ 1.15 times longer. e and μ_f do not depend on it; the fragment says so.
- Rolling friction is not exported: MindlinPhys has no rolling-friction coefficient.
- Yade's lubrication law (``Ip2_FrictMat_FrictMat_LubricationPhys`` with
  ``Law2_ScGeom_ImplicitLubricationPhys``) is not exported: measured against granudb's
  e(St) it misses by up to −0.17 and +0.34 (``LUBRICATION_MEASURED``); a wet fragment
  says so.
"""

from __future__ import annotations

import math

from granudb.dem import damping, deck
from granudb.dem.spec import TOLERANCES, DemModel, PairParameters

CODE = "Yade"
VERSION = "2023.02a, Debian package yade"

#: Yade's tangential spring: incremental (dF_t = −k_t a du), always corrected.
FRICTION_LAW = deck.FrictionLaw("MindlinPhys", incremental=True)

#: Yade's lubrication law measured against granudb's e(St) = 0.97 exp(−35/St_am)
#: (tools/yade_lubrication.py; glass and steel, 12.7 mm, in 37 % and 78 % glycerol; the
#: lowest and highest e of the four): St_am → (e against a wall, e between two spheres,
#: e(St)). The wall is a fixed sphere of 1000 R with η scaled to the sphere–plane force.
LUBRICATION_MEASURED = {
    20: ((0.001, 0.006), (0.473, 0.505), 0.169),
    50: ((0.572, 0.589), (0.789, 0.802), 0.482),
    200: ((0.893, 0.900), (0.947, 0.951), 0.814),
    700: ((0.969, 0.972), (0.985, 0.986), 0.923),
    2000: ((0.990, 0.991), (0.995, 0.995), 0.953),
}


def lubrication_note() -> str:
    """Why a wet fragment holds e constant instead of Yade's lubrication law, with the
    measured gap per Stokes number (``LUBRICATION_MEASURED``)."""

    def span(low_high: tuple[float, float]) -> str:
        low, high = low_high
        return f"{low:.3f}" if low == high else f"{low:.3f}-{high:.3f}"

    rows = "; ".join(
        f"St_am {st}: {span(wall)} (wall), {span(sphere)} (sphere) for e(St) {law:.3f}"
        for st, (wall, sphere, law) in LUBRICATION_MEASURED.items()
    )
    return (
        "Yade's lubrication law (Ip2_FrictMat_FrictMat_LubricationPhys with "
        "Law2_ScGeom_ImplicitLubricationPhys: viscosity eta, roughness eps = sigma/(R1+R2) "
        "from the materials, keps 1000, film from R/10) is NOT exported: it does not "
        f"follow e(St) within {TOLERANCES['restitution_law']:g}. Measured e (glass and steel "
        f"in 37 % and 78 % glycerol, tools/yade_lubrication.py): {rows}. It has no dry "
        "dissipation (e tends to 1, not e_dry); its Reynolds film between sigma and R/10 "
        "takes 2 ln(R/(10 sigma))/St (St = rho_p 2RV/(9 eta)) of the speed against a wall, "
        "about 0.6 of the 35/St_am the curve takes; at St_am 20 the sphere stays on the "
        "wall. So e is held constant here (the range it holds for is stated)."
    )


#: Why Ψ_out at 30° may miss Walton's relation with a measured β (``dem verify``).
REBOUND_LIMIT = deck.rebound_limit(CODE, "MindlinPhys's from the materials' E and nu")


def betan(pair: PairParameters, clamp: bool) -> deck.Limited:
    """β_n for the pair, so that Yade's clamped Hertz law gives the target e."""
    e = pair.restitution.value
    limited = deck.check(
        CODE,
        f"restitution {deck.pair_label(pair)}",
        e,
        e >= 0.01,
        "Hertz-Mindlin with viscous damping: e < 0.01 needs beta_n beyond its clamped-force "
        "range (granudb.dem.damping)",
        0.01,
        clamp,
    )
    return deck.Limited(damping.yade_betan(limited.value), limited.note)


def friction_input(
    model: DemModel, pair: PairParameters, betan: float, clamp: bool = False
) -> tuple[float, str]:
    """μ_in for the pair's ``frictAngle`` and the sentences saying why (module docstring,
    ``deck.friction_input``), with Yade's damping C = √6 β_n and stiffness ratio
    k_s/k_n = 8 G*/((4/3) E*)."""
    scales = model.contact(pair)
    ratio = scales.mindlin_stiffness / scales.hertz_stiffness
    mu_in, note = deck.friction_input(
        CODE, FRICTION_LAW, model, pair, math.sqrt(6.0) * betan, ratio, clamp
    )
    return mu_in, note or ""


def write(model: DemModel, *, clamp: bool = False) -> str:
    """Python to ``exec`` in a Yade script before building bodies and engines."""
    deck.check_poisson(CODE, model, -1.0, clamp)
    out = deck.header(CODE, VERSION, model)
    out += deck.comment(host_settings(model))
    out += deck.rebound_lines(model, REBOUND_LIMIT)
    if model.walls:
        out += deck.comment(
            "Yade's wall geometry gives a wall contact the sphere's radius (R* = R/2): the "
            "contact is softer than Hertz's by 1/sqrt(2); e and mu_f are unaffected."
        )
    if any(p.wet is not None for p in model.pairs):
        out += deck.comment(lubrication_note())
    if any(p.rolling_friction is not None for p in model.pairs):
        out += deck.comment("rolling friction not exported: MindlinPhys has no rolling coefficient")
    out += ["import math", "granudb_material = {}"]
    for t in model.types:
        out += deck.comment(f"{t.name}: material values of the type")
        out.append(
            f"granudb_material[{t.name!r}] = O.materials.append(FrictMat(label={t.name!r}, "
            f"young={deck.num(t.youngs_modulus_pa)}, poisson={deck.num(t.poisson_ratio)}, "
            f"density={deck.num(t.density_kg_m3)}, frictionAngle=0.0))"
        )
    beta_rows, friction_rows, shear_rows = [], [], []
    for a, b, pair in deck.ordered_pairs(model):
        beta = betan(pair, clamp)
        ids = f"granudb_material[{a.name!r}], granudb_material[{b.name!r}]"
        notes = [
            f"{deck.pair_label(pair)}: e = {deck.describe(pair.restitution)}; "
            f"beta_n = {deck.num(beta.value)} "
            "gives it in Yade's Hertz-Mindlin law (granudb.dem.damping)",
            f"{deck.pair_label(pair)}: mu_f = {deck.describe(pair.friction)}",
        ]
        if beta.note:
            notes.append(beta.note)
        if (note := deck.wet_note(pair, model.characteristic_velocity_m_s)) is not None:
            notes.append(note)
        beta_rows += [line for n in notes[:1] + notes[2:] for line in deck.comment(n, "    # ")]
        beta_rows.append(f"    ({ids}, {deck.num(beta.value)}),")
        mu_in, mu_note = friction_input(model, pair, beta.value, clamp)
        friction_rows += deck.comment(notes[1], "    # ") + deck.comment(mu_note, "    # ")
        friction_rows.append(f"    ({ids}, math.atan({deck.num(mu_in)})),")
        shear_rows += deck.comment(
            f"{deck.pair_label(pair)}: no tangential damping (its dashpot acts outside the "
            "Coulomb cap while the contact sticks)",
            "    # ",
        )
        shear_rows.append(f"    ({ids}, 0.0),")
    out.append("granudb_ip2 = Ip2_FrictMat_FrictMat_MindlinPhys(")
    out.append("  betan=MatchMaker(matches=(")
    out += beta_rows + ["  )),", "  frictAngle=MatchMaker(matches=("]
    out += friction_rows + ["  )),", "  betas=MatchMaker(matches=("]
    out += shear_rows + ["  )),", ")"]
    dt, _, _ = deck.time_step_bound(model)
    out += ["", *CHECK.format(dt=deck.num(dt), steps=deck.MIN_STEPS_PER_CONTACT).splitlines()]
    return "\n".join(out) + "\n"


#: Yade's NewtonIntegrator default: it scales every body's acceleration by (1 ± damping),
#: numerical damping on top of the contact's (measured: e 0.703 for a target 0.860).
DEFAULT_NEWTON_DAMPING = 0.2


def host_settings(model: DemModel) -> str:
    """The host script's settings the fragment's values depend on (``dem verify`` runs with
    exactly these), and how ``granudb_check()`` stops a script without them."""
    return (
        "Defines granudb_material (name -> material id), granudb_ip2 and granudb_check(). "
        "Host settings the values below depend on (dem verify runs with exactly these): "
        "(1) O.engines with InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), "
        "Ig2_Wall_Sphere_ScGeom(), Ig2_Facet_Sphere_ScGeom()], [granudb_ip2], "
        "[Law2_ScGeom_MindlinPhys_Mindlin()]); (2) NewtonIntegrator(damping=0.0, ...): "
        f"Yade's default damping={DEFAULT_NEWTON_DAMPING:g} damps every body's motion on top "
        "of the contact law (e = 0.703 for a target 0.860); (3) "
        + deck.time_step_sentence(model)
        + " Call granudb_check() after setting O.engines and O.dt and before O.run(): it "
        "raises RuntimeError naming any of (1)-(3) that is not in place."
    )


#: The check a Yade fragment ends with (``host_settings``); ``{dt}`` is the bound.
CHECK = """def granudb_check():
    # Stops a script whose settings would not give the values above (see the header).
    problems = []
    newton = [e for e in O.engines if type(e).__name__ == 'NewtonIntegrator']
    if not newton:
        problems.append('no NewtonIntegrator in O.engines')
    for e in newton:
        if e.damping != 0.0:
            problems.append('NewtonIntegrator(damping=%r): these values need damping=0.0 '
                            '(Yade default 0.2 lowers e, e.g. 0.703 for 0.860)' % e.damping)
    loops = [e for e in O.engines if type(e).__name__ == 'InteractionLoop']
    if not any(granudb_ip2 in list(e.physDispatcher.functors) for e in loops):
        problems.append('no InteractionLoop uses granudb_ip2')
    laws = [type(f).__name__ for e in loops for f in e.lawDispatcher.functors]
    if 'Law2_ScGeom_MindlinPhys_Mindlin' not in laws:
        problems.append('no InteractionLoop uses Law2_ScGeom_MindlinPhys_Mindlin')
    if O.dt > {dt}:
        problems.append('O.dt = %g s exceeds {dt} s (t_c/{steps}, see the header)' % O.dt)
    if problems:
        raise RuntimeError('granudb deck: ' + '; '.join(problems))"""


def friction_angle(mu: float) -> float:
    """φ = atan μ_f, Yade's Coulomb friction angle."""
    return math.atan(mu)
