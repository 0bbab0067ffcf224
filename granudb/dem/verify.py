"""Run the exported parameters in the real codes and read the rebound back.

For every installed code (binary found with :func:`shutil.which`) each requested collision
is run in a temporary directory: a sphere on a flat wall, normal and oblique, and head-on
on a resting sphere of a particle pair. The rebound gives the achieved e (e = −v_N,out/
v_N,in with relative velocities, docs/physics.md §5, §9) and, for oblique impacts, Ψ_out to
compare with Walton's sliding branch Ψ_out = Ψ_in − μ_f(1+e)(1+1/K²) and the achieved
μ_f = (Ψ_in − Ψ_out)/((1+e)·7/2) (Joseph & Hunt (2.6), (2.9)). A code that is not
installed gives records with status "not checked", never a pass.

Each checked record has a verdict against ``TOLERANCES``: e within 1 % of the exported e;
on the sliding branch of an oblique impact, the achieved μ_f within 3 % of the exported
μ_f (off the sliding branch μ_f from (2.9) is only a bound, and is not judged); where the
pair has a measured β, Ψ_out within 10 % of Walton's relation with β, μ_f and e
(max(−βΨ_in, Ψ_in − μ_f(1+e)(1+1/K²)), (2.6)–(2.7)). A code whose export says it cannot
set its tangential stiffness per pair (``REBOUND_LIMIT`` of its writer: LIGGGHTS, Yade)
gets the verdict "stated limit" for that comparison, with the deviation shown, instead of
a failure. A verification passes only when no checked record fails and at least one was
checked.
"""

from __future__ import annotations

import math
import shutil
import tempfile
import time
from collections.abc import Iterable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from granudb.dem import deck, lammps, liggghts, runs, yade
from granudb.dem.runs import Case
from granudb.dem.spec import TOLERANCES, DemModel
from granudb.physics.impact import (
    GROSS_SLIP,
    TANGENTIAL_REGIME_NAMES,
    gyration_factor,
    maw_chi,
    maw_psi,
    stiffness_ratio,
    tangential_regime,
    walton_rebound,
)

PASS, FAIL, LIMIT, NOT_CHECKED = "pass", "fail", "stated limit", "not checked"

#: Code name → the binary that runs it (Debian packages liggghts, lammps, yade).
BINARIES = {"liggghts": "liggghts", "lammps": "lmp", "yade": "yade"}
WRITERS = {"liggghts": liggghts, "lammps": lammps, "yade": yade}


@dataclass(frozen=True)
class Record:
    """One collision in one code: what was asked and what the code gave back."""

    code: str
    pair: str
    kind: str  # "normal", "oblique" or "sphere-sphere"
    speed_m_s: float
    angle_deg: float
    status: str  # "checked" or "not checked"
    target_e: float
    achieved_e: float | None = None
    e_rel_error: float | None = None
    psi_in: float | None = None
    psi_out: float | None = None
    psi_out_walton: float | None = None  # Walton's relation with β where known, else sliding
    rebound_rel_error: float | None = None  # Ψ_out against Walton's, where β is known
    target_beta: float | None = None
    achieved_beta: float | None = None  # −Ψ_out/Ψ_in
    target_friction: float | None = None
    achieved_friction: float | None = None
    friction_rel_error: float | None = None
    regime: str | None = None  # Maw's regime of the oblique impact (sliding branch or not)
    law_restitution: float | None = None  # an immersed pair's e(St) at this impact's speed
    law_gap: float | None = None  # achieved e − e(St): what a constant e misses
    seconds: float | None = None
    note: str = ""
    verdict: str = NOT_CHECKED  # "pass", "fail", "stated limit" or "not checked"
    reason: str = ""  # what failed, against which tolerance
    rebound_limit: str | None = None  # the deck's stated limit of Ψ_out here, if any
    stated_psi_out: float | None = None  # where so, the Ψ_out the deck states instead
    stated_rel_error: float | None = None  # Ψ_out against it


def installed_codes() -> dict[str, str | None]:
    """Each runnable code and the path of its binary, or None when it is not installed."""
    return {code: shutil.which(binary) for code, binary in BINARIES.items()}


def cases(
    model: DemModel,
    speeds: Sequence[float] = (0.1, 0.3, 0.5),
    angles_deg: Sequence[float] = (30.0, 60.0),
    oblique_speed: float | None = None,
) -> list[Case]:
    """Normal and oblique wall impacts for every particle/wall pair; head-on for particle pairs."""
    out: list[Case] = []
    v_oblique = oblique_speed or model.characteristic_velocity_m_s
    for p in model.particles:
        for w in model.walls:
            out += [Case(p.name, w.name, v, 0.0) for v in speeds]
            out += [Case(p.name, w.name, v_oblique, a) for a in angles_deg]
            sticking = deck.sticking_angle(model.pair(p.name, w.name))
            if sticking is not None and sticking not in angles_deg:
                out.append(Case(p.name, w.name, v_oblique, sticking))
        for q in model.particles:
            if model.index(q.name) >= model.index(p.name):
                out += [Case(p.name, q.name, v, 0.0) for v in speeds]
    return out


def verify(
    model: DemModel,
    case_list: Iterable[Case] | None = None,
    *,
    codes: Sequence[str] = ("liggghts", "lammps", "yade"),
    clamp: bool = False,
    workdir: Path | None = None,
) -> list[Record]:
    """Export ``model`` for each code, run every case in it, return one record per run."""
    todo = list(case_list) if case_list is not None else cases(model)
    found = installed_codes()
    records: list[Record] = []
    for code in codes:
        binary = found.get(code)
        if binary is None:
            records += [
                _record(model, code, c, None, "not checked", f"{BINARIES[code]} not found")
                for c in todo
            ]
            continue
        fragment = WRITERS[code].write(model, clamp=clamp)
        with tempfile.TemporaryDirectory(prefix=f"granudb-{code}-", dir=workdir) as tmp:
            records += _run_code(model, code, binary, fragment, todo, Path(tmp))
    return records


def _run_code(
    model: DemModel, code: str, binary: str, fragment: str, todo: list[Case], tmp: Path
) -> list[Record]:
    if code == "yade":
        script = tmp / "verify.py"
        script.write_text(runs.yade_script(model, fragment, todo))
        start = time.perf_counter()
        output = runs.run([binary, "-n", "-x", str(script)], tmp, timeout=600)
        per_case = (time.perf_counter() - start) / max(len(todo), 1)
        lines = [ln for ln in output.splitlines() if ln.startswith("GRANUDB ")]
        if len(lines) != len(todo):
            runs.parse(output, code)  # raises with the code's own last words
        return [
            _record(model, code, c, runs.parse(ln, code), "checked", seconds=per_case)
            for c, ln in zip(todo, lines, strict=True)
        ]

    def one(index_case: tuple[int, Case]) -> Record:
        index, case = index_case
        folder = tmp / f"case{index}"
        folder.mkdir()
        build = runs.liggghts_input if code == "liggghts" else runs.lammps_input
        (folder / "in.granudb").write_text(build(model, fragment, case))
        start = time.perf_counter()
        output = runs.run([binary, "-in", "in.granudb", "-log", "none", "-echo", "none"], folder)
        seconds = time.perf_counter() - start
        return _record(model, code, case, runs.parse(output, code), "checked", seconds=seconds)

    with ThreadPoolExecutor(max_workers=4) as pool:
        return list(pool.map(one, enumerate(todo)))


def _record(
    model: DemModel,
    code: str,
    case: Case,
    result: tuple[float, float, float, float] | None,
    status: str,
    note: str = "",
    seconds: float | None = None,
) -> Record:
    pair = model.pair(case.particle, case.target)
    assert pair is not None
    wall = model.type(case.target).is_wall
    kind = "sphere-sphere" if not wall else ("oblique" if case.angle_deg else "normal")
    base: dict[str, Any] = dict(
        code=code,
        pair=f"{case.particle}/{case.target}",
        kind=kind,
        speed_m_s=case.speed,
        angle_deg=case.angle_deg,
        target_e=pair.restitution.value,
    )
    if result is None:
        return Record(status=status, note=note, **base)
    vx1, vz1, wy1, vz2 = result
    e = (vz1 - vz2) / case.v_normal  # relative normal velocity out over in (docs/physics.md §9)
    fields: dict[str, Any] = dict(
        achieved_e=e, e_rel_error=e / pair.restitution.value - 1.0, seconds=seconds
    )
    if pair.wet is not None:  # St ∝ V: the law's St at this impact's normal speed
        stokes = pair.wet.stokes_at(pair.restitution.value) * case.v_normal
        law = pair.wet.restitution(stokes / model.characteristic_velocity_m_s)
        gap = e - law
        fields.update(law_restitution=law, law_gap=gap)
        if abs(gap) > TOLERANCES["restitution_law"]:
            fields["note"] = (
                f"e(St) here is {law:.3f}: the constant e is {gap:+.3f} from it (beyond "
                f"±{TOLERANCES['restitution_law']:g}; the deck states the speeds it holds for)"
            )
    if kind == "oblique":
        radius = model.type(case.particle).radius_m
        v_t_out = vx1 - wy1 * radius  # contact point at −R ẑ: v + ω × r, x component
        psi_in = case.v_tangential / case.v_normal
        psi_out = v_t_out / case.v_normal
        factor = float(gyration_factor())
        mu = pair.friction.value
        scales = model.contact(pair)
        ratio = float(stiffness_ratio(scales.reduced_shear_modulus_pa, scales.reduced_modulus_pa))
        regime = int(
            tangential_regime(maw_psi(ratio, case.v_tangential, mu, case.v_normal), maw_chi(ratio))
        )
        achieved_mu = (psi_in - psi_out) / ((1.0 + e) * factor)
        beta = pair.rotational_restitution
        walton = psi_in - mu * (1.0 + pair.restitution.value) * factor
        if beta is not None:
            walton = float(walton_rebound(psi_in, beta.value, mu, pair.restitution.value))
            limit = getattr(WRITERS.get(code), "REBOUND_LIMIT", None)
            if limit is None and code == "lammps":  # the range its deck states
                found = lammps.rebound_range(model, pair)
                if found is not None and not found.holds_at(case.angle_deg):
                    limit = found.sentence(pair)
                    stated = lammps.stated_rebound(model, pair, case.angle_deg)
                    fields.update(stated_psi_out=stated, stated_rel_error=psi_out / stated - 1.0)
            fields.update(
                target_beta=beta.value,
                rebound_rel_error=psi_out / walton - 1.0 if walton else math.nan,
                rebound_limit=limit,
            )
        fields.update(
            psi_in=psi_in,
            psi_out=psi_out,
            achieved_beta=-psi_out / psi_in,
            psi_out_walton=walton,
            target_friction=mu,
            achieved_friction=achieved_mu,
            friction_rel_error=achieved_mu / mu - 1.0 if mu > 0 else math.nan,
            regime=TANGENTIAL_REGIME_NAMES[regime],
            note="" if regime == GROSS_SLIP else "not on the sliding branch: mu_f is a bound",
        )
    fields.update(_verdict(fields))
    return Record(status=status, **base, **fields)


def _verdict(fields: dict[str, Any]) -> dict[str, str]:
    """Pass, fail or stated limit against ``TOLERANCES``, with the failures said."""
    failures: list[str] = []
    limits: list[str] = []
    limit = fields.get("rebound_limit")
    rebound_error = fields.get("rebound_rel_error")
    if rebound_error is not None and not abs(float(rebound_error)) <= TOLERANCES["rebound"]:
        said = (
            f"Psi_out {rebound_error:+.2%} from Walton's with beta (tolerance "
            f"±{TOLERANCES['rebound']:.0%})"
        )
        (limits if limit else failures).append(said + (": stated in the deck" if limit else ""))
    stated = fields.get("stated_rel_error")
    if stated is not None and not abs(float(stated)) <= TOLERANCES["rebound"]:
        failures.append(  # the deck states what its code gives here: that claim is judged
            f"Psi_out {float(stated):+.2%} from the Psi_out the deck states for this angle "
            f"(tolerance ±{TOLERANCES['rebound']:.0%})"
        )
    e_error = float(fields["e_rel_error"])
    if not abs(e_error) <= TOLERANCES["restitution"]:
        failures.append(f"e {e_error:+.2%} (tolerance ±{TOLERANCES['restitution']:.0%})")
    mu_error = fields.get("friction_rel_error")
    sliding = fields.get("regime") == TANGENTIAL_REGIME_NAMES[GROSS_SLIP]
    if sliding and mu_error is not None and not abs(float(mu_error)) <= TOLERANCES["friction"]:
        failures.append(f"mu_f {mu_error:+.2%} (tolerance ±{TOLERANCES['friction']:.0%})")
    verdict = FAIL if failures else (LIMIT if limits else PASS)
    return {"verdict": verdict, "reason": "; ".join(failures + limits)}


def passed(records: Sequence[Record]) -> bool:
    """True when at least one record was checked and no checked record failed (a stated
    limit is not a failure: the export says so in the deck)."""
    checked = [r for r in records if r.status == "checked"]
    return bool(checked) and all(r.verdict in (PASS, LIMIT) for r in checked)


def summary(records: Sequence[Record]) -> str:
    """One line: how many runs passed, failed and were not checked, and the verdict."""
    counts = {v: sum(r.verdict == v for r in records) for v in (PASS, FAIL, LIMIT, NOT_CHECKED)}
    said = ", ".join(f"{n} {v}" for v, n in counts.items() if n)
    if not any(r.status == "checked" for r in records):
        return f"{said}: nothing was checked (no DEM code installed), so nothing passed"
    verdict = "PASS" if passed(records) else "FAIL"
    limits = (
        f"e ±{TOLERANCES['restitution']:.0%}, mu_f ±{TOLERANCES['friction']:.0%}, "
        f"Psi_out with beta ±{TOLERANCES['rebound']:.0%}"
    )
    return f"{verdict}: {said} (tolerances {limits})"


@dataclass(frozen=True)
class Judged:
    """One quantity a verification judged: its target, what the code gave, the error and
    the tolerance it is judged against, and the verdict."""

    quantity: str
    target: float
    achieved: float
    error: float
    tolerance: float
    verdict: str


def judged(record: Record) -> list[Judged]:
    """The quantities ``record``'s verdict rests on, and only those: e always; μ_f where
    the impact slides throughout (elsewhere (2.9) gives only a bound); Ψ_out where the
    pair has a measured β (a "stated limit" where the deck states it cannot hold there)."""
    if record.status != "checked" or record.achieved_e is None or record.e_rel_error is None:
        return []

    def verdict(error: float, tolerance: float, limit: bool = False) -> str:
        return PASS if abs(error) <= tolerance else (LIMIT if limit else FAIL)

    out = [
        Judged("e", record.target_e, record.achieved_e, record.e_rel_error,
               TOLERANCES["restitution"], verdict(record.e_rel_error, TOLERANCES["restitution"]))
    ]  # fmt: skip
    sliding = record.regime == TANGENTIAL_REGIME_NAMES[GROSS_SLIP]
    if sliding and record.target_friction is not None and record.friction_rel_error is not None:
        out.append(
            Judged("mu_f", record.target_friction, float(record.achieved_friction or 0.0),
                   record.friction_rel_error, TOLERANCES["friction"],
                   verdict(record.friction_rel_error, TOLERANCES["friction"]))
        )  # fmt: skip
    if record.target_beta is not None and record.rebound_rel_error is not None:
        out.append(
            Judged("Psi_out", float(record.psi_out_walton or 0.0), float(record.psi_out or 0.0),
                   record.rebound_rel_error, TOLERANCES["rebound"],
                   verdict(record.rebound_rel_error, TOLERANCES["rebound"],
                           bool(record.rebound_limit)))
        )  # fmt: skip
    if record.stated_psi_out is not None and record.stated_rel_error is not None:
        out.append(
            Judged("Psi_out (as the deck states)", record.stated_psi_out,
                   float(record.psi_out or 0.0), record.stated_rel_error, TOLERANCES["rebound"],
                   verdict(record.stated_rel_error, TOLERANCES["rebound"]))
        )  # fmt: skip
    return out


def table(records: Sequence[Record]) -> str:
    """Records as a plain-text table: one line per quantity judged (``judged``), with its
    target, what the code gave, the error, the tolerance and the verdict; nothing that is
    not judged. A stated limit is explained once below the table, as the deck states it."""
    code, pair, kind = (
        max([len(title), *(len(getattr(r, name)) for r in records)])
        for title, name in (("code", "code"), ("pair", "pair"), ("kind", "kind"))
    )
    each = {id(r): judged(r) for r in records}
    width = max([8, *(len(j.quantity) for js in each.values() for j in js)])
    rows = [
        f"{'code':{code}} {'pair':{pair}} {'kind':{kind}} {'V m/s':>6} {'angle':>5} "
        f"{'quantity':{width}} {'target':>9} {'achieved':>9} {'error':>8} {'tolerance':>9}  verdict"
    ]
    limits: dict[str, str] = {}
    for r in records:
        start = f"{r.code:{code}} {r.pair:{pair}} {r.kind:{kind}} {r.speed_m_s:6.2f} "
        start += f"{r.angle_deg:5.1f} "
        if r.status != "checked":
            rows.append(f"{start}not checked ({r.note})")
            continue
        for j in each[id(r)]:
            mark = ""
            if j.verdict == LIMIT and r.rebound_limit:
                mark = f" [{limits.setdefault(r.rebound_limit, str(len(limits) + 1))}]"
            rows.append(
                f"{start}{j.quantity:{width}} {j.target:9.5f} {j.achieved:9.5f} {j.error:+8.2%} "
                f"{'±' + format(j.tolerance, '.0%'):>9}  {j.verdict.upper()}{mark}"
            )
    rows += [f"[{n}] stated limit in the deck: {text}" for text, n in limits.items()]
    rows.append(summary(records))
    return "\n".join(rows)
