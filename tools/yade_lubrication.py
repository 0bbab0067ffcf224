"""Measure Yade's lubrication law against granudb's e(St): the numbers behind
``granudb.dem.yade.LUBRICATION_GAP`` and docs/physics.md §13.

Yade 2023.02a's ``Ip2_FrictMat_FrictMat_LubricationPhys`` with
``Law2_ScGeom_ImplicitLubricationPhys`` (Chèvremont et al. 2020) is run on head-on impacts
of 12.7 mm glass and steel spheres (the seed materials) in 37 % and 78 % glycerol, at the
speeds where granudb's e(St) = e_dry exp(−35/St_am) (``spec.predicted_wet_restitution``,
the curve ``pair`` and the reports use) has St_am = 20, 50, 200, 700 and 2000:

- sphere–sphere: two free spheres, the second at rest;
- sphere–wall: the wall is a fixed sphere of 1000 R, because the law is written for two
  spheres of mean radius a (it takes ν_n = π η a² for the Reynolds force (3/2) ν_n u̇/u):
  η is scaled by 4 R*²/a² so that the force is the sphere–plane 6π η R*² u̇/u.

Inputs as the law reads them (from its source, pkg/dem/Lubrication.cpp): ``eta`` the
viscosity; ``eps`` the roughness relative to a, asperities touching when the gap u <
2 eps a, so eps = σ/(R₁ + R₂) with σ = √(σ₁² + σ₂²) of the materials; the particles'
stiffness k_n = 2E₁R₁E₂R₂/(E₁R₁ + E₂R₂) (a linear spring from the materials' E, not
Hertz); the roughness spring ``keps`` times k_n. Yade's default keps = 1 lets the gap
collapse to zero once the overlap exceeds σ ("nul gap found"), after which the law is
elastic and gains energy: keps = 1000 here. The film acts from a gap of R/10
(``MaxDist``), where each impact starts and where the rebound speed is read. The time
step is 0.05 √(m*/k_n); a step four times smaller changes e by 2e-4. Tangential, twist
and roll lubrication are off (head-on impacts).

    python tools/yade_lubrication.py         # about 5 minutes on one core
"""

from __future__ import annotations

import json
import math
import subprocess
import tempfile
from pathlib import Path

from granudb.dem.spec import ParticleType, Value, predicted_wet_restitution
from granudb.physics.flow import added_mass_stokes_number

#: Seed materials (seed_data/materials.csv): E [Pa], ν, ρ [kg/m³], σ [m]; Zerodur the wall.
MATERIALS = {
    "glass": (60e9, 0.23, 2540.0, 0.1305e-6),
    "steel": (190e9, 0.27, 7780.0, 0.0236e-6),
}
ZERODUR = (91e9, 0.24, 2540.0, 0.0155e-6)
#: Seed fluids (seed_data/fluids.csv): viscosity [Pa s], density [kg/m³].
FLUIDS = {"glycerol-37": (3e-3, 1090.4), "glycerol-78": (48e-3, 1202.2)}
STOKES = (20.0, 50.0, 200.0, 700.0, 2000.0)
RADIUS = 6.35e-3
WALL_FACTOR = 1000.0
START_GAP = 0.1  # of R
KEPS = 1000.0

SCRIPT = """
import json, math
for c in json.load(open(CASES)):
    O.reset()
    R, R2, V, h0 = c['R'], c['R2'], c['V'], c['h0']
    m1 = O.materials.append(FrictMat(young=c['E'], poisson=c['nu'], density=c['rho'],
                                     frictionAngle=0.0))
    m2 = O.materials.append(FrictMat(young=c['E2'], poisson=c['nu2'], density=c['rho'],
                                     frictionAngle=0.0))
    f = 1.0 + 1.2 * h0 / R
    s1 = utils.sphere((0, 0, R + R2 + h0), R, material=m1)
    s2 = utils.sphere((0, 0, 0), R2, material=m2, fixed=c['wall'])
    O.bodies.append([s1, s2])
    s1.state.vel = Vector3(0, 0, -V)
    law = Law2_ScGeom_ImplicitLubricationPhys(MaxDist=h0 / ((R + R2) / 2),
        activateTangencialLubrication=False, activateTwistLubrication=False,
        activateRollLubrication=False)
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=f)]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=f)],
            [Ip2_FrictMat_FrictMat_LubricationPhys(eta=c['eta'], eps=c['eps'], keps=c['keps'])],
            [law]),
        NewtonIntegrator(gravity=(0, 0, 0), damping=0)]
    m = 4.0 / 3.0 * math.pi * R**3 * c['rho']
    kn = 2 * c['E'] * R * c['E2'] * R2 / (c['E'] * R + c['E2'] * R2)
    O.dt = 0.05 * math.sqrt((m if c['wall'] else m / 2) / kn)
    chunk = max(1, int(0.02 * h0 / V / O.dt))
    while O.time < 20 * h0 / V:
        O.run(chunk, True)
        gap = s1.state.pos[2] - s2.state.pos[2] - R - R2
        if gap > h0 * 1.0001 and s1.state.vel[2] > s2.state.vel[2]:
            break
    print('GRANUDB_LUB %r' % ((s1.state.vel[2] - s2.state.vel[2]) / V), flush=True)
"""


def cases() -> list[dict[str, object]]:
    """Every impact: material, fluid, geometry, St_am, speed, e(St) and Yade's inputs."""
    out: list[dict[str, object]] = []
    for name, (e_mod, nu, rho, sigma) in MATERIALS.items():
        particle = ParticleType(name, e_mod, nu, rho, 2 * RADIUS)
        for fluid, (eta, rho_f) in FLUIDS.items():
            per_speed = float(added_mass_stokes_number(rho, rho_f, RADIUS, 1.0, eta))
            _, law = predicted_wet_restitution(Value(0.97, "seed"), particle, eta, 0.3, rho_f)
            for wall in (False, True):
                r2 = WALL_FACTOR * RADIUS if wall else RADIUS
                e2, nu2, _, sigma2 = ZERODUR if wall else (e_mod, nu, rho, sigma)
                a = (RADIUS + r2) / 2
                reduced = RADIUS * r2 / (RADIUS + r2)
                for stokes in STOKES:
                    out.append(
                        dict(
                            material=name, fluid=fluid, wall=wall, St=stokes,
                            law=law.restitution(stokes), R=RADIUS, R2=r2, E=e_mod, nu=nu,
                            E2=e2, nu2=nu2, rho=rho, V=stokes / per_speed,
                            h0=START_GAP * RADIUS, keps=KEPS,
                            eta=eta * (4 * reduced**2 / a**2 if wall else 1.0),
                            eps=math.hypot(sigma, sigma2) / (RADIUS + r2),
                        )
                    )  # fmt: skip
    return out


def measure(todo: list[dict[str, object]]) -> list[float]:
    """Run every case in one Yade process; e of each, in order."""
    with tempfile.TemporaryDirectory(prefix="granudb-lubrication-") as tmp:
        (Path(tmp) / "cases.json").write_text(json.dumps(todo))
        script = Path(tmp) / "run.py"
        script.write_text(f"CASES = {str(Path(tmp) / 'cases.json')!r}\n{SCRIPT}")
        proc = subprocess.run(
            ["yade", "-n", "-x", str(script)], capture_output=True, text=True, check=False
        )
    lines = proc.stdout.splitlines()
    found = [float(ln.split()[1]) for ln in lines if ln.startswith("GRANUDB_LUB")]
    if len(found) != len(todo):
        raise RuntimeError(f"yade printed {len(found)} of {len(todo)}: {proc.stderr[-500:]}")
    return found


def main() -> None:
    todo = cases()
    found = measure(todo)
    print(f"{'material':8} {'fluid':12} {'target':6} {'St_am':>6} {'V m/s':>7} {'e Yade':>7} "
          f"{'e(St)':>6} {'gap':>7}")  # fmt: skip
    for c, e in zip(todo, found, strict=True):
        target = "wall" if c["wall"] else "sphere"
        print(
            f"{c['material']:8} {c['fluid']:12} {target:6} {c['St']:6.0f} {c['V']:7.3f} "
            f"{e:7.3f} {c['law']:6.3f} {e - c['law']:+7.3f}"
        )
    worst = max(abs(e - c["law"]) for c, e in zip(todo, found, strict=True))
    print(f"largest |e - e(St)|: {worst:.3f} (granudb's tolerance for e(St): 0.03)")


if __name__ == "__main__":
    main()
