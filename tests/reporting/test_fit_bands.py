"""The 95 % bands of fitted curves (issue 27): made of the fit's own bootstrap sets (so they
agree with its intervals), holding the true curve on synthetic known truth, and drawn
behind the fitted lines of the report with a caption that says what they are, in
headless Chromium like the other report figures."""

from __future__ import annotations

import re

import numpy as np
import pytest
from analysis.synthetic import walton_frame
from analysis.test_restitution_fit import runs as restitution_runs
from paper_runs import paper_rows, write_csv
from reporting.test_report_browser import _check_report, _report

from granudb.analysis import bands, fits, walton_bootstrap
from granudb.analysis.groups import GROUP


def test_walton_bands_are_the_fits_bootstrap_sets() -> None:
    frame = walton_frame(80, seed=4)
    kept: dict = {}
    [row] = fits.walton(frame, sets=kept)
    sets = bands.walton_sets(frame, [row])[tuple(row[k] for k in GROUP)]
    assert len(sets.beta) == row["bootstrap_resamples"]
    # the sets the fit kept (which reports reuse) are the ones made anew
    [same] = kept.values()
    assert np.array_equal(same.beta, sets.beta, equal_nan=True)
    assert np.array_equal(same.friction, sets.friction, equal_nan=True)
    x = np.linspace(0.0, row["split_effective_incidence"], 20)
    low, high = bands.walton_band(sets, "sticking", x, 3.5)
    beta = sets.beta[np.isfinite(sets.beta)]
    # a line through the origin: its band is the line at the percentiles of β
    assert high[-1] == pytest.approx(-np.percentile(beta, 2.5) * x[-1], rel=1e-12)
    assert low[-1] == pytest.approx(-np.percentile(beta, 97.5) * x[-1], rel=1e-12)
    assert np.all(low <= -row["rotational_restitution"] * x + 1e-15)
    assert np.all(-row["rotational_restitution"] * x <= high + 1e-15)
    x = np.linspace(row["split_effective_incidence"], 2.5, 20)
    low, high = bands.walton_band(sets, "sliding", x, 3.5)
    truth = x - 0.11 * (1 + 0.97) * 3.5  # walton_frame's μ_f and e
    assert np.all((low <= truth) & (truth <= high))
    assert np.all(high - low > 0)


@pytest.mark.parametrize(("model", "parameter"), [("threshold", 10.0), ("exponential", 35.0)])
def test_restitution_band_holds_the_true_curve(model: str, parameter: float) -> None:
    grid = np.array([60.0, 300.0])
    truth = fits.restitution_curve(model, grid, 0.97, parameter)
    held = []
    for seed in range(100, 140):  # pointwise coverage of the band over 40 synthetic sets
        frame = restitution_runs(0.97, model, parameter, n=40, seed=seed)
        [row] = fits.restitution(frame, model)
        low, high = bands.restitution_band(frame, row, grid)
        held.append((low <= truth) & (truth <= high))
        fitted = fits.restitution_curve(model, grid, row["e_dry"], row["parameter"])
        assert np.all((low <= fitted + 1e-9) & (fitted - 1e-9 <= high))
    assert np.all(np.mean(held, axis=0) >= 0.85), np.mean(held, axis=0)  # nominal 0.95
    # fewer runs than the bootstrap's minimum: the profile-likelihood interval (issue 36),
    # and no band (a band is drawn from the bootstrap's sets)
    few = restitution_runs(0.97, model, parameter, n=12, seed=8)
    [short] = fits.restitution(few, model)
    assert short["interval_method"].startswith("profile likelihood")
    assert bands.restitution_band(few, short, grid) is None


def test_curve_band_refuses_when_few_sets_determine_the_curve() -> None:
    values = np.full((10, 3), np.nan)
    values[:4] = 1.0
    assert bands.curve_band(values) is None
    assert walton_bootstrap.DEFAULT_RESAMPLES >= 200  # enough sets for 2.5 % tails


@pytest.mark.slow
def test_report_draws_bands_behind_the_fitted_lines_in_chromium(cli, db, tmp_path) -> None:
    source = write_csv(tmp_path / "paper.csv", paper_rows(runs_per_group=40))
    assert cli("collisions", "import", str(source), "--dataset", "paper", db=db).exit_code == 0
    html = _report(cli, db, tmp_path / "bands.html", "--dataset", "paper")
    text = html.read_text("utf-8")
    for figure in ("fig-walton", "fig-restitution"):
        svg = re.search(rf'<svg id="{figure}".*?</svg>', text, re.S).group(0)
        drawn = re.findall(r'<path class="(band|series)"', svg)
        assert "band" in drawn, figure
        # every band comes before (behind) the first fitted line
        assert drawn.index("series") > max(i for i, k in enumerate(drawn) if k == "band")
    assert text.count("Shaded around") == 2  # both captions say what the band is
    assert "not the scatter of single runs" in text
    _check_report(tmp_path, html)
