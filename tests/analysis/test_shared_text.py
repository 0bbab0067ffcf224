"""A chunk's text column is kept with one string object per distinct value (issue 17's
memory bound on a million runs), and holds exactly what ``to_numpy()`` gives."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from granudb.scenario.collisions import _values


def test_text_cells_are_shared_and_equal_to_to_numpy() -> None:
    column = pd.Series(["film", None, "uncertain", "film", "asperity_contact", None] * 1000)
    shared = _values(column)
    plain = column.to_numpy()
    assert shared.dtype == object and len(shared) == len(plain)
    for got, want in zip(shared, plain, strict=True):
        if isinstance(want, float) and math.isnan(want):
            assert isinstance(got, float) and math.isnan(got)
        else:
            assert got == want
    present = [cell for cell in shared if isinstance(cell, str)]
    assert len({id(cell) for cell in present}) == 3  # one object per distinct value


def test_number_columns_pass_through() -> None:
    column = pd.Series([1.5, np.nan, 2.0])
    np.testing.assert_array_equal(_values(column), column.to_numpy())
    flags = pd.Series([True, False])
    assert _values(flags).dtype == bool
