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

# Any ASCII punctuation may be backslash-escaped in CommonMark (spec §2.4); only what could
# start markup is escaped, so the source stays readable ("(σ > x₁/3)", not "\\(σ \\> x₁/3\\)"):
# emphasis and code (* `, and _ unless inside a word, where it cannot open or close
# emphasis), links and images ([), raw HTML and autolinks (< before a letter, / ! ?),
# entities (& of "&name;" or "&#…;"), strikethrough (~~), table cells (|), a backslash
# before punctuation, and a block marker at the start of the text (# > - + = or "1." "1)").
_MD_INLINE = re.compile(
    r"[*`\[|]|(?<![^\W_])_|_(?![^\W_])|<(?=[A-Za-z/!?])|&(?=#?\w+;)|~(?=~)|(?<=~)~"
    r"|\\(?=[!-/:-@\[-`{-~]|$)"
)
_MD_BLOCK = re.compile(
    r"^(?:#{1,6}(?=\s|$)|>|[-+*](?=\s|$)|\d{1,9}(?=[.)](?:\s|$))|[-=_*](?=[-=_*\s]*$))"
)


def markdown_escape(value: Any) -> str:
    """``value`` as Markdown text that renders literally, on one line, with a backslash
    only where CommonMark would otherwise read markup.

    >>> markdown_escape("σ > x₁/3 (Λ < 1), St_n = 2·v_N,in; *bold* [link] <b>")
    'σ > x₁/3 (Λ < 1), St_n = 2·v_N,in; \\\\*bold\\\\* \\\\[link] \\\\<b>'
    """
    text = "" if value is None else str(value)
    text = " ".join(text.split())  # newlines would break tables and lists
    text = _MD_INLINE.sub(lambda m: "\\" + m.group(0), text)
    marker = _MD_BLOCK.match(text)  # "1." becomes "1\.", another marker gets a \ before it
    if marker is None:
        return text
    cut = marker.end() if marker.group(0)[0].isdigit() else 0
    return text[:cut] + "\\" + text[cut:]


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
