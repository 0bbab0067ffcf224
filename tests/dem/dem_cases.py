"""The DEM models of ``benchmarks/dem_models.py`` (there so that the benchmark imports no
test module, issue 36) and ``require``, for the tests of granudb.dem."""

import sys
from pathlib import Path

from support import require_binary

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from dem_models import (  # noqa: E402, F401
    BETA_GLASS,
    BETA_STEEL,
    BINARIES,
    E_DRY,
    FLUID_DENSITIES,
    FLUIDS,
    GLASS,
    MU_GLASS,
    MU_STEEL,
    STEEL,
    TABLE_1,
    WET_BETA,
    ZERODUR,
    dry_model,
    wet_model,
    with_restitution,
)


def require(code: str) -> None:
    """Skip a run-test when the code's binary is missing; fail instead where CI requires
    the codes (``GRANUDB_REQUIRE_DEM=1``)."""
    require_binary(BINARIES[code])
