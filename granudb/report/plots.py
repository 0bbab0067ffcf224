"""The report's figures, as deterministic SVG text.

Each function takes plain arrays and returns an SVG string with axis labels, units and a
legend. Output is byte-identical for the same input: matplotlib's SVG ids are seeded
(``svg.hashsalt``), the date metadata is dropped, and dense data is thinned with a fixed
random seed so 100,000 runs still make a figure of a few hundred kilobytes.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from typing import Any

import numpy as np

MAX_POINTS = 1500  # per series; more points add bytes, not information, to a scatter plot
FIGSIZE = (6.0, 4.2)
COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf"]


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update(
        {
            "svg.hashsalt": "granudb",
            "svg.fonttype": "none",  # text stays text: smaller, searchable, selectable
            "font.size": 10,
            "axes.grid": True,
            "grid.alpha": 0.3,
        }
    )
    return plt


def _svg(figure: Any, figure_id: str) -> str:
    plt = _pyplot()
    buffer = io.StringIO()
    figure.savefig(buffer, format="svg", bbox_inches="tight", metadata={"Date": None})
    plt.close(figure)
    text = buffer.getvalue()
    # Drop the XML prolog and DOCTYPE so the SVG can be inlined in HTML; give it an id.
    start = text.index("<svg")
    svg = text[start:]
    return svg.replace("<svg ", f'<svg id="{figure_id}" role="img" ', 1)


def thin(*arrays: np.ndarray, limit: int = MAX_POINTS) -> tuple[np.ndarray, ...]:
    """At most ``limit`` points, the same subset of every array (seeded, so repeatable)."""
    n = len(arrays[0])
    if n <= limit:
        return arrays
    keep = np.sort(np.random.default_rng(20040101).choice(n, size=limit, replace=False))
    return tuple(np.asarray(a)[keep] for a in arrays)


def _scatter_groups(ax: Any, x: np.ndarray, y: np.ndarray, groups: Sequence[str]) -> None:
    labels = np.asarray(groups, dtype=object)
    for index, name in enumerate(sorted(set(labels.tolist()))):
        mask = labels == name
        gx, gy = thin(x[mask], y[mask])
        ax.scatter(
            gx,
            gy,
            s=14,
            alpha=0.75,
            color=COLOURS[index % len(COLOURS)],
            label=f"{name} ({int(mask.sum())} runs)",
        )


def walton_plot(
    psi_in: np.ndarray,
    psi_out: np.ndarray,
    groups: Sequence[str],
    fits: Sequence[dict[str, Any]],
    figure_id: str = "fig-walton",
) -> str:
    """Ψ_out against Ψ_in with the fitted Walton lines (Joseph & Hunt figures 4, 6, 9).

    ``fits``: one dict per group with ``label``, ``rotational_restitution`` (β),
    ``sliding_friction`` (μ_f), ``normal_restitution_mean`` (ē): sticking line
    Ψ_out = −βΨ_in, sliding line Ψ_out = Ψ_in − μ_f(1+ē)(1 + 1/K²), K² = 2/5.
    """
    plt = _pyplot()
    figure, ax = plt.subplots(figsize=FIGSIZE)
    x, y = np.asarray(psi_in, float), np.asarray(psi_out, float)
    _scatter_groups(ax, x, y, groups)
    top = float(np.nanmax(x)) if x.size else 1.0
    line = np.linspace(0.0, top, 50)
    for index, fit in enumerate(fits):
        colour = COLOURS[index % len(COLOURS)]
        beta = fit.get("rotational_restitution")
        mu = fit.get("sliding_friction")
        e = fit.get("normal_restitution_mean")
        if beta is not None and np.isfinite(beta):
            ax.plot(
                line,
                -beta * line,
                "--",
                color=colour,
                lw=1.2,
                label=f"{fit['label']}: −βΨ_in, β = {beta:.3g}",
            )
        if mu is not None and e is not None and np.isfinite(mu) and np.isfinite(e):
            ax.plot(
                line,
                line - mu * (1 + e) * 3.5,
                "-",
                color=colour,
                lw=1.2,
                label=f"{fit['label']}: sliding, μ_f = {mu:.3g}",
            )
    ax.axhline(0.0, color="black", lw=0.6)
    ax.set_xlabel("Ψ_in = v_T,in / v_N,in  (–)")
    ax.set_ylabel("Ψ_out = v_T,out / v_N,in  (–)")
    ax.set_title("Tangential rebound (Walton model)")
    ax.legend(fontsize=7, loc="best")
    return _svg(figure, figure_id)


def against_incidence(
    psi_in: np.ndarray,
    values: np.ndarray,
    groups: Sequence[str],
    *,
    ylabel: str,
    title: str,
    figure_id: str,
    reference: float | None = None,
    reference_label: str = "",
) -> str:
    """A per-collision parameter (β or μ_f) against Ψ_in (figures 7, 8, 10, 11)."""
    plt = _pyplot()
    figure, ax = plt.subplots(figsize=FIGSIZE)
    _scatter_groups(ax, np.asarray(psi_in, float), np.asarray(values, float), groups)
    if reference is not None and np.isfinite(reference):
        ax.axhline(reference, color="black", ls=":", lw=1.0, label=reference_label)
    ax.set_xlabel("Ψ_in = v_T,in / v_N,in  (–)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=7, loc="best")
    return _svg(figure, figure_id)


def restitution_vs_stokes(
    stokes: np.ndarray,
    restitution: np.ndarray,
    groups: Sequence[str],
    curve: tuple[np.ndarray, np.ndarray, str] | None = None,
    critical_stokes: float | None = None,
    figure_id: str = "fig-restitution",
) -> str:
    """e against the normal Stokes number, with the fitted curve (figure 5)."""
    plt = _pyplot()
    figure, ax = plt.subplots(figsize=FIGSIZE)
    _scatter_groups(ax, np.asarray(stokes, float), np.asarray(restitution, float), groups)
    if curve is not None:
        ax.plot(curve[0], curve[1], "-", color="black", lw=1.2, label=curve[2])
    if critical_stokes is not None:
        ax.axvline(
            critical_stokes, color="grey", ls="--", lw=1.0, label=f"St_c = {critical_stokes:g}"
        )
    ax.set_xscale("log")
    ax.set_xlabel("normal Stokes number St_n = 2ρ_p R v_N,in / (9μ)  (–)")
    ax.set_ylabel("normal restitution e  (–)")
    ax.set_title("Restitution against Stokes number")
    ax.legend(fontsize=7, loc="best")
    return _svg(figure, figure_id)


def friction_vs_shear_strain(
    strain: np.ndarray,
    friction: np.ndarray,
    groups: Sequence[str],
    figure_id: str = "fig-shear-strain",
) -> str:
    """μ_f against the shear strain (μ₀U/(E*R))^{2/7} (figure 15)."""
    plt = _pyplot()
    figure, ax = plt.subplots(figsize=FIGSIZE)
    _scatter_groups(ax, np.asarray(strain, float), np.asarray(friction, float), groups)
    ax.set_xscale("log")
    ax.set_xlabel("shear strain (μ₀U / (E*R))^{2/7}  (–)")
    ax.set_ylabel("friction coefficient μ_f  (–)")
    ax.set_title("Friction against shear strain")
    ax.legend(fontsize=7, loc="best")
    return _svg(figure, figure_id)


REGIME_COLOURS = {
    "no rebound": "#d9d9d9",
    "rebound, asperity contact (σ > h_m)": "#fdae6b",
    "rebound, full film (σ ≤ h_m)": "#9ecae1",
}


def regime_map(
    velocity_m_s: np.ndarray,
    viscosity_pa_s: np.ndarray,
    regime: np.ndarray,
    gap_line: tuple[np.ndarray, np.ndarray] | None,
    stokes_line: tuple[np.ndarray, np.ndarray] | None,
    point: tuple[float, float] | None = None,
    figure_id: str = "fig-regime-map",
    runs: tuple[np.ndarray, np.ndarray] | None = None,
) -> str:
    """Impact velocity × viscosity plane shaded by regime, with h_m = σ and St = St_c.

    ``regime`` is a 2-D array of labels (keys of ``REGIME_COLOURS``) on the grid
    ``viscosity_pa_s`` (rows) × ``velocity_m_s`` (columns).
    """
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    plt = _pyplot()
    names = list(REGIME_COLOURS)
    codes = np.vectorize(names.index)(regime)
    figure, ax = plt.subplots(figsize=FIGSIZE)
    # contourf draws one polygon per region (a few kB); pcolormesh one per cell (~0.5 MB).
    ax.contourf(
        velocity_m_s,
        viscosity_pa_s * 1e3,
        codes,
        levels=np.arange(len(names) + 1) - 0.5,
        cmap=ListedColormap([REGIME_COLOURS[n] for n in names]),
    )
    handles = [Patch(color=REGIME_COLOURS[n], label=n) for n in names]
    if gap_line is not None:
        (line,) = ax.plot(
            gap_line[0], gap_line[1] * 1e3, "-", color="black", lw=1.4, label="h_m = σ"
        )
        handles.append(line)
    if stokes_line is not None:
        (line,) = ax.plot(
            stokes_line[0], stokes_line[1] * 1e3, "--", color="black", lw=1.2, label="St_n = St_c"
        )
        handles.append(line)
    if runs is not None and len(runs[0]):
        rv, rmu = thin(np.asarray(runs[0], float), np.asarray(runs[1], float))
        (dots,) = ax.plot(
            rv,
            rmu * 1e3,
            ".",
            color="black",
            ms=3,
            alpha=0.6,
            label=f"measured runs ({len(runs[0])})",
        )
        handles.append(dots)
    if point is not None:
        (marker,) = ax.plot(
            [point[0]], [point[1] * 1e3], "*", color="crimson", ms=12, label="this collision"
        )
        handles.append(marker)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(float(np.min(velocity_m_s)), float(np.max(velocity_m_s)))
    ax.set_ylim(float(np.min(viscosity_pa_s)) * 1e3, float(np.max(viscosity_pa_s)) * 1e3)
    ax.set_xlabel("normal impact velocity v_N,in  (m/s)")
    ax.set_ylabel("fluid viscosity μ  (mPa·s)")
    ax.set_title("Regime map")
    ax.legend(handles=handles, fontsize=7, loc="lower right")
    return _svg(figure, figure_id)
