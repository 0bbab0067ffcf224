"""The model refuses what would let a code's mixing rule or a bad number through."""

from __future__ import annotations

import math

import pytest
from dem.dem_cases import E_DRY, GLASS, MU_GLASS, STEEL, ZERODUR, dry_model

from granudb.dem.spec import (
    DemModel,
    PairParameters,
    ParticleType,
    Value,
    predicted_wet_restitution,
)
from granudb.errors import ValidationError


def test_missing_pair_is_named() -> None:
    pairs = [p for p in dry_model().pairs if {p.type_i, p.type_j} != {"glass", "steel"}]
    with pytest.raises(ValidationError, match="pair glass/steel: missing must be given"):
        DemModel([GLASS, STEEL, ZERODUR], pairs, 0.3)


def test_duplicate_pair_is_refused() -> None:
    pairs = list(dry_model().pairs) + [PairParameters("steel", "glass", E_DRY, MU_GLASS)]
    with pytest.raises(ValidationError, match="given once"):
        DemModel([GLASS, STEEL, ZERODUR], pairs, 0.3)


def test_wall_needs_no_diameter_and_particles_need_one() -> None:
    with pytest.raises(ValidationError, match="diameter"):
        ParticleType("w", 1e9, 0.2, 1000.0, 0.01, is_wall=True)
    with pytest.raises(ValidationError, match="poisson_ratio"):
        ParticleType("p", 1e9, 0.6, 1000.0, 0.01)


def test_value_needs_provenance() -> None:
    with pytest.raises(ValidationError, match="provenance"):
        Value(0.5, " ")


def test_contact_scales_match_physics() -> None:
    model = dry_model()
    scales = model.contact(model.pair("steel", "zerodur"))
    assert scales.reduced_modulus_pa == pytest.approx(65.64e9, rel=1e-3)
    assert scales.radius_m == pytest.approx(6.35e-3)
    assert scales.mass_kg == pytest.approx(8.344e-3, rel=1e-3)
    assert 60e-6 < scales.contact_time_s < 80e-6


def test_predicted_wet_restitution_states_its_stokes_number() -> None:
    e, law = predicted_wet_restitution(E_DRY, GLASS, 48e-3, 0.3, 1200.0)
    st = 2 * (2540 + 0.5 * 1200) * 6.35e-3 * 0.3 / (9 * 48e-3)  # with added mass
    assert e.value == pytest.approx(0.97 * math.exp(-35 / st))
    assert f"St_am = {st:.3g}" in e.provenance and "Legendre" in e.provenance
    assert law.restitution(st) == pytest.approx(e.value)


def test_a_run_that_dies_in_mpi_startup_is_tried_again(tmp_path) -> None:
    """Open MPI sometimes aborts before MPI_INIT on a busy machine: that is the runtime's
    failure, not the code's answer, so the run is repeated; other failures are not."""
    import sys

    from granudb.dem import runs

    counter = tmp_path / "count"
    script = tmp_path / "flaky.py"
    script.write_text(
        "import pathlib, sys\n"
        f"p = pathlib.Path({str(counter)!r})\n"
        "n = int(p.read_text()) if p.exists() else 0\n"
        "p.write_text(str(n + 1))\n"
        "if n == 0:\n"
        "    print('*** MPI_ERRORS_ARE_FATAL Local abort before MPI_INIT completed')\n"
        "    sys.exit(1)\n"
        "print('GRANUDB ok')\n"
    )
    assert "GRANUDB ok" in runs.run([sys.executable, str(script)], tmp_path)
    assert counter.read_text() == "2"
    failing = tmp_path / "fails.py"
    failing.write_text("import sys; print('some other error'); sys.exit(3)\n")
    assert "some other error" in runs.run([sys.executable, str(failing)], tmp_path)


def test_the_constant_e_holds_over_the_stated_stokes_range() -> None:
    """At both ends of the range the e(St) law is exactly the tolerance away from the
    constant, and inside it nearer (known truth from the law itself)."""
    from granudb.dem.spec import WetParameters

    law = WetParameters(0.048, 35.0, 0.97, "test")
    e = law.restitution(300.0)
    low, high = law.constant_range(e, 0.01)
    assert low < law.stokes_at(e) < high
    assert law.restitution(low) / e == pytest.approx(0.99, abs=1e-12)
    assert law.restitution(high) / e == pytest.approx(1.01, abs=1e-12)
    assert abs(law.restitution(0.5 * (low + high)) / e - 1.0) < 0.01
    # near e_max the law never leaves the band upwards
    assert law.constant_range(law.restitution(5000.0), 0.01)[1] == float("inf")
