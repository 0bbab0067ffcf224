"""One-off converter used to turn docs/physics.md's plain-text relations into TeX math.

Kept for the record of how the page was converted (and for pages that import more tables):
``python -m tools.physics_math docs/physics.md`` rewrites the "relation" column of every
table whose header has one into ``$…$`` (KaTeX, served by the site itself), leaving prose
after a comma or semicolon as text.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

SUB = str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789")
SUP = {"²": "2", "³": "3", "⁴": "4", "⁵": "5", "⁻": "-", "¹": "1", "ᵀ": "T"}
SYMBOLS = {
    "≈": r"\approx ",
    "−": "-",
    "≤": r"\le ",
    "≥": r"\ge ",
    "≪": r"\ll ",
    "≫": r"\gg ",
    "∞": r"\infty ",
    "·": r"\cdot ",
    "×": r"\times ",
    "∝": r"\propto ",
    "→": r"\to ",
    "…": r"\ldots ",
    "η̂": r"\hat{\eta}",
    "δ̇": r"\dot{\delta}",
    "δ̈": r"\ddot{\delta}",
    "u̇": r"\dot{u}",
    "ē": r"\bar{e}",
    "ζ": r"\zeta ",
    "π": r"\pi ",
    "ρ": r"\rho ",
    "μ": r"\mu ",
    "ν": r"\nu ",
    "σ": r"\sigma ",
    "δ": r"\delta ",
    "η": r"\eta ",
    "β": r"\beta ",
    "ψ": r"\psi ",
    "Ψ": r"\Psi ",
    "χ": r"\chi ",
    "κ": r"\kappa ",
    "λ": r"\lambda ",
    "Λ": r"\Lambda ",
    "α": r"\alpha ",
    "γ": r"\gamma ",
    "ω": r"\omega ",
    "θ": r"\theta ",
    "φ": r"\varphi ",
    "Σ": r"\Sigma ",
    "Δ": r"\Delta ",
    "∫": r"\int ",
    "ε": r"\varepsilon ",
    "τ": r"\tau ",
    "′": "'",
}
FUNCTIONS = {"exp", "ln", "min", "max", "cos", "sin", "tan", "log", "diag"}


def _sqrt(text: str) -> str:
    out = ""
    i = 0
    while i < len(text):
        if text[i] == "√":
            j = i + 1
            if j < len(text) and text[j] == "(":
                depth = 0
                k = j
                while k < len(text):
                    depth += {"(": 1, ")": -1}.get(text[k], 0)
                    if depth == 0:
                        break
                    k += 1
                out += r"\sqrt{" + _sqrt(text[j + 1 : k]) + "}"
                i = k + 1
                continue
            m = re.match(r"[\wπ₀-₉*]+", text[j:])
            token = m.group(0) if m else ""
            out += r"\sqrt{" + token + "}"
            i = j + len(token)
            continue
        out += text[i]
        i += 1
    return out


def tex(formula: str) -> str:
    s = _sqrt(formula)
    s = s.replace("∫₀¹", r"\int_0^1 ")
    s = re.sub(r"([₀-₉]+)", lambda m: "_{" + m.group(1).translate(SUB) + "}", s)
    s = re.sub(
        r"\*?([²³⁴⁵⁻¹ᵀ]+)",
        lambda m: (
            "^{"
            + ("*" if m.group(0).startswith("*") else "")
            + "".join(SUP[c] for c in m.group(1))
            + "}"
        ),
        s,
    )
    s = re.sub(r"(\w)\*\^\{", r"{\1^*}^{", s)
    s = re.sub(r"(\w)\*(?!\^)", r"\1^*", s)
    for key in sorted(SYMBOLS, key=len, reverse=True):
        s = s.replace(key, SYMBOLS[key])
    s = re.sub(r"_([A-Za-z]),([a-z]+)", r"_{\1,\\mathrm{\2}}", s)
    s = re.sub(r"_([A-Za-z][a-z]+)", lambda m: r"_{\mathrm{" + m.group(1) + "}}", s)
    s = re.sub(r"(?<![_\\{\w])(" + "|".join(FUNCTIONS) + r")\b", r"\\\1", s)
    s = re.sub(
        r"(?<![\\{\w])([a-z]{3,}(?:\s+[a-z]+)*)\b",
        lambda m: m.group(1) if m.group(1) in FUNCTIONS else r"\text{ " + m.group(1) + " }",
        s,
    )
    return " ".join(s.split())


PROSE = re.compile(
    r"(,|;|:)\s+(?=(?:[a-z]+\s){1,}|unless|with|where|the|a |an |as |twice|granudb|if )"
)


def cell(text: str) -> str:
    text = text.strip()
    if not text or text in {"–", "—"}:
        return text
    split = PROSE.search(text)
    formula, rest = (text[: split.start()], text[split.start() :]) if split else (text, "")
    if not re.search(r"[=≈/√^∫]", formula):
        return text.replace("*", r"\*")
    return f"${tex(formula)}${rest.replace('*', chr(92) + '*')}"


def convert(page: str) -> str:
    lines = page.split("\n")
    column = None
    for i, line in enumerate(lines):
        if not line.startswith("|"):
            column = None
            continue
        cells = line.split("|")
        if column is None:
            names = [c.strip() for c in cells]
            column = names.index("relation") if "relation" in names else -1
            continue
        if column < 0 or set(line) <= set("|-: "):
            continue
        cells[column] = " " + cell(cells[column]) + " "
        lines[i] = "|".join(cells)
    return "\n".join(lines)


if __name__ == "__main__":
    path = Path(sys.argv[1])
    path.write_text(convert(path.read_text(encoding="utf-8")), encoding="utf-8")
