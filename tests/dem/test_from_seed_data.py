"""Issue 16's "done when", from the shipped seed data through the database: steel and glass
on Zerodur, dry and in 37 % and 78 % glycerol, exported with the published values (and the
stated predictions where nothing is published) and run in LIGGGHTS, LAMMPS and Yade: e
within 2 % for normal impacts at 0.1–0.5 m/s, μ_f within 5 % on dry oblique sliding
impacts. A missing code skips this test, or fails it where CI requires the codes
(``GRANUDB_REQUIRE_DEM=1``)."""

from __future__ import annotations

import pytest
from support import require_binary

BINARIES = {"liggghts": "liggghts", "lammps": "lmp", "yade": "yade"}


@pytest.mark.dem_run
@pytest.mark.parametrize("fluid", [None, "glycerol-37", "glycerol-45", "glycerol-78"])
def test_the_codes_give_the_seed_data_back(db: str, fluid: str | None) -> None:
    import granudb

    for binary in BINARIES.values():
        require_binary(binary)
    records = granudb.dem_verify(
        ["steel", "glass"],
        ["Zerodur"],
        codes=tuple(BINARIES),
        fluid=fluid,
        diameter="12.7 mm",
        velocity="0.3 m/s",
        values="published",
        db=db,
    )
    checked = [r for r in records if r.status == "checked"]
    assert checked and len(checked) == len(records)
    normal = [r for r in checked if r.kind == "normal"]
    assert {r.speed_m_s for r in normal} == {0.1, 0.3, 0.5}
    assert all(abs(r.e_rel_error) <= 0.02 for r in normal), [
        (r.code, r.pair, r.speed_m_s, r.e_rel_error) for r in normal
    ]
    # issue 26's "done when": every run passes its tolerance in all three codes (a stated
    # limit, written in the deck, is LIGGGHTS's and Yade's beta at 30 degrees only) --
    # including glass in 78 % glycerol, which slides with the immersed mu = 0.15 (Joseph &
    # Hunt §4, what `pair` uses), and where Yade's friction came back 4.1 % low until its
    # fragment took the input that gives mu on the sliding branch (granudb.dem.yade).
    assert granudb.api.verify_passed(records), granudb.api.verify_table(records)
    sliding = [r for r in checked if r.regime == "gross_slip"]
    assert {r.angle_deg for r in sliding} >= {60.0}
    assert all(abs(r.friction_rel_error) <= 0.03 for r in sliding)
    limited = [r for r in checked if r.verdict == "stated limit"]
    # a stated limit: LIGGGHTS's and Yade's beta (they cannot set k_t) at 30 degrees and
    # mid sticking branch; LAMMPS's only below the range its deck states, where the Psi_out
    # the deck states for that angle is judged instead (issue 33)
    assert bool(limited) == (fluid in (None, "glycerol-37"))  # where a beta is published
    assert all(r.angle_deg == 30.0 or r.angle_deg < 20.0 for r in limited)
    for r in limited:
        if r.code == "lammps":
            assert r.angle_deg < 20.0 and abs(r.stated_rel_error) <= 0.10, r
