"""Complete inputs for one collision in each code, built around the exported fragment.

Each scenario is a sphere of type ``particle`` hitting a flat wall (normal or oblique) or a
resting sphere of type ``target`` head-on, with gravity off, time step t_c/200 and a run
that ends well after the contact. Each input prints one line
``GRANUDB vx1 vz1 wy1 vz2`` with the velocities after the run.
"""

from __future__ import annotations

import math
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

from granudb.dem import lammps, liggghts
from granudb.dem.spec import DemModel, ParticleType
from granudb.errors import GranudbError

STEPS_PER_CONTACT = 200


@dataclass(frozen=True)
class Case:
    particle: str
    target: str
    speed: float
    angle_deg: float  # from the wall normal; 0 for normal and sphere–sphere impacts

    @property
    def v_normal(self) -> float:
        return self.speed * math.cos(math.radians(self.angle_deg))

    @property
    def v_tangential(self) -> float:
        return self.speed * math.sin(math.radians(self.angle_deg))


def timing(model: DemModel, case: Case) -> tuple[float, int, float, float]:
    """(time step, steps, radius, start gap): dt = t_c/200, the run covers gap + 4 t_c."""
    pair = model.pair(case.particle, case.target)
    assert pair is not None
    t_c = model.contact(pair, case.v_normal).contact_time_s
    dt = t_c / STEPS_PER_CONTACT
    radius = model.type(case.particle).radius_m
    gap = 0.5 * case.v_normal * t_c
    steps = int((gap / case.v_normal + 4.0 * t_c) / dt) + 1
    return dt, steps, radius, gap


def parse(output: str, code: str) -> tuple[float, float, float, float]:
    for line in output.splitlines():
        if line.startswith("GRANUDB "):
            vx1, vz1, wy1, vz2 = (float(x) for x in line.split()[1:5])
            return vx1, vz1, wy1, vz2
    tail = " | ".join(output.strip().splitlines()[-3:])
    raise GranudbError(f"{code} run printed no result: {tail}")


def _atoms(model: DemModel, case: Case, radius: float, gap: float) -> list[tuple[int, float]]:
    """(type name index, z) of the moving sphere and, for sphere–sphere, the resting one."""
    target = model.type(case.target)
    if target.is_wall:
        return [(0, radius + gap)]
    r2 = target.radius_m
    return [(0, radius + gap + r2), (1, 0.0)]


#: The first lines of each code's input: SI units, spheres, a fixed box, velocities shared.
LIGGGHTS_SETUP = ["atom_style granular", "atom_modify map array", "boundary f f f",
                  "newton off", "communicate single vel yes", "units si"]  # fmt: skip
LAMMPS_SETUP = ["units si", "atom_style sphere", "atom_modify map array", "boundary f f f",
                "comm_modify vel yes"]  # fmt: skip


def _start(
    model: DemModel, case: Case, setup: list[str], types: int
) -> tuple[float, int, float, float, ParticleType, float, list[str]]:
    """Time step, steps, radius, gap, target, box half-size and the first lines (a box of
    20 radii either side, with ``types`` atom types)."""
    dt, steps, radius, gap = timing(model, case)
    size = 20 * radius
    box = f"region box block {-size} {size} {-size} {size} {-size} {size} units box"
    return (
        dt,
        steps,
        radius,
        gap,
        model.type(case.target),
        size,
        [*setup, box, f"create_box {types} box"],
    )


def _result(steps: int) -> list[str]:
    """The run and the one line every input prints: ``GRANUDB vx1 vz1 wy1 vz2``."""
    return [f"run {steps}", 'print "GRANUDB ${vx1} ${vz1} ${wy1} ${vz2}"']


def liggghts_input(model: DemModel, fragment: str, case: Case) -> str:
    dt, steps, radius, gap, target, size, lines = _start(
        model, case, LIGGGHTS_SETUP, len(model.types)
    )
    lines += [f"neighbor {radius / 5} bin", "neigh_modify delay 0"]
    lines += [f'variable {liggghts.wall_variable(w)} string "zplane 0.0"' for w in model.walls]
    keep = f"fix granudb_wall_{target.name} "  # only this case's wall, if any
    lines += [
        ln
        for ln in fragment.splitlines()
        if not ln.startswith("fix granudb_wall_") or ln.startswith(keep)
    ]
    lines.append(f"timestep {dt!r}")
    types = [model.index(case.particle), model.index(case.target)]
    for k, (which, z) in enumerate(_atoms(model, case, radius, gap), start=1):
        t = model.type(case.particle if which == 0 else case.target)
        lines.append(f"create_atoms {types[which]} single 0 0 {z!r} units box")
        vel = f"vx {case.v_tangential!r} vz {-case.v_normal!r}" if which == 0 else "vz 0"
        lines.append(f"set atom {k} diameter {t.diameter_m!r} density {t.density_kg_m3!r} {vel}")
    two = not target.is_wall
    if 1 not in types[: 2 if two else 1]:
        # LIGGGHTS refuses a run whose atom types do not start from 1: a still spectator far away
        first = model.types[0]
        k = 3 if two else 2
        lines.append(f"create_atoms 1 single {size / 2!r} {size / 2!r} {size / 2!r} units box")
        lines.append(
            f"set atom {k} diameter {(first.diameter_m or 2 * radius)!r} "
            f"density {first.density_kg_m3!r} vz 0"
        )
    lines += [
        "fix integr all nve/sphere",
        "variable vx1 equal vx[1]",
        "variable vz1 equal vz[1]",
        "variable wy1 equal omegay[1]",
        f"variable vz2 equal {'vz[2]' if two else '0'}",
        "thermo 100000",
    ] + _result(steps)
    return "\n".join(lines) + "\n"


def lammps_input(model: DemModel, fragment: str, case: Case) -> str:
    dt, steps, radius, gap, target, size, lines = _start(
        model, case, LAMMPS_SETUP, len(model.particles)
    )
    for wall in model.walls:
        lines.append(f'variable {lammps.wall_variable(wall)} string "zplane 0.0 NULL"')
    types = [lammps.type_number(model, case.particle)]
    if not target.is_wall:
        types.append(lammps.type_number(model, case.target))
    for k, (which, z) in enumerate(_atoms(model, case, radius, gap), start=1):
        t = model.type(case.particle if which == 0 else case.target)
        lines.append(f"create_atoms {types[which]} single 0 0 {z!r} units box")
        lines.append(f"set atom {k} diameter {t.diameter_m!r} density {t.density_kg_m3!r}")
    lines.append(fragment)
    keep = f"fix granudb_{target.name}_{case.particle} "  # only this pair's wall fix, if any
    lines = [
        ln
        for ln in "\n".join(lines).splitlines()
        if " wall/gran " not in ln or (target.is_wall and ln.startswith(keep))
    ]
    if target.is_wall:
        lines.append(f"velocity all set {case.v_tangential!r} 0 {-case.v_normal!r} units box")
    else:  # only sphere 1 moves
        lines += [
            "group granudb_moving id 1",
            f"velocity granudb_moving set 0 0 {-case.v_normal!r} units box",
        ]
    lines += [
        "fix integ all nve/sphere",
        f"timestep {dt!r}",
        "compute om all property/atom omegay",
        "variable vx1 equal vx[1]",
        "variable vz1 equal vz[1]",
        "variable wy1 equal c_om[1]",
        f"variable vz2 equal {'0' if target.is_wall else 'vz[2]'}",
        "thermo_style custom step v_vx1 v_vz1 v_wy1 v_vz2",  # keeps c_om current at the end
        "thermo 100000",
    ] + _result(steps)
    return "\n".join(ln for ln in lines if ln) + "\n"


def yade_script(model: DemModel, fragment: str, cases: list[Case]) -> str:
    """One Yade script running every case in turn (Yade's start-up is the slow part)."""
    lines = ["import math", f"FRAGMENT = {fragment!r}", "CASES = ["]
    for case in cases:
        dt, steps, radius, gap = timing(model, case)
        target = model.type(case.target)
        r2 = 0.0 if target.is_wall else target.radius_m
        lines.append(
            f"  ({case.particle!r}, {case.target!r}, {target.is_wall}, {radius!r}, {r2!r},"
            f" {gap!r}, {case.v_tangential!r}, {case.v_normal!r}, {dt!r}, {steps}),"
        )
    lines += ["]", _YADE_LOOP]
    return "\n".join(lines) + "\n"


_YADE_LOOP = """
def granudb_run(p, t, wall, r1, r2, gap, vt, vn, dt, steps):
    O.reset()
    g = {'O': O}
    g.update(globals())
    exec(FRAGMENT, g)
    mat = g['granudb_material']
    s = utils.sphere((0, 0, r1 + gap + r2), r1, material=mat[p])
    if wall:
        other = utils.wall(0.0, axis=2, sense=0, material=mat[t])
    else:
        other = utils.sphere((0, 0, 0), r2, material=mat[t])
    O.bodies.append([s, other])
    s.state.vel = Vector3(vt, 0, -vn)
    O.engines = [ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()],
                        [g['granudb_ip2']], [Law2_ScGeom_MindlinPhys_Mindlin()]),
        NewtonIntegrator(gravity=(0, 0, 0), damping=0)]
    O.dt = dt
    g['granudb_check']()  # as the fragment's header says
    O.run(steps, True)
    v2 = 0.0 if wall else other.state.vel[2]
    print('GRANUDB %r %r %r %r' % (float(s.state.vel[0]), float(s.state.vel[2]),
          float(s.state.angVel[1]), float(v2)), flush=True)


# Yade makes its own temporary folder (/tmp/yade-XXXXXX, whatever TMPDIR says) and leaves it
# behind: the script removes it, empty as this script leaves it, however the runs end.
import os as granudb_os
granudb_tmp = granudb_os.path.dirname(O.tmpFilename())
print('GRANUDB-TMP %s' % granudb_tmp, flush=True)
try:
    for case in CASES:
        granudb_run(*case)
finally:
    if granudb_os.path.basename(granudb_tmp).startswith('yade-'):
        try:
            granudb_os.rmdir(granudb_tmp)
        except OSError:
            pass
"""


#: What Open MPI prints when a process dies while starting up (before the code reads its
#: input): a failure of the machine's MPI runtime, not of the run, so it is tried again.
MPI_STARTUP_FAILURES = ("before MPI_INIT", "MPI_ERRORS_ARE_FATAL", "PMIX ERROR", "ORTE_ERROR")
ATTEMPTS = 3


def run(cmd: list[str], workdir: Path, timeout: float = 120.0) -> str:
    """The program's output; a run that died in MPI start-up is retried (up to
    ``ATTEMPTS`` times), any other outcome is returned as it is."""
    output = ""
    for attempt in range(ATTEMPTS):
        proc = subprocess.run(cmd, cwd=workdir, capture_output=True, timeout=timeout, check=False)
        output = (proc.stdout + proc.stderr).decode("utf-8", errors="replace")
        if proc.returncode == 0 or not any(m in output for m in MPI_STARTUP_FAILURES):
            return output
        time.sleep(0.5 * (attempt + 1))
    return output
