"""One escaping rule per target language, for every value that comes from data.

A name, title, citation, DOI or URL that a user (or an imported package) stored is data,
never markup: whatever it holds, each output shows it as the text it is.

- **HTML**: Jinja2's autoescape (the report's templates).
- **Markdown** (the Markdown report, the README.md of a package): ``markdown_text`` for
  text, ``markdown_code`` for a code span, ``markdown_link`` for an address written as a
  link. Text has every character CommonMark or GitHub-flavoured Markdown would read as
  markup backslash-escaped, and the triggers of GitHub's autolinks (``://``, ``www.``,
  ``@``) broken, so ``<img onerror=…>`` or ``https://evil.example`` in a name reads as
  that text. An address is percent-encoded inside its ``<…>`` (no ``<``, ``>``, space,
  quote or backslash survives), so it cannot end the link or start an element.
- **A terminal** (tables, ``display``): ``shown_text``: a control, bidirectional or
  invisible character (which text stored before the text rules could hold) is shown as
  its escape (``\\x1b``, ``\\u202e``), never sent to the terminal to act.
- **CSV bound for spreadsheets** (listings with ``--format csv``, the runs beside a report,
  posterior draws): ``spreadsheet_cell``: a text cell that a spreadsheet would run as a
  formula (starting ``=``, ``+``, ``-``, ``@``, tab or carriage return) is prefixed with
  ``'``, shown and not run (OWASP's CSV-injection advice). Files that are data for
  programs (a Data Package's CSV, which its hash covers byte for byte) keep values verbatim.
"""

from __future__ import annotations

import re
from typing import Any
from urllib.parse import quote

from granudb.vocabulary.text import text_forbidden_pattern

#: A text cell a spreadsheet would run as a formula starts with one of these (OWASP's CSV
#: injection advice); numbers are written as numbers and never start with them as text.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def spreadsheet_cell(value: Any) -> Any:
    """A CSV cell for people's spreadsheets: ``None`` as empty, and a text cell that would
    be read as a formula prefixed with ``'`` (shown, not run).

    >>> spreadsheet_cell('=HYPERLINK("http://x","y")')
    '\\'=HYPERLINK("http://x","y")'
    >>> spreadsheet_cell(-1.5)
    -1.5
    """
    if value is None:
        return ""
    if isinstance(value, str) and value.startswith(FORMULA_STARTS):
        return "'" + value
    return value


def spreadsheet_frame(frame: Any) -> Any:
    """A copy of the pandas DataFrame ``frame`` with ``spreadsheet_cell``'s rule applied to
    every text column at once (numbers, booleans and missing values as they are)."""
    out = frame.copy()
    for column in out.columns:
        series = out[column]
        if series.dtype.kind not in "OSU" and str(series.dtype) not in ("string", "str"):
            continue
        text = series.astype("string")
        formula = text.str.startswith(FORMULA_STARTS).fillna(False).astype(bool).to_numpy()
        if formula.any():
            values = series.to_numpy(dtype=object, copy=True)
            values[formula] = ["'" + str(v) for v in values[formula]]
            out[column] = type(series)(values, index=series.index, name=column).astype(series.dtype)
    return out


# Any ASCII punctuation may be backslash-escaped in CommonMark (spec §2.4); only what could
# start markup is escaped, so the source stays readable ("(σ > x₁/3)", not "\\(σ \\> x₁/3\\)"):
# emphasis and code (* `, and _ unless inside a word, where it cannot open or close
# emphasis), links and images ([), raw HTML and autolinks (< before a letter, / ! ?),
# entities (& of "&name;" or "&#…;"), strikethrough (~, which GFM reads single too),
# table cells (|), a backslash
# before punctuation, and a block marker at the start of the text (# > - + = or "1." "1)").
# GitHub's autolinks need "scheme://", "www." or a dot between letters (a bare domain, as
# markdown-it's linkify reads it, and "//host" too): ":" and "/" before "/", "." before
# a letter and after "www" are escaped.
_MD_INLINE = re.compile(
    r"[*`\[|~]|(?<![^\W_])_|_(?![^\W_])|<(?=[A-Za-z/!?])|&(?=#?\w+;)"
    r"|\\(?=[!-/:-@\[-`{-~]|$)|:(?=//)|/(?=/)|\.(?=[^\W\d_])|(?<=[wW]{3})\."
)
_MD_BLOCK = re.compile(
    r"^(?:#{1,6}(?=\s|$)|>|[-+*](?=\s|$)|\d{1,9}(?=[.)](?:\s|$))|[-=_*](?=[-=_*\s]*$))"
)
#: cmark-gfm finds e-mail autolinks after parsing, in text that escapes no longer split:
#: an empty HTML comment before "@" is the one separation it respects.
_MAIL_AT = re.compile(r"(?<=\S)@")


def markdown_text(value: Any) -> str:
    """``value`` as Markdown text that renders literally, on one line (a paragraph, a
    heading, a table cell), with a backslash only where CommonMark or GitHub-flavoured
    Markdown would otherwise read markup, so nothing in it becomes an element, an
    attribute, a link or a table column.

    >>> markdown_text("σ > x₁/3 (Λ < 1), St_n = 2·v_N,in; *bold* [link] <b>")
    'σ > x₁/3 (Λ < 1), St_n = 2·v_N,in; \\\\*bold\\\\* \\\\[link] \\\\<b>'
    >>> markdown_text("see https://www.evil.example")
    'see https\\\\:\\\\//www\\\\.evil\\\\.example'
    """
    text = "" if value is None else str(value)
    text = " ".join(text.split())  # newlines would break tables and lists
    text = _MD_INLINE.sub(lambda m: "\\" + m.group(0), text)
    text = _MAIL_AT.sub("<!-- -->@", text)
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


#: Characters kept as they are inside a link's address; everything else is
#: percent-encoded (RFC 3986 reserved and unreserved characters, without ``<``, ``>``,
#: quotes, backslash, space or backtick).
_URL_SAFE = "/:?#[]@!$&'()*+,;=-._~%"


def markdown_link(address: str) -> str:
    """The address ``address`` (an http(s) URL, or ``https://doi.org/`` and a DOI) as a
    Markdown autolink ``<…>``, percent-encoded so that nothing in it ends the link.

    >>> markdown_link("https://doi.org/10.1000/x><script>alert(1)</script>")
    '<https://doi.org/10.1000/x%3E%3Cscript%3Ealert(1)%3C/script%3E>'
    """
    return "<" + quote(address, safe=_URL_SAFE.replace("'", "")) + ">"


def doi_address(doi: str) -> str:
    """The https://doi.org/ address of a DOI, its suffix percent-encoded (DOI Handbook
    §2.5.2.4: characters outside the URI set are encoded)."""
    return "https://doi.org/" + quote(doi, safe="/:;()._-~!*+,=@$&")


_UNSHOWABLE = re.compile(text_forbidden_pattern())


def shown_text(value: str) -> str:
    """``value`` for a person's screen: every character the text rules forbid (controls
    but line feed and tab, bidirectional and invisible marks) written as its escape, so
    stored text cannot clear a screen, set a window title or read backwards.

    >>> shown_text("a\\x1b[2Jb\\u202ec")
    'a\\\\x1b[2Jb\\\\u202ec'
    """
    return _UNSHOWABLE.sub(lambda m: m.group().encode("unicode_escape").decode("ascii"), value)
