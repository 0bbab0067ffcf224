"""Past yield, the output says which e applies (issue 33): e_dry below the hand-over speed
V_h (where Thornton's e falls to e_dry), Thornton's elastic–plastic e above it; the JSON's
``restitution_model``, the value used and both verdicts' words agree."""

from __future__ import annotations

import pytest

import granudb
from granudb.physics.limits import handover_speed, thornton_restitution

HARD = {"youngs_modulus": "210 GPa", "poisson_ratio": 0.3, "yield_stress": "2 GPa"}
SOFT = {"youngs_modulus": "70 GPa", "poisson_ratio": 0.33, "yield_stress": "300 MPa"}


def _pair(db, speed: float) -> dict:
    return granudb.pair("hard steel", "aluminium", diameter="12.7 mm", velocity=speed, db=db)


def _said(document: dict) -> tuple[str, str]:
    texts = {v["key"]: v["text"] for v in document["verdicts"]}
    return texts["predicted_restitution"], texts["elastic_state"]


@pytest.fixture
def yielding(opened):
    granudb.add_material("hard steel", density=7800, roughness=0, **HARD, db=opened)
    granudb.add_material("aluminium", density=2700, roughness=0, **SOFT, db=opened)
    return opened


def test_just_past_yield_e_dry_applies_and_is_said_so(yielding) -> None:
    v_y = _pair(yielding, 0.3)["yield_speed_m_s"]
    document = _pair(yielding, 1.02 * v_y)
    e_dry = document["dry_values"]["dry_restitution"]
    assert document["elastic_state"] == "yield_exceeded"
    assert document["restitution_model"] == "elastic"  # the e that applies: e_dry
    assert document["restitution_ceiling"] == document["predicted_restitution"] == e_dry
    for text in _said(document):
        assert f"e_dry = {e_dry:g}" in text and "which applies" in text
        assert "below the hand-over speed" in text
        assert f"elastic–plastic e = {e_dry:g}" not in text


def test_above_the_hand_over_thornton_applies_and_is_said_so(yielding) -> None:
    document = _pair(yielding, 0.3)
    e_t = float(thornton_restitution(document["yield_speed_m_s"], 0.3))
    assert document["restitution_model"] == "elastic_plastic"
    assert document["predicted_restitution"] == pytest.approx(e_t, rel=1e-12)
    for text in _said(document):
        assert f"Thornton's elastic–plastic e = {e_t:.3g}, which applies above the hand-over" in (
            text
        )


def test_the_hand_over_speed_is_where_the_record_changes(yielding) -> None:
    first = _pair(yielding, 0.3)
    v_h = handover_speed(first["dry_values"]["dry_restitution"], first["yield_speed_m_s"])
    assert first["yield_speed_m_s"] < v_h < 0.3
    below, above = _pair(yielding, 0.99 * v_h), _pair(yielding, 1.01 * v_h)
    assert (below["restitution_model"], above["restitution_model"]) == (
        "elastic",
        "elastic_plastic",
    )
    assert above["predicted_restitution"] < below["predicted_restitution"]
    words = f"V_h = {v_h * 1e3:.3g} mm/s"
    assert all(words in text for text in (*_said(below), *_said(above)))
