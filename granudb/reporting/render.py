"""Rendering a report context to HTML or Markdown with the package's Jinja2 templates.

HTML autoescapes every value (a material named ``<script>`` shows as text); the only
unescaped content is the SVG that granudb's own plotting code produced. In Markdown every
string passes the ``md`` filter and every address the ``mdlink`` filter
(``granudb.vocabulary.escaping``), so data cannot become markup, links, images or HTML.
"""

from __future__ import annotations

from typing import Any

from granudb.lazy import jinja2
from granudb.vocabulary.escaping import markdown_code, markdown_link, markdown_text

#: The Markdown escaping rules live in ``granudb.vocabulary.escaping`` (one rule for every
#: Markdown granudb writes: reports and package READMEs); the names here stay for callers.
markdown_escape = markdown_text


def environment() -> Any:
    """Jinja2 with the package's templates, autoescaping HTML, failing on a missing name."""
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("granudb.reporting", "templates"),
        autoescape=jinja2.select_autoescape(
            enabled_extensions=("html", "html.j2"), default_for_string=True, default=True
        ),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=False,
    )
    env.filters["md"] = markdown_escape
    env.filters["mdcode"] = markdown_code
    env.filters["mdlink"] = markdown_link
    return env


def render(report: dict[str, Any], fmt: str) -> str:
    """The report as ``html`` or ``md`` text."""
    env = environment()
    if fmt == "html":
        return env.get_template("report.html.j2").render(report=report)
    if fmt == "md":
        # Markdown is not HTML: autoescape off, every value goes through ``md`` instead.
        env.autoescape = False
        return env.get_template("report.md.j2").render(report=report)
    raise ValueError(f"format: {fmt!r} must be html or md")
