"""Issue 15's report findings, one test each; every one fails on the report code before
the split (empty materials section, published values on the wrong group, "nan" legends,
float noise, column names as labels, TeX source, references, one regime map, crashes on
LaTeX-looking names, silent assumptions)."""

from __future__ import annotations

import html as htmllib
import re
from pathlib import Path

import pytest

from granudb.reporting.references import cited_in


def _report(cli, db, tmp_path: Path, *args: str, fmt: str = "html") -> str:
    out = tmp_path / f"r-{abs(hash(args)) % 10**8}.{fmt}"
    result = cli("report", *args, "--format", fmt, "--output", str(out), db=db)
    assert result.exit_code == 0, result.stderr
    return out.read_text(encoding="utf-8")


def _rows(html: str, table_id: str) -> dict[str, str]:
    """Rows of a report table by their group cell's text (tags dropped)."""
    section = html[html.index(f'id="{table_id}"') :]
    section = section[: section.index("</table>")]
    rows = {}
    for row in re.findall(r"<tr>(.*?)</tr>", section, re.S):
        cells = [
            htmllib.unescape(re.sub(r"<[^>]+>", "", c))
            for c in re.findall(r"<td[^>]*>(.*?)</td>", row, re.S)
        ]  # noqa: E501
        if cells:
            rows[cells[0]] = " | ".join(cells[1:])
    return rows


def _legend_texts(svg_html: str) -> list[str]:
    texts = []
    for legend in re.findall(r'<g class="legend">(.*?)</g></g>', svg_html, re.S):
        texts += [htmllib.unescape(t) for t in re.findall(r"<text[^>]*>([^<]*)</text>", legend)]
    return texts


@pytest.mark.parametrize("fmt", ["html", "md"])
def test_dataset_report_lists_materials_and_fluids(cli, example_db, tmp_path, fmt) -> None:
    text = _report(cli, example_db, tmp_path, "--dataset", "example", fmt=fmt)
    section = text[text.index("Materials and fluid") :]
    for heading in ("Particle: glass", "Particle: steel", "Wall: Zerodur", "Fluid: glycerol-37",
                    "Fluid: glycerol-45"):  # fmt: skip
        assert heading in section.split("Derived quantities")[0].split("Walton fits")[0]
    assert "60 GPa" in section and "joseph-hunt-2004, table 1" in section


def test_published_values_land_on_their_own_group(cli, paper_db, tmp_path) -> None:
    rows = _rows(_report(cli, paper_db, tmp_path, "--dataset", "paper"), "walton-fits")
    dry_steel = rows["paper: steel/Zerodur dry"]
    assert "β = 0.34 ± 0.07" in dry_steel and "μ_f = 0.11 ± 0.003" in dry_steel
    assert "μ_f ≈ 0.02" not in dry_steel and "β ≈ 0.6" not in dry_steel
    assert "μ_f ≈ 0.02" in rows["paper: steel/Zerodur glycerol-37"]
    assert "β ≈ 0.6" in rows["paper: steel/Zerodur glycerol-37"]
    assert "μ_f = 0.15 ± 0.03" in rows["paper: glass/Zerodur glycerol-45"]
    assert "0.15" not in rows["paper: glass/Zerodur dry"]


def test_dry_is_dry_everywhere_and_never_nan(cli, example_db, tmp_path) -> None:
    html = _report(cli, example_db, tmp_path, "--dataset", "example")
    legends = _legend_texts(html)
    assert legends, "figures have legends"
    assert not [t for t in legends if "nan" in t.lower()]
    assert any(t.startswith("steel/Zerodur dry (6 runs)") for t in legends)
    assert "nan" not in re.sub(r"<svg.*?</svg>", "", html, flags=re.S).lower()


def _significant(number: str) -> int:
    digits = number.replace(".", "").lstrip("0")
    return len(digits if "." in number else digits.rstrip("0")) or 1


def test_uncertainties_have_one_or_two_significant_digits(cli, example_db, tmp_path) -> None:
    html = _report(cli, example_db, tmp_path, "--dataset", "example")
    text = htmllib.unescape(re.sub(r"<[^>]+>", " ", html))
    errors = re.findall(r"± ([0-9][0-9.]*(?:e[-+]?\d+)?)", text)
    assert errors and not [e for e in errors if "e" in e or _significant(e) > 2], errors
    assert "e-17" not in text and "e-16" not in text  # no float noise shown as uncertainty


def test_beta_axis_does_not_inflate_a_tiny_spread(cli, example_db, tmp_path) -> None:
    html = _report(cli, example_db, tmp_path, "--dataset", "example")
    svg = html[html.index('<svg id="fig-beta"') :]
    svg = svg[: svg.index("</svg>")]
    ticks = re.findall(r'<g class="ytick">.*?<text[^>]*>([^<]*)</text>', svg, re.S)
    assert ticks and all(len(t.split(".")[-1]) <= 3 for t in ticks if "." in t), ticks


def test_derived_quantities_show_symbols_units_and_machine_names(cli, db, tmp_path) -> None:
    html = _report(cli, db, tmp_path, "--pair", "steel", "Zerodur", "--fluid", "glycerol-37",
                   "--diameter", "12.7 mm", "--velocity", "0.3 m/s")  # fmt: skip
    for symbol, name in (("E*", "reduced_modulus_pa"), ("G*", "reduced_shear_modulus_pa"),
                         ("St_n", "normal_stokes_number"), ("h_m", "min_gap_m"),
                         ("Λ", "film_parameter")):  # fmt: skip
        assert f'<span class="sym" title="{name}">{symbol}</span>' in html
        assert f">{name}</code>" in html
    assert "reduced modulus pa" not in html and "eta hat pa inv" not in html
    assert re.search(r"E\*</span>, reduced modulus.*?GPa", html, re.S)


@pytest.mark.parametrize("fmt", ["html", "md"])
def test_math_is_unicode_not_tex(cli, example_db, tmp_path, fmt) -> None:
    text = _report(cli, example_db, tmp_path, "--dataset", "example", fmt=fmt)
    pair = _report(cli, example_db, tmp_path, "--pair", "glass", "Zerodur", "--fluid",
                   "glycerol-45", fmt=fmt)  # fmt: skip
    for body in (text, pair):
        assert not re.search(r"\^\\?\{", body), re.findall(r".{30}\^\\?\{.{10}", body)[:3]
    assert "²⁄⁷" in text and "R³⁄²" in pair


def test_references_once_each_with_doi_and_every_citation_listed(cli, example_db, tmp_path):
    html = _report(cli, example_db, tmp_path, "--pair", "steel", "Zerodur", "--fluid",
                   "glycerol-37")  # fmt: skip
    refs = re.findall(r"<li>([^<]*)</li>", html[html.index("<h3>References</h3>") :])
    refs = [htmllib.unescape(r) for r in refs]
    assert sum("Joseph, G. G. & Hunt" in r for r in refs) == 1
    assert any(r.startswith("Davis, R. H.") and "doi.org/10.1017/S0022112086002392" in r
               for r in refs)  # fmt: skip
    assert any(r.startswith("Joseph, G. G., Zenit") and "doi.org/" in r for r in refs)
    assert all("doi.org/" in r for r in refs), refs
    assert len(refs) == len(set(refs))
    text = htmllib.unescape(re.sub(r"<[^>]+>", " ", html.split("<h3>References</h3>")[0]))
    listed = " ".join(refs)
    for citation in cited_in(text):
        author, year = citation.rsplit(" (", 1)
        assert author.split(",")[0].split(" ")[0] in listed and year[:4] in listed, citation


def test_dataset_report_has_a_regime_map_per_pair_with_every_run(cli, paper_db, tmp_path):
    html = _report(cli, paper_db, tmp_path, "--dataset", "paper")
    for figure_id in ("fig-regime-map", "fig-regime-map-2"):
        svg = html[html.index(f'<svg id="{figure_id}"') :]
        svg = svg[: svg.index("</svg>")]
        legends = _legend_texts(svg)
        runs = sum(int(m) for t in legends for m in re.findall(r"\((\d+) runs\)", t))
        assert runs == 20, legends  # 10 dry and 10 immersed runs of each pair
        assert any(re.match(r"\w+/Zerodur dry: ", t) for t in legends)  # group, as elsewhere
        assert any(re.match(r"\w+/Zerodur glycerol-\d+: ", t) for t in legends)


@pytest.mark.parametrize("name", [r"$\frac{a}{b}$", r"\textbf{x}", "$x^2$ and $"])
def test_latex_looking_names_do_not_crash_a_report(cli, db, tmp_path, csv_writer, name):
    rows = [["r1", name, "Zerodur", "", "12.7", "30", "300", "173.2", "0", "290", "150",
             "-10", "", ""],
            ["r2", name, "Zerodur", "", "12.7", "45", "300", "300", "0", "290", "250",
             "-20", "", ""]]  # fmt: skip
    added = cli("materials", "add", name, "--density", "2500 kg/m^3", "--youngs-modulus",
                "70 GPa", "--poisson-ratio", "0.2", "--roughness", "10 nm", db=db)  # fmt: skip
    assert added.exit_code == 0, added.stderr
    source = csv_writer(tmp_path / "latex.csv", rows)
    assert cli("collisions", "import", str(source), "--dataset", "tex", db=db).exit_code == 0
    html = _report(cli, db, tmp_path, "--dataset", "tex")
    assert "internal error" not in html and htmllib.escape(name, quote=False) in html


def test_markdown_never_links_hostile_names(cli, db, tmp_path) -> None:
    from markdown_it import MarkdownIt

    for name in ("<https://evil.example>", "[x](javascript:alert(1))"):
        added = cli("materials", "add", name, "--density", "2500 kg/m^3", "--youngs-modulus",
                    "70 GPa", "--poisson-ratio", "0.2", "--roughness", "10 nm", db=db)  # fmt: skip
        assert added.exit_code == 0, added.stderr
        text = _report(cli, db, tmp_path, "--pair", name, "Zerodur", fmt="md")
        rendered = MarkdownIt("commonmark").enable("table").render(text)
        links = re.findall(r'<a href="([^"]*)"', rendered)
        assert all(link.startswith("https://doi.org/") for link in links), (name, links)
        assert rendered.count("href=") == len(links), name


def test_pair_report_states_assumed_inputs(cli, db, tmp_path) -> None:
    html = _report(cli, db, tmp_path, "--pair", "steel", "Zerodur")
    assert 'id="assumed"' in html and "Particle diameter = 12.7 mm" in html
    assert "Impact speed = 300 mm/s" in html
    table = html[html.index("<h3>Scenario</h3>") :].split("</table>")[0]
    assert "assumed (not given" in table and ">given<" not in table
    given = _report(cli, db, tmp_path, "--pair", "steel", "Zerodur", "--diameter", "5 mm",
                    "--velocity", "1 m/s", "--angle", "20 deg")  # fmt: skip
    assert 'id="assumed"' not in given and "5 mm" in given
