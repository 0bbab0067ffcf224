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
