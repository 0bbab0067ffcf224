"""``dem verify``'s text table lines up (issue 24): every column starts where its header
does, whatever the length of the pair names, checked or not."""

from __future__ import annotations

from granudb.dem import verify as dem_verify


def test_columns_line_up_with_long_pair_names() -> None:
    checked = dict(status="checked", target_e=0.8, achieved_e=0.801, e_rel_error=0.001,
                   psi_in=0.9, psi_out=0.5, psi_out_walton=0.49, target_friction=0.11,
                   achieved_friction=0.111, friction_rel_error=0.01, verdict="pass")  # fmt: skip
    records = [
        dem_verify.Record("lammps", "glass/Zerodur glycerol-78", "oblique", 0.3, 30, **checked),
        dem_verify.Record("yade", "a/b", "normal", 0.3, 0, **checked),
        dem_verify.Record(
            "liggghts",
            "steel/Zerodur",
            "sphere-sphere",
            1.25,
            0,
            status="not checked",
            target_e=0.9,
            note="not installed",
        ),  # fmt: skip
    ]
    lines = dem_verify.table(records).splitlines()
    head, rows = lines[0], lines[1:4]
    for title in ("pair", "kind"):
        assert {row.index(" ", head.index(title) - 1) for row in rows} == {head.index(title) - 1}
    right = head.index("V m/s") + len("V m/s")
    assert {row[right - 4 : right] for row in rows} == {"0.30", "1.25"}  # speeds end there
    verdict = head.index("verdict")
    assert [row[verdict:].split()[0] for row in rows[:2]] == ["PASS", "PASS"]


def test_the_table_shows_only_what_it_judges() -> None:
    """Issue 33: one line per judged quantity with its tolerance and verdict; μ_f off the
    sliding branch (only a bound) and Ψ_out without a measured β are not shown."""
    base = dict(status="checked", target_e=0.8, achieved_e=0.801, e_rel_error=0.00125,
                psi_in=0.5, psi_out=-0.1, psi_out_walton=-0.17, target_friction=0.11,
                achieved_friction=0.2, friction_rel_error=0.8, verdict="pass")  # fmt: skip
    sticking = dem_verify.Record("lammps", "a/b", "oblique", 0.3, 27, regime="slip_then_stick",
                                 **base)  # fmt: skip
    sliding = dem_verify.Record("lammps", "a/b", "oblique", 0.3, 60, regime="gross_slip",
                                **{**base, "friction_rel_error": 0.01})  # fmt: skip
    rows = dem_verify.table([sticking, sliding]).splitlines()[1:-1]
    quantities = [row.split()[5] for row in rows]
    assert quantities == ["e", "e", "mu_f"]
    assert all(row.split()[-1] in ("PASS", "FAIL") and "%" in row.split()[-2] for row in rows)
    assert rows[0].split()[-2] == "±1%" and rows[2].split()[-2] == "±3%"
