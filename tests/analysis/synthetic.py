"""The fit tests' synthetic generators: they live in ``granudb.analysis.synthetic`` (shared
with benchmarks/fit_coverage.py, which imports no test module)."""

from granudb.analysis.synthetic import (  # noqa: F401
    RADIUS,
    WALTON_FACTOR,
    walton_frame,
    walton_measured,
    with_stated_u,
)
