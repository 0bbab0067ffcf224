"""A deck says and checks what it needs from the host (issue 33): a minimal host script
written from the deck's own header, not from granudb's runner, reproduces the target e
within 1 % at the largest time step the header allows, or stops with the deck's message.

Yade: the host keeps Yade's default ``NewtonIntegrator`` (damping 0.2), and the deck's
``granudb_check()`` stops it; with ``damping=0.0`` (what the header says) e comes back.
LIGGGHTS and LAMMPS: the host writes no pair_style at all (no ``limitForce on`` anywhere in
it): the fragment writes its own.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
from dem.dem_cases import dry_model, require, with_restitution

from granudb.dem import deck, lammps, liggghts, yade

pytestmark = pytest.mark.dem_run

TARGET = 0.86
SPEED = 0.3


def _model():  # noqa: ANN202
    return with_restitution(dry_model(), TARGET)


def _stated_time_step(text: str) -> float:
    """The largest time step the deck's header states (``dt <= X s``)."""
    found = re.search(r"dt <= ([0-9.eE+-]+) s", " ".join(text.split("\n# ")))
    assert found, "the deck states no time step bound"
    return float(found.group(1))


#: Runs the host script as it is, then removes the folder Yade makes for itself in /tmp
#: (whatever TMPDIR says) and leaves behind: the test cleans up after the code it runs.
YADE_WRAPPER = """import os
granudb_tmp = os.path.dirname(O.tmpFilename())
try:
    exec(open('host.py').read())
finally:
    if os.path.basename(granudb_tmp).startswith('yade-') and not os.listdir(granudb_tmp):
        os.rmdir(granudb_tmp)
"""


def _run(cmd: list[str], folder: Path) -> str:
    if cmd[0] == "yade":
        (folder / "wrapper.py").write_text(YADE_WRAPPER)
        cmd = [*cmd[:-1], "wrapper.py"]
    proc = subprocess.run(cmd, cwd=folder, capture_output=True, timeout=300, check=False)
    return (proc.stdout + proc.stderr).decode("utf-8", errors="replace")


def _rebound(output: str) -> float:
    found = re.findall(r"^E (\S+)", output, re.MULTILINE)
    assert found, output[-2000:]
    return abs(float(found[-1])) / SPEED


def _steps(dt: float) -> int:
    return int(6e-4 / dt) + 1  # a 0.05 mm gap at 0.3 m/s and several contact times


YADE_HOST = """exec(open('deck.py').read())
s = utils.sphere((0, 0, 0.00640), 0.00635, material=granudb_material['steel'])
w = utils.wall(0.0, axis=2, sense=0, material=granudb_material['zerodur'])
O.bodies.append([s, w])
s.state.vel = Vector3(0, 0, -{speed})
O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
    InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [granudb_ip2],
                    [Law2_ScGeom_MindlinPhys_Mindlin()]),
    {newton}]
O.dt = {dt!r}
granudb_check()
O.run({steps}, True)
print('E %r' % float(s.state.vel[2]))
"""


def test_yade_default_integrator_stops_with_the_decks_message(tmp_path: Path) -> None:
    require("yade")
    text = yade.write(_model())
    assert "NewtonIntegrator(damping=0.0" in text and "granudb_check()" in text
    dt = _stated_time_step(text)
    (tmp_path / "deck.py").write_text(text)
    for newton, stops in (
        ("NewtonIntegrator(gravity=(0, 0, 0))", True),  # Yade's default damping 0.2
        ("NewtonIntegrator(gravity=(0, 0, 0), damping=0.0)", False),
    ):
        (tmp_path / "host.py").write_text(
            YADE_HOST.format(speed=SPEED, newton=newton, dt=dt, steps=_steps(dt))
        )
        output = _run(["yade", "-n", "-x", "host.py"], tmp_path)
        if stops:
            assert "granudb deck: NewtonIntegrator(damping=0.2)" in output, output[-2000:]
            assert not re.search(r"^E ", output, re.MULTILINE)
        else:
            assert _rebound(output) == pytest.approx(TARGET, rel=0.01)
    # a time step above the stated bound stops it too
    (tmp_path / "host.py").write_text(
        YADE_HOST.format(
            speed=SPEED,
            newton="NewtonIntegrator(gravity=(0, 0, 0), damping=0.0)",
            dt=2 * dt,
            steps=10,
        )
    )
    assert "exceeds" in _run(["yade", "-n", "-x", "host.py"], tmp_path)


LIGGGHTS_HOST = """units si
atom_style granular
atom_modify map array
boundary f f f
newton off
region box block -0.1 0.1 -0.1 0.1 -0.1 0.1 units box
create_box 3 box
neighbor 0.001 bin
variable granudb_wall_zerodur string "zplane 0.0"
include deck.in
create_atoms 1 single 0 0 0.00640 units box
set atom 1 diameter 0.0127 density 2540 vz -{speed}
fix integr all nve/sphere
timestep {dt!r}
variable vz equal vz[1]
run {steps}
print "E ${{vz}}"
"""

LAMMPS_HOST = """units si
atom_style sphere
atom_modify map array
boundary f f f
region box block -0.1 0.1 -0.1 0.1 -0.1 0.1 units box
create_box 2 box
create_atoms 1 single 0 0 0.00640 units box
set atom 1 diameter 0.0127 density 2540
variable granudb_wall_zerodur string "zplane 0.0 NULL"
include deck.in
velocity all set 0 0 -{speed} units box
fix integ all nve/sphere
timestep {dt!r}
variable vz equal vz[1]
thermo_style custom step v_vz
run {steps}
print "E ${{vz}}"
"""


@pytest.mark.parametrize(
    ("code", "writer", "host", "binary"),
    [
        ("liggghts", liggghts, LIGGGHTS_HOST, "liggghts"),
        ("lammps", lammps, LAMMPS_HOST, "lmp"),
    ],
)
def test_a_host_without_the_contact_options_gets_the_target(
    code: str, writer: object, host: str, binary: str, tmp_path: Path
) -> None:
    """The host writes no pair_style (so no ``limitForce on``): the fragment's own
    pair_style carries the options, and glass on Zerodur rebounds with e within 1 % at the
    largest time step the header states."""
    require(code)
    text = writer.write(_model())  # type: ignore[attr-defined]
    dt = _stated_time_step(text)
    assert dt == pytest.approx(deck.time_step_bound(_model())[0], rel=1e-3)
    (tmp_path / "deck.in").write_text(text)
    script = host.format(speed=SPEED, dt=dt, steps=_steps(dt))
    assert "limitForce" not in script and "pair_style" not in script
    (tmp_path / "in.host").write_text(script)
    output = _run([binary, "-in", "in.host", "-log", "none", "-echo", "none"], tmp_path)
    assert _rebound(output) == pytest.approx(TARGET, rel=0.01)
    if code == "lammps":  # a step above the stated bound stops the run, naming the check
        script = host.format(speed=SPEED, dt=2 * dt, steps=_steps(dt))
        (tmp_path / "in.host").write_text(script)
        output = _run([binary, "-in", "in.host", "-log", "none", "-echo", "none"], tmp_path)
        assert f"fix-id {lammps.TIME_STEP_FIX} met" in output, output[-2000:]
        assert not re.search(r"^E ", output, re.MULTILINE)
