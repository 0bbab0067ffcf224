"""From stored materials, published values, fits and predictions to DEM inputs that the
real codes are checked to reproduce (``granudb dem export|verify``).

A simulation has one fluid (or none), particle types and walls. For each particle/wall
pair e_dry and μ_f are the ones ``granudb pair`` uses for the same pair, fluid and speed
(one record: ``derive_pair`` and its ``dry_values``), labelled as ``pair`` labels them
(measured for the pair, from the materials' own values, borrowed, or the lubricated (5.8));
an immersed e is the prediction ``pair`` makes, e = e_dry exp(−35/St_am) (Legendre et al.
2006). A published value of the pair that this record does not use is named in the
comment with the reason. ``values`` chooses what else comes in:

- ``values="published"`` (default): Walton's β of the pair and fluid where one is
  published (``pair`` has none);
- ``values="dataset"``: a dataset's Walton fit (μ_f and β with their intervals) and its
  runs' mean e, in place of ``pair``'s values, said so;
- ``values="predicted"``: ``pair``'s values only, no β.

Each value's interval (for ``parameter_set`` low / high) is the source's ± of that very
value, else the materials' stored u, else the u ``pair`` propagates from the stated inputs,
and the comment says which.

Particle–particle pairs have no measurement in the paper: they take the particle's values
on the first wall, and the comment says so.
"""

from __future__ import annotations

import math
from dataclasses import asdict, replace
from pathlib import Path
from typing import Any

from granudb.analysis import fits
from granudb.api import inputs
from granudb.api.database import opened
from granudb.db import catalog_rows, lookup_rows, sources
from granudb.dem import (
    PARAMETER_SETS,
    WRITER_NAMES,
    DemModel,
    PairParameters,
    ParticleType,
    Value,
    lammps,
    liggghts,
    mercurydpm,
    predicted_wet_restitution,
    yade,
)
from granudb.dem.spec import COVERAGE_FACTOR, TOLERANCES, identifier
from granudb.dem.verify import Record, judged, passed, summary, table, verify
from granudb.errors import ValidationError
from granudb.output_files import write_text
from granudb.reporting.pinned import announce_pinned
from granudb.scenario.collision_query import CollisionQuery
from granudb.scenario.collisions import select_collisions
from granudb.scenario.dry_values import NO_IMMERSED
from granudb.scenario.fluid_state import fluid_state
from granudb.scenario.pair import derive_pair, is_dry

#: The codes ``dem_export`` writes for, and those ``dem_verify`` runs.
DEM_CODES = WRITER_NAMES
VERIFY_CODES = ("liggghts", "lammps", "yade")
WRITERS = {"liggghts": liggghts, "lammps": lammps, "yade": yade, "mercurydpm": mercurydpm}


def _provenance(basis: str, source: str) -> str:
    """A dry value's label in a deck's comment, from its basis and source as
    ``granudb.dry_values`` gives them: "measured for steel on Zerodur (…)" and
    "borrowed: …" say themselves; the materials' combination says so."""
    return f"from the materials' own values: {source}" if basis == "materials" else source


VALUE_SOURCES = ("published", "dataset", "predicted")
DEM_VALUE_SOURCES = VALUE_SOURCES


#: What a DEM export reads from the published values: ē, μ_f and Walton's β, with the
#: physical range an interval of each is cut to.
PUBLISHED_QUANTITIES = {
    "normal_restitution_mean": (0.0, 1.0),
    "sliding_friction": (0.0, math.inf),
    "rotational_restitution": (-1.0, 1.0),
}


def _is_immersed(row: dict[str, Any]) -> bool:
    return row["fluid"] is not None or (row["label"] or "").startswith("immersed")


def _published(session: Any, particle: str, wall: str, fluid: str | None) -> dict[str, Any]:
    """The published rows of the pair in ``fluid`` (None: dry), by quantity (the first of
    each): {quantity: row}."""
    found: dict[str, Any] = {}
    for row in sources.published_records(session):
        same_pair = (row["particle"], row["wall"]) == (particle, wall)
        if not same_pair or row["quantity"] not in PUBLISHED_QUANTITIES:
            continue
        if _is_immersed(row) != (fluid is not None) or (row["fluid"] and row["fluid"] != fluid):
            continue
        found.setdefault(row["quantity"], row)
    return found


def _printed(row: dict[str, Any]) -> str:
    return f"{row['source']} {row['source_locator']}: {row['value_as_printed']}"


def _source_u(
    session: Any, pair: tuple[str, str], quantity: str, value: float, immersed: bool
) -> tuple[float | None, str]:
    """The ± a published row prints for this very value of the pair (dry, or immersed in
    any liquid), or (None, "")."""
    for row in sources.published_records(session):
        if (row["particle"], row["wall"]) != pair or row["quantity"] != quantity:
            continue
        if _is_immersed(row) == immersed and row["value"] == value and row["uncertainty"]:
            return float(row["uncertainty"]), f"(the source's ±: {_printed(row)})"
    return None, ""


def _materials_u(result: Any, column: str, value: float) -> tuple[float | None, str]:
    """u of a dry value combined from the two materials' own values (``dry_values``'
    rule) from their stored u: the chosen one's for the lower e, GUM's for √(μ₁μ₂);
    (None, "") where an input's u is not stated."""
    same = result.wall["name"] == result.particle["name"]
    bodies = [result.particle] + ([] if same else [result.wall])
    known = [m for m in bodies if m.get(column) is not None]
    if column == "dry_restitution" or len(known) == 1:
        chosen = next((m for m in known if m[column] == value), None)
        u = None if chosen is None else chosen.get(f"u_{column}")
        if chosen is None or not u:
            return None, ""
        return u, f"(the stated u of {chosen['name']}'s {column.replace('_', ' ')})"
    if any(not m.get(f"u_{column}") for m in known):
        return None, ""
    relative = math.hypot(*(m[f"u_{column}"] / m[column] for m in known)) / 2.0
    return value * relative, "(GUM, from the stated u of both materials' dry friction)"


def _stated(u: Any) -> float:
    """A propagated u as a number: 0 where ``pair`` states none (None or NaN: no input
    that reaches it carries one)."""
    return float(u) if u is not None and math.isfinite(float(u)) and u > 0 else 0.0


def _predicted(
    session: Any, particle: str, wall: str, fluid: str | None, scenario: dict[str, Any], pinned: Any
) -> Any:
    return derive_pair(session, particle, wall, fluid=fluid, dataset_id=pinned, **scenario)


def _friction(session: Any, result: Any, material: str, wall: str, fluid: Any) -> Value:
    """μ_f as ``granudb pair`` uses it, labelled as it labels it, with its interval: the
    source's ± of that very value, else the materials' stated u, else the u ``pair``
    propagates; a published value for the pair that the record does not use is named."""
    derived, pair_dry = result.derived, result.dry
    used = float(derived["friction_coefficient_used"])
    lubricated = (
        fluid is not None
        and derived.get("lubricated_friction_state") == "in_range"
        and used == derived.get("lubricated_friction")
    )
    immersed = fluid is not None and not lubricated and used == pair_dry.immersed_friction
    u_mu, stated = None, ""
    if lubricated:
        said = f"predicted: lubricated μ_f (5.8) of {material}/{wall} at the stated speed"
    else:  # the pair's dry (or, asperities touching in a liquid, immersed) value
        kind, basis, source = (
            ("immersed", pair_dry.immersed_friction_basis, pair_dry.immersed_friction_source)
            if immersed
            else ("dry", pair_dry.friction_basis, pair_dry.friction_source)
        )
        said = f"the {kind} friction {used:g} granudb pair uses, {_provenance(basis, source)}"
        if fluid is not None:  # the export is of a normal impact: (5.8) has no sliding speed
            said += " (the export has no sliding speed, so (5.8) gives no lubricated μ_f)"
        if basis == "pair":
            in_liquid = immersed and not source.startswith(NO_IMMERSED)  # its own value
            u_mu, stated = _source_u(session, (material, wall), "sliding_friction", used, in_liquid)
        elif basis == "materials":
            u_mu, stated = _materials_u(result, "dry_friction", used)
    propagated = _stated(derived.get("u_friction_coefficient_used"))
    if u_mu is None and propagated:
        u_mu, stated = float(propagated), "(propagated, GUM, as granudb pair gives it)"
    other = _published(session, material, wall, fluid.name if fluid else None).get(
        "sliding_friction"
    )
    if other is not None and other["value"] != used:
        said += (
            f"; not the published {_printed(other)}: granudb's pair values do not hold it "
            f"for {material} on {wall}{' in a liquid' if fluid else ''}, so granudb pair does "
            "not use it either"
        )
    return Value.uncertain(used, said, u_mu, stated, PUBLISHED_QUANTITIES["sliding_friction"])


def _dry_restitution(session: Any, result: Any, material: str, wall: str) -> Value:
    """e_dry as ``granudb pair`` uses it (Thornton's past yield), with its interval: the
    source's ± of that very value, else the materials' stated u."""
    derived, pair_dry = result.derived, result.dry
    ceiling = float(derived["restitution_ceiling"])
    said = _provenance(pair_dry.restitution_basis, pair_dry.restitution_source)
    u_e, stated = None, ""
    if derived.get("restitution_model") == "elastic_plastic":
        said += f"; past yield at the stated speed Thornton (1997) gives {ceiling:.3g}"
    elif pair_dry.restitution_basis == "pair":
        u_e, stated = _source_u(
            session, (material, wall), "normal_restitution_mean", ceiling, False
        )
    elif pair_dry.restitution_basis == "materials":
        u_e, stated = _materials_u(result, "dry_restitution", ceiling)
    return Value.uncertain(
        ceiling, said, u_e, stated, PUBLISHED_QUANTITIES["normal_restitution_mean"]
    )


def _pair_values(
    session: Any,
    particle: Any,
    wall: str,
    fluid: Any,
    scenario: dict[str, Any],
    values: str,
    dataset: Any,
    pinned: int | None = None,
    parameter_set: str = "central",
) -> tuple[Any, Any, Any, Any]:
    """(restitution Value, friction Value, WetParameters or None, β Value or None) for one
    pair, each with its interval where one is stated and at ``parameter_set``'s end of it
    (``Value.at``); with ``pinned`` (a dataset's id) the catalogue as that dataset's runs
    use it.

    e_dry and μ_f are ``granudb pair``'s (one record: ``derive_pair`` and its
    ``dry_values``), labelled as it labels them (``_friction``, ``_dry_restitution``).
    Only ``values="dataset"`` replaces them (by the dataset's fit, saying so); Walton's β
    is published (``values="published"``) or fitted (``"dataset"``): pair has none."""
    material = particle.material
    result = _predicted(session, material, wall, fluid.name if fluid else None, scenario, pinned)
    friction = _friction(session, result, material, wall, fluid)
    dry = _dry_restitution(session, result, material, wall)
    beta = None
    if values == "published":
        row = _published(session, material, wall, fluid.name if fluid else None).get(
            "rotational_restitution"
        )
        if row is not None:
            beta = Value.uncertain(
                row["value"], f"measured: {_printed(row)}", row["uncertainty"],
                "(the source's ±)", PUBLISHED_QUANTITIES["rotational_restitution"],
            )  # fmt: skip
    elif values == "dataset":
        friction, dry, beta = _dataset_values(
            session, dataset, material, wall, fluid, friction, dry
        )
    beta = None if beta is None else beta.at(parameter_set)
    friction = friction.at(parameter_set)
    if fluid is None:
        return dry.at(parameter_set), friction, None, beta
    restitution, law = _wet_restitution(particle, fluid, scenario, dry, result, parameter_set)
    if restitution.value == 0.0:
        raise ValidationError(
            f"restitution {material}/{wall}",
            "0",
            "no rebound is predicted (normal Stokes number at or below the critical 10 at this "
            "speed): no DEM contact law represents that; give a higher --velocity",
        )
    return restitution, friction, law, beta


def _wet_restitution(
    particle: Any, fluid: Any, scenario: dict[str, Any], dry: Value, result: Any, parameter_set: str
) -> tuple[Value, Any]:
    """The predicted e_wet (``predicted_wet_restitution``, the one ``pair`` makes) with the
    interval ± 2u, u by GUM from the dry e's u and the u ``pair`` propagates from the
    inputs' stated ones, at ``parameter_set``'s end; and the e(St) law through it."""

    def wet(e_dry: Value) -> tuple[Value, Any]:
        return predicted_wet_restitution(
            e_dry, particle, fluid.viscosity_pa_s, scenario["speed_m_s"], fluid.density_kg_m3
        )

    restitution, law = wet(dry)
    u_dry = None  # the dry e's u: half the wider side of its interval (one side may be cut)
    if dry.high is not None and dry.low is not None:
        u_dry = max(dry.value - dry.low, dry.high - dry.value) / COVERAGE_FACTOR
    u_flow = _stated(result.derived.get("u_predicted_restitution"))
    share = 0.0 if u_dry is None else restitution.value / dry.value * u_dry
    if share or u_flow:  # e_wet ∝ e_dry: GUM's sum of the two contributions
        parts = [f"{share:.2g} from the dry e's u"] if share else []
        if u_flow:
            parts.append(f"{u_flow:.2g} from the inputs' stated u as granudb pair gives it")
        restitution = Value.uncertain(
            restitution.value, restitution.provenance, math.hypot(share, u_flow),
            f"(propagated, GUM: {' and '.join(parts)})",
            PUBLISHED_QUANTITIES["normal_restitution_mean"],
        )  # fmt: skip
    restitution = restitution.at(parameter_set)
    if parameter_set != "central":  # the law through the e written
        law = wet(dry.at(parameter_set))[1]
        if restitution.value >= law.max_restitution:
            law = replace(law, max_restitution=min(1.0, restitution.value * 1.000001))
    return restitution, law


def _dataset_values(
    session: Any, dataset: str, particle: str, wall: str, fluid: Any, friction: Any, dry: Any
) -> tuple[Any, Any, Any]:
    name, version = inputs.dataset_ref(dataset)  # NAME@VERSION: that version's runs
    query = CollisionQuery(
        dataset=name,
        version=version,
        particle=particle,
        wall=wall,
        fluid=fluid.name if fluid else "dry",
    )
    beta = None
    for fit in fits.walton(select_collisions(session, query)):
        b = fit.get("rotational_restitution")
        if b is not None and b == b and -1.0 < b < 1.0:
            beta = _fitted(
                fit, "rotational_restitution", "Walton fit of the sticking runs", dataset
            )
        mu = fit.get("sliding_friction")
        if mu is not None and mu == mu:
            friction = _instead(_fitted(fit, "sliding_friction", "Walton fit", dataset), friction)
        elif fit.get("reason"):
            friction = replace(
                friction,
                provenance=f"{friction.provenance}; dataset {dataset} does not determine μ_f "
                f"({fit['reason']})",
            )
        e = fit.get("normal_restitution_mean")
        if e is not None and e == e and fluid is None:
            fitted = _fitted(fit, "normal_restitution", "mean e of the dry runs", dataset, e)
            dry = _instead(fitted, dry)
    return friction, dry, beta


def _instead(fitted: Value, record: Value) -> Value:
    """A dataset's fitted value, saying which value of ``granudb pair`` it replaces."""
    return replace(
        fitted,
        provenance=f"{fitted.provenance}; --values dataset: instead of the {record.value:g} "
        "granudb pair uses",
    )


def _fitted(fit: dict[str, Any], name: str, what: str, dataset: str, value: Any = None) -> Value:
    """A fitted value (``fit[name]``, or ``value``) with its 95 % bootstrap interval
    (``name``_low/_high), or the fit's reason why it has none."""
    central = float(fit[name] if value is None else value)
    bounds = PUBLISHED_QUANTITIES.get(name, PUBLISHED_QUANTITIES["normal_restitution_mean"])
    central = min(max(central, bounds[0]), bounds[1])
    low, high = fit.get(f"{name}_low"), fit.get(f"{name}_high")
    said = f"dataset {dataset}: {what}"
    if low is not None and high is not None and high - low > 1e-9 * abs(central):
        low, high = max(float(low), bounds[0]), min(float(high), bounds[1])
        if low <= central <= high:
            method = fit.get(f"{name}_interval_method") or "studentized bootstrap"
            return Value(central, said, low, high, f"95 % interval: {method}")
    symbol = {"sliding_friction": "μ_f", "rotational_restitution": "β"}.get(name, "ē")
    why = [p for p in str(fit.get("reason") or "").split("; ") if f"of {symbol}" in p]
    return Value(
        central,
        f"{said}, interval not determined" + (f" ({why[0].split(': ', 1)[-1]})" if why else ""),
    )


#: What a DEM model is built from, besides the materials, and the defaults.
MODEL_OPTIONS = {
    "diameter": None, "velocity": None, "fluid": None, "values": "published", "dataset": None,
    "parameter_set": "central",
}  # fmt: skip


def dem_model(particles: list[str], walls: list[str], *, db: Any = None, **options: Any) -> Any:
    """The ``granudb.dem.DemModel`` for these particle and wall materials, ``options``
    being ``MODEL_OPTIONS`` (diameter, velocity, fluid, values, dataset, parameter_set)."""
    inputs.known_options(options, MODEL_OPTIONS, "a DEM model option")
    diameter, velocity, fluid, values, dataset, parameter_set = (
        {**MODEL_OPTIONS, **options}[k] for k in MODEL_OPTIONS
    )
    parameter_set = inputs.choice(parameter_set, PARAMETER_SETS, "parameter_set")
    if values not in VALUE_SOURCES:
        raise ValidationError(
            "values", values, f"must be one of {', '.join(VALUE_SOURCES)}", parameter=True
        )
    if values == "dataset" and not dataset:
        raise ValidationError("dataset", "(none)", "is needed with values=dataset", parameter=True)
    if not particles or not walls:
        raise ValidationError(
            "particles", particles, "need at least one particle and one wall", parameter=True
        )
    for name, given in (("diameter", diameter), ("velocity", velocity)):
        if given is None:
            raise inputs.missing(name)
    scenario: dict[str, Any] = {  # neither is None: both were required above
        "diameter_m": inputs.quantity(diameter, "diameter_m", "diameter"),
        "speed_m_s": inputs.quantity(velocity, "impact_speed_m_s", "velocity"),
    }
    with opened(db) as database, database.reading() as session:
        pinned = None  # values=dataset: the catalogue as the dataset's runs use it
        if values == "dataset":
            row = lookup_rows.dataset_row(session, *inputs.dataset_ref(dataset))
            pinned = row.id
            announce_pinned(session, pinned, f"{row.name}@{row.version}")
        fluid_row = None if is_dry(fluid) else catalog_rows.get_fluid_row(session, fluid, pinned)
        state = fluid_state(fluid_row) if fluid_row else None
        types: list[ParticleType] = []
        pairs: list[PairParameters] = []
        taken: set[str] = set()
        for name in particles:
            m = catalog_rows.get_material_row(session, name, pinned)
            types.append(
                ParticleType(
                    identifier(m.name, taken),
                    m.youngs_modulus_pa,
                    m.poisson_ratio,
                    m.density_kg_m3,
                    scenario["diameter_m"],
                    material=m.name,
                )
            )
        for name in walls:
            m = catalog_rows.get_material_row(session, name, pinned)
            types.append(
                ParticleType(
                    identifier(f"{m.name}_wall", taken),
                    m.youngs_modulus_pa,
                    m.poisson_ratio,
                    m.density_kg_m3,
                    None,
                    is_wall=True,
                    material=m.name,
                )
            )
        on_first_wall: dict[str, tuple[Any, Any, Any, str]] = {}
        for particle in [t for t in types if not t.is_wall]:
            for wall in [t for t in types if t.is_wall]:
                e, mu, law, beta = _pair_values(
                    session, particle, wall.material, state, scenario, values, dataset, pinned,
                    parameter_set,
                )  # fmt: skip
                on_first_wall.setdefault(particle.name, (e, mu, law, wall.name))
                pairs.append(
                    PairParameters(
                        particle.name, wall.name, e, mu, wet=law, rotational_restitution=beta
                    )
                )
    pairs += _particle_pairs([t for t in types if not t.is_wall], on_first_wall)
    return DemModel(types, pairs, scenario["speed_m_s"], parameter_set)


def _particle_pairs(particles: list[Any], on_wall: dict[str, Any]) -> list[Any]:
    pairs = []
    for i, first in enumerate(particles):
        for second in particles[i:]:
            e, mu, law, wall = on_wall[first.name]
            note = (
                f"borrowed from {first.name} on {wall}, assumed for {first.name}/"
                f"{second.name}: no {first.name}/{second.name} value is stored"
            )
            pairs.append(
                PairParameters(
                    first.name,
                    second.name,
                    Value(e.value, f"{note} ({e.provenance})", e.low, e.high, e.interval),
                    Value(mu.value, f"{note} ({mu.provenance})", mu.low, mu.high, mu.interval),
                    wet=law,
                )
            )
    return pairs


@inputs.shows_keywords(MODEL_OPTIONS)
def dem_export(
    code: str,
    particles: list[str],
    walls: list[str],
    *,
    clamp: bool = False,
    output: str | Path | None = None,
    db: Any = None,
    **options: Any,
) -> str:
    """The input fragment for ``code`` (liggghts, lammps, yade or mercurydpm) for these
    particle and wall materials in ``fluid``, every number commented with its source.
    ``options`` are ``MODEL_OPTIONS``: ``diameter`` and ``velocity`` (required), ``fluid``,
    ``values``, ``dataset`` and ``parameter_set``.

    ``values`` says where e, μ_f and Walton's β come from: "published" (the paper's fits
    where the database has them), "dataset" (``dataset``'s Walton fit) or "predicted" (no
    β). Each value's comment gives its interval where one is stated (a fit's 95 %
    interval, or ± 2u from a stated standard uncertainty u); ``parameter_set`` "low" or
    "high" writes every value at that end of its interval, for sensitivity runs
    (``PARAMETER_SETS``; a value without an interval keeps its central value and its
    comment says so). An immersed pair's comment states the speeds over which its constant
    e holds. A value the code cannot take is refused naming its rule, or with
    ``clamp=True`` written at the nearest allowed value with a comment. With ``output``
    the fragment is also written to that new file (an existing one is refused). Returns
    the fragment.

    Examples
    --------
    >>> import granudb
    >>> text = granudb.dem_export("liggghts", ["steel"], ["Zerodur"], diameter="12.7 mm",
    ...                           velocity="0.3 m/s", db=db)
    >>> "coefficientFriction peratomtypepair 2" in text and "μ_f = 0.11 ± 0.003" in text
    True
    >>> low = granudb.dem_export("liggghts", ["steel"], ["Zerodur"], diameter="12.7 mm",
    ...                          velocity="0.3 m/s", parameter_set="low", db=db)
    >>> "Parameter set: LOW" in low and "the low end of the ± 2u" in low
    True
    """
    writer = WRITERS[inputs.choice(code, DEM_CODES, "code")]
    target = None if output is None else Path(inputs.path(output, "output"))
    if target is not None and (target.exists() or target.is_symlink()):
        raise ValidationError(
            "output", str(target), "exists already (choose a new file)", parameter=True
        )
    text: str = writer.write(dem_model(particles, walls, db=db, **options), clamp=clamp)
    if target is not None:
        write_text(target, text, field="output")
    return text


@inputs.shows_keywords(MODEL_OPTIONS)
def dem_verify(
    particles: list[str],
    walls: list[str],
    *,
    codes: tuple[str, ...] | None = None,
    clamp: bool = False,
    db: Any = None,
    **options: Any,
) -> list[Record]:
    """Run the exported parameters in every installed code (LIGGGHTS, LAMMPS, Yade) on
    normal wall impacts at 0.1, 0.3 and 0.5 m/s, oblique ones at 30° and 60° (and, for a
    pair with a measured β, mid-way along Walton's sticking branch) and head-on sphere
    pairs; one record per run, with its verdict against ``VERIFY_TOLERANCES`` (e within
    1 %; μ_f within 3 % on the sliding branch; Ψ_out within 10 % of Walton's relation
    where β is measured, or a "stated limit" the deck explains, in which case the Ψ_out
    the deck states instead is judged), and "not checked" (never "pass") for a code that
    is not installed; ``codes`` chooses some.
    The options are ``dem_export``'s (a low or high ``parameter_set`` is verified as
    written); ``verify_table(records)`` prints them,
    ``verify_passed(records)`` is the overall verdict (the command's exit status).

    Examples
    --------
    >>> import granudb
    >>> records = granudb.dem_verify(["steel"], ["Zerodur"], codes=("liggghts",),
    ...                              diameter="12.7 mm", velocity="0.3 m/s", db=db)
    >>> granudb.api.verify_passed(records), sorted({r.verdict for r in records})
    (True, ['pass', 'stated limit'])
    """
    model = dem_model(particles, walls, db=db, **options)
    chosen = tuple(inputs.choice(c, VERIFY_CODES, "code") for c in codes or VERIFY_CODES)
    return verify(model, codes=chosen, clamp=clamp)


def verify_table(records: list[Record]) -> str:
    """``dem_verify``'s records as a plain-text table (target against achieved, the
    verdict of each run) ending with the summary line."""
    return table(records)


def verify_passed(records: list[Record]) -> bool:
    """The verification's verdict: something was checked and every checked run passed."""
    return passed(records)


def verify_document(records: list[Record]) -> dict[str, Any]:
    """The verification for scripts: the verdict, the summary, the tolerances and every
    record as a dict, with ``judged``: the quantities its verdict rests on (quantity,
    target, achieved, error, tolerance, verdict), as the table prints them."""
    return {
        "passed": passed(records),
        "summary": summary(records),
        "tolerances": dict(VERIFY_TOLERANCES),
        "records": [{**asdict(r), "judged": [asdict(j) for j in judged(r)]} for r in records],
    }


#: The largest relative error a verdict accepts, by quantity.
VERIFY_TOLERANCES = TOLERANCES
