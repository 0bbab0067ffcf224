"""Rendering a report context to HTML or Markdown with the package's Jinja2 templates.

HTML autoescapes every value (a material named ``<script>`` shows as text); the only
unescaped content is the SVG that granudb's own plotting code produced. In Markdown every
string passes the ``md`` filter, which backslash-escapes CommonMark's punctuation and the
table pipe, so data cannot become markup, links, images or HTML.
"""

from __future__ import annotations

import re
from typing import Any

from granudb.lazy import jinja2

# Any ASCII punctuation may be backslash-escaped in CommonMark (spec §2.4); these are the
# ones that can start emphasis, code, links, images, HTML, entities or a table cell.
_MD_SPECIAL = re.compile(r"([\\`*_{}\[\]<>()#!|~&])")


def markdown_escape(value: Any) -> str:
    """``value`` as Markdown text that renders literally, on one line."""
    text = "" if value is None else str(value)
    text = " ".join(text.split())  # newlines would break tables and lists
    return _MD_SPECIAL.sub(r"\\\1", text)


def markdown_code(value: Any) -> str:
    """``value`` as an inline code span (backtick fences longer than any run inside)."""
    text = " ".join(("" if value is None else str(value)).split())
    longest = max((len(m) for m in re.findall(r"`+", text)), default=0)
    fence = "`" * (longest + 1)
    text = text.replace("|", "\\|")  # GFM tables split on | even inside code spans
    return f"{fence} {text} {fence}"


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
