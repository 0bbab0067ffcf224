"""The catalogue's share of St_n is an error shared by every run of a restitution fit
(issue 36, "nothing held fixed that was estimated"): St_c and k scale with it, so their
interval is widened by it whatever the method; without, the interval misses the truth
that an error of the catalogue moved."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from paper_runs import RADIUS_MM
from paper_runs import write_csv as write_paper_csv
from support import write_csv

import granudb
from granudb import api
from granudb.analysis import bands, fits, gap_viscosity_fit, shared_scale
from granudb.analysis.synthetic import restitution_runs, sliding_runs
from granudb.api.database import opened
from granudb.reporting.format import interval
from granudb.scenario import plug_ins
from granudb.scenario.collision_query import CollisionQuery
from granudb.scenario.collisions import select_collisions

# the study's μ(T) curve (a benchmark imports no test module; the test imports the
# benchmark's, as tests/physics/test_propagation_study.py does)
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from shared_scale_coverage import curve  # noqa: E402

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


def _runs(tmp_path, st_at_1: float, slope: float = 0.0) -> object:
    """20 immersed runs of steel on Zerodur in glycerol-37 at 20 °C, on e = 0.97
    exp(−35/St_n) with a small scatter, speeds from 20 to 900 mm/s, v_t = ``slope`` v_n."""
    rng = np.random.default_rng(5)
    rows = []
    for i, v in enumerate(np.geomspace(0.02, 0.9, 20)):
        e = 0.97 * math.exp(-35.0 / (st_at_1 * v)) + rng.normal(0, 0.01)
        rows.append([f"g{i}", "steel", "Zerodur", "glycerol-37", "12.7", "",
                     f"{v * 1e3:.3f}", f"{slope * v * 1e3:.3f}", "0", f"{e * v * 1e3:.3f}",
                     f"{0.5 * slope * v * 1e3:.3f}", "0", "20", ""])  # fmt: skip
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


def test_a_catalogue_error_of_g_is_covered_only_with_its_share() -> None:
    """The gap viscosity: an error of the catalogue's E* moves every run's g by one factor
    (g ∝ E*^2.9 here, through A(c) of (5.9)), μ₀ by its −7/2 power."""
    truth, r_e, sets = 1.6e-3, 0.02, 30
    frame = sliding_runs(truth, n=300, seed=0)
    inputs = frame.assign(normal_speed_m_s=frame["v_n_in_m_s"])
    g = gap_viscosity_fit.model_friction(inputs, 1.0)
    moved = inputs.assign(reduced_modulus_pa=inputs["reduced_modulus_pa"] * 1.001)
    slope = float(np.mean(np.log(gap_viscosity_fit.model_friction(moved, 1.0) / g)))
    share = abs(slope / math.log(1.001)) * r_e
    key = ("synthetic", "steel", "Zerodur", "glycerol-37")
    hits = {False: 0, True: 0}
    for seed in range(sets):
        frame = sliding_runs(truth, n=300, seed=seed)
        frame["reduced_modulus_pa"] *= math.exp(r_e * np.random.default_rng(seed).normal())
        for widen in (False, True):
            scale = {key: (share, "E*")} if widen else None
            [row] = fits.gap_viscosity(frame, {}, gap_scale=scale)
            hits[widen] += row["gap_viscosity_low_pa_s"] <= truth <= row["gap_viscosity_high_pa_s"]
            assert ("catalogue's share of g of (5.8)" in row["interval_method"]) is widen
    assert hits[True] >= 25 and hits[False] < hits[True] - 6, hits


def test_the_share_of_g_leaves_out_the_viscosity_the_fit_replaces(db: str, tmp_path) -> None:
    scenario = {"fluid": "glycerol-37", "diameter": "12.7 mm", "temperature": "20 degC"}
    st_at_1 = granudb.pair("steel", "Zerodur", velocity="1 m/s", db=db, **scenario)
    granudb.import_collisions(_runs(tmp_path, st_at_1["normal_stokes_number"], 0.6),
                              dataset="g", db=db)  # fmt: skip

    def shares() -> tuple[dict, dict]:  # on the runs as the fits read them
        with opened(db) as database, database.session() as session:
            frame = select_collisions(session, CollisionQuery())
            apart = plug_ins.stokes_scale(session, frame), plug_ins.gap_scale(session, frame)
            assert plug_ins.catalogue_shares(session, frame) == apart  # the report's way
            return apart

    assert shares() == ({}, {})  # nothing stated
    granudb.update_fluid("glycerol-37", reference_viscosity="3.0 ± 0.15 mPa s", db=db)
    stokes, gap = shares()
    assert list(stokes) == [("g", "steel", "Zerodur")] and gap == {}  # μ is what g leaves out
    granudb.update_material("steel", youngs_modulus="190 GPa ± 5 %", db=db)
    stokes, gap = shares()
    [(share, sources)] = gap.values()
    v_n = float(np.median(np.geomspace(0.02, 0.9, 20)))  # the runs' median speeds
    speed, angle = math.hypot(v_n, 0.6 * v_n), math.atan2(0.6 * v_n, v_n)
    document = granudb.pair("steel", "Zerodur", velocity=f"{speed} m/s",
                            angle=f"{math.degrees(angle)} deg", db=db, **scenario)  # fmt: skip
    u_mu = 2 / 7 * 0.05  # μ_f ∝ μ^(2/7), 5 % on μ
    relative = document["u_lubricated_friction"] / document["lubricated_friction"]
    assert share == pytest.approx(math.sqrt(relative**2 - u_mu**2), rel=1e-3)
    assert sources == plug_ins.GAP_SOURCES


def test_the_report_band_carries_the_share_its_interval_carries() -> None:
    frame = restitution_runs(0.97, "exponential", 35.0, n=30, seed=3)
    [plain] = fits.restitution(frame, "exponential")
    [wide] = fits.restitution(frame, "exponential", stokes_scale={KEY: (0.1, "x")})
    assert math.isnan(plain["shared_scale_u"]) and wide["shared_scale_u"] == 0.1
    grid = np.geomspace(15, 3000, 50)
    (low0, high0), (low1, high1) = (bands.restitution_band(frame, r, grid) for r in (plain, wide))
    steep = grid < 100  # where e(St) moves with k
    assert np.all(high1[steep] - low1[steep] > high0[steep] - low0[steep])


def test_the_gap_temperature_carries_the_curve_it_is_read_from() -> None:
    """μ₀ is turned into the gap temperature through the catalogue's μ(T): an error of that
    curve (5 % here, one draw per set) moves the temperature of every run alike (2 K
    here), which no interval of μ₀ sees; the temperature's interval maps μ₀'s widened by
    the curve's share and then covers the true temperature."""
    truth, share, sets = 1.6e-3, 0.05, 30
    key = "glycerol-37"
    true_temperature = float(curve().temperature_for_viscosity(truth))
    hits = {False: 0, True: 0}
    for seed in range(sets):
        frame = sliding_runs(truth, n=100, seed=seed, fluid=key)
        error = math.exp(share * np.random.default_rng(20_000 + seed).standard_normal())
        models = {key: curve(error)}  # the catalogue's curve, off by one factor
        for widen in (False, True):
            curves = {key: lambda _t: share} if widen else None
            [row] = fits.gap_viscosity(frame, models, curves=curves)
            low, high = row["gap_temperature_low_c"], row["gap_temperature_high_c"]
            hits[widen] += low <= true_temperature <= high
            assert (row["temperature_curve_u"] == share) is widen
            assert ("fluid's μ(T) at that temperature" in row["interval_method"]) is widen
            if widen:  # the temperature's interval is μ₀'s widened, read through the curve
                wide = shared_scale.widened(row["gap_viscosity_low_pa_s"],
                                            row["gap_viscosity_high_pa_s"],
                                            row["gap_viscosity_pa_s"], share, 0.95)  # fmt: skip
                assert low == pytest.approx(float(models[key].temperature_for_viscosity(wide[1])))
                assert high == pytest.approx(float(models[key].temperature_for_viscosity(wide[0])))
    assert hits[True] >= 26 and hits[False] < hits[True] - 8, hits


def _sliding_csv(tmp_path) -> object:
    """40 smooth sliding runs of steel on Zerodur in glycerol-37 at 20 °C whose μ_f is
    (5.8) at μ₀ = 1.6 mPa·s (``sliding_runs``), as a lab's CSV (mm/s; the spin after
    impact from the tangential impulse of a solid sphere)."""
    frame = sliding_runs(1.6e-3, n=40, seed=4)
    v_n, v_t = frame["v_n_in_m_s"] * 1e3, frame["tangential_speed_m_s"] * 1e3
    v_t_out = v_t + (frame["effective_rebound"] * v_n - v_t) / 3.5
    omega_out = (frame["effective_rebound"] * v_n - v_t_out) / RADIUS_MM
    rows = [[f"s{i}", "steel", "Zerodur", "glycerol-37", "12.7",
             f"{math.degrees(math.atan2(v_t[i], v_n[i])):.4f}", f"{v_n[i]:.4f}",
             f"{v_t[i]:.4f}", "0", f"{frame['normal_restitution'][i] * v_n[i]:.4f}",
             f"{v_t_out[i]:.4f}", f"{omega_out[i]:.5f}", "20", "synthetic"]
            for i in range(len(frame))]  # fmt: skip
    return write_paper_csv(tmp_path / "sliding.csv", rows)


def test_fit_and_report_give_the_gap_temperature_the_curves_share(db: str, tmp_path) -> None:
    """Through the database: once the fluid states its viscosity's u, ``fit_gap_viscosity``
    widens the gap temperature's interval by that u at the gap temperature (as
    ``granudb.pair`` states u(μ) there) and says so, and the report's table gives the
    same interval; μ₀'s own interval is not touched (μ is what the fit replaces)."""
    granudb.import_collisions(_sliding_csv(tmp_path), dataset="s", db=db)
    [before] = granudb.fit_gap_viscosity(db=db, as_frame=False)
    assert math.isfinite(before["gap_temperature_low_c"]) and math.isnan(
        before["temperature_curve_u"]
    )
    granudb.update_fluid("glycerol-37", reference_viscosity="3.0 ± 0.15 mPa s", db=db)
    [after] = granudb.fit_gap_viscosity(db=db, as_frame=False)
    at = f"{after['gap_temperature_c']} degC"
    at_gap = granudb.pair("steel", "Zerodur", velocity="1 m/s", db=db, fluid="glycerol-37",
                          diameter="12.7 mm", temperature=at)  # fmt: skip
    u_mu = at_gap["inputs"]["u_viscosity_pa_s"] / at_gap["fluid"]["viscosity_pa_s"]
    assert after["temperature_curve_u"] == pytest.approx(u_mu, rel=1e-9)
    assert after["temperature_curve_u"] == pytest.approx(0.05, rel=1e-6)
    for key in ("gap_viscosity_pa_s", "gap_viscosity_low_pa_s", "gap_viscosity_high_pa_s"):
        assert after[key] == before[key]
    assert after["gap_temperature_low_c"] < before["gap_temperature_low_c"]
    assert after["gap_temperature_high_c"] > before["gap_temperature_high_c"]
    assert f"u_r = {u_mu:.2%}" in after["interval_method"]
    lines = dict(api.fit_people_view("gap_viscosity", after)[1])  # the command's lines
    assert lines["intervals"].startswith("95% ")  # the share's "%" is not a level
    assert after["interval_method"] in lines["intervals"]
    markdown = granudb.report(dataset="s", format="md", db=db)
    cell = interval(after["gap_temperature_c"], after["gap_temperature_low_c"],
                    after["gap_temperature_high_c"])  # fmt: skip
    assert f"{cell} °C".replace("[", "\\[") in markdown  # Markdown escapes the bracket
    assert f"u_r = {u_mu:.2%}: its stated u" in markdown
    assert interval(before["gap_temperature_c"], before["gap_temperature_low_c"],
                    before["gap_temperature_high_c"]) != cell  # fmt: skip
