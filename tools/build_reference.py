"""Build the reference library of published collision data (seed_data/reference/).

Run from the repository root: ``python tools/build_reference.py [OUT_DIR]``. It reads the
copies of the public digitisations in ``seed_data/reference/_raw/`` (each file's first line
names its repository, file and commit) and writes one Frictionless Data Package per
published dataset: ``datapackage.json``, ``data/values.csv`` (one row per reported value,
with its source, locator, digitiser, licence, standard uncertainty u and the repository,
file and commit it was read from), ``CITATION.cff`` and ``README.md``.
``tests/reference/test_library.py`` runs this script into a temporary folder and checks the
committed packages are what it writes (so a hand edit of a package is caught).

How u is stated (the ``u_basis`` column says which rule gave each value's u):

- two digitisations of one point: the value is their mean and u half their difference, at
  least the median half-difference of that figure's paired points (two readings that
  happen to coincide do not make a value exact);
- one digitisation of a figure the other also digitised: u is the largest half-difference
  of that figure's paired points;
- one digitisation of a figure nobody else digitised (the rebound angles): u is the
  largest half-difference of the incidence angles read from the paired figures;
- a number printed in a file (a configuration, a table, a measurement list): the rounding
  of its last printed digit, u = half a unit of it / √3 (rectangular);
- a value printed with ± in the paper (Joseph & Hunt's tables): that ±.
"""

from __future__ import annotations

import csv
import json
import math
import re
import statistics
import sys
from decimal import Decimal
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RAW = ROOT / "seed_data" / "reference" / "_raw"
VERSION = "1.0.0"
RELEASED = "2026-11-26"

LETHE = {
    "digitiser": "Lethe developers (chaos-polymtl/lethe)",
    "licence": "LGPL-3.0-only (licence of chaos-polymtl/lethe, README.md at "
    "01be874b0ae38c865feaacd34134a2f79c45ed96)",
    "repository": "https://github.com/chaos-polymtl/lethe",
    "file": "examples/dem/3d-oblique-wall-impact/oblique_wall_impact_postprocessing.py",
    "commit": "255b519263fbb22f758d40763a12290296d53200",
}
KRATOS = {
    "digitiser": "Kratos Multiphysics developers (KratosMultiphysics/Kratos)",
    "licence": "Kratos Multiphysics licence (kratos/license.txt at "
    "9160960d2db83b2e157c251003f745fbb1f9627a defers to each application's licence; "
    "the DEMApplication's own licence file was not found in the read snapshot)",
    "repository": "https://github.com/KratosMultiphysics/Kratos",
    "file": "applications/DEMApplication/test_examples/basic_benchmarks/paper_data/"
    "benchmark4_graph{n}.dat",
    "commit": "650ccb263d910608aa74112ddb4c8fa45ca5ba96",
}
KRATOS_GRAPH = {
    "tangential_restitution": 1,
    "angular_velocity_out_rad_s": 2,
    "rebound_angle_contact_deg": 3,
}
WALBERLA = {
    "digitiser": "waLBerla developers (lssfau/walberla), configuration values",
    "licence": "GPL-3.0-or-later (licence of lssfau/walberla, COPYING.txt)",
    "repository": "https://github.com/lssfau/walberla",
    "commit": "17a9f647db63c0874428cb254b446005ad2d83f6",
}
VSSUQ = {
    "digitiser": "VSSUQ experimenters (W. C. LaMarche, Hrenya Research Group); files by W. Fullmer",
    "licence": "MIT (Copyright (c) 2021 William Fullmer; LICENSE of wfullmer/vssuq, "
    "shipped as LICENSE-vssuq in this package)",
    "repository": "https://github.com/wfullmer/vssuq",
    "commit": "75bc52d37adfa0b4cd6e0029078c4b61683724ca",
}

UNITS = {
    "incidence_angle_deg": "deg",
    "tangential_restitution": "1",
    "angular_velocity_out_rad_s": "rad/s",
    "rebound_angle_centre_deg": "deg",
    "rebound_angle_contact_deg": "deg",
    "normal_restitution": "1",
    "friction_coefficient": "1",
    "impact_speed_m_s": "m/s",
    "diameter_m": "m",
    "density_sphere_kg_m3": "kg/m^3",
    "density_fluid_kg_m3": "kg/m^3",
    "dynamic_viscosity_pa_s": "Pa s",
    "reynolds_number": "1",
    "stokes_number": "1",
    "dry_restitution": "1",
    "poisson_ratio": "1",
    "sphere_poisson_ratio": "1",
    "wall_poisson_ratio": "1",
    "sphere_youngs_modulus_pa": "Pa",
    "wall_youngs_modulus_pa": "Pa",
    "sphere_density_kg_m3": "kg/m^3",
    "sliding_friction": "1",
}

#: What each quantity is, in words (the README and the docs render these).
MEANINGS = {
    "incidence_angle_deg": "angle of the incoming centre-of-mass velocity from the wall normal",
    "tangential_restitution": "e_t = v_t,out / v_t,in of the centre of mass (no spin in)",
    "angular_velocity_out_rad_s": "magnitude of the spin after impact",
    "rebound_angle_centre_deg": "rebound angle of the centre of mass from the normal, "
    "atan(v_t,out / v_n,out) (Lethe's 'rebound angle')",
    "rebound_angle_contact_deg": "rebound angle of the contact point from the normal, "
    "atan((v_t,out + ω_out R) / v_n,out); negative when the contact point recoils "
    "(Kratos's graph 3)",
    "normal_restitution": "e = v_n,out / v_n,in",
    "friction_coefficient": "coefficient of friction measured per collision",
    "reynolds_number": "Re = ρ_f V D / μ at impact, as reported",
    "stokes_number": "St = ρ_p V D / (9 μ) at impact, as reported",
}

FIELDS = [
    ("value_id", "string", "one reported value: dataset point and quantity"),
    ("point", "string", "the run, case or figure point the value belongs to"),
    ("quantity", "string", "what was reported (granudb name, unit in the name or 'unit')"),
    ("value", "number", "the value in the unit of the 'unit' column"),
    ("unit", "string", "unit of value and u"),
    ("u", "number", "standard uncertainty of value (one standard deviation)"),
    ("u_basis", "string", "the rule that gave u"),
    ("role", "string", "measured, derived (by a stated relation) or condition"),
    ("particle", "string", "sphere material"),
    ("wall", "string", "wall or target material"),
    ("fluid", "string", "surrounding fluid (empty: dry)"),
    ("source", "string", "the publication the value comes from"),
    ("locator", "string", "figure, table or file position in the publication"),
    ("digitiser", "string", "who read the value off the figure or wrote it down"),
    ("licence", "string", "licence of the file it was read from"),
    ("repository", "string", "public repository it was read from"),
    ("file", "string", "file in that repository"),
    ("commit", "string", "commit of that file"),
    ("notes", "string", "anything else"),
]


def _read_raw(name: str) -> list[dict[str, str]]:
    lines = (RAW / name).read_text(encoding="utf-8").splitlines()
    return list(csv.DictReader(line for line in lines if not line.startswith("#")))


def rounding_u(text: str) -> float:
    """Half a unit of the last printed digit of ``text``, rectangular: /√3."""
    exponent = Decimal(text.strip()).as_tuple().exponent
    return float(Decimal(5).scaleb(exponent - 1)) / math.sqrt(3)


#: Units of granudb's names by their suffix (longest first), for names not in ``UNITS``.
SUFFIX_UNITS = (
    ("_pa_inv", "1/Pa"),
    ("_rad_s", "rad/s"),
    ("_kg_m3", "kg/m^3"),
    ("_pa_s", "Pa s"),
    ("_n_m", "N m"),
    ("_m_s", "m/s"),
    ("_rad", "rad"),
    ("_deg", "deg"),
    ("_pa", "Pa"),
    ("_c", "degC"),
    ("_m", "m"),
    ("_s", "s"),
)


def unit_of(quantity: str) -> str:
    """The unit of a granudb quantity name: ``UNITS``, else its suffix, else "1"."""
    if quantity in UNITS:
        return UNITS[quantity]
    return next((unit for suffix, unit in SUFFIX_UNITS if quantity.endswith(suffix)), "1")


def printed_rounding_u(printed: str, value: float) -> tuple[float, str]:
    """u of a value printed without ± ("ζ_in = 20°", "η̂ ≈ 375 × 10⁻¹² Pa⁻¹"): the rounding
    of the first number after the last "=" or "≈", carried to the stored unit by the ratio
    value / that number; an order of magnitude ("≈ 10⁻⁴") gets u = the value."""
    tail = re.split(r"[=≈]", printed)[-1]
    if re.match(r"^\s*10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+", tail):
        return abs(value), "an order of magnitude as printed: u = the value"
    numbers = re.findall(r"\d+(?:\.\d+)?(?:e[-+]?\d+)?", tail)
    basis = "rounding of the last printed digit (of the value as printed, in the stored unit)"
    if not numbers or float(numbers[0]) == 0.0:
        return rounding_u(repr(value)), basis
    return rounding_u(numbers[0]) * abs(value / float(numbers[0])), basis


def _row(**kw) -> dict:
    row = {name: "" for name, _, _ in FIELDS}
    row.update(kw)
    row["value_id"] = f"{row['point']}:{row['quantity']}"
    if not row["unit"]:
        row["unit"] = unit_of(row["quantity"])
    return row


def _fmt(x: float) -> str:
    """A number to 10 significant digits."""
    return repr(float(f"{float(x):.10g}"))


# --------------------------------------------------------------------- Kharaz et al. 2001
KHARAZ_SOURCE = (
    "Kharaz, A. H., Gorham, D. A. & Salman, A. D. (2001). An experimental study of the "
    "elastic rebound of spheres. Powder Technology 120(3), 281-291. "
    "doi:10.1016/S0032-5910(01)00283-2"
)
PAIR_TOLERANCE_DEG = 2.0


def _pairs(lethe: list, kratos: list) -> list[tuple]:
    """Points of one figure matched by incidence angle (nearest within 2°)."""
    out, used = [], set()
    for a in lethe:
        best = min(
            (k for k in range(len(kratos)) if k not in used),
            key=lambda k: abs(kratos[k][0] - a[0]),
            default=None,
        )
        if best is not None and abs(kratos[best][0] - a[0]) <= PAIR_TOLERANCE_DEG:
            used.add(best)
            out.append((a, kratos[best]))
        else:
            out.append((a, None))
    out += [(None, kratos[k]) for k in range(len(kratos)) if k not in used]
    return sorted(out, key=lambda p: (p[0] or p[1])[0])


def kharaz_rows() -> tuple[list[dict], list[dict]]:
    lethe = _read_raw("kharaz_lethe.csv")
    kratos = _read_raw("kharaz_kratos.csv")
    series = {}
    for who, rows in (("lethe", lethe), ("kratos", kratos)):
        for r in rows:
            value = float(r["value"])
            if r["series"] == "angular_velocity_out_rad_s":
                value = abs(value)  # Kratos plots the spin negative (its sign convention)
            series.setdefault((r["series"], who), []).append(
                (float(r["incidence_angle_deg"]), value)
            )
    digitisations = []
    for who, rows in (("lethe", lethe), ("kratos", kratos)):
        prov = LETHE if who == "lethe" else KRATOS
        for r in rows:
            file = prov["file"].format(n=KRATOS_GRAPH.get(r["series"], ""))
            digitisations.append(
                {
                    "digitisation": who,
                    "series": r["series"],
                    "incidence_angle_deg": r["incidence_angle_deg"],
                    "value_as_written": r["value"],
                    "file": file,
                    "commit": prov["commit"],
                }
            )
    # half-differences of paired points, per figure and on the angle axis
    paired = {}
    for quantity in ("tangential_restitution", "angular_velocity_out_rad_s"):
        paired[quantity] = _pairs(
            series.get((quantity, "lethe"), []), series.get((quantity, "kratos"), [])
        )
    half_value = {q: max(abs(a[1] - b[1]) / 2 for a, b in p if a and b) for q, p in paired.items()}
    half_angle = max(abs(a[0] - b[0]) / 2 for p in paired.values() for a, b in p if a and b)
    common = {
        "particle": "aluminium oxide",
        "wall": "soda-lime glass",
        "source": KHARAZ_SOURCE,
    }
    rows = []
    figure = {
        "tangential_restitution": "figure of e_t against incidence angle",
        "angular_velocity_out_rad_s": "figure of rebound spin against incidence angle",
        "rebound_angle_centre_deg": "figure of centre-of-mass rebound angle",
        "rebound_angle_contact_deg": "figure of contact-point rebound angle",
    }
    short = {
        "tangential_restitution": "et",
        "angular_velocity_out_rad_s": "omega",
        "rebound_angle_centre_deg": "rcom",
        "rebound_angle_contact_deg": "rcp",
    }

    def emit(quantity, index, a, b, value_u, value_basis, angle_u, angle_basis):
        point = f"{short[quantity]}-{index:02d}"
        who = [p for p, x in (("lethe", a), ("kratos", b)) if x]
        provs = [LETHE if p == "lethe" else KRATOS for p in who]
        prov = {
            key: " | ".join(
                (p[key].format(n=KRATOS_GRAPH.get(quantity, "")) if key == "file" else p[key])
                for p in provs
            )
            for key in ("digitiser", "licence", "repository", "file", "commit")
        }
        points = [x for x in (a, b) if x]
        written = "; ".join(f"{p}: ({x[0]!r}, {x[1]!r})" for p, x in zip(who, points, strict=True))
        angle = sum(x[0] for x in points) / len(points)
        value = sum(x[1] for x in points) / len(points)
        locator = f"{figure[quantity]} (as digitised; digitisations read: {written})"
        rows.append(
            _row(
                point=point,
                quantity="incidence_angle_deg",
                value=_fmt(angle),
                u=_fmt(angle_u),
                u_basis=angle_basis,
                role="measured",
                locator=locator,
                **common,
                **prov,
            )
        )
        rows.append(
            _row(
                point=point,
                quantity=quantity,
                value=_fmt(value),
                u=_fmt(value_u),
                u_basis=value_basis,
                role="measured",
                locator=locator,
                notes=MEANINGS[quantity],
                **common,
                **prov,
            )
        )

    two = (
        "half the difference of the two digitisations (value: their mean), at least the "
        "median half-difference of the figure's paired points"
    )
    floor_value = {
        q: statistics.median(abs(a[1] - b[1]) / 2 for a, b in p if a and b)
        for q, p in paired.items()
    }
    floor_angle = statistics.median(
        abs(a[0] - b[0]) / 2 for p in paired.values() for a, b in p if a and b
    )
    for quantity, pairs in paired.items():
        for i, (a, b) in enumerate(pairs, start=1):
            if a and b:
                u_value = max(abs(a[1] - b[1]) / 2, floor_value[quantity])
                u_angle = max(abs(a[0] - b[0]) / 2, floor_angle)
                emit(quantity, i, a, b, u_value, two, u_angle, two)
            else:
                one = "one digitisation: the largest half-difference of this figure's paired points"
                emit(quantity, i, a, b, half_value[quantity], one, half_angle, one)
    for quantity, who in (
        ("rebound_angle_centre_deg", "lethe"),
        ("rebound_angle_contact_deg", "kratos"),
    ):
        basis = (
            "one digitisation of a figure no other source digitised: the largest "
            "half-difference of the incidence angles of the paired figures"
        )
        for i, x in enumerate(series[(quantity, who)], start=1):
            a, b = (x, None) if who == "lethe" else (None, x)
            emit(quantity, i, a, b, half_angle, basis, half_angle, basis)
    conditions = [
        (
            "impact_speed_m_s",
            "3.9",
            "the impact speed Lethe's example keeps at every angle ('a magnitude of "
            "3.9 m/s') and Chung & Ooi's test 4 uses",
            "Lethe oblique-wall-impact documentation page, Insertion Info",
        ),
        (
            "diameter_m",
            "0.005",
            "5 mm aluminium oxide spheres (Kharaz et al. 2001 abstract)",
            "abstract",
        ),
        (
            "normal_restitution",
            "0.98",
            "Chung & Ooi (2011) test 4 normal restitution 'en = 0.98' as Yade's Test4.py "
            "gives it (seed source yade-chung-ooi-test4); neither digitisation gives "
            "Kharaz et al.'s own e_n: the Walton fit needs it for c = (1+e)·7/2",
            "Yade Test4.py, en (granudb seed source yade-chung-ooi-test4)",
        ),
    ]
    # the material constants and the paper's friction, as granudb's seed sources quote
    # them (seed_data/published_values.csv: lethe-oblique-wall-impact, yade-chung-ooi-test4)
    seeded = {
        ("alumina sphere (Kharaz et al. 2001)", "density_kg_m3"): "sphere_density_kg_m3",
        ("alumina sphere (Kharaz et al. 2001)", "youngs_modulus_pa"): "sphere_youngs_modulus_pa",
        ("alumina sphere (Kharaz et al. 2001)", "poisson_ratio"): "sphere_poisson_ratio",
        ("soda-lime glass anvil (Kharaz et al. 2001)", "youngs_modulus_pa"): (
            "wall_youngs_modulus_pa"
        ),
        ("soda-lime glass anvil (Kharaz et al. 2001)", "poisson_ratio"): "wall_poisson_ratio",
        ("dry alumina on soda-lime glass (Kharaz et al. 2001)", "sliding_friction"): (
            "sliding_friction"
        ),
    }
    with (ROOT / "seed_data" / "published_values.csv").open(encoding="utf-8") as f:
        for r in csv.DictReader(f):
            name = seeded.get((r["label"], r["quantity"]))
            if name is None:
                continue
            u, _ = printed_rounding_u(r["value_as_printed"], float(r["value"]))
            conditions.append(
                (
                    name,
                    _fmt(float(r["value"])),
                    u,
                    f"as granudb's seed source {r['source']} gives it ({r['value_as_printed']}); "
                    + r["notes"],
                    f"{r['source_locator']} (granudb seed source {r['source']}, "
                    "seed_data/published_values.csv)",
                )
            )
    for entry in conditions:
        if len(entry) == 4:  # a number written in the page: the rounding of its digits
            quantity, text, notes, locator = entry
            u = rounding_u(text)
        else:
            quantity, text, u, notes, locator = entry
        rows.append(
            _row(
                point="conditions",
                quantity=quantity,
                value=text,
                u=_fmt(u),
                u_basis="rounding of the last printed digit",
                role="condition",
                locator=locator,
                digitiser="granudb contributors, read from the page the locator names",
                licence="a number quoted as a fact from the page the locator names; no "
                "licence is claimed for it",
                notes=notes,
                **common,
            )
        )
    return rows, digitisations


# -------------------------------------------------------------------------------- VSSUQ
VSSUQ_SOURCE = (
    "VSSUQ repository (2021-2022): measurements of the VSSUQ, a Very Small-Scale particle "
    "fluidization experiment designed and operated by W. C. LaMarche (Hrenya Research Group, "
    "University of Colorado), data and documentation by W. Fullmer. "
    "https://github.com/wfullmer/vssuq (docs/particleprops.rst)"
)
VSSUQ_FILES = [
    ("epp_glass-glass", "normal_restitution", "glass", "glass", "particle-particle"),
    ("epp_glass-hdpe", "normal_restitution", "glass", "HDPE", "particle-particle"),
    ("epp_hdpe-hdpe", "normal_restitution", "HDPE", "HDPE", "particle-particle"),
    ("epw_glass-acrylic", "normal_restitution", "glass", "acrylic", "particle-wall"),
    ("mupp_glass-glass", "friction_coefficient", "glass", "glass", "particle-particle"),
    ("mupp_glass-hdpe", "friction_coefficient", "glass", "HDPE", "particle-particle"),
    ("mupp_hdpe-hdpe", "friction_coefficient", "HDPE", "HDPE", "particle-particle"),
    ("mupw_glass-acrylic", "friction_coefficient", "glass", "acrylic", "particle-wall"),
]


def vssuq_rows() -> list[dict]:
    rows = []
    for stem, quantity, particle, wall, kind in VSSUQ_FILES:
        values = (RAW / "vssuq" / f"{stem}.txt").read_text(encoding="utf-8").split()
        for i, text in enumerate(values, start=1):
            rows.append(
                _row(
                    point=f"{stem}-{i:03d}",
                    quantity=quantity,
                    value=text,
                    u=_fmt(rounding_u(text)),
                    u_basis="rounding of the last printed digit (the scatter between "
                    "collisions is the dataset's sd, not this u)",
                    role="measured",
                    particle=particle,
                    wall=wall,
                    source=VSSUQ_SOURCE,
                    locator=f"docs/particleprops.rst, {kind} {particle}-{wall}; "
                    f"line {i} of data/particle_properties/{stem}.txt",
                    file=f"data/particle_properties/{stem}.txt",
                    notes=f"dry, {kind}; one collision",
                    **{k: v for k, v in VSSUQ.items()},
                )
            )
    summary = {r["stem"]: r for r in _read_raw("vssuq/summary.csv")}
    for stem, quantity, particle, wall, kind in VSSUQ_FILES:
        printed = summary[stem]
        count = len((RAW / "vssuq" / f"{stem}.txt").read_text(encoding="utf-8").split())
        line = int(printed["line"])
        for statistic, column in (("mean", "mean"), ("sd", "stdev")):
            text = printed[column]
            rows.append(
                _row(
                    point=f"{stem}-printed",
                    quantity=f"{quantity}_{statistic}",
                    value=text,
                    u=_fmt(rounding_u(text)),
                    u_basis="rounding of the last printed digit",
                    role="derived",
                    particle=particle,
                    wall=wall,
                    source=VSSUQ_SOURCE,
                    locator=f"docs/particleprops.rst line {line + (column == 'stdev')}"
                    f" ({kind} {particle}-{wall})",
                    file="docs/particleprops.rst",
                    notes=f"the {column} VSSUQ prints for the {count} values of "
                    f"data/particle_properties/{stem}.txt",
                    **VSSUQ,
                )
            )
    return rows


# ----------------------------------------------------------------- waLBerla wet cases
GONDRET_SOURCE = (
    "Gondret, P., Lance, M. & Petit, L. (2002). Bouncing motion of spherical particles in "
    "fluids. Physics of Fluids 14(2), 643-652. doi:10.1063/1.1427920"
)
JOSEPH_SOURCE = (
    "Joseph, G. G. & Hunt, M. L. (2004). Oblique particle-wall collisions in a liquid. "
    "Journal of Fluid Mechanics 510, 71-93. doi:10.1017/S002211200400919X"
)


def _config_rows(raw: str, file: str, source: str, cases: list, columns: dict) -> list[dict]:
    rows = []
    for case in cases:
        for column, (role, particle_key, notes) in columns.items():
            text = case[column]
            rows.append(
                _row(
                    point=case["case"],
                    quantity=column,
                    value=_fmt(float(text)),
                    u=_fmt(rounding_u(text)),
                    u_basis="rounding of the last printed digit",
                    role=role,
                    particle=case["material"].lower(),
                    wall=particle_key,
                    fluid=case.get("fluid", ""),
                    source=source,
                    locator=case.get("locator", "")
                    or f"{case['case']} block ({case.get('material')} in {case.get('fluid')})",
                    file=file,
                    notes=f"written '{text}' in {raw}; {notes}",
                    **WALBERLA,
                )
            )
    return rows


def gondret_rows() -> list[dict]:
    cases = _read_raw("gondret_walberla.csv")
    for case in cases:
        case["stokes_number"] = case["case"].removeprefix("Case_St")
        case["fluid"] = f"liquid of {case['case']} (not named in the file)"
        case["material"] = "sphere (not named in the file)"
    wall = "plate (not named in the file)"
    columns = {
        "reynolds_number": ("derived", wall, MEANINGS["reynolds_number"]),
        "stokes_number": (
            "derived",
            wall,
            MEANINGS["stokes_number"] + "; read from the waLBerla case name Case_StNN",
        ),
        "density_fluid_kg_m3": ("condition", wall, "fluid density"),
        "dynamic_viscosity_pa_s": ("condition", wall, "fluid viscosity"),
        "density_sphere_kg_m3": ("condition", wall, "sphere density"),
        "diameter_m": ("condition", wall, "sphere diameter"),
        "dry_restitution": (
            "condition",
            wall,
            "the dry restitution waLBerla takes as input for these cases",
        ),
    }
    return _config_rows(
        "inputSphereWallCollision.dat",
        "apps/benchmarks/FluidParticleCoupling/inputSphereWallCollision.dat",
        GONDRET_SOURCE,
        cases,
        columns,
    )


def joseph_walberla_rows() -> list[dict]:
    cases = _read_raw("joseph_hunt_walberla.csv")
    for case in cases:
        case["locator"] = f"{case['case']}: Mat_{case['material']}, Fluid_{case['fluid']}"
        # waLBerla's GlycerolNN is NN % wt glycerol in water: granudb's glycerol-NN
        case["fluid"] = "glycerol-" + case["fluid"].removeprefix("Glycerol")
    columns = {
        "density_sphere_kg_m3": ("condition", "Zerodur", "sphere density"),
        "diameter_m": ("condition", "Zerodur", "sphere diameter"),
        "dry_restitution": ("condition", "Zerodur", "dry restitution (model input)"),
        "friction": ("condition", "Zerodur", "friction coefficient (model input)"),
        "poisson_ratio": ("condition", "Zerodur", "sphere Poisson ratio ('Joseph 2001')"),
        "density_fluid_kg_m3": (
            "condition",
            "Zerodur",
            "fluid density (waLBerla cites internetchemie.info)",
        ),
        "dynamic_viscosity_pa_s": (
            "condition",
            "Zerodur",
            "fluid viscosity (waLBerla cites internetchemie.info)",
        ),
    }
    return _config_rows(
        "inputObliqueWetCollision.dat",
        "apps/benchmarks/FluidParticleCoupling/inputObliqueWetCollision.dat",
        JOSEPH_SOURCE,
        cases,
        columns,
    )


def joseph_seeded_rows() -> list[dict]:
    rows = []
    path = ROOT / "seed_data" / "published_values.csv"
    with path.open(encoding="utf-8", newline="") as f:
        for i, r in enumerate(csv.DictReader(f), start=2):
            if r["source"] != "joseph-hunt-2004":
                continue
            u_text = r["uncertainty"]
            basis = "± printed in the paper"
            if not u_text:
                u, basis = printed_rounding_u(r["value_as_printed"], float(r["value"]))
                u_text = _fmt(u)
            rows.append(
                _row(
                    point=f"row-{i:03d} {r['label']}",
                    quantity=r["quantity"],
                    value=r["value"],
                    u=u_text,
                    u_basis=basis,
                    role="measured",
                    particle=r["particle"],
                    wall=r["wall"],
                    fluid=r["fluid"],
                    source=JOSEPH_SOURCE,
                    locator=r["source_locator"],
                    digitiser="granudb seed data (seed_data/published_values.csv)",
                    licence="granudb seed data (values as printed in the paper)",
                    file="seed_data/published_values.csv",
                    notes=f"printed '{r['value_as_printed']}'; {r['condition']}; {r['notes']}",
                )
            )
    return rows


# ------------------------------------------------------------------------------ packages
DATASETS = {
    "kharaz-gorham-salman-2001": {
        "title": "Kharaz, Gorham & Salman (2001): oblique impact of 5 mm alumina spheres on "
        "soda-lime glass, e_t, spin and rebound angles against incidence angle "
        "(two public digitisations)",
        "source": KHARAZ_SOURCE,
        "doi": "10.1016/S0032-5910(01)00283-2",
        "licences": [LETHE["licence"], KRATOS["licence"]],
        "rows": lambda: kharaz_rows()[0],
    },
    "vssuq-dry-collisions": {
        "title": "VSSUQ per-collision dry restitution and friction (glass-glass, "
        "glass-HDPE, HDPE-HDPE, glass-acrylic wall)",
        "source": VSSUQ_SOURCE,
        "doi": None,
        "licences": [VSSUQ["licence"]],
        "rows": vssuq_rows,
    },
    "gondret-lance-petit-2002": {
        "title": "Gondret, Lance & Petit (2002): conditions of five bouncing-sphere cases in "
        "liquids, with their reported Re and St (as waLBerla encodes them)",
        "source": GONDRET_SOURCE,
        "doi": "10.1063/1.1427920",
        "licences": [WALBERLA["licence"]],
        "rows": gondret_rows,
    },
    "joseph-hunt-2004-walberla": {
        "title": "Joseph & Hunt (2004): the four oblique wet-collision cases as waLBerla "
        "encodes them (sphere, fluid and contact inputs)",
        "source": JOSEPH_SOURCE,
        "doi": "10.1017/S002211200400919X",
        "licences": [WALBERLA["licence"]],
        "rows": joseph_walberla_rows,
    },
    "joseph-hunt-2004-tables": {
        "title": "Joseph & Hunt (2004): the fitted values of their tables and figures, as "
        "granudb seeds them",
        "source": JOSEPH_SOURCE,
        "doi": "10.1017/S002211200400919X",
        "licences": ["values as printed in the paper, granudb seed data"],
        "rows": joseph_seeded_rows,
    },
}


def _schema() -> dict:
    fields = []
    for name, kind, description in FIELDS:
        field = {"name": name, "type": kind, "description": description}
        if name in ("value_id", "point", "quantity", "unit", "role", "source", "u_basis"):
            field["constraints"] = {"required": True}
        if name == "u":
            field["constraints"] = {"required": True, "minimum": 0}
        if name == "value":
            field["constraints"] = {"required": True}
        if name == "role":
            field["constraints"] = {"required": True, "enum": ["measured", "derived", "condition"]}
        fields.append(field)
    return {"fields": fields, "primaryKey": ["value_id"]}


def _write_csv(path: Path, rows: list[dict], names: list[str]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", encoding="utf-8", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=names, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)


def _citation(name: str, spec: dict) -> str:
    title = spec["title"].replace('"', "'")
    lines = [
        "cff-version: 1.2.0",
        'message: "If you use this dataset, cite it and the publication it comes from."',
        f'title: "granudb reference dataset {name}: {title}"',
        "type: dataset",
        f'version: "{VERSION}"',
        f'date-released: "{RELEASED}"',
        "authors:",
        '  - name: "granudb contributors"',
        "references:",
        "  - type: article",
        f'    title: "{spec["source"]}"',
        "    authors:",
        '      - name: "see title"',
    ]
    if spec["doi"]:
        lines.append(f'    doi: "{spec["doi"]}"')
    return "\n".join(lines) + "\n"


def build(out: Path) -> list[str]:
    names = []
    for name, spec in DATASETS.items():
        folder = out / name
        rows = spec["rows"]()
        _write_csv(folder / "data" / "values.csv", rows, [f for f, _, _ in FIELDS])
        resources = [
            {
                "name": "values",
                "path": "data/values.csv",
                "profile": "tabular-data-resource",
                "format": "csv",
                "mediatype": "text/csv",
                "encoding": "utf-8",
                "schema": _schema(),
            }
        ]
        if name == "kharaz-gorham-salman-2001":
            digitisations = kharaz_rows()[1]
            columns = list(digitisations[0])
            _write_csv(folder / "data" / "digitisations.csv", digitisations, columns)
            resources.append(
                {
                    "name": "digitisations",
                    "path": "data/digitisations.csv",
                    "profile": "tabular-data-resource",
                    "format": "csv",
                    "mediatype": "text/csv",
                    "encoding": "utf-8",
                    "schema": {"fields": [{"name": c, "type": "string"} for c in columns]},
                }
            )
        if name == "vssuq-dry-collisions":
            (folder / "LICENSE-vssuq").write_text(
                (RAW / "vssuq" / "LICENSE").read_text(encoding="utf-8"), encoding="utf-8"
            )
        descriptor = {
            "profile": "tabular-data-package",
            "name": name,
            "title": spec["title"],
            "version": VERSION,
            "created": RELEASED + "T00:00:00Z",
            "licenses": [{"name": "other", "title": text} for text in spec["licences"]],
            "sources": [{"title": spec["source"]}],
            "granudb_reference": {
                "kind": "reported values",
                "values": len(rows),
                "meanings": {
                    q: MEANINGS[q] for q in sorted({r["quantity"] for r in rows}) if q in MEANINGS
                },
            },
            "resources": resources,
        }
        (folder / "datapackage.json").write_text(
            json.dumps(descriptor, indent=2, ensure_ascii=False) + "\n", encoding="utf-8"
        )
        (folder / "CITATION.cff").write_text(_citation(name, spec), encoding="utf-8")
        names.append(name)
    return names


if __name__ == "__main__":
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "seed_data" / "reference"
    print("\n".join(build(target)))
