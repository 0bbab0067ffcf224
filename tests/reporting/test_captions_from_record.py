"""Every caption and method sentence about a fit is read from the fit's own record
(issue 33): fitted with another form or another resample count, the table's note and the
figure's caption change with it; the interval method they name is the one the fit's
record gives (studentized bootstrap-t, not "percentile"); each predicted curve's caption
gives the e_dry that curve was drawn with. Fits on synthetic known truth."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from granudb.analysis import fits
from granudb.analysis.restitution_fit import restitution_model
from granudb.physics.derive import derive
from granudb.reporting import figures, tables

E_DRY, ST_C = 0.9, 12.0


def _runs(n: int = 30, seed: int = 7) -> pd.DataFrame:
    """Immersed runs on the threshold form e = e_dry (1 − St_c/St_n) with 1 % noise."""
    rng = np.random.default_rng(seed)
    st = np.geomspace(20.0, 400.0, n)
    e = E_DRY * (1.0 - ST_C / st) + rng.normal(0.0, 0.01, n)
    return pd.DataFrame({"dataset": "d", "particle": "glass", "wall": "Zerodur",
                         "fluid": "water", "normal_stokes_number": st,
                         "normal_restitution": e})  # fmt: skip


def _figure_caption(rows: list[dict], frame: pd.DataFrame) -> str:
    wet = frame.assign(added_mass_stokes_number=frame["normal_stokes_number"] * 1.2,
                       restitution_ceiling=E_DRY)  # fmt: skip
    labels = ["glass/Zerodur in water"] * len(frame)
    fitted = {"restitution": rows, "critical_stokes": 10.0}
    return figures.restitution_figure(wet, labels, {labels[0]: "#000"}, fitted)["caption"]


def test_the_note_and_caption_follow_the_fit_s_form_and_resamples() -> None:
    frame = _runs()
    threshold = fits.restitution(frame, "threshold", resamples=200)
    exponential = fits.restitution(frame, "exponential", resamples=300)
    assert threshold[0]["parameter"] == pytest.approx(ST_C, rel=0.15)  # the known truth
    said = {}
    for name, rows in (("threshold", threshold), ("exponential", exponential)):
        row = rows[0]
        note = tables.restitution_table(rows)["note"]
        caption = _figure_caption(rows, frame)
        said[name] = (note, caption)
        for text in (note, caption):
            assert f"{name} " in text and row["formula"] in text and row["model_reason"] in text
        assert f"{row['bootstrap_resamples']} resamples, seed {row['bootstrap_seed']}" in note
        assert row["interval_method"] in note and "percentile" not in note
        assert f"e_dry {row['e_dry']:.3g}" in caption  # the table's e_dry words
    assert "200 resamples" in said["threshold"][0] and "300 resamples" in said["exponential"][0]
    assert "fitted St_c" in tables.restitution_table(threshold)["columns"]
    assert "fitted k" in tables.restitution_table(exponential)["columns"]
    assert "St_c is the no-rebound threshold" in said["threshold"][0]
    assert "St_c is the no-rebound threshold" not in said["exponential"][0]
    assert "fitted St_c" not in said["exponential"][1]
    assert all(said["threshold"][i] != said["exponential"][i] for i in (0, 1))


def test_one_decision_of_the_default_form() -> None:
    frame = _runs()
    default, why = restitution_model()
    assert fits.restitution(frame, resamples=50)[0]["model"] == default
    reported = fits.restitution(frame, report=True, resamples=50)[0]
    assert reported["model"] == restitution_model(report=True)[0]
    # where the report shows another form than the default, its note says why
    if reported["model"] != default:
        note = tables.restitution_table([reported])["note"]
        assert reported["model_reason"] in note and default in reported["model_reason"]


def test_each_predicted_curve_s_caption_gives_its_own_e_dry() -> None:
    speeds = np.array([0.1, 0.2, 0.4])
    parts = []
    for e_dry in (0.97, 0.6):
        derived = derive(
            diameter_m=12.7e-3, v_n_in_m_s=speeds, v_t_in_m_s=0.0,
            particle_density_kg_m3=2200.0, particle_youngs_modulus_pa=0.5e9,
            particle_poisson_ratio=0.46, particle_roughness_rms_m=130e-9,
            wall_density_kg_m3=2540.0, wall_youngs_modulus_pa=91e9, wall_poisson_ratio=0.24,
            wall_roughness_rms_m=15e-9, viscosity_pa_s=4.5e-3, fluid_density_kg_m3=1112.0,
            dry_restitution=e_dry,
        )  # fmt: skip
        part = pd.DataFrame({c: derived[c] for c in figures.WET_COLUMNS if c in derived})
        parts.append(part.assign(normal_restitution=0.5))
    wet = pd.concat(parts, ignore_index=True)
    labels = ["glass/Zerodur"] * 3 + ["PTFE/Zerodur"] * 3
    caption = figures.restitution_figure(
        wet,
        labels,
        {"glass/Zerodur": "#000", "PTFE/Zerodur": "#c00"},
        {"restitution": [], "critical_stokes": 10.0},
    )["caption"]
    assert "0.97 (glass/Zerodur)" in caption and "0.6 (PTFE/Zerodur)" in caption
    assert "e_dry = 0.97," not in caption
