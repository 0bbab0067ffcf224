"""Every shipped reference package through the one door of reported runs: the packages
that state runs import (``granudb reference import``) with their provenance and u per
run, list with it (JSON and CSV), and fit; the others, a second import of one version
and a reference package given to ``granudb dataset import`` are refused in one line with
the database unchanged. The Kharaz import gives ``reference reproduce``'s μ_f, the VSSUQ
import the package's own glass–glass ē; nothing shows a velocity. (The packages'
``frictionless validate`` and ``cffconvert --validate``: tests/reference/test_library.py.)"""

from __future__ import annotations

import csv
import io
import json
import math
import shutil
import sys
from pathlib import Path

import pytest
from support import dump_hash

import granudb
from granudb.io import reference_library

NAMES = reference_library.names()
VELOCITY = ("v_n_in", "v_t_in", "v_n_out", "v_t_out", "velocity", "speed")
#: The package's particle and wall names that the seeded catalogue spells otherwise, and
#: the materials a test database lacks (added with plausible constants: no fit uses them).
MAPPED = {"aluminium oxide": "alumina", "soda-lime glass": "soda-lime glass (Kharaz anvil)"}
ADDED = ("HDPE", "acrylic")
PROVENANCE = ("source", "source_locator", "digitiser", "licence", "reference_package", "notes")


def _runs_in(name: str) -> set[str]:
    """The points of the package that state a measured e or e_t: the runs it holds."""
    return {
        v["point"]
        for v in reference_library.values(name)
        if v["role"] == "measured"
        and v["quantity"] in ("normal_restitution", "tangential_restitution")
        and v["particle"]
        and v["wall"]
    }


def _prepare(db: str) -> None:
    for material in ADDED:
        granudb.add_material(material, density="1000 kg/m^3", youngs_modulus="2 GPa",
                             poisson_ratio=0.4, roughness="1 um", db=db)  # fmt: skip


def _import(cli, db: str, name: str):
    mapping = [x for k, v in MAPPED.items() for x in ("--material", f"{k}={v}")]
    return cli("reference", "import", name, *mapping, db=db)


@pytest.mark.parametrize("name", NAMES)
def test_each_package_imports_lists_with_provenance_and_fits(cli, db: str, name: str) -> None:
    _prepare(db)
    expected = _runs_in(name)
    before = dump_hash(db)
    done = _import(cli, db, name)
    if not expected:  # conditions and fitted coefficients only: refused, nothing stored
        assert done.exit_code == 1 and done.stderr.count("\n") == 1, done.stderr
        assert "states no run" in done.stderr and f"reference show {name}" in done.stderr
        assert dump_hash(db) == before
        return
    assert done.exit_code == 0, done.stderr
    version = reference_library.descriptor(name)["version"]
    assert f"stored {len(expected)} runs of {name} {version}" in done.stdout

    listed = json.loads(cli("reported", "list", "--collection", name, "--format", "json",
                            db=db).stdout)  # fmt: skip
    assert {r["run"] for r in listed} == expected
    values = {(v["point"], v["quantity"]): v for v in reference_library.values(name)}
    for run in listed:
        assert not any(k.startswith(VELOCITY) for k in run), run
        assert all(run[k] for k in PROVENANCE), run
        assert run["reference_package"] == f"{name} {version}"
        for quantity in ("normal_restitution", "tangential_restitution"):
            stated = values.get((run["run"], quantity))
            if stated is not None and stated["role"] == "measured":  # as the package says
                assert run[quantity] == pytest.approx(float(stated["value"]), rel=1e-12)
                assert run[f"u_{quantity}"] == pytest.approx(float(stated["u"]), rel=1e-12)
                assert run["source_locator"] == stated["locator"]
                assert run["digitiser"] == stated["digitiser"]
                assert run["licence"] == stated["licence"]
    table = csv.DictReader(io.StringIO(cli("reported", "list", "--collection", name,
                                           "--format", "csv", db=db).stdout))  # fmt: skip
    rows = list(table)
    assert {r["run"] for r in rows} == expected
    assert all(r[k] for r in rows for k in PROVENANCE)
    shown = cli("reported", "list", "--collection", name, db=db).stdout  # the table says it too
    for run in listed:
        said = f"{name}: reference package {name} {version}; source {name}; digitiser "
        assert said + f"{run['digitiser']}; licence {run['licence']}" in shown.replace("\n", "")
    source = json.loads(cli("sources", "show", name, "--format", "json", db=db).stdout)
    cited = "; ".join(s["title"] for s in reference_library.descriptor(name)["sources"])
    assert source["citation"].rstrip(".") in cited
    assert (f"doi:{source['doi']}" in cited) == ("doi:" in cited)

    model = "walton" if any(r["tangential_restitution"] is not None for r in listed) else (
        "restitution"
    )  # fmt: skip
    fitted = json.loads(cli("reported", "fit", "--collection", name, "--model", model,
                            "--format", "json", db=db).stdout)  # fmt: skip
    assert fitted and sum(f["n_runs"] for f in fitted) == len(expected)


def test_kharaz_import_gives_the_reproduction_s_friction(cli, db: str) -> None:
    assert _import(cli, db, "kharaz-gorham-salman-2001").exit_code == 0
    fit = granudb.fit_reported("kharaz-gorham-salman-2001", model="walton", db=db)[0]
    check = granudb.reference_reproduce("kharaz-gorham-salman-2001")["checks"][0]
    assert check["quantity"] == "sliding_friction"
    assert fit["sliding_friction"] == pytest.approx(float(check["computed"]), rel=1e-12)
    assert abs(fit["sliding_friction"] - 0.092) < 0.01
    # e is the dataset's condition, not measured: every run says so
    runs = granudb.reported_runs("kharaz-gorham-salman-2001", db=db)
    assert all("condition, not measured" in r["notes"] for r in runs)


def test_vssuq_import_gives_the_package_s_glass_glass_mean(cli, db: str) -> None:
    _prepare(db)
    assert _import(cli, db, "vssuq-dry-collisions").exit_code == 0
    fits = granudb.fit_reported("vssuq-dry-collisions", model="restitution", db=db)
    glass = next(f for f in fits if f["particle"] == "glass" and f["wall"] == "glass")
    derived = {
        v["quantity"]: float(v["value"])
        for v in reference_library.values("vssuq-dry-collisions")
        if v["role"] == "derived" and "glass-glass" in v["point"]
    }
    assert glass["normal_restitution_mean"] == pytest.approx(
        derived["normal_restitution_mean"], abs=5e-5
    )
    assert glass["normal_restitution_std"] == pytest.approx(
        derived["normal_restitution_sd"], abs=5e-5
    )
    assert math.isfinite(glass["normal_restitution_low"])


def test_a_second_import_and_an_unmapped_material_are_refused(cli, db: str) -> None:
    before = dump_hash(db)
    unmapped = cli("reference", "import", "kharaz-gorham-salman-2001", db=db)
    assert unmapped.exit_code == 1 and unmapped.stderr.count("\n") == 1
    assert "aluminium oxide" in unmapped.stderr and "--material" in unmapped.stderr
    assert dump_hash(db) == before
    for bad in ("aluminium oxide", "=alumina", "aluminium oxide="):
        refused = cli("reference", "import", "kharaz-gorham-salman-2001", "--material", bad,
                      db=db)  # fmt: skip
        assert refused.exit_code == 1 and "must be PACKAGE=DATABASE" in refused.stderr
    assert dump_hash(db) == before
    assert _import(cli, db, "kharaz-gorham-salman-2001").exit_code == 0
    imported = dump_hash(db)
    again = cli("reference", "import", "kharaz-gorham-salman-2001", "--as", "other",
                *[x for k, v in MAPPED.items() for x in ("--material", f"{k}={v}")],
                db=db)  # fmt: skip
    assert again.exit_code == 1 and again.stderr.count("\n") == 1
    assert "already imported (collection 'kharaz-gorham-salman-2001')" in again.stderr
    assert dump_hash(db) == imported
    with pytest.raises(granudb.ValidationError, match="already imported"):
        granudb.reference_import("kharaz-gorham-salman-2001", materials=MAPPED, db=db)


def test_dataset_import_points_a_reference_package_to_its_door(
    cli, db: str, tmp_path: Path
) -> None:
    before = dump_hash(db)
    path = reference_library.package_dir("vssuq-dry-collisions")
    for given in (path, path / "datapackage.json"):
        refused = cli("dataset", "import", str(given), db=db)
        assert refused.exit_code == 1 and refused.stderr.count("\n") == 1
        assert "granudb reference import vssuq-dry-collisions" in refused.stderr
    zipped = Path(shutil.make_archive(str(tmp_path / "vssuq"), "zip", path))
    for command in ("import", "validate"):  # the zip too, and validation says the same
        refused = cli(
            "dataset", command, str(zipped), **({"db": db} if command == "import" else {})
        )
        assert refused.exit_code == 1
        assert "granudb reference import vssuq-dry-collisions" in refused.stdout + refused.stderr
    assert dump_hash(db) == before


def test_the_downgrade_names_the_provenance_it_drops(cli, db: str) -> None:
    assert _import(cli, db, "kharaz-gorham-salman-2001").exit_code == 0
    refused = cli("db", "downgrade", "0012", db=db)
    assert refused.exit_code != 0
    assert "reported_runs.digitiser: 11 values" in refused.stdout + refused.stderr


def test_the_reference_page_s_examples_print_what_it_shows() -> None:
    """docs/reference/index.md is not among the pages tests/test_docs_examples.py runs;
    its console blocks (a reference import and its fit, a lab's own CSV with digitiser
    and licence) run here, in the same fixture."""
    repo = Path(__file__).resolve().parents[2]
    if str(repo) not in sys.path:
        sys.path.insert(0, str(repo))
    from tools import docs_examples

    page = repo / "docs" / "reference" / "index.md"
    result = docs_examples.check_page(page)
    assert result.commands >= 5
    assert not result.differences and not result.errors, docs_examples.report([result])


def test_a_lab_s_own_package_imports_from_its_folder(cli, db: str, tmp_path: Path) -> None:
    """A package of reported values outside the shipped library (a copy of VSSUQ's under
    another name and version) imports from its folder, as a shipped one does."""
    own = tmp_path / "our lab"
    shutil.copytree(reference_library.package_dir("vssuq-dry-collisions"), own)
    described = own / "datapackage.json"
    meta = json.loads(described.read_text(encoding="utf-8"))
    meta.update(name="our-lab-2026", version="0.1.0")
    described.write_text(json.dumps(meta), encoding="utf-8")
    _prepare(db)
    done = cli("reference", "import", str(own), db=db)
    assert done.exit_code == 0, done.stderr
    assert "of our-lab-2026 0.1.0 in collection 'our-lab-2026'" in done.stdout
    runs = granudb.reported_runs("our-lab-2026", db=db)
    assert len(runs) == len(_runs_in("vssuq-dry-collisions"))
    assert {r["reference_package"] for r in runs} == {"our-lab-2026 0.1.0"}
    refused = cli("dataset", "import", str(own), db=db)
    assert refused.exit_code == 1
    assert "granudb reference import FOLDER (the package's folder" in refused.stderr
