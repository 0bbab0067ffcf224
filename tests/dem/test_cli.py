"""``granudb dem export|verify`` and ``granudb.dem_export``: from the database to a code's
input, every value with its provenance, checked by the real code where installed."""

from __future__ import annotations

import pytest
from dem.dem_cases import with_restitution
from support import require_binary

SCENARIO = ["--diameter", "12.7 mm", "--velocity", "0.3 m/s"]
CODES = ("liggghts", "lammps", "yade")


def test_export_from_published_values_names_every_source(cli, db: str) -> None:
    out = cli(
        "dem",
        "export",
        "--code",
        "liggghts",
        "--particle",
        "steel",
        "--particle",
        "glass",
        "--wall",
        "Zerodur",
        *SCENARIO,
        db=db,
    )
    assert out.exit_code == 0, out.stderr
    text = out.stdout
    assert "coefficientRestitution peratomtypepair 3" in text
    assert "μ_f = 0.11 ± 0.003" in text  # steel's dry fit, as printed
    assert "μ_f = 0.106 ± 0.008" in text  # glass's
    flat = " ".join(line.lstrip("# ") for line in text.splitlines())
    assert "borrowed from steel on Zerodur_wall, assumed for steel/glass" in flat


def test_immersed_export_states_the_prediction(db: str) -> None:
    import granudb

    text = granudb.dem_export(
        "lammps",
        ["steel"],
        ["Zerodur"],
        fluid="glycerol-37",
        diameter="12.7 mm",
        velocity="0.3 m/s",
        db=db,
    )
    assert "predicted: e = e_dry exp(-35/St_am)" in text
    assert "μ_f ≈ 0.02" in text  # immersed steel, Joseph & Hunt figure 11


@pytest.mark.parametrize(
    ("particle", "fluid"), [("glass", "glycerol-78"), ("steel", "glycerol-37")]
)
def test_pair_and_the_deck_predict_one_wet_restitution(db: str, particle: str, fluid: str) -> None:
    """The issue's case: glass in glycerol-78 at 0.3 m/s had e = 0.203 in the deck (St
    without added mass) and 0.274 in ``pair``; both now take ``flow.predicted_restitution``
    of the added-mass Stokes number."""
    import re

    import granudb

    scenario = {"fluid": fluid, "diameter": "12.7 mm", "velocity": "0.3 m/s", "db": db}
    predicted = granudb.pair(particle, "Zerodur", **scenario)["predicted_restitution"]
    model = granudb.api.dem.dem_model([particle], ["Zerodur"], values="predicted", **scenario)
    in_deck = model.pair(particle, "Zerodur_wall").restitution
    assert in_deck.value == pytest.approx(predicted, rel=1e-12)
    text = granudb.dem_export("liggghts", [particle], ["Zerodur"], values="predicted", **scenario)
    written = re.search(r"coefficientRestitution = ([0-9.]+)", text)
    assert written and float(written.group(1)) == pytest.approx(predicted, rel=1e-3)


def test_a_pair_a_code_cannot_represent_is_refused_in_one_line(cli, db: str) -> None:
    out = cli(
        "dem",
        "export",
        "--code",
        "liggghts",
        "--particle",
        "glass",
        "--wall",
        "Zerodur",
        "--fluid",
        "glycerol-78",
        "--diameter",
        "12.7 mm",
        "--velocity",
        "0.05 m/s",
        db=db,
    )
    assert out.exit_code == 1
    assert out.stderr.count("\n") == 1 and "no rebound is predicted" in out.stderr


def test_unknown_code_names_the_option(cli, db: str) -> None:
    out = cli(
        "dem",
        "export",
        "--code",
        "espresso",
        "--particle",
        "steel",
        "--wall",
        "Zerodur",
        *SCENARIO,
        db=db,
    )
    assert out.exit_code == 1 and out.stderr.startswith("Error: --code: espresso must be one of")


@pytest.mark.dem_run
def test_verify_runs_the_real_code(cli, db: str) -> None:
    require_binary("liggghts")
    out = cli(
        "dem", "verify", "--particle", "steel", "--wall", "Zerodur", *SCENARIO, "--code",
        "liggghts", db=db,
    )  # fmt: skip
    assert out.exit_code == 0, out.stderr
    lines = [line for line in out.stdout.splitlines() if line.startswith(CODES)]
    assert lines and all(line.startswith("liggghts") for line in lines)
    assert all("not checked" not in line for line in lines)
    # the matrix: normal at 0.1, 0.3, 0.5 m/s, oblique at 30 and 60 degrees, and
    # (issue 33) mid sticking branch for a pair with a measured beta
    kinds = {(line.split()[2], line.split()[3], line.split()[4]) for line in lines}
    assert {("normal", v, "0.0") for v in ("0.10", "0.30", "0.50")} <= kinds
    assert {("oblique", "0.30", a) for a in ("30.0", "60.0", "15.8")} <= kinds
    # only judged quantities, each with its tolerance and verdict
    assert {line.split()[5] for line in lines} == {"e", "mu_f", "Psi_out"}
    assert all(line.split()[9].startswith("±") for line in lines)


@pytest.mark.dem_run
def test_verify_for_scripts_is_json_with_the_verdict(cli, db: str) -> None:
    import json

    require_binary("liggghts")
    out = cli(
        "dem", "verify", "--particle", "steel", "--wall", "Zerodur", *SCENARIO, "--format",
        "json", "--code", "liggghts", db=db,
    )  # fmt: skip
    assert out.exit_code == 0, out.stderr
    document = json.loads(out.stdout)
    assert document["passed"] is True and document["summary"].startswith("PASS")
    assert document["tolerances"] == {
        "restitution": 0.01, "friction": 0.03, "rebound": 0.10, "restitution_law": 0.03
    }  # fmt: skip
    checked = [r for r in document["records"] if r["status"] == "checked"]
    # steel on Zerodur has a measured beta that LIGGGHTS cannot set: a limit its deck states
    assert checked and {r["verdict"] for r in checked} == {"pass", "stated limit"}
    limited = [r for r in checked if r["verdict"] == "stated limit"]
    # at 30° and mid sticking branch (15.8°), where dem verify now also checks beta
    assert [(r["kind"], r["angle_deg"]) for r in limited] == [("oblique", 30.0), ("oblique", 15.8)]


@pytest.mark.dem_run
def test_glycerol_78_verifies_and_a_wrong_deck_exits_non_zero(cli, db: str, monkeypatch) -> None:
    """Issue 26: 78 % glycerol gave μ_f +67 % in LIGGGHTS and exited 0; it now passes, and
    the same command on a deck that gives the wrong e fails with the verdict said."""
    from granudb.dem import verify as dem_verify

    require_binary("liggghts")
    args = ["dem", "verify", "--particle", "glass", "--wall", "Zerodur", *SCENARIO, "--fluid",
            "glycerol-78", "--code", "liggghts"]  # fmt: skip
    out = cli(*args, db=db)
    assert out.exit_code == 0, out.stdout
    assert out.stdout.splitlines()[-1].startswith("PASS:")
    writer = dem_verify.WRITERS["liggghts"]
    wrong = staticmethod(lambda m, clamp=False: writer.write(with_restitution(m, 0.8), clamp=clamp))
    monkeypatch.setitem(dem_verify.WRITERS, "liggghts", type("Wrong", (), {"write": wrong}))
    out = cli(*args, db=db)
    assert out.exit_code == 1
    failed = [line.split() for line in out.stdout.splitlines() if line.endswith("FAIL")]
    assert failed and all(row[5] == "e" and row[9] == "±1%" for row in failed)
    assert out.stdout.splitlines()[-1].startswith("FAIL:")


def test_a_dry_fallback_friction_is_not_called_a_prediction(db: str) -> None:
    """Issue 26: a wet export is of a normal impact, so (5.8) has no sliding speed and
    gives no μ_f; the value written is the pair's own (for glass on Zerodur in a liquid the
    immersed 0.15 Joseph & Hunt measured, as ``pair`` uses), and its label says so."""
    import granudb

    text = granudb.dem_export("liggghts", ["glass"], ["Zerodur"], fluid="glycerol-78",
                              diameter="12.7 mm", velocity="0.3 m/s", values="predicted",
                              db=db)  # fmt: skip
    comments = " ".join(line.lstrip("# ") for line in text.splitlines() if line.startswith("#"))
    assert "predicted: lubricated μ_f (5.8)" not in comments
    said = (
        "coefficientFriction = 0.15 (the immersed friction 0.15 granudb pair uses, measured for "
        "glass on Zerodur"
    )
    assert said in comments and "no sliding speed" in comments
    pair = granudb.pair("glass", "Zerodur", fluid="glycerol-78", diameter="12.7 mm",
                        velocity="0.3 m/s", db=db)  # fmt: skip
    assert pair["friction_coefficient_used"] == 0.15  # one answer: pair and the deck


@pytest.mark.parametrize(
    ("fluid", "said"),
    [(None, "rebounds with beta = 0.34 (measured: joseph-hunt-2004 §3, figure 4: β = 0.34 ± 0.07; "
            "± 2u (k = 2, about 95 %), u = 0.07 (the source's ±): 0.2–0.48)"),
     ("glycerol-37",
      "rebounds with beta = 0.6 (measured: joseph-hunt-2004 §4, figure 10: β ≈ 0.6)"),
     ("glycerol-78", "no measured beta for this pair")],
)  # fmt: skip
def test_the_published_beta_of_the_pair_and_fluid_is_exported(db: str, fluid, said) -> None:
    """Walton's β comes from the published values of the same pair and fluid (dry 0.34,
    steel's 0.6 in 37 % glycerol); where none is published the deck says so."""
    import granudb

    text = granudb.dem_export("lammps", ["steel"], ["Zerodur"], fluid=fluid,
                              diameter="12.7 mm", velocity="0.3 m/s", db=db)  # fmt: skip
    flat = " ".join(line.lstrip("# ") for line in text.splitlines() if line.startswith("#"))
    assert said in flat


def test_yade_clamps_a_tiny_restitution_to_its_floor(cli, db: str) -> None:
    """A stored dry e of 0.005 for a putty-like sphere on Zerodur is below Yade's floor
    0.01. Without --clamp one line names the rule; with it the deck is written at 0.01
    (whose clamped damping needs C ≈ 11, past the first bracket of the root search) and
    says so."""
    added = cli("materials", "add", "putty", "--density", "2500 kg/m^3", "--youngs-modulus",
                "70 GPa", "--poisson-ratio", "0.2", "--roughness", "10 nm", db=db)  # fmt: skip
    assert added.exit_code == 0, added.stderr
    stored = cli(
        "pairs", "add", "putty", "Zerodur", "--dry-restitution", "0.005", "--dry-friction",
        "0.11", "--notes", "a nearly dead impact, for the test", db=db,
    )  # fmt: skip
    assert stored.exit_code == 0, stored.stderr
    args = ["dem", "export", "--code", "yade", "--particle", "putty", "--wall", "Zerodur"]
    args += [*SCENARIO, "--values", "predicted"]
    refused = cli(*args, db=db)
    assert refused.exit_code == 1
    assert refused.stderr.count("\n") == 1 and "e < 0.01" in refused.stderr, refused.stderr
    out = cli(*args, "--clamp", db=db)
    assert out.exit_code == 0, out.stderr
    assert "CLAMPED from 0.005 to 0.01: Yade" in out.stdout
