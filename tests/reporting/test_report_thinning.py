"""Scatter figures of many runs are thinned by the documented rule and say so; the fits
and the groups' counts still use every run (issue 17)."""

from __future__ import annotations

import re

import numpy as np

from granudb.reporting import figures, plots
from granudb.reporting.groups import colours, group_keys, labels_of


def _points(svg: str) -> int:
    """Markers drawn: each data series is one <path class="series">, a marker one sub-path
    (``M``) of it; the legend's samples are outside ``<g class="legend">``'s data."""
    data = svg.split('<g class="legend">')[0]
    return sum(d.count("M") for d in re.findall(r'<path class="series" d="([^"]*)"', data))


def test_a_dense_figure_draws_at_most_the_limit_each_group_its_share() -> None:
    rng = np.random.default_rng(3)
    sizes = {"a/b dry": 3000, "a/b water": 1000}
    labels = [name for name, n in sizes.items() for _ in range(n)]
    x, y = rng.random(len(labels)), rng.random(len(labels))
    palette = colours(labels)
    kwargs = {"ylabel": "y", "title": "t", "figure_id": "fig-t"}
    svg = plots.against_incidence(x, y, labels, palette, **kwargs)
    assert _points(svg) <= plots.MAX_POINTS
    assert "1,500 of 3,000 runs shown" in svg and "500 of 1,000 runs shown" in svg
    assert svg == plots.against_incidence(x, y, labels, palette, **kwargs)  # same rule, same figure


def test_a_small_figure_draws_every_run_and_says_nothing_of_thinning() -> None:
    labels = ["a/b dry"] * 40
    svg = plots.against_incidence(
        np.linspace(0, 1, 40), np.linspace(0, 1, 40), labels, colours(labels),
        ylabel="y", title="t", figure_id="fig-t",
    )  # fmt: skip
    assert _points(svg) == 40 and "40 runs" in svg and "shown" not in svg
    assert figures.thinned(40) == ""
    assert "2,000 of the 5,000 runs are drawn" in figures.thinned(5000)


def test_share_and_legend_wording() -> None:
    assert plots.share(10, 100) == 10
    assert plots.share(33_334, 100_000) == 667
    assert plots.shown(12, 12) == "12 runs"
    assert plots.shown(33_334, 667) == "667 of 33,334 runs shown"


def test_group_keys_and_labels_treat_missing_fluids_as_dry() -> None:
    import pandas as pd

    frame = pd.DataFrame(
        {"particle": ["s", "s", "g", "s"], "wall": ["Z", "Z", "Z", "Z"],
         "fluid": [None, "water", float("nan"), None]}
    )  # fmt: skip
    assert labels_of(frame) == ["s/Z dry", "s/Z water", "g/Z dry", "s/Z dry"]
    keys = group_keys(frame["particle"], frame["wall"])
    assert keys.tolist() == [("s", "Z"), ("s", "Z"), ("g", "Z"), ("s", "Z")]


def test_a_large_group_states_its_resample_count_beside_the_interval() -> None:
    """A count other than the default is said beside the interval, in the report's cell
    and the command's line alike (``fit_view.value_line``), and the rule in the note."""
    from granudb.analysis.walton_bootstrap import RESAMPLE_RULE
    from granudb.reporting import tables
    from granudb.reporting.fit_view import WALTON, value_line

    method = "studentized bootstrap (bootstrap-t) over runs"
    fit = {
        "dataset": "d", "particle": "steel", "wall": "Zerodur", "fluid": "dry",
        "rotational_restitution": 0.34,
        "rotational_restitution_low": 0.339,
        "rotational_restitution_high": 0.341,
        "rotational_restitution_determined": 1.0,
        "rotational_restitution_interval_method": method,
        "interval_method": method,
        "confidence_level": 0.95,
        "bootstrap_resamples": 303,
        "bootstrap_seed": 0,
        "bootstrap_rule": RESAMPLE_RULE,
    }  # fmt: skip
    cell = tables.walton_table([fit], [], {})["rows"][0][2]
    assert cell == value_line(fit, WALTON[0]) and cell.endswith("(303 resamples, seed 0)")
    note = tables.bootstrap_note([fit, {**fit, "bootstrap_resamples": 1000}])
    assert "303 resamples, seed 0" in note and "1000 resamples" in note
    assert RESAMPLE_RULE in note
    usual = {**fit, "bootstrap_resamples": 1000}
    assert "resamples" not in value_line(usual, WALTON[0])
    assert RESAMPLE_RULE not in tables.bootstrap_note([usual])
