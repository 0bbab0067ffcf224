"""The bootstrap's allowed split range per resample (``walton_bootstrap._allowed``), found
over a short window first, is the range its definition gives, for dense and sparse draws."""

from __future__ import annotations

import numpy as np
import pytest

from granudb.analysis import walton as core
from granudb.analysis import walton_bootstrap as fast


def _by_definition(w: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    need = core.MIN_RUNS_PER_LINE
    lo, hi, distinct = [], [], []
    for row in w:
        drawn = np.flatnonzero(row[:n] > 0)
        distinct.append(len(drawn))
        if len(drawn) < 2 * need:
            lo.append(n), hi.append(0)
        else:  # the need-th drawn run stays sticking, the need-th last starts sliding
            lo.append(drawn[need - 1] + 1), hi.append(drawn[-need])
    return np.array(lo), np.array(hi), np.array(distinct)


@pytest.mark.parametrize("share", [0.005, 0.03, 0.3, 0.63, 1.0])
def test_allowed_range_is_the_definition(share: float) -> None:
    rng = np.random.default_rng(7)
    for n in (1, 3, 4, 5, 63, 64, 65, 130, 700):
        size = -(-n // fast.BLOCK_RUNS) * fast.BLOCK_RUNS
        w = np.zeros((9, size))
        w[:, :n] = (rng.random((9, n)) < share) * rng.integers(1, 4, (9, n))
        got = fast._allowed(w, n)
        for mine, want in zip(got, _by_definition(w, n), strict=True):
            np.testing.assert_array_equal(mine, want)
