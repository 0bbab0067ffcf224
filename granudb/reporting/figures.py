"""The report's figures as dicts (id, SVG, caption): the regime map of a pair and the
figures of a set of runs.

The regime map is computed by ``granudb.physics.derive`` on a velocity × viscosity grid;
its two lines are level sets of what derive returns (h_m/σ = 1, St_n = St_c), so no
relation is re-derived here.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from sqlalchemy.engine import Connection

from granudb.analysis import asymptotic, bands, fits
from granudb.analysis.groups import GROUP
from granudb.db import catalog_rows
from granudb.lazy import pandas as pd
from granudb.physics import flow
from granudb.physics.derive import DRY_RESTITUTION, derive
from granudb.physics.impact import gyration_factor
from granudb.reporting import plots
from granudb.reporting.fit_view import (
    e_dry_words,
    parameter_label,
    restitution_model,
    restitution_parameter,
    value_line,
)
from granudb.reporting.format import display, is_number
from granudb.reporting.groups import (
    group_label,
    key_codes,
    sorted_codes,
)

#: Dry runs are drawn at the viscosity of air at 20 °C, so they appear on the map.
AIR_VISCOSITY_PA_S = 1.8e-5
_MATERIAL_KEYS = ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m")


def _regime_grid(materials: tuple[dict, dict], *scenario: float) -> dict[str, Any]:
    """``derive`` on the map's grid for the pair ``materials``; ``scenario``: diameter (m),
    fluid density (kg/m³), critical Stokes number and the lowest viscosity drawn (Pa·s)."""
    particle, wall = materials
    diameter_m, fluid_density, critical_stokes, lowest_viscosity = scenario
    velocity = np.geomspace(1e-3, 3.0, 120)
    viscosity = np.geomspace(lowest_viscosity, 1.0, 100)
    v_grid, mu_grid = np.meshgrid(velocity, viscosity)
    # a roughness not stated is NaN: the map then shades it "not determined"
    inputs: dict[str, Any] = {
        f"{side}_{k}": np.nan if record[k] is None else record[k]
        for side, record in (("particle", particle), ("wall", wall))
        for k in _MATERIAL_KEYS
    }
    out = derive(
        **inputs,
        diameter_m=diameter_m,
        v_n_in_m_s=v_grid,
        viscosity_pa_s=mu_grid,
        fluid_density_kg_m3=fluid_density,
        critical_stokes=critical_stokes,
    )
    regime = plots.regime_names(out["rebound_expected"], out["roughness_regime"])
    with np.errstate(divide="ignore", invalid="ignore"):
        sigma_over_x1 = np.asarray(out["composite_roughness_m"] / out["elastic_length_m"], float)
    return {
        "velocity": velocity,
        "viscosity": viscosity,
        "regime": regime,
        "sigma_over_x1": sigma_over_x1,
        "stokes": np.asarray(out["normal_stokes_number"], float),
    }


def regime_map_figure(
    particle: dict[str, Any],
    wall: dict[str, Any],
    diameter_m: float,
    fluid_density: float,
    critical_stokes: float,
    *,
    point: tuple[float, float] | None = None,
    runs: Sequence[dict[str, Any]] = (),
    colours: Mapping[str, str] | None = None,
    figure_id: str = "fig-regime-map",
) -> dict[str, Any]:
    """Impact velocity × viscosity plane for the pair, shaded by regime, with runs."""
    has_dry = any(r["dry"] for r in runs)
    grid = _regime_grid(
        (particle, wall),
        diameter_m,
        fluid_density,
        critical_stokes,
        AIR_VISCOSITY_PA_S / 2 if has_dry else 1e-4,
    )
    svg = plots.regime_map(
        grid["velocity"],
        grid["viscosity"],
        grid["regime"],
        grid["sigma_over_x1"],
        grid["stokes"],
        critical_stokes,
        point=point,
        runs=runs,
        colours=colours,
        figure_id=figure_id,
    )
    caption = (
        f"Regime map for {particle['name']} on {wall['name']}, d = "
        f"{display(diameter_m, 'diameter_m')}, shaded by the roughness verdict with Davis et "
        "al.'s band h_m = x₁/4 … x₁/3: asperity contact below the solid line σ = x₁/3 "
        "(Λ = h_m/σ < 1 with h_m = x₁/3), uncertain between it and the dotted line σ = x₁/4, "
        "film above (Λ ≥ 4/3); right of the dashed line St_n > St_c (rebound)."
    )
    if runs:
        count = sum(len(r["v"]) for r in runs)
        caption += (
            f" Markers: the {count} measured runs of this pair, coloured by group (as in every "
            "figure and table of this report), shaped by the branch its group's Walton fit "
            "counts (sticking, sliding, no rebound, not determined)"
            + (" (dry runs drawn at the viscosity of air, 0.018 mPa·s)." if has_dry else ".")
            + thinned(count)
        )
    return {"id": figure_id, "svg": svg, "file": f"{figure_id}.svg", "caption": caption}


def pair_maps(
    reader: Any,
    frame: Any,
    branches: np.ndarray,
    labels: Sequence[str],
    colours: Mapping[str, str],
    critical_stokes: float,
    fluids: Any,
    pinned: int | None,
) -> list[dict[str, Any]]:
    """One regime map per particle/wall pair, with every run of that pair on it, in its
    group's colour (the one of every figure and table) and shaped by ``branches`` (the one
    classification, ``granudb.analysis.fits.walton_branches``). ``fluids``: each run's
    ``fluid_names``; ``pinned``: the one dataset version of the runs
    (``lookup_rows.single_dataset_id``), whose catalogue a release keeps.
    ``reader``: a Core connection or a session (the catalogue is read through Core)."""
    connection = reader if isinstance(reader, Connection) else reader.connection()
    # each run's group and branch as codes into their sorted names, once for every pair
    # (the labels' codes are the ones the scatter figures made: ``sorted_codes`` keeps them)
    group_codes, group_names = sorted_codes(labels)
    branch_codes, branch_names = sorted_codes(branches)
    densities = {
        name: catalog_rows.get_fluid_row(connection, name, pinned).reference_density_kg_m3
        for name in set(fluids.tolist()) - {"dry"}
    }
    figures = []
    pair_codes, pair_keys = key_codes([frame["particle"], frame["wall"]])
    pairs = sorted(pair_keys.tolist())
    for index, (particle, wall) in enumerate(pairs):
        mask = pair_codes == pair_keys.tolist().index((particle, wall))
        # only the two columns the series read (not a copy of every column of the pair)
        speeds = frame.loc[mask, ["v_n_in_m_s", "viscosity_pa_s"]]
        runs = _run_series(speeds, (group_codes[mask], group_names), fluids[mask],
                           (branch_codes[mask], branch_names))  # fmt: skip
        wet = [densities[f] for f in set(fluids[mask].tolist()) if f in densities]
        figure = regime_map_figure(
            catalog_rows.material_record(
                catalog_rows.get_material_row(connection, particle, pinned)
            ),
            catalog_rows.material_record(catalog_rows.get_material_row(connection, wall, pinned)),
            float(np.nanmedian(frame.loc[mask, "diameter_m"].to_numpy(float))),
            float(np.median(wet)) if wet else math.nan,
            critical_stokes,
            runs=runs,
            colours=colours,
            figure_id="fig-regime-map" if index == 0 else f"fig-regime-map-{index + 1}",
        )
        figures.append(figure)
    return figures


def _run_series(
    frame: Any, groups: tuple[np.ndarray, list], fluids: np.ndarray, branches: tuple
) -> list[dict[str, Any]]:
    """The runs of one pair as series of one group and one branch each, dry groups first;
    ``groups`` and ``branches``: each run's code and the sorted names (``sorted_codes``),
    names without a run of the pair giving no series."""
    v = frame["v_n_in_m_s"].to_numpy(float)
    mu = frame["viscosity_pa_s"].to_numpy(float)
    mu = np.where(np.isfinite(mu), mu, AIR_VISCOSITY_PA_S)
    (group_codes, group_list), (branch_codes, branch_list) = groups, branches
    in_dry = np.unique(group_codes[np.asarray(fluids == "dry", dtype=bool)]).tolist()
    dry = {group_list[code] for code in in_dry}  # the groups with a dry run
    series = []
    for group in sorted(group_list, key=lambda g: (g not in dry, g)):
        in_group = group_codes == group_list.index(group)
        for branch in plots.RUN_MARKERS:
            if branch not in branch_list:
                continue
            keep = in_group & (branch_codes == branch_list.index(branch))
            if keep.any():
                series.append({"v": v[keep], "mu": mu[keep], "group": group, "regime": branch,
                               "dry": group in dry})  # fmt: skip
    return series


def walton_lines(
    psi_in: np.ndarray,
    labels: Sequence[str],
    branches: np.ndarray,
    walton: Sequence[Mapping[str, Any]],
    sets: Mapping[tuple, Any] | None = None,
) -> list[dict[str, Any]]:
    """The Walton lines of each group, each over the folded Ψ_in range where its branch
    holds for that group (``branches``, the one classification): the sticking line from 0
    up to the split (a sticking-only group: to its largest Ψ_in), the sliding line from
    the split (a sliding-only group: its smallest sliding Ψ_in) to the largest. A line is
    drawn only where the fit determined its parameter (β; μ_f and ē). Dicts with ``label``
    (the group), ``branch``, ``x``, ``y`` and the legend ``text``; with ``sets`` (the
    groups' bootstrap parameter sets, ``bands.walton_sets``) each line whose parameter has
    an interval gets its 95 % ``band`` (low, high over ``x``), else ``band`` is None."""
    folded = np.abs(np.asarray(psi_in, float))
    # each run's group and branch compared as codes, not as 100,000 strings per group
    codes, names = pd.factorize(np.asarray(labels, dtype=object))
    code_of = {name: code for code, name in enumerate(names)}
    finite = np.isfinite(folded)
    sticking, sliding = branches == "sticking", branches == "sliding"
    factor = float(gyration_factor())
    lines = []
    for fit in walton:
        label = group_label(fit["particle"], fit["wall"], fit.get("fluid"))
        mine = (codes == code_of.get(label, -2)) & finite
        stick = folded[mine & sticking]
        slide = folded[mine & sliding]
        split = fit.get("split_effective_incidence")
        split = float(split) if is_number(split) and fit.get("model") == "split" else None
        beta = fit.get("rotational_restitution")
        mu, e = fit.get("sliding_friction"), fit.get("normal_restitution_mean")
        found = (sets or {}).get(tuple(fit.get(k) for k in GROUP))
        normal = fit.get("bootstrap_resamples") == 0  # asymptotic: normal-law sets
        if is_number(beta) and stick.size:
            x = np.linspace(0.0, split if split is not None else float(stick.max()), 50)
            lines.append({"label": label, "branch": "sticking", "x": x, "y": -beta * x,
                          "text": f"{label}: sticking, β = {beta:.2g}",
                          "band": _line_band(found, fit, "sticking", x, factor),
                          "normal": normal})  # fmt: skip
        if is_number(mu) and is_number(e) and slide.size:
            start = split if split is not None else float(slide.min())
            x = np.linspace(start, float(slide.max()), 50)
            lines.append({"label": label, "branch": "sliding", "x": x,
                          "y": x - mu * (1 + e) * factor,
                          "text": f"{label}: sliding, μ_f = {mu:.2g}",
                          "band": _line_band(found, fit, "sliding", x, factor),
                          "normal": normal})  # fmt: skip
    return lines


def _line_band(sets: Any, fit: Mapping[str, Any], branch: str, x: np.ndarray, factor: float):
    """A Walton line's band, or None without sets or without the parameter's interval."""
    interval = "rotational_restitution" if branch == "sticking" else "sliding_friction"
    if sets is None or not is_number(fit.get(f"{interval}_low")):
        return None
    return bands.walton_band(sets, branch, x, factor)


def walton_caption(lines: Sequence[Mapping[str, Any]]) -> str:
    """The Walton figure's caption, saying which lines are drawn (none, if none are)."""
    caption = "Ψ_out against Ψ_in (figures 4, 6, 9)"
    kinds = sorted({line["branch"] for line in lines}, reverse=True)
    if not kinds:
        return caption + "; no Walton line is drawn: no group's fit determined β or μ_f."
    words = {
        "sticking": "sticking lines Ψ_out = −βΨ_in (dashed) from 0 up to the split",
        "sliding": "sliding lines Ψ_out = Ψ_in − μ_f(1+ē)(1+1/K²) (solid) from the split on",
    }
    groups = len({line["label"] for line in lines})
    return (
        f"{caption}, with the fitted {' and '.join(words[k] for k in kinds)}, each over the "
        f"Ψ_in range of the runs its group's fit counts on that branch ({groups} "
        f"group{'s' if groups != 1 else ''} with a line; a group without one had no β or μ_f "
        "determined)."
        + band_caption(
            sum(line.get("band") is not None for line in lines),
            sum(line.get("band") is not None and bool(line.get("normal")) for line in lines),
        )
    )


def band_caption(count: int, normal: int = 0) -> str:
    """What the shaded bands are ('' when none is drawn); ``normal`` of the ``count`` bands
    are drawn over the asymptotic interval's normal-law sets (``asymptotic.normal_sets``)."""
    if not count:
        return ""
    over = "the fit's bootstrap parameter sets (the resamples of its intervals)"
    if normal == count:
        over = asymptotic.BAND_SETS_WORDS
    elif normal:
        over += f", or, where the fit's interval is asymptotic, {asymptotic.BAND_SETS_WORDS}"
    return (
        f" Shaded around a line: its {bands.LEVEL:.0%} band, the "
        f"{50 * (1 - bands.LEVEL):g}–{100 - 50 * (1 - bands.LEVEL):g} percentiles of the line at "
        f"each abscissa over {over}: "
        "the uncertainty of the fitted line, not the scatter of single runs (drawn only "
        "where the fit gives the parameter's interval)."
    )


def dataset_figures(
    frame: Any, labels: Sequence[str], colours: Mapping[str, str], fitted: Mapping[str, Any]
) -> list[dict[str, Any]]:
    """The Walton, β, μ_f, restitution and shear-strain figures of a set of runs.
    ``fitted``: ``walton``, ``branches``, ``restitution`` and ``critical_stokes``, and
    optionally ``walton_sets`` (the Walton fits' bootstrap sets, else made anew)."""
    psi_in = frame["effective_incidence"].to_numpy(dtype=float)
    sets = fitted.get("walton_sets")
    if sets is None:
        sets = bands.walton_sets(frame, fitted["walton"])
    lines = walton_lines(psi_in, labels, fitted["branches"], fitted["walton"], sets)
    errors = _errors(frame, "effective_incidence", "effective_rebound")
    figures = [
        _figure("fig-walton", walton_caption(lines) + (plots.ERROR_BARS if errors else ""),
                plots.walton_plot(psi_in, frame["effective_rebound"].to_numpy(float), labels,
                                  lines, colours, errors=errors), len(psi_in)),  # fmt: skip
        _figure("fig-beta", "Rotational restitution β against Ψ_in (figures 7, 10).",
                plots.against_incidence(psi_in, frame["rotational_restitution"].to_numpy(float),
                                        labels, colours, ylabel="β = −v_T,out / v_T,in  (–)",
                                        title="Rotational restitution", figure_id="fig-beta"),
                len(psi_in)),
        _figure("fig-friction",
                "Friction from one collision, μ_f (2.9), against Ψ_in (figures 8, 11).",
                plots.against_incidence(psi_in, frame["sliding_friction"].to_numpy(float),
                                        labels, colours, ylabel="μ_f (2.9)  (–)",
                                        title="Friction coefficient", figure_id="fig-friction"),
                len(psi_in)),
    ]  # fmt: skip
    immersed = frame["normal_stokes_number"].notna().to_numpy()
    if not immersed.any():
        return figures
    wet_labels = np.asarray(labels, dtype=object)[immersed].tolist()
    # Only the columns the figure reads: a copy of every column of a million immersed runs
    # was the report's peak memory (about 200 MB more).
    wet = frame.loc[immersed, [c for c in WET_COLUMNS if c in frame]]
    figures.append(restitution_figure(wet, wet_labels, colours, fitted, frame))
    strain = frame["shear_strain"].to_numpy(float)[immersed]
    figures.append(
        _figure(
            "fig-shear-strain",
            "μ_f against the shear strain (μ₀U/(E*R))²⁄⁷ (figure 15).",
            plots.friction_vs_shear_strain(
                strain, frame["sliding_friction"].to_numpy(float)[immersed], wet_labels, colours
            ),
            len(strain),
        )
    )
    return figures


#: What ``restitution_figure`` and ``predicted_curves`` read of the immersed runs.
WET_COLUMNS = (
    "normal_stokes_number",
    "normal_restitution",
    "added_mass_stokes_number",
    "restitution_ceiling",
    "u_normal_stokes_number",
    "u_normal_restitution",
)


def _errors(frame: Any, x: str, y: str) -> tuple[Any, Any] | None:
    """(u of ``x``, u of ``y``) by run where the frame has them and any run states one,
    else None (no bars)."""
    u_x, u_y = (frame[f"u_{c}"].to_numpy(float) if f"u_{c}" in frame else None for c in (x, y))
    return (u_x, u_y) if plots.has_errors(u_x, u_y) else None


def predicted_curves(frame: Any, labels: Sequence[str], critical_stokes: float) -> list[dict]:
    """Per group, the predicted e(St_n) = e_dry exp(−35/St) of Legendre et al. (2006) with
    St the group's added-mass Stokes number (St_am = St_n (1 + ρ_f/(2ρ_p)), its median
    ratio in the group), 0 where St_n ≤ St_c, as ``derive``'s ``predicted_restitution``;
    e_dry is the pair's own (``restitution_ceiling``, the resolved dry value ``derive``
    used for the group's runs; their median), the borrowed 0.97 only without it."""
    if "added_mass_stokes_number" not in frame:
        return []
    st_n = frame["normal_stokes_number"].to_numpy(float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = frame["added_mass_stokes_number"].to_numpy(float) / st_n
    names = np.asarray(labels, dtype=object)
    dry = frame["restitution_ceiling"].astype(float) if "restitution_ceiling" in frame else None
    curves = []
    for label in sorted(set(names.tolist())):
        mask = (names == label) & np.isfinite(ratio) & np.isfinite(st_n) & (st_n > 0)
        if not mask.any():
            continue
        low, high = float(np.min(st_n[mask])), float(np.max(st_n[mask]))
        grid = np.geomspace(max(min(low / 2, critical_stokes / 2), 0.1), high * 2, 200)
        e_dry = float(dry[mask].median()) if dry is not None else DRY_RESTITUTION
        e = flow.predicted_restitution(
            grid * float(np.median(ratio[mask])), e_dry, critical_stokes
        )  # fmt: skip
        curves.append({"label": label, "st_n": grid, "e": np.where(grid > critical_stokes, e, 0.0),
                       "e_dry": e_dry})  # fmt: skip
    return curves


def curves_e_dry(curves: Sequence[Mapping[str, Any]]) -> str:
    """The e_dry each predicted curve was drawn with, as its caption says it: "e_dry =
    0.97" when all agree, else each group's ("e_dry = 0.97 (glass on Zerodur in water),
    0.6 (PTFE on Zerodur in water)")."""
    values = {round(c["e_dry"], 3) for c in curves}
    if len(values) == 1:
        return f"e_dry = {next(iter(values)):.3g}"
    return "e_dry = " + ", ".join(f"{c['e_dry']:.3g} ({c['label']})" for c in curves)


def restitution_figure(
    wet: Any,
    labels: Sequence[str],
    colours: Mapping[str, str],
    fitted: Mapping[str, Any],
    frame: Any = None,
) -> dict[str, Any]:
    """Measured e(St_n) of the immersed runs against the predicted curves (§10), with the
    threshold fit when there is one (its St_c labelled as fitted) and, given the whole
    ``frame`` of runs (the fit's groups), the fit's 95 % band; ``fitted`` as in
    ``dataset_figures``."""
    restitution, critical_stokes = fitted["restitution"], fitted["critical_stokes"]
    st_n = wet["normal_stokes_number"].to_numpy(float)
    curves = predicted_curves(wet, labels, critical_stokes)
    errors = _errors(wet, "normal_stokes_number", "normal_restitution")
    line = _restitution_curve(restitution, st_n)
    band = None
    if line is not None and frame is not None:
        band = bands.restitution_band(frame, line[3], line[0])
    svg = plots.restitution_with_prediction(
        st_n, wet["normal_restitution"].to_numpy(float), labels, colours, curves,
        critical_stokes, None if line is None else line[:3], band=band, errors=errors,
    )  # fmt: skip
    caption = (
        "Measured normal restitution against the normal Stokes number St_n = m* v_N,in / "
        "(6πμR*²) (figure 5)"
        + (
            ", with each group's predicted curve (dotted, in the group's colour): e = e_dry "
            "exp(−35/St), Legendre et al. (2006), St = (ρ_p + ρ_f/2) 2R* v_N,in / (9μ) the "
            f"added-mass Stokes number, {curves_e_dry(curves)} (the pair's dry value each "
            f"group's runs used), 0 for St_n ≤ St_c = {critical_stokes:g}"
            if curves
            else ""
        )
        + "."
        + ("" if line is None else " The grey line is the " + fit_said(line[3]) + ".")
        + band_caption(
            band is not None,
            band is not None and line is not None and line[3].get("bootstrap_resamples") == 0,
        ).replace("a line", "the grey line", 1)
        + (plots.ERROR_BARS if errors else "")
    )
    return _figure("fig-restitution", caption, svg, len(st_n))


def _restitution_curve(
    restitution: Sequence[Mapping[str, Any]], st_n: np.ndarray
) -> tuple[np.ndarray, np.ndarray, str, Mapping[str, Any]] | None:
    """(St_n grid, e, legend text, the fit's row) of the first fitted group's curve."""
    fitted = [r for r in restitution if is_number(r.get("parameter")) and is_number(r.get("e_dry"))]
    if not fitted:
        return None
    r = fitted[0]
    grid = np.geomspace(max(1.0, float(np.nanmin(st_n)) * 0.5), float(np.nanmax(st_n)) * 2, 200)
    curve = fits.restitution_curve(r["model"], grid, r["e_dry"], r["parameter"])
    name = parameter_label(r)
    return grid, curve, f"{r['model']} fit, {name} = {r['parameter']:.2g}", r


def fit_said(fit: Mapping[str, Any]) -> str:
    """The restitution fit a figure draws, from its record, in the words of its table and
    of ``granudb fit restitution`` (``fit_view``): its group, form, why, e_dry and its
    parameter ("threshold fit of d: glass/Zerodur, threshold form e = … (…), the report's
    choice …; e_dry 0.968 (interval not determined: not fitted); source: mean e of …;
    fitted St_c 33 [29, 38], fitted, not the verdict's St_c")."""
    name = parameter_label(fit)
    words = (
        f"{fit['model']} fit of {fit['dataset']}: {fit['particle']}/{fit['wall']}, "
        f"{restitution_model(fit)}; e_dry {e_dry_words(fit)}; "
        f"{name} {value_line(fit, restitution_parameter(fit))}"
    )
    if fit.get("parameter_name") == "fitted_critical_stokes":
        words += ", fitted, not the verdict's St_c"
    return words


def thinned(count: int) -> str:
    """The caption's word on thinning (``plots.MAX_POINTS``), or '' when all runs are drawn."""
    if count <= plots.MAX_POINTS:
        return ""
    return (
        f" {plots.MAX_POINTS:,} of the {count:,} runs are drawn (a fixed-seed sample, each "
        "group its share; the legend gives each group's count); fits and tables use every run."
    )


def _figure(figure_id: str, caption: str, svg: str, count: int = 0) -> dict[str, Any]:
    caption += thinned(count)
    return {"id": figure_id, "file": f"{figure_id}.svg", "caption": caption, "svg": svg}
