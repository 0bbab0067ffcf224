"""Intervals that hold their promise (issue 23): a quick coverage check of each kind of fit
(the full table is ``benchmarks/fit_coverage.py``), and never a zero-width interval: three
runs, exact data and a degenerate bootstrap all say "not determined"."""

from __future__ import annotations

import math

import numpy as np
import pytest
from analysis import coverage
from analysis.synthetic import walton_frame
from paper_runs import paper_rows, write_csv

import granudb
from granudb.analysis import fits, gap_viscosity_fit, intervals
from granudb.analysis.synthetic import restitution_runs, sliding_runs

SETS, QUICK_BOUND = 60, 0.85  # true coverage 0.93 (0.95): P(< 51 of 60) = 0.8 % (0.07 %)


@pytest.mark.parametrize(
    "name",
    ["Walton μ_f, split data", "restitution exponential k", "gap viscosity"],
)
def test_quick_coverage(name: str) -> None:
    [case] = [c for c in coverage.CASES if c.name.startswith(name)]
    got = coverage.tally(case, 30, SETS, resamples=300, first_seed=10_000)
    assert got.given >= 0.9 * SETS
    assert got.zero_width == 0
    assert got.coverage >= QUICK_BOUND, got


def test_three_runs_never_give_a_zero_width_interval() -> None:
    # issue 23: three dry runs, one sticking: μ_f 0.0854 [0.0854, 0.0854], "exact"; issue 36:
    # an interval at three runs is the t-interval, of width > 0, or none with the reason
    for seed in range(10):
        [walton] = fits.walton(walton_frame(3, seed=seed))
        for name in ("rotational_restitution", "sliding_friction", "normal_restitution"):
            low, high = walton[f"{name}_low"], walton[f"{name}_high"]
            method = walton[f"{name}_interval_method"]
            if math.isnan(low) or math.isnan(high):
                assert math.isnan(low) and math.isnan(high) and not method, (seed, name)
            else:
                assert high > low and method == (
                    fits.MEAN_METHOD if name == "normal_restitution" else fits.SMALL_N_METHOD
                ), (seed, name)
        if math.isfinite(walton["rotational_restitution"]):
            assert "3 runs cannot test a split" in walton["reason"]
        [restitution] = fits.restitution(restitution_runs(0.97, "threshold", 10.0, n=3, seed=seed))
        for name in ("parameter", "e_dry"):  # issue 36: the profile likelihood, or the reason
            low, high = restitution[f"{name}_low"], restitution[f"{name}_high"]
            if math.isnan(low):
                assert math.isnan(high) and restitution["interval_reason"], seed
            else:
                assert high > low and restitution["interval_method"].startswith("profile")
    [gap] = fits.gap_viscosity(sliding_runs(1.6e-3, n=3, seed=1), {})
    low, high = gap["gap_viscosity_low_pa_s"], gap["gap_viscosity_high_pa_s"]
    if math.isnan(low):
        assert gap["interval_reason"] or gap["reason"]
    else:  # issue 36: the t-interval of q = μ₀^(2/7), of width > 0
        assert high > low and gap["interval_method"].startswith(gap_viscosity_fit.SMALL_N_METHOD)


def test_exact_data_give_no_interval_rather_than_zero_width() -> None:
    # every run exactly on the sliding line: zero standard error, zero bootstrap spread
    [fit] = fits.walton(walton_frame(20, psi_range=(0.75, 2.5), noise=0.0, seed=2))
    assert fit["sliding_friction"] == pytest.approx(0.11, rel=1e-9)
    assert math.isnan(fit["sliding_friction_low"]) and math.isnan(fit["sliding_friction_high"])
    assert "interval of μ_f not determined" in fit["reason"]


def test_a_degenerate_bootstrap_is_not_determined() -> None:
    same = np.full(500, 0.3)
    assert intervals.studentized(0.3, 0.0, same, np.zeros(500)).reason
    got = intervals.studentized(0.3, 0.01, same, np.zeros(500))  # every pivot 0/0
    assert math.isnan(got.low) and "degenerate" in got.reason
    rare = np.where(np.arange(500) < 100, 0.31, np.nan)  # determined in 20 % of resamples
    assert "20%" in intervals.studentized(0.3, 0.01, rare, np.full(500, 0.01)).reason
    assert intervals.too_few(3, 6) == "not determined: 3 runs, at least 6 needed"
    assert intervals.too_few(6, 6) == ""


def test_three_runs_read_interval_not_determined_in_reports_and_decks(cli, db, tmp_path) -> None:
    # issue 23's case end to end: three dry runs, printed "0.0854 [exact]" and written into a
    # deck as "95 % interval 0.0854–0.0854"
    rows = [r for r in paper_rows(runs_per_group=3) if r[3] == ""][:3]
    source = write_csv(tmp_path / "three.csv", rows)
    assert cli("collisions", "import", str(source), "--dataset", "three", db=db).exit_code == 0
    out = tmp_path / "r.md"
    result = cli("report", "--dataset", "three", "--format", "md", "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    text = out.read_text("utf-8")
    assert "interval not determined" in text or "not determined by these runs" in text
    particle, wall = rows[0][1], rows[0][2]
    deck = granudb.dem_export(
        "lammps", [particle], [wall], values="dataset", dataset="three", db=db,
        diameter="12.7 mm", velocity="0.3 m/s",
    )  # fmt: skip
    assert "95 % interval" not in deck or "–" not in deck.split("95 % interval")[1][:30]
    comments = " ".join(deck.replace("\n#", " ").split())  # comments wrap across lines
    # issue 36: one of the three runs sticks by its own kinematics, so no μ_f at all
    assert "does not determine μ_f (model not determined (1 sticking, 2 sliding runs)" in comments
    [fit] = granudb.fit_walton(db, as_frame=False, dataset="three")
    assert fit["model"] is None and math.isnan(fit["sliding_friction"])
    assert "sticks by its own kinematics" in fit["model_reason"]


def test_the_benchmarks_import_no_test_module() -> None:
    # issue 36: benchmarks run without the test extras (no pytest, no tests/ on the path)
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "benchmarks"
    for name in ("fit_coverage.py", "coverage_cases.py", "propagation.py", "fit_speed.py"):
        tree = ast.parse((root / name).read_text("utf-8"))
        imported = [
            n.module if isinstance(n, ast.ImportFrom) else a.name
            for n in ast.walk(tree)
            if isinstance(n, ast.Import | ast.ImportFrom)
            for a in (n.names if isinstance(n, ast.Import) else [n])
        ]
        assert not [m for m in imported if m and m.split(".")[0] in {"analysis", "pytest", "tests"}]
        assert '"tests"' not in (root / name).read_text("utf-8"), name
