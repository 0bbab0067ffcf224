"""The regime verdicts in words, for the terminal and the reports alike."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from granudb.report.format import engineering

GAP_DEFINITION = "h_m = x₁/3, the EHD minimum gap of the normal approach (Joseph & Hunt §1, §4)"


@dataclass(frozen=True)
class Verdict:
    key: str
    name: str
    text: str
    raised: bool = False  # a warning the reader must not miss


def _finite(value: Any) -> bool:
    return isinstance(value, int | float) and math.isfinite(value)


def verdicts(
    derived: dict[str, Any], critical_stokes: float = 10.0, immersed: bool = True
) -> list[Verdict]:
    """Rebound, roughness against gap, Maw's tangential regime and Hertz validity."""
    out: list[Verdict] = []
    st_n = derived.get("normal_stokes_number")
    if not immersed or not _finite(st_n):
        out.append(
            Verdict(
                "rebound_expected",
                "Rebound",
                "expected: a dry collision rebounds "
                "(restitution set by the solids, ē ≈ 0.97 on Zerodur).",
            )
        )
    elif derived["rebound_expected"]:
        out.append(
            Verdict(
                "rebound_expected",
                "Rebound",
                f"expected: normal Stokes number {st_n:.3g} > St_c = {critical_stokes:g}.",
            )
        )
    else:
        out.append(
            Verdict(
                "rebound_expected",
                "Rebound",
                f"not expected: normal Stokes number {st_n:.3g} ≤ St_c = "
                f"{critical_stokes:g}; the fluid absorbs the impact.",
                raised=True,
            )
        )
    out.append(roughness_verdict(derived, immersed))
    regime = derived.get("tangential_regime")
    words = {
        "stick": "stick — the contact point sticks, micro-slip only at the rim (ψ_in ≤ 1)",
        "slip_then_stick": "slip, then stick (1 < ψ_in < 4χ − 1)",
        "gross_slip": "gross slip throughout the contact (ψ_in ≥ 4χ − 1)",
    }
    psi, chi, mu = (derived.get(k) for k in ("maw_psi_in", "maw_chi", "friction_coefficient_used"))
    detail = (
        f" ψ_in = {psi:.3g}, χ = {chi:.3g}, with μ_f = {mu:.3g}."
        if _finite(psi)
        else " No tangential motion (normal impact)."
    )
    out.append(
        Verdict(
            "tangential_regime",
            "Tangential regime (Maw)",
            words.get(str(regime), str(regime)) + "." + detail,
        )
    )
    ratio = derived.get("quasi_static_ratio")
    if derived.get("quasi_static_valid"):
        out.append(
            Verdict(
                "quasi_static_valid",
                "Hertz quasi-static",
                f"valid: contact radius / wavelength = {ratio:.2g} ≪ 1.",
            )
        )
    else:
        out.append(
            Verdict(
                "quasi_static_valid",
                "Hertz quasi-static",
                f"questionable: contact radius / wavelength = {ratio:.2g}; elastic "
                "waves carry energy away.",
                raised=True,
            )
        )
    return out


def roughness_verdict(derived: dict[str, Any], immersed: bool = True) -> Verdict:
    """σ against h_m, with Λ and what it implies (PHYSICS.md §4)."""
    sigma, h_m, film = (
        derived.get(k) for k in ("composite_roughness_m", "min_gap_m", "film_parameter")
    )
    if not immersed or not _finite(h_m):
        return Verdict(
            "roughness_exceeds_gap",
            "Roughness against gap",
            "no fluid film: a dry contact, asperities touch (friction dry).",
        )
    numbers = (
        f"σ = {engineering(sigma, 'm')} (composite RMS), h_m = {engineering(h_m, 'm')} "
        f"({GAP_DEFINITION}), Λ = h_m/σ = {film:.3g}"
    )
    if derived.get("roughness_exceeds_gap"):
        return Verdict(
            "roughness_exceeds_gap",
            "Roughness exceeds the gap",
            f"{numbers}. Asperities touch through the film: expect dry-like "
            "friction (glass on Zerodur in glycerol: μ_f ≈ 0.15).",
            raised=True,
        )
    regime = "full film" if film > 3 else "mixed lubrication"
    return Verdict(
        "roughness_exceeds_gap",
        "Roughness within the gap",
        f"{numbers}. The film separates the surfaces ({regime}): friction comes "
        "from shearing the film and is low (steel on Zerodur: μ_f ≈ 0.02).",
    )
