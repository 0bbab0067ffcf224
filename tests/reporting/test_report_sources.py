"""Every value a report shows is credited to the source the catalogue's own commands give
for it (issue 33): a material's stored properties to its source and locator, its own dry
e and μ to its dry provenance (``materials show``), a fluid's values to the fluid's
sources (``fluids show``), the dry values a pair uses to the pair's record (``pairs
show``, whose measured values ``pairs list`` cites); a user's ``--dry-source`` shows; every
source key a value cites is in the references. Read from the HTML and the Markdown
themselves, not from the report's dict."""

from __future__ import annotations

import csv
import html as htmllib
import io
import json
import re
from pathlib import Path

import pytest
from paper_runs import EXAMPLE

#: The stored properties a material block shows under the material's source.
SOURCED = ("density_kg_m3", "youngs_modulus_pa", "poisson_ratio", "roughness_rms_m")


def _blocks_html(text: str) -> dict[str, dict[str, tuple[str, str]]]:
    """{block heading: {machine name: (value, source)}} of an HTML report's properties."""
    section = text[text.index('<section id="properties">') :]
    section = section[: section.index("</section>")]
    out: dict[str, dict[str, tuple[str, str]]] = {}
    for heading, body in re.findall(r"<h3>(.*?)</h3>(.*?)</table>", section, re.S):
        rows = re.findall(
            r'<code class="name"[^>]*>([^<]+)</code></td><td class="num" data-label="Value">'
            r'(.*?)</td><td data-label="Source">(.*?)</td>',
            body,
        )
        out[htmllib.unescape(heading)] = {
            n: (htmllib.unescape(v), htmllib.unescape(s)) for n, v, s in rows
        }
    return out


def _plain_md(text: str) -> str:
    return re.sub(r"\\(.)", r"\1", text).strip()


def _blocks_md(text: str) -> dict[str, dict[str, tuple[str, str]]]:
    """The same, from a Markdown report."""
    section = text[text.index("## Materials and fluid") :]
    section = section[: section.index("\n## ", 5)]
    out: dict[str, dict[str, tuple[str, str]]] = {}
    for part in section.split("\n### ")[1:]:
        heading, _, body = part.partition("\n")
        rows = {}
        for line in body.splitlines():
            found = re.match(r"\|.*`\s*([a-z_0-9]+)\s*` \| (.*?) \| (.*) \|$", line)
            if found:
                rows[found.group(1)] = (_plain_md(found.group(2)), _plain_md(found.group(3)))
        out[_plain_md(heading)] = rows
    return out


def _references(text: str, fmt: str) -> str:
    if fmt == "html":
        return htmllib.unescape(text[text.index("<h3>References</h3>") :])
    return _plain_md(text[text.index("References") :])


def _json(cli, db: str, *args: str) -> dict:
    out = cli(*args, "--format", "json", db=db)
    assert out.exit_code == 0, out.stderr
    return json.loads(out.stdout)


def _report(cli, db: str, tmp_path: Path, fmt: str, *args: str) -> str:
    path = tmp_path / f"report-{len(list(tmp_path.iterdir()))}.{fmt}"
    out = cli("report", *args, "--format", fmt, "--output", str(path), db=db)
    assert out.exit_code == 0, out.stderr
    return path.read_text(encoding="utf-8")


def _check_materials(cli, db, blocks, names) -> set[str]:
    """Each material block's sources against ``materials show``; returns the keys cited."""
    keys = set()
    for name in names:
        shown = _json(cli, db, "materials", "show", name)
        block = next(rows for heading, rows in blocks.items() if heading.endswith(f": {name}"))
        where = (shown["source"] or "—") + (
            f", {shown['source_locator']}" if shown["source"] and shown["source_locator"] else ""
        )
        for column in SOURCED:
            assert block[column][1] == where, (name, column, block[column])
        for column in ("dry_restitution", "dry_friction"):
            expected = shown["dry_provenance"] or "not stated"
            assert block[column][1].startswith(expected), (name, column, block[column])
        keys.add(shown["source"])
    return keys - {None}


def _check_pair(cli, db, blocks, particle, wall) -> set[str]:
    """The pair's dry values used against ``pairs show`` (and ``pairs list``'s source)."""
    shown = _json(cli, db, "pairs", "show", particle, wall)
    block = blocks[f"Dry values used for the pair: {particle} on {wall}"]
    for name in ("dry_restitution", "dry_friction", "immersed_friction"):
        value, source = block[name]
        assert float(value) == pytest.approx(shown[name], rel=1e-3)
        assert source == f"{shown[f'{name}_basis']}: {shown[f'{name}_source']}"
    listed = [
        row
        for row in _json(cli, db, "pairs", "list")
        if {row["particle"], row["wall"]} == {particle, wall}
    ]
    for row in listed:  # a measured pair: its source and locator as pairs list gives them
        assert f"{row['source']}, {row['source_locator']}" in block["dry_friction"][1]
    return {
        key
        for name in ("dry_restitution", "dry_friction", "immersed_friction")
        for key in (shown[f"{name}_source_keys"] or "").split("; ")
        if key
    }


def _check_references(cli, db, text, fmt, keys) -> None:
    listed = _references(text, fmt)
    for key in keys:
        citation = _json(cli, db, "sources", "show", key)["citation"]
        assert citation in listed or key in listed, (fmt, key)


@pytest.fixture
def ptfe_db(cli, db: str) -> str:
    out = cli("materials", "add", "PTFE", "--density", "2200 kg/m^3", "--youngs-modulus",
              "0.5 GPa", "--poisson-ratio", "0.46", "--roughness", "0.5 um",
              "--dry-restitution", "0.6", "--dry-source", "lab note 12", db=db)  # fmt: skip
    assert out.exit_code == 0, out.stderr
    return db


@pytest.mark.parametrize("fmt", ["html", "md"])
def test_pair_report_cites_what_the_catalogue_says(cli, ptfe_db, tmp_path, fmt) -> None:
    for particle, wall in (("glass", "Zerodur"), ("PTFE", "Zerodur")):
        text = _report(cli, ptfe_db, tmp_path, fmt, "--pair", particle, wall, "--fluid", "water")
        blocks = (_blocks_html if fmt == "html" else _blocks_md)(text)
        keys = _check_materials(cli, ptfe_db, blocks, (particle, wall))
        keys |= _check_pair(cli, ptfe_db, blocks, particle, wall)
        fluid = _json(cli, ptfe_db, "fluids", "show", "water")
        fluid_section = blocks["Fluid: water"]
        where = f"{fluid['source']}, {fluid['source_locator']}"
        assert fluid_section["reference_viscosity_pa_s"][1] == where
        # the pair's CSV carries the same record as the report's table
        out = cli("pair", particle, wall, "--fluid", "water", "--diameter", "12.7 mm",
                  "--velocity", "0.3 m/s", "--format", "csv", db=ptfe_db)  # fmt: skip
        [row] = list(csv.DictReader(io.StringIO(out.stdout)))
        used = blocks[f"Dry values used for the pair: {particle} on {wall}"]
        for name in ("dry_restitution", "dry_friction", "immersed_friction"):
            basis, source = row[f"dry_values_{name}_basis"], row[f"dry_values_{name}_source"]
            assert used[name][1] == f"{basis}: {source}"
        if particle == "glass":
            # glass's own dry values are Nijssen et al.'s, and the pair's are not its own
            keys.add("nijssen-ottens-padding-2022")
            assert "this pair uses 0.106, measured for the pair" in blocks[
                "Particle: glass"]["dry_friction"][1]  # fmt: skip
        else:
            assert blocks["Particle: PTFE"]["dry_restitution"][1].startswith("lab note 12")
            used = blocks["Dry values used for the pair: PTFE on Zerodur"]["dry_restitution"]
            assert used[0] == "0.6" and "lab note 12" in used[1]
        _check_references(cli, ptfe_db, text, fmt, keys)


@pytest.mark.parametrize("fmt", ["html", "md"])
def test_dataset_report_cites_what_the_catalogue_says(cli, db, tmp_path, fmt) -> None:
    out = cli("collisions", "import", str(EXAMPLE), "--dataset", "example", db=db)
    assert out.exit_code == 0, out.stderr
    text = _report(cli, db, tmp_path, fmt, "--dataset", "example")
    blocks = (_blocks_html if fmt == "html" else _blocks_md)(text)
    keys = _check_materials(cli, db, blocks, ("glass", "steel", "Zerodur"))
    for particle in ("glass", "steel"):
        keys |= _check_pair(cli, db, blocks, particle, "Zerodur")
    assert "nijssen-ottens-padding-2022" not in keys
    keys.add("nijssen-ottens-padding-2022")  # glass's and steel's own dry provenance
    _check_references(cli, db, text, fmt, keys)
