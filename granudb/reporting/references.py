"""What a report cites: the methods table and the works behind it, each listed once.

A work is listed when the report's text cites it (by its short form, "Davis et al.
(1986)") or a stored number comes from it, so the reference list and the text cannot
disagree. Formulas are written in Unicode (x₁, R³⁄², ²⁄⁵), never as TeX source.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Work:
    """One cited work: the database's source key when it has one, how the text cites it,
    and the full reference with its DOI."""

    key: str
    cited_as: tuple[str, ...]
    text: str
    doi: str | None = None

    def entry(self) -> dict[str, str | None]:
        """The reference as a report lists it: its text and, with a DOI, its link."""
        return {"text": self.text, "url": f"https://doi.org/{self.doi}" if self.doi else None}


WORKS = [
    Work(
        "joseph-hunt-2004",
        ("Joseph & Hunt (2004)", "joseph-hunt-2004"),
        "Joseph, G. G. & Hunt, M. L. (2004). Oblique particle–wall collisions in a liquid. "
        "J. Fluid Mech. 510, 71–93.",
        "10.1017/S002211200400919X",
    ),
    Work(
        "davis-serayssol-hinch-1986",
        ("Davis et al. (1986)", "Davis, Serayssol & Hinch (1986)", "Davis et al. 1986"),
        "Davis, R. H., Serayssol, J.-M. & Hinch, E. J. (1986). The elastohydrodynamic "
        "collision of two spheres. J. Fluid Mech. 163, 479–497.",
        "10.1017/S0022112086002392",
    ),
    Work(
        "joseph-et-al-2001",
        ("Joseph et al. (2001)",),
        "Joseph, G. G., Zenit, R., Hunt, M. L. & Rosenwinkel, A. M. (2001). Particle–wall "
        "collisions in a viscous fluid. J. Fluid Mech. 433, 329–346.",
        "10.1017/S0022112000003470",
    ),
    Work(
        "johnson-1985",
        ("Johnson (1985)", "johnson-1985", "Johnson 1985"),
        "Johnson, K. L. (1985). Contact Mechanics. Cambridge University Press.",
        "10.1017/CBO9781139171731",
    ),
    Work(
        "legendre-et-al-2006",
        (
            "Legendre et al. (2006)",
            "Legendre, Zenit, Daniel & Guiraud (2006)",
            "Legendre, Zenit, Daniel & Guiraud 2006",
            "Legendre et al. 2006",
        ),
        "Legendre, D., Zenit, R., Daniel, C. & Guiraud, P. (2006). A note on the modelling "
        "of the bouncing of spherical drops or solid spheres on a wall in viscous fluid. "
        "Chem. Eng. Sci. 61, 3543–3549.",
        "10.1016/j.ces.2005.12.018",
    ),
    Work(
        "gondret-lance-petit-2002",
        ("Gondret et al. (2002)", "Gondret, Lance & Petit (2002)"),
        "Gondret, P., Lance, M. & Petit, L. (2002). Bouncing motion of spherical particles "
        "in fluids. Phys. Fluids 14, 643–652.",
        "10.1063/1.1427920",
    ),
    Work(
        "bair-winer-1979",
        ("Bair & Winer (1979)", "Bair & Winer 1979"),
        "Bair, S. & Winer, W. O. (1979). A rheological model for elastohydrodynamic "
        "contacts based on primary laboratory data. J. Lubr. Technol. 101, 258–264.",
        "10.1115/1.3453342",
    ),
    Work(
        "thornton-1997",
        ("Thornton (1997)", "Thornton 1997"),
        "Thornton, C. (1997). Coefficient of restitution for collinear collisions of "
        "elastic-perfectly plastic spheres. J. Appl. Mech. 64, 383–386.",
        "10.1115/1.2787319",
    ),
    Work(
        "cheng-2008",
        ("Cheng (2008)", "cheng-2008"),
        "Cheng, N.-S. (2008). Formula for the viscosity of a glycerol–water mixture. "
        "Ind. Eng. Chem. Res. 47, 3285–3288.",
        "10.1021/ie071349z",
    ),
    Work(
        "volk-kahler-2018",
        ("Volk & Kähler (2018)", "volk-kahler-2018"),
        "Volk, A. & Kähler, C. J. (2018). Density model for aqueous glycerol solutions. "
        "Exp. Fluids 59, 75.",
        "10.1007/s00348-018-2527-y",
    ),
]

J_H = "Joseph & Hunt (2004)"

METHODS = [
    ("reduced modulus", "1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂", f"{J_H} §1"),
    ("reduced shear modulus", "1/G* = (2−ν₁)/G₁ + (2−ν₂)/G₂", f"{J_H} Appendix"),
    (
        "Reynolds, Stokes numbers",
        "Re = 2ρ_f R V/μ, St = 2ρ_p R V/(9μ), St_n = St cos ζ_in",
        f"{J_H} §1, §4",
    ),
    (
        "impact load, contact radius, pressure",
        "W = (4/3)R²E*(5πρ_pV²/(4E*))³⁄⁵, a = (3RW/(4E*))¹⁄³, p_max = 3W/(2πa²)",
        f"{J_H} (2.1), (2.2), (5.5)",
    ),
    ("contact time", "t_c ≈ 2.87 (m²/(R E*² V))¹⁄⁵", "Johnson (1985) §11.4"),
    (
        "EHD minimum gap",
        "h_m = x₁/3, x₁ = (4μv₀R³⁄²/(πE*))²⁄⁵",
        f"{J_H} §1 after Davis et al. (1986)",
    ),
    ("piezoviscous length", "x₃ = (η̂μ₀v₀R)¹⁄², η̂ = C/16", f"{J_H} §1, §5"),
    (
        "roughness against gap",
        "σ = √(σ₁²+σ₂²), Λ = h_m/σ; asperity contact σ > x₁/3, uncertain x₁/4 < σ ≤ x₁/3, "
        "film σ ≤ x₁/4",
        f"{J_H} §4; band h_m = x₁/4 … x₁/3 of Davis et al. (1986)",
    ),
    (
        "predicted wet restitution",
        "e = e_dry exp(−35/St), St = (ρ_p + ρ_f/2) 2R* v_N,in/(9μ); 0 for St_n ≤ St_c",
        "Legendre et al. (2006); {e_dry}",
    ),
    (
        "onset of yield",
        "p_max = 1.6 Y of the softer body; ρ_p V_y²/Y = (π⁴ 1.6⁵/40)(Y/E*)⁴",
        "Johnson (1985) §11.4",
    ),
    (
        "bound of the lubricated friction",
        "(5.8) above min(μ_dry, γ_max = 0.1): outside the model's range, not used",
        "Bair & Winer (1979)",
    ),
    (
        "rebound",
        "expected when St_n > St_c (default 10)",
        f"{J_H} §1; Joseph et al. (2001)",
    ),
    (
        "collision parameters",
        "e = v_n,out/v_n,in, β = −v_T,out/v_T,in, Ψ = v_T/v_N,in",
        f"{J_H} (2.5), (2.8)",
    ),
    (
        "friction from one collision",
        "μ_f = (Ψ_in − Ψ_out)/((1+e)(1+1/K²)), K² = 2/5",
        f"{J_H} (2.9)",
    ),
    (
        "Maw regime",
        "χ = (2G*/E*)(1+1/K²), ψ = 2(2G*/E*)v_T/(μ_f v_N,in)",
        f"{J_H} (2.3), (2.4); 2G*/E* = (1−ν)/(2−ν) for one material",
    ),
    (
        "lubricated friction",
        "μ_f = (2πμ₀U/(W h)) a² A(η̂ p_max), h from (5.6)",
        f"{J_H} (5.6), (5.8), (5.9)",
    ),
    (
        "Walton fit",
        "sticking: Ψ_out = −βΨ_in; sliding: Ψ_out = Ψ_in − μ_f(1+e)(1+1/K²)",
        f"{J_H} (2.6), (2.7)",
    ),
]


#: What the methods table says of e_dry on a report over stored runs (each run's pair).
E_DRY_OF_RUNS = (
    "e_dry of each run's pair by the dry-values rule (the pair's measured value, else the "
    "two materials' own, else borrowed; docs/physics.md §18)"
)


def e_dry_words(used: dict[str, Any]) -> str:
    """The methods table's e_dry, from a pair's dry values record (``DryValues.record()``)."""
    return (
        f"e_dry = {used['dry_restitution']:g}, {used['dry_restitution_basis']}: "
        f"{used['dry_restitution_source']}"
    )


def methods(e_dry: str = E_DRY_OF_RUNS) -> list[dict[str, str]]:
    """The methods table; ``e_dry``: where the predicted restitution's e_dry comes from
    (``e_dry_words`` of the pair's record, or each run's pair)."""
    return [
        {"quantity": q, "relation": r, "source": s.replace("{e_dry}", e_dry)} for q, r, s in METHODS
    ]


def _strings(value: Any) -> Iterable[str]:
    """Every string inside a report dict (SVG figures aside: they repeat the captions)."""
    if isinstance(value, str):
        yield value
    elif isinstance(value, dict):
        for key, item in value.items():
            if key not in {"svg", "references"}:
                yield from _strings(item)
    elif isinstance(value, list | tuple):
        for item in value:
            yield from _strings(item)


def references(report: dict[str, Any], citations: dict[str, Any]) -> list[dict[str, str | None]]:
    """The works the report cites, once each, in a stable order, each ``{"text", "url"}``
    (the DOI's link, which the HTML and the Markdown show as links).

    ``citations`` maps database source keys to their stored citation: its text, or a
    source row (``citation`` and ``doi``) as the report reads it (a release: as
    released). A stored source is listed with its stored text, so a user's correction
    (``sources update``) shows; a key granudb knows (``joseph-hunt-2004``) keeps its
    place and, without a stored DOI, the curated DOI; a work the text cites that is not
    stored is listed with the curated entry.
    """
    text = "\n".join(_strings(report))
    listed: list[dict[str, str | None]] = []
    known = {work.key for work in WORKS}
    for work in WORKS:
        if work.key in citations:
            listed.append(_stored(work.key, citations[work.key], work.doi))
        elif any(c in text for c in work.cited_as):
            listed.append(work.entry())
    for key, citation in sorted(citations.items()):
        if key not in known:
            stored = _stored(key, citation, None)
            listed.append({**stored, "text": f"[{key}] {stored['text']}"})
    return listed


def _stored(key: str, citation: Any, doi: str | None) -> dict[str, str | None]:
    """A stored source as a reference: its text, and its DOI's link (else ``doi``)."""
    text = citation if isinstance(citation, str) else citation.citation
    doi = (None if isinstance(citation, str) else citation.doi) or doi
    return Work(key, (), text, doi).entry()


CITATION = re.compile(r"([A-Z][\w–-]+(?:,? (?:[A-Z][\w–-]+|&))*(?: et al\.)?) \((\d{4})\)")


def cited_in(text: str) -> set[str]:
    """The author–year citations in ``text`` ("Davis et al. (1986)"), for checking that
    each one is listed."""
    return {f"{m.group(1)} ({m.group(2)})" for m in CITATION.finditer(text)}
