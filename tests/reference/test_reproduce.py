"""Reproduction of the reference datasets: the Kharaz Walton fit, VSSUQ's printed
statistics, the wet cases' Stokes numbers and Legendre's e(St); the command line says what
the Python function returns; the relations from reported e_t to Walton's Ψ recover a
known truth."""

from __future__ import annotations

import doctest
import json
import math

import numpy as np
import pytest

import granudb
from granudb.analysis import fits
from granudb.lazy import pandas as pd
from granudb.physics import reported

KHARAZ = "kharaz-gorham-salman-2001"


def test_every_reference_dataset_has_checks_with_verdicts() -> None:
    names = [d["name"] for d in granudb.reference_list()]
    assert len(names) == 5
    for name in names:
        result = granudb.reference_reproduce(name)
        assert result["checks"], name
        for check in result["checks"]:
            assert check["verdict"] in ("agrees", "differs") or check["verdict"].startswith(
                "prediction only"
            ), check


def test_kharaz_walton_fit_gives_the_papers_friction() -> None:
    result = granudb.reference_reproduce(KHARAZ)
    fit = next(c for c in result["checks"] if c["quantity"] == "sliding_friction")
    assert fit["reported"] == 0.092
    assert abs(fit["computed"] - 0.092) <= 0.01
    assert fit["verdict"] == "agrees"
    said = result["summary"][0]
    assert f"μ_f = {fit['computed']:.4f}" in said
    interval = said.split("interval ")[1]
    assert interval.startswith("["), said  # 7 sliding runs: a small-n interval, labelled
    low, high = (float(x) for x in interval[1:].split("]")[0].split(", "))
    assert low <= fit["computed"] <= high and low <= 0.092 <= high
    assert "t-interval" in said


def test_kharaz_checks_cover_every_figure_point() -> None:
    shown = granudb.reference_show(KHARAZ)
    points = {v["point"] for v in shown["values"] if v["point"] != "conditions"}
    checked = {c["point"] for c in granudb.reference_reproduce(KHARAZ)["checks"]}
    assert points <= checked


def test_vssuq_statistics_are_the_printed_ones() -> None:
    result = granudb.reference_reproduce("vssuq-dry-collisions")
    glass = {c["quantity"]: c for c in result["checks"] if c["point"] == "epp_glass-glass"}
    assert round(glass["normal_restitution_mean"]["computed"], 4) == 0.9696
    assert round(glass["normal_restitution_sd"]["computed"], 4) == 0.0150
    assert {c["verdict"] for c in result["checks"]} == {"agrees"}
    assert any("epp_glass-glass: normal_restitution n = 24" in s for s in result["summary"])


def test_wet_cases_predict_without_inventing_a_measured_e() -> None:
    gondret = granudb.reference_reproduce("gondret-lance-petit-2002")["checks"]
    predictions = [c for c in gondret if c["quantity"] == "normal_restitution"]
    assert len(predictions) == 5
    assert all(math.isnan(c["reported"]) for c in predictions)
    assert all(c["verdict"].startswith("prediction only") for c in predictions)
    e = {c["point"]: c["computed"] for c in predictions}
    assert e["Case_St27"] < e["Case_St152"] < e["Case_St742"] < 0.97  # e rises with St
    joseph = granudb.reference_reproduce("joseph-hunt-2004-tables")["checks"]
    figure3 = next(c for c in joseph if c["quantity"] == "normal_restitution")
    assert figure3["reported"] == 0.708 and abs(figure3["residual"]) < 0.02


def test_the_command_line_prints_what_the_function_returns(cli) -> None:
    shown = cli("reference", "reproduce", KHARAZ, "--format", "json")
    assert shown.exit_code == 0, shown.stderr
    printed = json.loads(shown.stdout)
    direct = granudb.reference_reproduce(KHARAZ)
    assert printed["summary"] == direct["summary"]
    assert [c["verdict"] for c in printed["checks"]] == [c["verdict"] for c in direct["checks"]]
    listed = cli("reference", "list", "--format", "json")
    assert [d["name"] for d in json.loads(listed.stdout)] == [
        d["name"] for d in granudb.reference_list()
    ]
    table = cli("reference", "reproduce", "vssuq-dry-collisions")
    assert table.exit_code == 0 and "0.9696" in table.stdout


def test_an_unknown_name_is_one_line(cli) -> None:
    result = cli("reference", "show", "kharaz-2001")
    assert result.exit_code == 1
    assert result.stderr.strip().count("\n") == 0
    assert "did you mean kharaz-gorham-salman-2001?" in result.stderr
    with pytest.raises(granudb.ValidationError):
        granudb.reference_reproduce("nope")


def test_reported_relations_doctests() -> None:
    result = doctest.testmod(reported, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0


def test_e_t_of_a_known_walton_model_fits_back_to_its_parameters() -> None:
    """Synthetic truth: μ_f = 0.12, β = 0.3, e = 0.9. e_t(θ) from the textbook laws (sliding
    e_t = 1 − μ_f (1+e)/tan θ; sticking e_t = (5 − 2β)/7), turned into Ψ by the no-spin-in
    relations, fitted by granudb's Walton fit."""
    mu, beta, e = 0.12, 0.3, 0.9
    theta = np.radians(np.linspace(3.0, 75.0, 40))
    rng = np.random.default_rng(7)
    sliding = 1.0 - mu * (1.0 + e) / np.tan(theta)
    sticking = np.full_like(theta, (5.0 - 2.0 * beta) / 7.0)
    e_t = np.maximum(sliding, sticking) + rng.normal(0.0, 0.002, theta.size)
    psi_in = reported.incidence_from_angle(theta)
    frame = pd.DataFrame(
        {
            "dataset": "synthetic",
            "particle": "p",
            "wall": "w",
            "fluid": None,
            "effective_incidence": psi_in,
            "effective_rebound": reported.rebound_from_tangential_restitution(psi_in, e_t),
            "normal_restitution": np.full(theta.size, e),
        }
    )
    row = fits.walton(frame, resamples=200, seed=1)[0]
    assert row["model"] == "split"
    assert row["sliding_friction"] == pytest.approx(mu, abs=0.004)
    assert row["rotational_restitution"] == pytest.approx(beta, abs=0.03)
    # the inverse relation gives e_t back
    back = reported.tangential_restitution_from_rebound(
        psi_in, reported.rebound_from_tangential_restitution(psi_in, e_t)
    )
    assert np.allclose(back, e_t)
