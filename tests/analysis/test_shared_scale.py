"""The catalogue's share of St_n is an error shared by every run of a restitution fit
(issue 36, "nothing held fixed that was estimated"): St_c and k scale with it, so their
interval is widened by it whatever the method; without, the interval misses the truth
that an error of the catalogue moved."""

from __future__ import annotations

import math

import numpy as np
import pytest
from support import write_csv

import granudb
from granudb.analysis import fits, shared_scale
from granudb.analysis.synthetic import restitution_runs
from granudb.scenario import plug_ins

SETS, SHARE, QUICK_BOUND = 40, 0.05, 0.825  # true ≥ 0.95: P(< 33 of 40) ≈ 0.3 %
KEY = ("d", "steel", "Zerodur")


@pytest.mark.parametrize(
    ("model", "truth", "n"), [("exponential", 35.0, 30), ("threshold", 10.0, 8)]
)
def test_a_catalogue_error_is_covered_only_with_its_share(model: str, truth: float, n: int) -> None:
    hits = {False: 0, True: 0}
    for seed in range(SETS):
        frame = restitution_runs(0.97, model, truth, n=n, seed=seed)
        z = np.random.default_rng(10_000 + seed).standard_normal()
        frame["normal_stokes_number"] *= math.exp(SHARE * z)  # the catalogue's one error
        for widen in (False, True):
            scale = {KEY: (SHARE, "the test's catalogue")} if widen else None
            [row] = fits.restitution(frame, model, stokes_scale=scale)
            hits[widen] += row["parameter_low"] <= truth <= row["parameter_high"]
            said = "widened by the catalogue's share of St_n (u_r = 5.00%: the test's catalogue"
            assert (said in row["interval_method"]) is widen
    assert hits[True] / SETS >= QUICK_BOUND, hits
    assert hits[False] < hits[True] - 6, hits  # the share is what covers it


def test_the_widening_is_the_log_quadrature_and_leaves_e_dry() -> None:
    frame = restitution_runs(0.97, "exponential", 35.0, n=30, seed=3)
    [plain] = fits.restitution(frame, "exponential")
    [wide] = fits.restitution(frame, "exponential", stokes_scale={KEY: (0.04, "x")})
    assert wide["parameter"] == plain["parameter"] and wide["e_dry"] == plain["e_dry"]
    assert (wide["e_dry_low"], wide["e_dry_high"]) == (plain["e_dry_low"], plain["e_dry_high"])
    low, high = plain["parameter_low"], plain["parameter_high"]
    value = plain["parameter"]
    z = 1.959963984540054
    assert wide["parameter_low"] == pytest.approx(
        value * math.exp(-math.hypot(math.log(value / low), z * 0.04)), rel=1e-12
    )
    assert wide["parameter_high"] == pytest.approx(
        value * math.exp(math.hypot(math.log(high / value), z * 0.04)), rel=1e-12
    )
    # a share of 0 or an interval not given changes nothing
    assert shared_scale.widened(low, high, value, 0.0, 0.95) == (low, high)
    assert all(map(math.isnan, shared_scale.widened(math.nan, math.nan, value, 0.1, 0.95)))


def _runs(tmp_path, st_at_1: float) -> object:
    """20 immersed runs of steel on Zerodur in glycerol-37 at 20 °C, on e = 0.97
    exp(−35/St_n) with a small scatter, speeds from 20 to 900 mm/s."""
    rng = np.random.default_rng(5)
    rows = []
    for i, v in enumerate(np.geomspace(0.02, 0.9, 20)):
        e = 0.97 * math.exp(-35.0 / (st_at_1 * v)) + rng.normal(0, 0.01)
        rows.append([f"g{i}", "steel", "Zerodur", "glycerol-37", "12.7", "0", f"{v * 1e3:.3f}",
                     "0", "0", f"{e * v * 1e3:.3f}", "0", "0", "20", ""])  # fmt: skip
    return write_csv(tmp_path / "runs.csv", rows)


def test_fit_and_report_take_the_share_pair_propagates(db: str, tmp_path) -> None:
    """Through the database: the fluid's stated u of its viscosity reaches St_c's interval
    as ``granudb.pair`` propagates it into St_n, in ``fit_restitution`` and in the report's
    table alike; before the u is stated nothing is widened."""
    scenario = {"fluid": "glycerol-37", "diameter": "12.7 mm", "temperature": "20 degC"}
    st_at_1 = granudb.pair("steel", "Zerodur", velocity="1 m/s", db=db, **scenario)
    granudb.import_collisions(_runs(tmp_path, st_at_1["normal_stokes_number"]), dataset="g", db=db)
    [before] = granudb.fit_restitution(db=db, model="exponential", as_frame=False)
    assert "catalogue's share" not in before["interval_method"]
    granudb.update_fluid("glycerol-37", reference_viscosity="3.0 ± 0.15 mPa s", db=db)
    document = granudb.pair("steel", "Zerodur", velocity="0.3 m/s", db=db, **scenario)
    share = document["u_normal_stokes_number"] / document["normal_stokes_number"]
    assert 0.04 < share < 0.06  # 5 % on μ, St_n ∝ 1/μ
    [after] = granudb.fit_restitution(db=db, model="exponential", as_frame=False)
    assert f"(u_r = {share:.2%}: {plug_ins.SOURCES};" in after["interval_method"]
    assert after["parameter"] == before["parameter"]
    low, high = shared_scale.widened(
        before["parameter_low"], before["parameter_high"], before["parameter"], share, 0.95
    )
    assert (after["parameter_low"], after["parameter_high"]) == pytest.approx((low, high))
    markdown = granudb.report(dataset="g", format="md", db=db)
    assert f"u_r = {share:.2%}" in markdown
