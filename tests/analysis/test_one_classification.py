"""One classification per run (issue 24): the regime map's branches are the Walton fit's
own counts, group by group, and a group without a fit is "not determined", never drawn as
sticking."""

from __future__ import annotations

import re

import numpy as np
from paper_runs import paper_rows, write_csv

import granudb
from granudb.analysis import fits


def test_the_map_and_the_walton_table_count_the_same_runs(db, tmp_path) -> None:
    rows = paper_rows(runs_per_group=12)
    rows += [[f"few-{i}", "glass", "Zerodur", "water", "12.7", "20", "300", "109.2", "0",
              "280", "20", "0", "20", "two runs: no fit"] for i in (1, 2)]  # fmt: skip
    source = write_csv(tmp_path / "runs.csv", rows)
    database = granudb.connect(db)
    try:
        granudb.import_collisions(source, dataset="d", db=database)
        frame = granudb.collisions(dataset="d", db=database, wide=True)
        walton = granudb.fit_walton(dataset="d", db=database, as_frame=False)
        report = granudb.report(dataset="d", format="html", db=database)
    finally:
        database.dispose()
    branches = fits.walton_branches(frame, walton)
    assert set(branches) <= set(fits.BRANCHES)
    for fit in walton:
        mask = (frame["particle"] == fit["particle"]).to_numpy() & (
            frame["fluid"].fillna("dry") == (fit["fluid"] or "dry")
        ).to_numpy()
        counted = {b: int(np.sum(branches[mask] == b)) for b in ("sticking", "sliding")}
        if fit.get("model"):
            assert counted == {"sticking": fit["n_sticking"], "sliding": fit["n_sliding"]}, fit
        else:
            assert counted == {"sticking": 0, "sliding": 0}
    few = (frame["fluid"] == "water").to_numpy()
    assert set(branches[few]) == {"not determined"}
    joined = re.sub(r"</text><text[^>]*>", " ", report)  # a long legend label wraps
    legend = re.findall(
        r"(glycerol-\d+|dry|water): (sticking|sliding|not determined) \((\d+)", joined
    )
    assert ("water", "not determined", "2") in legend
