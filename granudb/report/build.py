"""Assembling a report: what was asked, the properties with their sources, the derived
quantities and verdicts, fits next to the published values, figures and methods.

The result is a plain dict (``report``) that the HTML and Markdown templates render; every
string in it that came from the database is escaped by the templates, never here.
"""

from __future__ import annotations

import math
from datetime import UTC, datetime
from typing import Any

import numpy as np

from granudb.report.format import display
from granudb.report.verdicts import GAP_DEFINITION, verdicts
from granudb.version import __version__
from granudb.vocabulary import DERIVED_TERMS

METHODS = [
    ("reduced modulus", "1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂", "Joseph & Hunt (2004) §1"),
    ("reduced shear modulus", "1/G* = (2−ν₁)/G₁ + (2−ν₂)/G₂", "Joseph & Hunt (2004) Appendix"),
    (
        "Reynolds, Stokes numbers",
        "Re = 2ρ_f R V/μ, St = 2ρ_p R V/(9μ), St_n = St cos ζ_in",
        "Joseph & Hunt (2004) §1, §4",
    ),
    (
        "impact load, contact radius, pressure",
        "W = (4/3)R²E*(5πρ_pV²/(4E*))^{3/5}, a = (3RW/(4E*))^{1/3}, p_max = 3W/(2πa²)",
        "Joseph & Hunt (2004) (2.1), (2.2), (5.5)",
    ),
    ("contact time", "t_c ≈ 2.87 (m²/(R E*² V))^{1/5}", "Johnson (1985) §11.4"),
    (
        "EHD minimum gap",
        "h_m = x₁/3, x₁ = (4μv₀R^{3/2}/(πE*))^{2/5}",
        "Joseph & Hunt (2004) §1 after Davis et al. (1986)",
    ),
    ("piezoviscous length", "x₃ = (η̂μ₀v₀R)^{1/2}, η̂ = C/16", "Joseph & Hunt (2004) §1, §5"),
    (
        "roughness against gap",
        "σ = √(σ₁²+σ₂²); flag when σ > h_m; Λ = h_m/σ",
        "Joseph & Hunt (2004) §4",
    ),
    ("rebound", "expected when St_n > St_c (default 10)", "Joseph & Hunt (2004) §1"),
    (
        "collision parameters",
        "e = v_n,out/v_n,in, β = −v_T,out/v_T,in, Ψ = v_T/v_N,in",
        "Joseph & Hunt (2004) (2.5), (2.8)",
    ),
    (
        "friction from one collision",
        "μ_f = (Ψ_in − Ψ_out)/((1+e)(1+1/K²)), K² = 2/5",
        "Joseph & Hunt (2004) (2.9)",
    ),
    (
        "Maw regime",
        "χ = (2G*/E*)(1+1/K²), ψ = 2(2G*/E*)v_T/(μ_f v_N,in)",
        "Joseph & Hunt (2004) (2.3), (2.4); 2G*/E* = (1−ν)/(2−ν) for one material",
    ),
    (
        "lubricated friction",
        "μ_f = (2πμ₀U/(W h)) a² A(η̂ p_max), h from (5.6)",
        "Joseph & Hunt (2004) (5.6), (5.8), (5.9)",
    ),
    (
        "Walton fit",
        "sticking: Ψ_out = −βΨ_in; sliding: Ψ_out = Ψ_in − μ_f(1+e)(1+1/K²)",
        "Joseph & Hunt (2004) (2.6), (2.7)",
    ),
]

REFERENCES = [
    "Joseph, G. G. & Hunt, M. L. (2004). Oblique particle–wall collisions in a liquid. "
    "J. Fluid Mech. 510, 71–93. https://doi.org/10.1017/S002211200400919X",
    "Johnson, K. L. (1985). Contact Mechanics. Cambridge University Press.",
    "Cheng, N.-S. (2008). Formula for the viscosity of a glycerol–water mixture. Ind. Eng. "
    "Chem. Res. 47, 3285–3288. https://doi.org/10.1021/ie071349z",
    "Volk, A. & Kähler, C. J. (2018). Density model for aqueous glycerol solutions. Exp. "
    "Fluids 59, 75. https://doi.org/10.1007/s00348-018-2527-y",
]

PROPERTY_COLUMNS = [
    "density_kg_m3",
    "youngs_modulus_pa",
    "poisson_ratio",
    "roughness_rms_m",
    "correlation_length_m",
    "shear_modulus_pa",
]


def _label(column: str) -> str:
    from granudb.vocabulary import term

    return term(column).title


def _source(record: dict[str, Any], citations: dict[str, str]) -> str:
    key = record.get("source")
    if not key:
        return "—"
    where = f", {record['source_locator']}" if record.get("source_locator") else ""
    return f"{key}{where}"  # the full citation is in the references


def _material_block(role: str, record: dict[str, Any], citations: dict[str, str]) -> dict[str, Any]:
    source = _source(record, citations)
    rows = []
    for column in PROPERTY_COLUMNS:
        value = record.get(column)
        note = source
        if column == "shear_modulus_pa" and record.get("shear_modulus_derived"):
            note = "derived: G = E / (2(1 + ν))"
        rows.append({"label": _label(column), "value": display(value, column), "source": note})
    return {"heading": f"{role}: {record['name']}", "rows": rows}


def _fluid_block(record: dict[str, Any], state: Any, citations: dict[str, str]) -> dict[str, Any]:
    source = _source(record, citations)
    rows = [
        {
            "label": "Viscosity used",
            "value": display(state.viscosity_pa_s, "viscosity_pa_s"),
            "source": state.basis,
        },
        {
            "label": "Density used",
            "value": display(state.density_kg_m3, "density_kg_m3"),
            "source": record.get("density_source") or source,
        },
        {
            "label": "Temperature",
            "value": display(state.temperature_c, "temperature_c"),
            "source": "given" if state.basis.startswith("interpolated") else "reference",
        },
        {
            "label": "Reference viscosity",
            "value": display(record["reference_viscosity_pa_s"], "viscosity_pa_s"),
            "source": source,
        },
        {
            "label": "Pressure–viscosity coefficient C",
            "value": display(record.get("pressure_viscosity_pa_inv"), "pressure_viscosity_pa_inv"),
            "source": record.get("pressure_viscosity_source") or "—",
        },
        {
            "label": "Glycerol mass fraction",
            "value": display(record.get("glycerol_mass_fraction"), "glycerol_mass_fraction"),
            "source": source,
        },
    ]
    return {"heading": f"Fluid: {record['name']}", "rows": rows}


def roughness_flag(derived: dict[str, Any], immersed: bool) -> dict[str, Any]:
    """The prominent flag: σ against h_m, stated with the definition used and Λ."""
    from granudb.report.verdicts import roughness_verdict

    verdict = roughness_verdict(derived, immersed)
    headline = (
        "Roughness exceeds the EHD gap (σ > h_m): asperity contact, dry-like friction expected"
        if verdict.raised
        else verdict.name
    )
    return {
        "id": "roughness-flag",
        "raised": verdict.raised,
        "headline": headline,
        "detail": verdict.text,
    }


def _derived_rows(derived: dict[str, Any]) -> list[dict[str, str]]:
    rows = []
    for name, described in DERIVED_TERMS.items():
        description = described.description
        if name not in derived or name == "incidence_angle_rad":
            continue
        rows.append(
            {
                "label": _label(name) if name in _titled() else name.replace("_", " "),
                "value": display(derived[name], name),
                "relation": description,
            }
        )
    return rows


def _titled() -> set[str]:
    from granudb.vocabulary import TERMS

    return set(TERMS)


def regime_map_figure(
    particle: dict[str, Any],
    wall: dict[str, Any],
    fluid_state: Any,
    diameter_m: float,
    point: tuple[float, float] | None,
    critical_stokes: float,
    figure_id: str = "fig-regime-map",
    runs: tuple[np.ndarray, np.ndarray] | None = None,
) -> dict:
    """Impact velocity × viscosity plane for the pair, shaded by regime."""
    from granudb.physics.derive import derive
    from granudb.report import plots

    velocity = np.geomspace(1e-3, 3.0, 80)
    viscosity = np.geomspace(1e-4, 1.0, 70)
    v_grid, mu_grid = np.meshgrid(velocity, viscosity)
    inputs = {
        f"particle_{k}": particle[k]
        for k in ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m")
    }
    inputs.update(
        {
            f"wall_{k}": wall[k]
            for k in ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m")
        }
    )
    density = fluid_state.density_kg_m3 if fluid_state else 1000.0
    out = derive(
        **inputs,
        diameter_m=diameter_m,
        v_n_in_m_s=v_grid,
        viscosity_pa_s=mu_grid,
        fluid_density_kg_m3=density,
        critical_stokes=critical_stokes,
    )
    regime = np.where(
        ~out["rebound_expected"],
        "no rebound",
        np.where(
            out["roughness_exceeds_gap"],
            "rebound, asperity contact (σ > h_m)",
            "rebound, full film (σ ≤ h_m)",
        ),
    ).astype(object)
    radius = diameter_m / 2
    e_star = float(out["reduced_modulus_pa"].ravel()[0])
    sigma = float(out["composite_roughness_m"].ravel()[0])
    gap_mu = (3 * sigma) ** 2.5 * math.pi * e_star / (4 * velocity * radius**1.5)
    stokes_mu = 2 * particle["density_kg_m3"] * radius * velocity / (9 * critical_stokes)
    svg = plots.regime_map(
        velocity,
        viscosity,
        regime,
        (velocity, gap_mu),
        (velocity, stokes_mu),
        point,
        figure_id,
        runs,
    )
    return {
        "id": figure_id,
        "svg": svg,
        "file": f"{figure_id}.svg",
        "caption": f"Regime map for {particle['name']} on {wall['name']}, d = "
        f"{display(diameter_m, 'diameter_m')}: above the solid line h_m > σ "
        "(full film); right of the dashed line St_n > St_c (rebound).",
    }


def _header(title: str, query: str, database: str) -> dict[str, Any]:
    return {
        "title": title,
        "query": query,
        "database": database,
        "version": __version__,
        "generated_at": datetime.now(UTC).replace(microsecond=0).isoformat(),
        "dataset": None,
        "flags": [],
        "verdicts": [],
        "properties": [],
        "derived": [],
        "tables": [],
        "figures": [],
        "methods": [{"quantity": q, "relation": r, "source": s} for q, r, s in METHODS],
        "references": list(REFERENCES),
    }


def pair_report(
    session: Any,
    *,
    title: str | None,
    query: str,
    database: str,
    particle: str,
    wall: str,
    fluid: str | None,
    diameter_m: float,
    speed_m_s: float,
    angle_rad: float,
    temperature_c: float | None,
    viscosity_pa_s: float | None,
    critical_stokes: float,
) -> dict[str, Any]:
    """A report for one scenario, plus the stored runs of the same pair if there are any."""
    from granudb.analysis.pair import derive_pair

    result = derive_pair(
        session,
        particle,
        wall,
        fluid=fluid,
        diameter_m=diameter_m,
        speed_m_s=speed_m_s,
        angle_rad=angle_rad,
        temperature_c=temperature_c,
        viscosity_pa_s=viscosity_pa_s,
        critical_stokes=critical_stokes,
    )
    name = f"{result.particle['name']} on {result.wall['name']}" + (
        f" in {result.fluid['name']}" if result.fluid else " (dry)"
    )
    report = _header(title or f"granudb report: {name}", query, database)
    immersed = result.fluid_state is not None
    report["flags"].append(roughness_flag(result.derived, immersed))
    report["verdicts"] = [
        {"name": v.name, "text": v.text}
        for v in verdicts(result.derived, critical_stokes, immersed)
    ]
    citations = result.citations
    report["properties"] = [
        _material_block("Particle", result.particle, citations),
        _material_block("Wall", result.wall, citations),
    ]
    if immersed:
        report["properties"].append(_fluid_block(result.fluid, result.fluid_state, citations))
    scenario = [
        {
            "label": "Particle diameter",
            "value": display(diameter_m, "diameter_m"),
            "relation": "given",
        },
        {
            "label": "Impact speed",
            "value": display(speed_m_s, "impact_speed_m_s"),
            "relation": "given",
        },
        {
            "label": "Incidence angle",
            "value": display(angle_rad, "incidence_angle_rad"),
            "relation": "given",
        },
    ]
    report["derived"] = [
        {"heading": "Scenario", "rows": scenario},
        {"heading": "Derived", "rows": _derived_rows(result.derived)},
    ]
    report["figures"].append(
        regime_map_figure(
            result.particle,
            result.wall,
            result.fluid_state,
            diameter_m,
            (result.inputs["v_n_in_m_s"], result.fluid_state.viscosity_pa_s) if immersed else None,
            critical_stokes,
        )
    )
    report["references"] = sorted(
        {f"[{key}] {text}" for key, text in citations.items()} | set(REFERENCES)
    )
    from granudb.analysis.collisions import CollisionQuery

    _add_collisions(
        session, report, CollisionQuery(particle=particle, wall=wall, fluid=fluid), with_flag=False
    )
    return report


def dataset_report(
    session: Any, *, title: str | None, query_text: str, database: str, query: Any
) -> dict[str, Any]:
    """A report on stored collisions (a dataset or any query)."""
    from granudb.db import datasets

    report = _header(title or f"granudb report: {query.describe()}", query_text, database)
    if query.dataset is not None:
        dataset = datasets.get_dataset(session, query.dataset, query.version)
        report["dataset"] = {
            "name": dataset.name,
            "version": dataset.version,
            "content_hash": dataset.content_hash,
        }
    _add_collisions(session, report, query, with_flag=True)
    return report


def _group_label(row: Any) -> str:
    return f"{row['particle']}/{row['wall']} {row['fluid'] or 'dry'}"


def _add_collisions(session: Any, report: dict[str, Any], query: Any, *, with_flag: bool) -> None:
    from granudb.analysis import fits
    from granudb.analysis.collisions import select_collisions
    from granudb.db import catalog
    from granudb.report import plots

    frame = select_collisions(session, query)
    if frame.empty:
        if with_flag:
            report["flags"].append(
                {
                    "id": "no-runs",
                    "raised": False,
                    "headline": "No stored collisions match",
                    "detail": f"Query: {query.describe()}.",
                }
            )
        return
    groups = [
        f"{p}/{w} {f or 'dry'}"
        for p, w, f in zip(frame["particle"], frame["wall"], frame["fluid"], strict=True)
    ]
    if with_flag:
        rough = frame[frame["roughness_exceeds_gap"].astype(bool)]
        immersed = frame[frame["fluid"].notna()]
        raised = not rough.empty
        sigma = immersed["composite_roughness_m"]
        detail = (
            (
                f"{len(rough)} of {len(immersed)} immersed runs have σ > h_m "
                f"({GAP_DEFINITION}); median Λ = h_m/σ = "
                f"{float(np.nanmedian(immersed['film_parameter'])):.3g}, σ from "
                f"{display(float(sigma.min()), 'composite_roughness_m')} to "
                f"{display(float(sigma.max()), 'composite_roughness_m')}. "
                + (
                    "Asperities touch through the film in those runs: expect dry-like friction."
                    if raised
                    else "The film separates the surfaces in every immersed run."
                )
            )
            if not immersed.empty
            else "All runs are dry."
        )
        report["flags"].append(
            {
                "id": "roughness-flag",
                "raised": raised,
                "headline": (
                    "Roughness exceeds the EHD gap (σ > h_m) in "
                    f"{len(rough)} runs: asperity contact"
                    if raised
                    else "Roughness within the EHD gap"
                ),
                "detail": detail,
            }
        )

    walton = fits.walton(frame)
    published = catalog.published_records(session)
    report["tables"].append(
        {
            "id": "walton-fits",
            "heading": "Walton fits (figures 4, 6, 9)",
            "note": "β from the sticking runs (Ψ_out = −βΨ_in), μ_f from the sliding runs; "
            "standard errors and run counts; ē ± std over all runs of the group.",
            "columns": ["group", "β", "μ_f", "ē", "sticking / sliding runs", "published"],
            "rows": [
                [
                    f"{r['dataset']}: {r['particle']}/{r['wall']} {r['fluid']}",
                    _pm(r["rotational_restitution"], r["rotational_restitution_stderr"]),
                    _pm(r["sliding_friction"], r["sliding_friction_stderr"]),
                    _pm(r["normal_restitution_mean"], r["normal_restitution_std"]),
                    f"{r['n_sticking']} / {r['n_sliding']}",
                    _published_for(published, r),
                ]
                for r in walton
            ],
        }
    )
    restitution = fits.restitution(frame, "threshold")
    if restitution:
        report["tables"].append(
            {
                "id": "restitution-fit",
                "heading": "Restitution against Stokes number (figure 5)",
                "note": f"Threshold form {fits.RESTITUTION_MODELS['threshold'][0]} "
                f"({fits.RESTITUTION_MODELS['threshold'][1]}).",
                "columns": ["group", "e_dry", "St_c", "runs"],
                "rows": [
                    [
                        f"{r['dataset']}: {r['particle']}/{r['wall']}",
                        _pm(r["e_dry"], r["e_dry_stderr"]),
                        _pm(r["parameter"], r["parameter_stderr"]),
                        str(r["n_runs"]),
                    ]
                    for r in restitution
                ],
            }
        )
    from granudb.analysis.fluid_state import fluid_model

    models = {f.name: fluid_model(f) for f in catalog.list_fluids(session)}
    gap = fits.gap_viscosity(frame, models)
    if gap:
        report["tables"].append(
            {
                "id": "gap-viscosity",
                "heading": "Gap viscosity and temperature (figure 14, table 2)",
                "note": "μ₀ that makes (5.10) match each smooth sliding run's μ_f; the gap "
                "temperature follows from the fluid's μ(T).",
                "columns": ["group", "μ₀", "ambient μ", "gap temperature", "runs"],
                "rows": [
                    [
                        f"{r['dataset']}: {r['particle']}/{r['wall']} {r['fluid']}",
                        display(r["gap_viscosity_pa_s"], "viscosity_pa_s"),
                        display(r["ambient_viscosity_pa_s"], "viscosity_pa_s"),
                        display(r["gap_temperature_c"], "temperature_c")
                        if not math.isnan(r["gap_temperature_c"])
                        else (r["note"] or "—"),
                        str(r["n_runs"]),
                    ]
                    for r in gap
                ],
            }
        )

    psi_in = frame["effective_incidence"].to_numpy(dtype=float)
    psi_out = frame["effective_rebound"].to_numpy(dtype=float)
    fit_lines = [{**r, "label": f"{r['particle']}/{r['wall']} {r['fluid']}"} for r in walton]
    report["figures"] += [
        {
            "id": "fig-walton",
            "file": "fig-walton.svg",
            "caption": "Ψ_out against Ψ_in with the fitted Walton lines (figures 4, 6, 9).",
            "svg": plots.walton_plot(psi_in, psi_out, groups, fit_lines),
        },
        {
            "id": "fig-beta",
            "file": "fig-beta.svg",
            "caption": "Rotational restitution β against Ψ_in (figures 7, 10).",
            "svg": plots.against_incidence(
                psi_in,
                frame["rotational_restitution"].to_numpy(float),
                groups,
                ylabel="β = −v_T,out / v_T,in  (–)",
                title="Rotational restitution",
                figure_id="fig-beta",
            ),
        },
        {
            "id": "fig-friction",
            "file": "fig-friction.svg",
            "caption": "Friction from one collision, μ_f (2.9), against Ψ_in (figures 8, 11).",
            "svg": plots.against_incidence(
                psi_in,
                frame["sliding_friction"].to_numpy(float),
                groups,
                ylabel="μ_f (2.9)  (–)",
                title="Friction coefficient",
                figure_id="fig-friction",
            ),
        },
    ]
    immersed = frame["normal_stokes_number"].notna().to_numpy()
    if with_flag and immersed.any():
        _add_regime_map(session, report, frame[immersed], query.critical_stokes)
    if immersed.any():
        st_n = frame["normal_stokes_number"].to_numpy(float)[immersed]
        e = frame["normal_restitution"].to_numpy(float)[immersed]
        curve = None
        fitted = [r for r in restitution if not math.isnan(r["parameter"])]
        if fitted:
            r = fitted[0]
            grid = np.geomspace(max(1.0, float(st_n.min()) * 0.5), float(st_n.max()) * 2, 200)
            curve = (
                grid,
                fits.restitution_curve("threshold", grid, r["e_dry"], r["parameter"]),
                f"threshold fit, St_c = {r['parameter']:.3g}",
            )
        report["figures"].append(
            {
                "id": "fig-restitution",
                "file": "fig-restitution.svg",
                "caption": "Normal restitution against the normal Stokes number (figure 5).",
                "svg": plots.restitution_vs_stokes(
                    st_n,
                    e,
                    [g for g, m in zip(groups, immersed, strict=True) if m],
                    curve,
                    query.critical_stokes,
                ),
            }
        )
        strain = frame["shear_strain"].to_numpy(float)[immersed]
        report["figures"].append(
            {
                "id": "fig-shear-strain",
                "file": "fig-shear-strain.svg",
                "caption": "μ_f against the shear strain (μ₀U/(E*R))^{2/7} (figure 15).",
                "svg": plots.friction_vs_shear_strain(
                    strain,
                    frame["sliding_friction"].to_numpy(float)[immersed],
                    [g for g, m in zip(groups, immersed, strict=True) if m],
                ),
            }
        )


def _pm(value: float, error: float) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "—"
    if error is None or (isinstance(error, float) and math.isnan(error)):
        return f"{value:.3g}"
    return f"{value:.3g} ± {error:.2g}"


def _published_for(published: list[dict[str, Any]], fit: dict[str, Any]) -> str:
    fluid = None if fit["fluid"] == "dry" else fit["fluid"]
    matches = [
        p
        for p in published
        if p["particle"] == fit["particle"]
        and p["wall"] == fit["wall"]
        and p["fluid"] == fluid
        and p["quantity"] in {"rotational_restitution", "sliding_friction"}
    ]
    if not matches and fluid is not None:  # immersed values are printed per sphere material
        matches = [
            p
            for p in published
            if p["particle"] == fit["particle"]
            and p["condition"]
            and "immersed" in p["condition"]
            and p["quantity"] in {"rotational_restitution", "sliding_friction"}
        ]
    return (
        "; ".join(
            f"{p['value_as_printed']} ({p['source']}, {p['source_locator']})" for p in matches
        )
        or "—"
    )


def _add_regime_map(
    session: Any, report: dict[str, Any], immersed: Any, critical_stokes: float
) -> None:
    """The regime map of the pair with the most immersed runs, with those runs on it."""
    from granudb.db import catalog

    pairs = immersed.groupby(["particle", "wall"]).size().sort_values(ascending=False)
    particle, wall = pairs.index[0]
    runs = immersed[(immersed["particle"] == particle) & (immersed["wall"] == wall)]
    first = catalog.material_record(catalog.get_material(session, particle))
    second = catalog.material_record(catalog.get_material(session, wall))
    figure = regime_map_figure(
        first,
        second,
        None,
        float(runs["diameter_m"].median()),
        None,
        critical_stokes,
        runs=(runs["v_n_in_m_s"].to_numpy(float), runs["viscosity_pa_s"].to_numpy(float)),
    )
    figure["caption"] += f" Dots: the {len(runs)} immersed runs of this pair."
    report["figures"].append(figure)
