"""What runs as papers report them give: Walton's Ψ where the relation is exact, and fits.

A reported run states some of e, e_t, ω_out and θ. Where it states θ and e_t and that the
sphere arrives without spin, Ψ_in = tan θ and Ψ_out = Ψ_in (3.5 e_t − 2.5) exactly
(``granudb.physics.reported``); with its e it then enters a Walton fit. A run with e
enters the restitution fit of its pair (ē with its interval). No velocity is made.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from granudb.analysis import defaults, fits
from granudb.analysis.intervals import t_interval
from granudb.lazy import pandas as pd
from granudb.physics import reported

#: How each derived quantity is obtained, in words (listings and fits say it).
RELATION = (
    "Ψ_in = tan θ, Ψ_out = Ψ_in (3.5 e_t − 2.5): exact for a rigid sphere arriving without "
    "spin (granudb.physics.reported)"
)
GROUP = ("collection", "particle", "wall", "fluid")
CONFIDENCE_LEVEL = defaults.CONFIDENCE_LEVEL


def derived(record: dict[str, Any]) -> dict[str, Any]:
    """``record`` with ``effective_incidence``, ``effective_rebound`` and ``derived_by``
    where the exact relation applies (else NaN and the reason), and ``stated``: the
    quantities the paper gives."""
    out = dict(record)
    theta, e_t = record.get("incidence_angle_rad"), record.get("tangential_restitution")
    stated = [
        q
        for q in (
            "incidence_angle_rad",
            "normal_restitution",
            "tangential_restitution",
            "omega_out_rad_s",
        )  # fmt: skip
        if record.get(q) is not None
    ]
    out["stated"] = ", ".join(stated)
    out["effective_incidence"] = out["effective_rebound"] = math.nan
    if theta is None or e_t is None:
        out["derived_by"] = "no Ψ: θ and e_t are both needed"
    elif not record.get("no_spin_in"):
        out["derived_by"] = "no Ψ: the paper does not state that the sphere arrives without spin"
    else:
        psi_in = float(reported.incidence_from_angle(theta))
        out["effective_incidence"] = psi_in
        out["effective_rebound"] = float(reported.rebound_from_tangential_restitution(psi_in, e_t))
        out["derived_by"] = RELATION
    return out


def walton(records: list[dict[str, Any]], seed: int) -> list[dict[str, Any]]:
    """Walton fit per group of the runs with Ψ and e; each group says which runs it left
    out and why."""
    rows = [derived(r) for r in records]
    usable = [
        r for r in rows
        if math.isfinite(r["effective_incidence"]) and r.get("normal_restitution") is not None
    ]  # fmt: skip
    left = len(rows) - len(usable)
    if not usable:
        return []
    frame = pd.DataFrame(
        {
            "dataset": [r["collection"] for r in usable],
            "particle": [r["particle"] for r in usable],
            "wall": [r["wall"] for r in usable],
            "fluid": [r["fluid"] for r in usable],
            "effective_incidence": [r["effective_incidence"] for r in usable],
            "effective_rebound": [r["effective_rebound"] for r in usable],
            "normal_restitution": [r["normal_restitution"] for r in usable],
        }
    )
    found = fits.walton(frame, seed=seed)
    for row in found:
        row["collection"] = row.pop("dataset")
        row["relation"] = RELATION
        row["runs_left_out"] = left
    return found


def restitution(records: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """ē of each group's runs that state e, with the sample standard deviation and the
    t interval of the mean (a constant e: the restitution a run given as e alone enters)."""
    groups: dict[tuple, list[float]] = {}
    for r in records:
        if r.get("normal_restitution") is not None:
            key = tuple(r.get(k) for k in GROUP)
            groups.setdefault(key, []).append(float(r["normal_restitution"]))
    out = []
    for key, values in groups.items():
        e = np.array(values)
        n = len(e)
        row: dict[str, Any] = dict(zip(GROUP, key, strict=True))
        row.update(n_runs=n, model="constant e", normal_restitution_mean=float(e.mean()))
        row["normal_restitution_std"] = float(e.std(ddof=1)) if n > 1 else math.nan
        if n > 1:
            # the fits' own t-interval: one rule for a mean of per-run values
            interval = t_interval(
                row["normal_restitution_mean"],
                row["normal_restitution_std"] / math.sqrt(n),
                n,
                level=CONFIDENCE_LEVEL,
            )
            row["normal_restitution_low"] = interval.low
            row["normal_restitution_high"] = interval.high
            row["reason"] = f"t interval of the mean ({CONFIDENCE_LEVEL:.0%}, {n - 1} d.o.f.)"
        else:
            row["normal_restitution_low"] = row["normal_restitution_high"] = math.nan
            row["reason"] = "one run: no interval"
        out.append(row)
    return out
