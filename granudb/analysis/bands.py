"""The 95 % band of a fitted curve from the fit's own parameter sets (issue 27; docs/physics.md,
"Bands on fitted curves").

Why this shape. A fit's interval states the uncertainty of each parameter; the curve drawn
through the runs is a function of all of them at once, so its uncertainty at each abscissa
is the spread of the curve over parameter sets drawn together: the fit's bootstrap resamples
(the same draws, seed and count as its intervals, so band and interval come from one set)
or a posterior's draws. The band is pointwise: at each abscissa, the 2.5 and 97.5
percentiles of the curve over the sets that determined it. It is the uncertainty of the
fitted line, not the scatter of single runs about it. A band is drawn only where the fit
gave the parameter's interval (below a fit's minimum number of runs there is neither).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from granudb.analysis import asymptotic, defaults, restitution_fit, restitution_small_n
from granudb.analysis import walton as core
from granudb.analysis import walton_bootstrap as resampling
from granudb.analysis.groups import GROUP, WALTON_INPUTS, group_frames, walton_arrays

LEVEL = defaults.CONFIDENCE_LEVEL
#: A band needs the curve determined in at least this share of the sets.
MIN_DETERMINED = 0.5


def curve_band(values: np.ndarray, level: float = LEVEL) -> tuple[np.ndarray, np.ndarray] | None:
    """Pointwise (low, high) of curves ``values`` (sets × abscissae) at ``level``, over the
    sets whose curve is finite everywhere; None when fewer than MIN_DETERMINED of them are.

    >>> x = np.linspace(0.0, 1.0, 3)
    >>> slopes = np.linspace(1.0, 2.0, 1001)[:, None]
    >>> low, high = curve_band(slopes * x)
    >>> np.round(high - low, 3).tolist()
    [0.0, 0.475, 0.95]
    """
    values = np.asarray(values, dtype=float)
    finite = np.all(np.isfinite(values), axis=1)
    if values.shape[0] == 0 or np.mean(finite) < MIN_DETERMINED:
        return None
    tail = 50.0 * (1.0 - level)
    low, high = np.percentile(values[finite], [tail, 100.0 - tail], axis=0)
    return low, high


def walton_sets(frame: Any, walton: list[Mapping[str, Any]]) -> dict[tuple, core.Decision]:
    """Each fitted group's bootstrap parameter sets, keyed by its (dataset, particle, wall,
    fluid) as the fit's row names it: the resamples of its intervals (same count and seed,
    so the same draws, the runs' stated u perturbing them alike)."""
    rows = {tuple(r[k] for k in GROUP): r for r in walton if r.get("model")}
    runs = [name for name in WALTON_INPUTS if name not in GROUP] + resampling.STATED_COLUMNS
    found = {}
    for key, group in group_frames(frame, GROUP, runs, fill={"fluid": "dry"}):
        row = rows.get(tuple(key))
        if row is None:
            continue
        if row.get("bootstrap_resamples") == 0:  # asymptotic: the same normal law's sets
            found[tuple(key)] = asymptotic.normal_sets(row, int(row["bootstrap_seed"]))
            continue
        arrays = walton_arrays(group)
        x, y, c, e = arrays[:4]
        stated = resampling.stated_inputs(group, arrays)
        found[tuple(key)] = resampling.bootstrap(
            x, y, c, e, int(row["bootstrap_resamples"]), int(row["bootstrap_seed"]), stated
        )
    return found


def walton_band(sets: core.Decision, branch: str, x: np.ndarray, factor: float):
    """The band of the sticking line Ψ_out = −βΨ_in or the sliding line
    Ψ_out = Ψ_in − μ_f(1+ē)B (``factor`` = B) over ``x`` (None when too few sets have it)."""
    x = np.asarray(x, dtype=float)
    if branch == "sticking":
        return curve_band(-sets.beta[:, None] * x[None, :])
    reach = sets.friction * (1 + sets.restitution) * factor
    return curve_band(x[None, :] - reach[:, None])


#: Resamples of a restitution band: the first BAND_SETS of the fit's own resamples (the
#: draws come in order, so they are a subset of the sets behind its intervals), five sets
#: in each 2.5 % tail, at a fifth of the fit's bootstrap cost.
BAND_SETS = 200


def restitution_band(frame: Any, row: Mapping[str, Any], grid: np.ndarray):
    """The band of ``row``'s fitted e(St_n) (a ``restitution_fit.restitution`` row) over
    ``grid``, from the first ``BAND_SETS`` of the bootstrap sets behind its intervals, or,
    where its interval is asymptotic (``bootstrap_resamples`` 0), ``asymptotic.SETS`` sets
    of the same normal law (``restitution_fit.asymptotic_sets``), each set's parameter
    times its own draw of the catalogue's shared error (``shared_scale_u``, log-normal)
    where one is stated; None where it has none."""
    if not all(math.isfinite(row.get(k, math.nan)) for k in ("parameter", "parameter_low")):
        return None
    if restitution_small_n.gave(row):  # a profile-likelihood interval: no bootstrap sets
        return None
    mine = np.ones(len(frame), dtype=bool)
    for k in ("dataset", "particle", "wall"):
        mine &= (frame[k] == row[k]).to_numpy()
    st = frame["normal_stokes_number"].to_numpy(dtype=float)[mine]
    e = frame["normal_restitution"].to_numpy(dtype=float)[mine]
    immersed = np.isfinite(st) & np.isfinite(e)
    fit = (row["e_dry"], row["e_dry_stderr"], row["parameter"], row["parameter_stderr"])
    model = row["model"]
    speeds = resampling.stated_speeds(frame)  # as the fit's resamples perturb them
    stated = None if speeds is None else tuple(r[mine][immersed] for r in speeds)
    stated = stated if stated is not None and any(r.any() for r in stated) else None
    dry = e[
        (frame["fluid"].isna().to_numpy()[mine] if "fluid" in frame else False) & np.isfinite(e)
    ]
    if row.get("bootstrap_resamples") == 0:  # asymptotic: sets of the same normal law
        a, p = restitution_fit.asymptotic_sets(
            model, st[immersed], e[immersed], fit, row["n_dry_runs"] > 0, asymptotic.SETS,
            int(row["bootstrap_seed"]), stated, dry if row["n_dry_runs"] > 0 else None,
        )  # fmt: skip
    else:
        (a, _), (p, _) = restitution_fit.bootstrap_sets(
            model, st[immersed], e[immersed], fit, row["n_dry_runs"] > 0,
            min(BAND_SETS, int(row["bootstrap_resamples"])), int(row["bootstrap_seed"]), stated,
            dry if row["n_dry_runs"] > 0 else None,
        )  # fmt: skip
    share = float(row.get("shared_scale_u", math.nan))
    if share > 0:  # the catalogue's error shared by every run scales the parameter too
        z = np.random.default_rng(int(row["bootstrap_seed"]) + 1).standard_normal(len(p))
        p = p * np.exp(share * z)
    curves = restitution_fit.restitution_curve(model, grid[None, :], a[:, None], p[:, None])
    return curve_band(curves)
