"""The coverage cases and tally of ``benchmarks/coverage_cases.py`` (moved there so that the
benchmark imports no test module, issue 36), for the quick tests."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from coverage_cases import (  # noqa: E402, F401
    BOUND,
    CASES,
    E_DRY,
    LARGE_TRUTH,
    PARAMETER,
    SIZES,
    Case,
    Tally,
    large_sets,
    rows,
    tally,
)
