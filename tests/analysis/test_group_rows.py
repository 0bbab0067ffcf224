"""``group_rows`` finds the same groups and rows as pandas' groupby with missing keys kept."""

import numpy as np
import pandas as pd

from granudb.scenario.row_groups import group_rows


def test_group_rows_match_pandas_groupby_with_missing_keys() -> None:
    rng = np.random.default_rng(5)
    n = 2_000
    frame = pd.DataFrame(
        {
            "particle": rng.choice(np.array(["steel", "glass", None], dtype=object), n),
            "fluid": rng.choice(np.array(["water", "glycerol", None, np.nan], dtype=object), n),
            "e": rng.random(n),
        }
    )
    keys = ["particle", "fluid"]
    found = group_rows(frame, keys)
    cells = frame[keys].astype(object).where(frame[keys].notna(), None)
    expected = {
        tuple(None if pd.isna(k) else k for k in key): rows
        for key, rows in cells.groupby(keys, dropna=False).indices.items()
    }
    assert set(found) == set(expected)
    assert (None, None) in found and ("steel", None) in found  # None and NaN: one group
    for key, rows in expected.items():
        np.testing.assert_array_equal(found[key], rows)
    assert sum(len(r) for r in found.values()) == n
    assert group_rows(frame.iloc[:0], keys) == {}


def test_group_frames_fill_joins_missing_and_fill_value_and_drops_other_missing() -> None:
    from granudb.analysis.groups import group_frames

    frame = pd.DataFrame(
        {
            "particle": np.array(["b", "a", "a", None, "a", "b"], dtype=object),
            "fluid": np.array([None, "dry", np.nan, "water", "water", "water"], dtype=object),
            "e": np.arange(6.0),
        }
    )
    got = [
        (key, rows["e"].tolist())
        for key, rows in group_frames(frame, ["particle", "fluid"], ["e"], fill={"fluid": "dry"})
    ]
    assert got == [
        (("a", "dry"), [1.0, 2.0]),
        (("a", "water"), [4.0]),
        (("b", "dry"), [0.0]),
        (("b", "water"), [5.0]),
    ]
