"""The large-n interval (issue 36, "Fast at large n"): from ``asymptotic_from`` runs in a
group the Walton and gap-viscosity fits give θ̂ ± z·se (sandwich) instead of the bootstrap,
say so in the record, and hold their coverage. A small version of benchmarks/fit_coverage.py's
n = 10,000 cells: n = 2,000 with the switch lowered to 1,000 through the fits' parameter."""

from __future__ import annotations

import math

import numpy as np
import pytest

from granudb.analysis import asymptotic, bands, fits, gap_viscosity_fit
from granudb.analysis.synthetic import sliding_measured, sliding_runs, walton_frame, walton_measured
from granudb.reporting import figures, tables

N, SWITCH, SETS, QUICK_BOUND = 2000, 1000, 50, 0.84  # true 0.95: P(< 42 of 50) ≈ 0.2 %
TRUTH = {"rotational_restitution": 0.34, "sliding_friction": 0.11, "normal_restitution": 0.97}


def _said_shifts(words: str) -> dict[str, float]:
    """b̂ of each parameter, as the method's words give them ("b̂ = β 0.001, μ_f …")."""
    assert "the value is θ̂, the fit of the runs as measured, not corrected" in words
    given = words.split("(b̂ = ", 1)[1].split(")", 1)[0]
    return {part.rsplit(" ", 1)[0]: float(part.rsplit(" ", 1)[1]) for part in given.split(", ")}


def _covered(rows: list[dict], name: str) -> float:
    hits = [row[f"{name}_low"] <= TRUTH[name] <= row[f"{name}_high"] for row in rows]
    return float(np.mean(hits))


@pytest.mark.parametrize("stated", [False, True])
def test_walton_asymptotic_interval_holds_its_coverage_and_says_its_method(stated) -> None:
    make = (lambda s: walton_measured(N, seed=s)) if stated else (
        lambda s: walton_frame(N, spin=30.0, seed=s)
    )  # fmt: skip
    rows = [fits.walton(make(500 + s), asymptotic_from=SWITCH)[0] for s in range(SETS)]
    said = asymptotic.stated_method(SWITCH) if stated else asymptotic.method(SWITCH, False)
    for row in rows:
        assert row["model"] == "split" and row["bootstrap_resamples"] == 0
        assert row["bootstrap_rule"] == asymptotic.rule(SWITCH)
        assert row["interval_method"].startswith(said)  # one method for the three parameters
        for name in TRUTH:
            assert row[f"{name}_interval_method"] == row["interval_method"]
            assert row[f"{name}_high"] > row[f"{name}_low"]
        if stated:  # the words give each b̂: the interval is centred on the value − b̂
            shifts = _said_shifts(row["interval_method"])
            for name, symbol in zip(TRUTH, ("β", "μ_f", "ē"), strict=True):
                centre = (row[f"{name}_low"] + row[f"{name}_high"]) / 2
                value = row["normal_restitution_mean" if name == "normal_restitution" else name]
                assert centre == pytest.approx(value - shifts[symbol], abs=1e-4 * abs(centre))
        else:
            assert "b̂" not in row["interval_method"]
    for name in TRUTH:
        assert _covered(rows, name) >= QUICK_BOUND, (name, _covered(rows, name))


def test_below_the_switch_and_with_a_count_asked_the_bootstrap_is_unchanged() -> None:
    frame = walton_frame(N, spin=30.0, seed=3)
    default = fits.walton(frame)[0]  # 2,000 < ASYMPTOTIC_FROM: the bootstrap as before
    asked = fits.walton(frame, resamples=1000, asymptotic_from=SWITCH)[0]
    assert default["bootstrap_resamples"] == 1000 and "bootstrap" in default["interval_method"]
    for key in ("rotational_restitution_low", "sliding_friction_high", "normal_restitution_low"):
        assert asked[key] == default[key]  # a count asked for: the same draws, same interval
    large = fits.walton(frame, asymptotic_from=SWITCH)[0]
    for name in TRUTH:  # the two methods agree at this size to a fraction of the width
        low, high = default[f"{name}_low"], default[f"{name}_high"]
        assert abs(large[f"{name}_low"] - low) < 0.25 * (high - low)
        assert abs(large[f"{name}_high"] - high) < 0.25 * (high - low)


def test_gap_viscosity_at_large_n_without_stated_u_is_refused_with_its_bias() -> None:
    """μ₀'s estimate is biased at large n (g from the same noisy speeds as μ_f: the
    uncorrected interval covered 0.465 at n = 10,000, docs/intervals.md): without stated u
    the asymptotic interval is refused where that bias exceeds half its standard error."""
    frame = sliding_runs(1.6e-3, n=N, seed=700)
    [row] = fits.gap_viscosity(frame, {}, asymptotic_from=SWITCH)
    [boot] = fits.gap_viscosity(frame, {}, resamples=300, asymptotic_from=SWITCH)
    assert row["bootstrap_resamples"] == 0 and math.isnan(row["gap_viscosity_low_pa_s"])
    assert "errors-in-variables bias" in row["interval_reason"]
    assert "state the speeds' u" in row["interval_reason"]
    assert row["gap_viscosity_pa_s"] == boot["gap_viscosity_pa_s"]


def test_gap_viscosity_with_stated_u_is_centred_on_the_bias_corrected_value() -> None:
    frame = sliding_measured(701, n=N)
    [row] = fits.gap_viscosity(frame, {}, asymptotic_from=SWITCH)
    assert gap_viscosity_fit.STATED_SHIFT.format(draws=16) in row["interval_method"]
    low, high = row["gap_viscosity_low_pa_s"], row["gap_viscosity_high_pa_s"]
    # the measurement error biases μ₀ low: the corrected interval sits above the estimate's
    # symmetric one, and holds the truth
    assert low < 1.6e-3 < high
    assert (high - row["gap_viscosity_pa_s"]) > (row["gap_viscosity_pa_s"] - low)
    # the value is q̂^(7/2) as measured, and the words give b̂ in q: the interval of q is
    # centred on q̂ − b̂
    words = row["interval_method"]
    assert "the value is q̂^(7/2), the fit of the runs as measured, not corrected" in words
    shift = float(words.split("(b̂ = ", 1)[1].split(" in q)", 1)[0])
    centre = (low ** (2 / 7) + high ** (2 / 7)) / 2
    assert centre == pytest.approx(row["gap_viscosity_pa_s"] ** (2 / 7) - shift, rel=1e-5)


def test_the_report_note_and_the_bands_follow_the_record() -> None:
    frame = walton_frame(N, spin=30.0, seed=4)
    sets: dict = {}
    [row] = fits.walton(frame, sets=sets, asymptotic_from=SWITCH)
    note = tables.bootstrap_note([row])
    assert row["interval_method"] in note and "resamples" not in note
    [key] = sets
    anew = bands.walton_sets(frame, [row])[key]  # made again from the record: the same sets
    assert np.array_equal(anew.beta, sets[key].beta)
    assert np.array_equal(anew.friction, sets[key].friction)
    # the band's sets are the interval's normal law: their spread is the record's se
    assert math.isclose(np.std(sets[key].beta), row["rotational_restitution_stderr"], rel_tol=0.1)


def test_the_band_caption_says_which_sets_the_band_is_drawn_over() -> None:
    said = figures.band_caption(2, 2)
    assert asymptotic.BAND_SETS_WORDS in said and "bootstrap" not in said
    mixed = figures.band_caption(2, 1)
    assert asymptotic.BAND_SETS_WORDS in mixed and "bootstrap parameter sets" in mixed
    assert asymptotic.BAND_SETS_WORDS not in figures.band_caption(2)
