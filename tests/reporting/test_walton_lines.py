"""Walton lines are drawn only over the Ψ_in range where their branch holds (issue 24), and
the Walton figure's caption says what is drawn."""

from __future__ import annotations

import math
import re

import numpy as np
from paper_runs import paper_rows, write_csv

from granudb.reporting.figures import walton_caption, walton_lines

BETA, MU, E = 0.3, 0.1, 0.9


def _fit(fluid: str | None, model: str | None, **values: float) -> dict:
    return {"particle": "steel", "wall": "Zerodur", "fluid": fluid, "model": model,
            "rotational_restitution": math.nan, "sliding_friction": math.nan,
            "normal_restitution_mean": E, "split_effective_incidence": math.nan,
            **values}  # fmt: skip


def test_each_line_spans_only_its_branch() -> None:
    # split group (a backspin run of folded Ψ_in 0.8 slides), sticking-only, unfitted
    psi = np.array([0.1, 0.2, 0.3, 0.5, 0.6, -0.8, 0.05, 0.4, 0.2, 0.9])
    labels = ["steel/Zerodur dry"] * 6 + ["steel/Zerodur oil"] * 2 + ["steel/Zerodur water"] * 2
    branches = np.array(["sticking"] * 3 + ["sliding"] * 3 + ["sticking"] * 2
                        + ["not determined"] * 2, dtype=object)  # fmt: skip
    fits = [
        _fit(
            None,
            "split",
            rotational_restitution=BETA,
            sliding_friction=MU,
            split_effective_incidence=0.5,
        ),  # fmt: skip
        _fit("oil", "sticking", rotational_restitution=BETA),
        _fit("water", None),
    ]
    lines = {(x["label"], x["branch"]): x for x in walton_lines(psi, labels, branches, fits)}
    assert set(lines) == {("steel/Zerodur dry", "sticking"), ("steel/Zerodur dry", "sliding"),
                          ("steel/Zerodur oil", "sticking")}  # fmt: skip
    stick, slide = lines["steel/Zerodur dry", "sticking"], lines["steel/Zerodur dry", "sliding"]
    assert (stick["x"].min(), stick["x"].max()) == (0.0, 0.5)  # up to the split
    assert (slide["x"].min(), slide["x"].max()) == (0.5, 0.8)  # beyond it, to the last run
    np.testing.assert_allclose(stick["y"], -BETA * stick["x"])
    np.testing.assert_allclose(slide["y"], slide["x"] - MU * (1 + E) * 3.5)
    assert lines["steel/Zerodur oil", "sticking"]["x"].max() == 0.4  # its largest Ψ_in
    caption = walton_caption(list(lines.values()))
    assert "sticking lines" in caption and "sliding lines" in caption and "2 groups" in caption
    only = walton_caption([lines["steel/Zerodur oil", "sticking"]])
    assert "sliding" not in only and "1 group with a line" in only
    assert "no Walton line is drawn" in walton_caption([])


def test_report_without_fits_says_no_line_is_drawn(cli, db, tmp_path) -> None:
    source = write_csv(tmp_path / "two.csv", paper_rows(runs_per_group=2))
    assert cli("collisions", "import", str(source), "--dataset", "two", db=db).exit_code == 0
    out = tmp_path / "two.html"
    result = cli("report", "--dataset", "two", "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    html = out.read_text("utf-8")
    figure = html[html.index('<figure id="fig-walton-figure"') :]
    figure = figure[: figure.index("</figure>")]
    caption = re.search(r"<figcaption>(.*?)</figcaption>", figure, re.S).group(1)
    assert "fitted" not in caption and "no Walton line is drawn" in caption
    assert "sticking, β" not in figure and "sliding, μ_f" not in figure
