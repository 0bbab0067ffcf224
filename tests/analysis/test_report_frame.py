"""The report's lean frame and the fits' grouping by index (issue 17: a report on a million
runs in bounded memory) give what the plain frame and a plain groupby give."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from analysis.synthetic import walton_frame
from paper_runs import paper_rows, write_csv  # noqa: E402

from granudb.analysis import fits  # noqa: E402
from granudb.analysis.restitution_fit import _group_row  # noqa: E402
from granudb.api.database import connect  # noqa: E402
from granudb.io.collision_import import import_collisions  # noqa: E402
from granudb.reporting.build import REPORT_COLUMNS  # noqa: E402
from granudb.scenario.collision_query import CollisionQuery
from granudb.scenario.collisions import select_collisions  # noqa: E402


def _same(a: object, b: object) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def test_shared_text_frame_holds_the_cells_of_the_plain_frame(db: str, tmp_path: Path) -> None:
    database = connect(db)
    import_collisions(database, write_csv(tmp_path / "paper.csv", paper_rows()), dataset="p")
    with database.session() as session:
        plain = select_collisions(session, CollisionQuery(), columns=REPORT_COLUMNS)
        lean = select_collisions(
            session, CollisionQuery(), columns=REPORT_COLUMNS, shared_text=True
        )
    database.dispose()
    assert list(lean.columns) == list(plain.columns) and len(lean) == len(plain) == 40
    for name in plain.columns:
        if plain[name].dtype.kind in "biuf":
            pd.testing.assert_series_equal(lean[name], plain[name])
            continue
        assert lean[name].dtype == object, name
        cells = lean[name].tolist()
        assert all(_same(a, b) for a, b in zip(cells, plain[name].tolist(), strict=True)), name
        present = [cell for cell in cells if isinstance(cell, str)]
        assert len({id(cell) for cell in present}) == len(set(present)), name
    assert lean["fluid"].isna().sum() == plain["fluid"].isna().sum() > 0  # dry runs


def _groups_frame() -> pd.DataFrame:
    """Runs of several groups interleaved, dry ones with a missing fluid, some NaN."""
    parts = []
    for i, (dataset, fluid) in enumerate(
        [("b", None), ("a", "water"), ("a", None), ("b", "glycerol-37"), ("a", "glycerol-37")]
    ):
        part = walton_frame(60 + 7 * i, seed=i)
        part["dataset"], part["fluid"] = dataset, fluid
        part["normal_stokes_number"] = np.nan if fluid is None else np.linspace(5, 200, len(part))
        parts.append(part)
    frame = pd.concat(parts, ignore_index=True)
    frame = frame.sample(frac=1.0, random_state=1).reset_index(drop=True)
    frame.loc[::17, "effective_rebound"] = np.nan
    frame.loc[::13, "normal_stokes_number"] = np.nan
    return frame


def test_walton_groups_are_those_of_a_groupby() -> None:
    frame = _groups_frame()
    keyed = frame.assign(fluid=frame["fluid"].fillna("dry"))
    expected = [
        fits._walton_group(key, group, None, fits.DEFAULT_SEED)
        for key, group in keyed.groupby(fits.GROUP, sort=True)
    ]
    got = fits.walton(frame)
    assert [tuple(r[k] for k in fits.GROUP) for r in got] == [
        tuple(r[k] for k in fits.GROUP) for r in expected
    ]
    assert len(got) == 5
    for row, want in zip(got, expected, strict=True):
        assert row.pop("fit_method") == "bootstrap"  # set by walton() over every group
        assert row.keys() == want.keys()
        assert all(_same(row[k], want[k]) for k in row), row["fluid"]


@pytest.mark.parametrize("model", ["threshold", "exponential"])
def test_restitution_groups_are_those_of_a_groupby(model: str) -> None:
    frame = _groups_frame()
    frame["normal_restitution"] *= 1 - 5 / frame["normal_stokes_number"].fillna(1e9)
    finite_e = np.isfinite(frame["normal_restitution"])
    immersed = frame[np.isfinite(frame["normal_stokes_number"]) & finite_e]
    dry = frame[frame["fluid"].isna() & finite_e]
    expected = []
    for key, group in immersed.groupby(["dataset", "particle", "wall"], sort=True):
        same = (dry["dataset"] == key[0]) & (dry["particle"] == key[1]) & (dry["wall"] == key[2])
        st = group["normal_stokes_number"].to_numpy(dtype=float)
        e = group["normal_restitution"].to_numpy(dtype=float)
        dry_e = dry.loc[same, "normal_restitution"].to_numpy(dtype=float)
        expected.append(_group_row(model, key, st, e, dry_e))
    got = fits.restitution(frame, model)
    assert len(got) == 2 and [r["n_dry_runs"] for r in got] == [r["n_dry_runs"] for r in expected]
    for row, want in zip(got, expected, strict=True):
        assert row.pop("fit_method") == "bootstrap"  # set by restitution() over every group
        assert row.pop("model_reason") == "as asked"  # restitution_model's, with the form
        assert row.keys() == want.keys()
        assert all(_same(row[k], want[k]) for k in row), row["dataset"]
