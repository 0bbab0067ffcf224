"""The gap viscosity μ₀ of smooth sliding collisions and the gap temperature it implies
(Joseph & Hunt 2004 §5, figure 14, table 2; docs/physics.md §6, §9, §14).

Why this shape:

- **Which runs.** The runs on the *measured* sliding line of the group's Walton fit (model
  ``sliding``, or the upper line of a ``split``), never runs chosen by the predicted regime,
  which is computed with the ambient viscosity (circular). Runs whose roughness exceeds the
  EHD gap (asperity contact, when the frame says so) are left out: (5.8) is for smooth
  contacts. Each run's measured μ_f is (2.9) on the folded Ψ with its own B.
- **Which physics.** (5.8) with the pair's reduced radius R* and the Hertz load of the
  reduced mass m* (``contact.peak_impact_force``), so two-sphere runs are consistent; U is
  the contact point's tangential speed |v_T,in|.
- **Which estimator.** Least squares of (5.8) against the measured μ_f. (5.8) is
  μ_f,i = μ₀^{2/7} g_i exactly (h ∝ μ₀^{5/7}; A(η̂ p_max) does not involve μ₀), so the
  least-squares q = μ₀^{2/7} is Σ μ_f,i g_i / Σ g_i² and μ₀ = q^{7/2}: the minimiser of
  the sum of squares in closed form (checked; a bounded 1-D minimiser in ln μ₀ takes over if
  the model ever stops being a power law). Averaging per-run inversions μ_f^{7/2} instead
  is biased upward by noise.
- **Uncertainty.** A studentized bootstrap (``granudb.analysis.intervals``) over *all* the
  group's runs: each resample re-decides, by the Walton fit, which runs slide (the old
  bootstrap over the sliding runs alone kept the split fixed: coverage 0.90, bias −2.4 %),
  and gives q* = Σ w μ_f g / Σ w g² over its smooth sliding runs with the standard error
  √(S/(n−1)/Σ w g²) of a line through the origin. The interval is found for q and mapped to
  μ₀ = q^{7/2} (monotone); the temperature interval maps the μ₀ interval through the
  monotone μ(T), widened first on μ's log scale by the curve's own relative u at the gap
  temperature where the catalogue states one (``curves``: the curve is one error for
  every run, which no interval of μ₀ sees; ``granudb.analysis.shared_scale``).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from granudb.analysis import asymptotic, defaults, intervals, shared_scale
from granudb.analysis import walton as core
from granudb.analysis import walton_bootstrap as resampling
from granudb.analysis.groups import GROUP, WALTON_INPUTS, group_frames, walton_arrays
from granudb.lazy import scipy_optimize
from granudb.physics import contact, lubrication
from granudb.physics.numeric import PhysicsInputError

RESAMPLES = resampling.DEFAULT_RESAMPLES
SEED = 0
LEVEL = defaults.CONFIDENCE_LEVEL
LOG_BOUNDS = (math.log(1e-6), math.log(10.0))  # μ₀ search range [Pa·s] of the fallback
#: Sliding runs below which μ₀'s interval is the t-interval (SMALL_N_METHOD), not the
#: bootstrap: the bootstrap-t interval covered 0.81 at n = 5 and 0.89 at n = 10
#: (benchmarks/fit_coverage.py, 100 sets); the t-interval 0.956, 0.913, 0.937 and 0.940 at
#: n = 3, 5, 10, 19 (200 sets, issue 36).
MIN_RUNS_FOR_INTERVAL = 20
#: The interval below MIN_RUNS_FOR_INTERVAL sliding runs (issue 36).
SMALL_N_METHOD = (
    f"{intervals.T_METHOD} of q = μ₀^(2/7) (μ_f = q g is a line through the origin; "
    f"standard error the larger of least squares' and the sandwich's, HC1), mapped to "
    f"μ₀ = q^(7/2); the sliding runs of the Walton fit held (fewer than "
    f"{MIN_RUNS_FOR_INTERVAL} sliding runs)"
)
#: What SMALL_N_METHOD adds when the runs state a u.
STATED_SMALL_N = "; the runs' stated u is not redrawn: it is in the per-run values' scatter"
METHOD = (
    "least squares of (5.8) (Hertz load of m*, R*) against μ_f (2.9) of the runs on the "
    "measured sliding line"
)


#: The columns (5.8) reads for each run (``model_friction``).
_MODEL_INPUTS = ["effective_radius_m", "reduced_modulus_pa", "eta_hat_pa_inv", "normal_speed_m_s",
                 "tangential_speed_m_s", "effective_mass_kg", "particle_density_kg_m3"]  # fmt: skip


def model_inputs(group: Any) -> dict[str, np.ndarray]:
    """Each run's inputs of (5.8): R*, E*, η̂, v_N, U = |v_T,in| and m*."""
    radius = group["effective_radius_m"].to_numpy(dtype=float)
    if "effective_mass_kg" in group:
        mass = group["effective_mass_kg"].to_numpy(dtype=float)
    else:  # a sphere on a flat wall: R* = R
        mass = contact.sphere_mass(group["particle_density_kg_m3"].to_numpy(float), 2 * radius)
    return {
        "radius": radius,
        "e_star": group["reduced_modulus_pa"].to_numpy(dtype=float),
        "eta_hat": group["eta_hat_pa_inv"].to_numpy(dtype=float),
        "vn": group["normal_speed_m_s"].to_numpy(dtype=float),  # relative: a moving target's too
        "u": np.abs(group["tangential_speed_m_s"].to_numpy(dtype=float)),
        "mass": mass,
    }


def friction_of(inputs: dict[str, np.ndarray], viscosity: float) -> np.ndarray:
    """(5.8) at gap viscosity ``viscosity`` [Pa·s] for ``model_inputs`` (any shape)."""
    radius, e_star, eta_hat = inputs["radius"], inputs["e_star"], inputs["eta_hat"]
    u = inputs["u"]
    load = contact.peak_impact_force(inputs["mass"], inputs["vn"], e_star, radius)
    a = contact.max_contact_radius(radius, load, e_star)
    p_max = contact.max_pressure(load, a)
    film = lubrication.traction_film_thickness(radius, viscosity, u, eta_hat, load, e_star)
    return np.asarray(lubrication.lubricated_friction(viscosity, u, load, film, a, eta_hat, p_max))


def model_friction(group: Any, viscosity: float) -> np.ndarray:
    """(5.8) for each run of ``group`` at gap viscosity ``viscosity`` [Pa·s]."""
    return friction_of(model_inputs(group), viscosity)


def _least_squares(measured: np.ndarray, group: Any) -> tuple[float, np.ndarray | None]:
    """μ₀ minimising Σ(μ_f − (5.8))², and g_i = (5.8) at μ₀ = 1 Pa·s when (5.8) is exactly
    μ₀^{2/7} g_i (else None, and a bounded minimiser in ln μ₀ gives μ₀)."""
    g = model_friction(group, 1.0)
    probe = model_friction(group, 1e-3)
    if np.allclose(probe, g * 1e-3 ** (2 / 7), rtol=1e-9, atol=0.0):
        q = float(np.sum(measured * g) / np.sum(g * g))
        return (q**3.5 if q > 0 else math.nan), g
    result = scipy_optimize.minimize_scalar(
        lambda s: float(np.sum((measured - model_friction(group, math.exp(s))) ** 2)),
        bounds=LOG_BOUNDS,
        method="bounded",
        options={"xatol": 1e-10},
    )
    return math.exp(result.x), None


def _bootstrap(arrays: tuple, g: np.ndarray, smooth: np.ndarray, resamples: int, seed: int):
    """(q*, se*) of each resample of all the group's runs (sorted as ``walton_arrays``),
    the sliding runs re-decided by the Walton fit in each: q = Σ w μ_f g / Σ w g² over the
    resample's smooth sliding runs (NaN with fewer than three distinct ones)."""
    x, y, c, e = arrays
    n = len(x)
    measured = (x - y) / c
    smooth = smooth & np.isfinite(g) & np.isfinite(measured)
    # Σ w μ_f g, Σ w g², Σ w μ_f², Σ w over the smooth runs: a resample's sums over its
    # sliding runs [k, n) are its counts times these, no (resamples × runs) temporaries
    series = np.stack([measured * g, g * g, measured * measured, np.ones(n)], axis=1)
    series[~smooth] = 0.0
    everywhere = bool(smooth.all())
    q_all, se_all = [], []
    for counts, decision in resampling.batches(x, y, c, e, resamples, seed):
        w = counts[:, :n]
        sums = w @ series  # every run: right where the resample has no sticking line
        drawn = np.empty(len(w), dtype=np.int64)
        for row, k in enumerate(decision.split.tolist()):
            if k:
                sums[row] = w[row, k:] @ series[k:]
            drawn[row] = np.count_nonzero(w[row, k:] if everywhere else w[row, k:] * smooth[k:])
        runs = sums[:, 3]
        with np.errstate(invalid="ignore", divide="ignore"):
            q = sums[:, 0] / sums[:, 1]
            residual = sums[:, 2] - q * sums[:, 0]
        q = np.where(drawn >= core.MIN_RUNS_FOR_PARAMETER, q, np.nan)
        q_all.append(q)
        se_all.append(core.standard_error(residual, runs, sums[:, 1]))
    return np.concatenate(q_all), np.concatenate(se_all)


def _bootstrap_stated(arrays: tuple, inputs: dict, smooth: np.ndarray, stated: tuple,
                      resamples: int, seed: int):  # fmt: skip
    """``_bootstrap`` with every run's measured speeds perturbed by their stated u in each
    resample (``walton_bootstrap.perturbed_batches``): the sliding runs re-decided on the
    perturbed, re-sorted runs, their μ_f (2.9) from the perturbed Ψ_in, Ψ_out and e, and g
    of (5.8) from the perturbed v_N,in and sliding speed U = |Ψ_in| v_N,in (2.5)."""
    x, y, c, e = arrays
    n = len(x)
    q_all, se_all = [], []
    b, u = stated
    for runs, decision in resampling.perturbed_batches(x, y, b, e, u, resamples, seed):
        at = {name: value[runs.order] for name, value in inputs.items()}
        at["vn"] = at["vn"] * runs.f
        at["u"] = runs.x * at["vn"]
        g = friction_of(at, 1.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            measured = (runs.x - runs.y) / runs.c
        ok = smooth[runs.order] & np.isfinite(g) & np.isfinite(measured)
        w = np.where(ok & (np.arange(n) >= decision.split[:, None]), runs.w, 0.0)
        g, measured = np.where(ok, g, 0.0), np.where(ok, measured, 0.0)
        sums = [np.einsum("ij,ij->i", w, v) for v in (measured * g, g * g, measured**2)]
        with np.errstate(invalid="ignore", divide="ignore"):
            q = sums[0] / sums[1]
            residual = sums[2] - q * sums[0]
        drawn = np.count_nonzero(w, axis=1)
        q_all.append(np.where(drawn >= core.MIN_RUNS_FOR_PARAMETER, q, np.nan))
        se_all.append(core.standard_error(residual, w.sum(axis=1), sums[1]))
    return np.concatenate(q_all), np.concatenate(se_all)


def scatter_noise(
    runs: tuple[np.ndarray, ...], measured: np.ndarray, g: np.ndarray, inputs: dict, q: float
) -> float:
    """σ̂, the relative noise of the measured speeds that the sliding runs' own scatter
    about the fit implies, all of the scatter taken as noise (real scatter of μ_f only
    adds to it: an upper bound). To first order, each of the four speeds (v_N,in, v_T,in,
    v_N,out, v_T,out) with relative noise σ moves r_i = μ_f,i − q g_i by σ h_i,

        h_i² = (Ψ_in/c − q g a)² + (Ψ_out/c)² + (μ_f e/(1+e))² + (μ_f/(1+e) + q g b)²

    (c = (1+e)B of (2.9); a, b the log slopes of (5.8)'s g in U = |v_T,in| and v_N, by a
    difference), so σ̂² = n/(n−1) Σ r_i² / Σ h_i². ``runs``: (Ψ_in, Ψ_out, e, c) of the
    runs of ``measured`` (their μ_f), in the same order; ``inputs``: their (5.8) inputs.
    On synthetic runs with 2, 5 and 10 % noise on every speed it gives 2.0, 4.9–5.0 and
    9.6–9.9 % (benchmarks/gap_noise.py)."""
    x, y, e, c = runs
    step = 1e-6
    slopes = [
        (np.log(friction_of({**inputs, k: inputs[k] * (1 + step)}, 1.0)) - np.log(g))
        / math.log1p(step)
        for k in ("u", "vn")
    ]
    fit = q * g
    h2 = (x / c - fit * slopes[0]) ** 2 + (y / c) ** 2 + (measured * e / (1 + e)) ** 2
    h2 += (measured / (1 + e) + fit * slopes[1]) ** 2
    residual = measured - fit
    ok = np.isfinite(h2) & np.isfinite(residual)  # a run (5.8) cannot take says nothing
    n = int(np.count_nonzero(ok))
    total = float(np.sum(h2[ok]))
    if n < 2 or not total > 0:
        return math.nan
    return math.sqrt(float(np.sum(residual[ok] ** 2)) / total * n / (n - 1))


def implied_noise(group: Any) -> float:
    """σ̂ of one group's runs as the fit reads it (``scatter_noise`` over the smooth
    sliding runs at the least-squares μ₀); NaN where they give no sliding line or μ₀."""
    if "normal_speed_m_s" not in group:  # as ``gap_viscosity`` takes a wall's table
        group = group.assign(normal_speed_m_s=group["v_n_in_m_s"])
    sliding, measured, _, everything, held = _sliding_runs(group)
    if sliding is None:
        return math.nan
    viscosity, g = _least_squares(measured, sliding)
    if g is None or not math.isfinite(viscosity):
        return math.nan
    runs = _held_runs(everything, held)
    return scatter_noise(runs, measured, g, model_inputs(sliding), viscosity ** (2 / 7))


def noise_bias(
    runs: tuple[np.ndarray, ...], measured: np.ndarray, g: np.ndarray, inputs: dict,
    sigma: float, seed: int, share: float, se: float,
) -> tuple[float, float]:  # fmt: skip
    """(b̂, its Monte Carlo sd): the bias of q that relative speed noise ``sigma`` makes
    in these runs, by ``stated_shift`` with every speed's u = ``sigma`` × the speed (the
    same perturbed copies that correct a stated u), on a seeded sample of ``NOISE_SAMPLE``
    runs where there are more (the bias is the design's, not the count's). Batches of
    ``NOISE_DRAWS`` copies until b̂ is two Monte Carlo sd from ``share`` × ``se`` (the
    refusal's line) or ``NOISE_MAX_DRAWS`` copies are drawn."""
    x, y, e, c = runs
    pick = np.arange(len(measured))
    if pick.size > NOISE_SAMPLE:
        pick = np.sort(np.random.default_rng(seed).choice(pick.size, NOISE_SAMPLE, replace=False))
    x, y, e, c, mu, gs = (a[pick] for a in (x, y, e, c, measured, g))
    at = {name: value[pick] for name, value in inputs.items()}
    q = float(mu @ gs / (gs @ gs))  # the sample's own fit: the copies shift from it
    u = np.stack([np.full(pick.size, sigma), sigma * e, sigma * np.abs(x), sigma * np.abs(y)])
    means: list[float] = []
    variances: list[float] = []
    while True:
        batch = len(means)
        mean, variance = stated_shift(x, y, e, at, (c / (1 + e), u), q, seed + 7919 * batch,
                                      draws=NOISE_DRAWS)  # fmt: skip
        means.append(mean)
        variances.append(variance)
        shift = float(np.mean(means))
        spread = math.sqrt(float(np.mean(variances)) / (NOISE_DRAWS * len(means)))
        clear = abs(abs(shift) - share * se) > 2 * spread
        if clear or NOISE_DRAWS * len(means) >= NOISE_MAX_DRAWS or not math.isfinite(shift):
            return shift, spread


def _unstated_bias(
    runs: tuple[np.ndarray, ...], measured: np.ndarray, g: np.ndarray, inputs: dict,
    q: float, seed: int, bootstrap: bool = False,
) -> str:  # fmt: skip
    """Why μ₀'s interval is refused without stated u ('' where it is not): the bias of q
    that the runs' own scatter implies (``scatter_noise``, ``noise_bias``) above
    ``BIAS_SHARE`` of q's standard error (the larger of least squares' and HC1's,
    ``asymptotic.line_se``), or above ``BOOTSTRAP_BIAS_SHARE`` for the bootstrap-t
    (``bootstrap``). ``runs``: (Ψ_in, Ψ_out, e, c) of the runs of ``measured``."""
    se = asymptotic.line_se(g, measured - q * g)
    share, measured_text = (
        (BOOTSTRAP_BIAS_SHARE, UNSTATED_BOOTSTRAP)
        if bootstrap
        else (BIAS_SHARE, UNSTATED_ASYMPTOTIC)
    )
    sigma = scatter_noise(runs, measured, g, inputs, q)
    if not (se > 0 and sigma > 0):
        return ""
    shift, _ = noise_bias(runs, measured, g, inputs, sigma, seed, share, se)
    ratio = abs(shift) / se
    if not ratio > share:
        return ""
    return UNSTATED_LARGE.format(n=len(measured), ratio=ratio, share=share, shift=shift / q,
                                 sigma=sigma, measured=measured_text)  # fmt: skip


def _held_runs(everything: tuple, held: np.ndarray) -> tuple[np.ndarray, ...]:
    """(Ψ_in, Ψ_out, e, c) of the smooth runs on the sliding line (``held``, positions in
    ``walton_arrays``' order), in ``_sliding_runs``' order, from its ``everything``."""
    x, y, c, e, _order, _smooth = everything
    return x[held], y[held], e[held], c[held]


def _take(stated: tuple, held: np.ndarray) -> tuple:
    """``stated_inputs``' (B, stated u) at the runs ``held``."""
    b, u = stated
    return b[held], u[:, held]


def _temperature(model: Any, viscosity: float) -> tuple[float, str]:
    if model is None:
        return math.nan, "the fluid has no μ(T) model: no gap temperature"
    try:
        return float(model.temperature_for_viscosity(viscosity)), ""
    except PhysicsInputError:
        return math.nan, (
            f"μ₀ = {viscosity * 1e3:.3g} mPa·s is outside the fluid's μ(T) data: no gap temperature"
        )


def _sliding_runs(group: Any) -> tuple[Any, np.ndarray, str, tuple, np.ndarray]:
    """The group's runs on the measured sliding line, their μ_f (2.9), or a reason; and
    (x, y, c, e, order, smooth) of all its runs for the bootstrap; and the positions (in
    that order) of the smooth sliding runs, the runs of μ_f (none without a line)."""
    x, y, c, e, _, order, _ = walton_arrays(group)
    everything = (x, y, c, e, order, np.ones(len(x), dtype=bool))
    none = np.empty(0, dtype=np.int64)
    if len(x) < core.MIN_RUNS_FOR_PARAMETER:
        reason = f"{len(x)} runs: too few for a Walton fit to find sliding runs"
        return None, np.empty(0), reason, everything, none
    fit = core.decide(np.ones((1, len(x))), x, y, c, e)
    k = int(fit.split[0])
    # the Walton fit's sliding line leaves out runs that stick by their own kinematics
    moved, _ = (0, "") if k == len(x) else core.kinematic_sticking(x, y, c, k)
    k += moved
    if moved and min(k, len(x) - k) < core.MIN_RUNS_PER_LINE:
        reason = (
            f"no sliding line: the Walton fit's model is not determined ({k} runs stick by "
            f"their own kinematics or with them, {len(x) - k} slide)"
        )
        return None, np.empty(0), reason, everything, none
    if len(x) - k < core.MIN_RUNS_FOR_PARAMETER:
        what = "all runs stick" if k == len(x) else f"{len(x) - k} sliding runs (< 3)"
        return None, np.empty(0), f"no sliding line: the Walton fit finds {what}", everything, none
    sliding = group.iloc[order[k:]]
    measured = (x[k:] - y[k:]) / c[k:]
    held = np.arange(k, len(x))
    if "roughness_exceeds_gap" in group:
        rough = group["roughness_exceeds_gap"].iloc[order]
        everything = (*everything[:5], ~rough.fillna(False).astype(bool).to_numpy())
        smooth = everything[5][k:]
        if smooth.sum() < core.MIN_RUNS_FOR_PARAMETER:
            reason = (
                f"{int(smooth.sum())} smooth sliding runs: roughness exceeds the EHD gap "
                "(asperity contact) in the others, and (5.8) is for smooth contacts"
            )
            return None, np.empty(0), reason, everything, none
        sliding, measured, held = sliding[smooth], measured[smooth], held[smooth]
    if not np.all(np.isfinite(group["eta_hat_pa_inv"].to_numpy(dtype=float))):
        reason = "the fluid has no pressure–viscosity coefficient: (5.8) needs η̂ = C/16"
        return None, np.empty(0), reason, everything, none
    return sliding, measured, "", everything, held


#: The interval from asymptotic.ASYMPTOTIC_FROM sliding runs (issue 36), of q as below.
ASYMPTOTIC_OF_Q = " of q = μ₀^(2/7) (μ_f = q g), mapped to μ₀ = q^(7/2)"
#: What the large-n method adds with the runs' stated u: the errors-in-variables bias
#: (g_i is computed from the same measured speeds as μ_f,i) corrected, as the Walton fit's
#: (``asymptotic.STATED_SHIFT``), by perturbed copies of the sliding runs (SIMEX with a
#: linear extrapolation: one more layer of the stated noise shifts q by about its bias).
STATED_SHIFT = (
    "; centred on q̂ − b̂, b̂ the mean shift of q over {draws} copies of the sliding runs "
    "with every measured speed perturbed by its stated u (normal) and μ_f and g "
    "recomputed (the errors-in-variables bias: g is computed from the same speeds as "
    "μ_f); se² plus the copies' variance v and b̂'s own v/{draws}"
)
#: Why the interval is refused without the runs' stated u (measured, issue 36).
UNSTATED_LARGE = (
    "interval not determined: at {n} sliding runs the errors-in-variables bias of μ₀ (g is "
    "computed from the same measured speeds as μ_f) is about {ratio:.1f} times its standard "
    "error (refused above {share}): q = μ₀^(2/7) shifts by {shift:+.2%} in copies of the "
    "runs perturbed by the speed noise their own scatter implies ({sigma:.1%} of each "
    "speed, all of the scatter taken as noise), and the runs state no u to correct it by "
    "({measured}); state the speeds' u (u_v_n_in_m_s, …) for the bias-corrected interval"
)
#: The measured coverage behind each refusal (200 synthetic sets, 2 % speed noise).
UNSTATED_ASYMPTOTIC = "the uncorrected interval covered 0.465 at 10,000 runs, 200 sets"
UNSTATED_BOOTSTRAP = (
    "given anyway, the bootstrap-t covered 0.885 at 2,000 runs and 2 % speed noise, 200 "
    "sets, and 0.85 at 300 runs and 5 %, 0.68 at 1,000, 100 sets"
)
#: Without stated u the asymptotic interval (from asymptotic.ASYMPTOTIC_FROM sliding runs)
#: is refused where the bias the runs' scatter implies exceeds this share of q's standard
#: error (a shift of 0.5 se leaves a ±1.96 se interval 0.92 coverage).
BIAS_SHARE = 0.5
#: The bootstrap-t's pivot does not absorb the bias either: measured (300 sets a cell,
#: no stated u; benchmarks/gap_noise.py) with the line at 0.6 se the given intervals
#: covered 0.899 at 150 runs and 5 % noise and 0.889 at 60 runs and 10 %; at 0.5 se, as
#: the asymptotic interval, the cells near the line cover 0.84–0.94 on the few sets given
#: (0.89–0.92 over all their sets): docs/intervals.md, "Where they stop".
BOOTSTRAP_BIAS_SHARE = 0.5
#: Copies of the runs a batch of ``noise_bias`` draws, the most it draws, and the runs it
#: takes at most (a seeded sample): 100,000 runs cost it about as many evaluations of
#: (5.8) as 5,000.
NOISE_DRAWS, NOISE_MAX_DRAWS, NOISE_SAMPLE = 16, 256, 5_000


def stated_shift(sliding_x, sliding_y, e, inputs: dict, stated: tuple, q: float, seed: int,
                 draws: int = asymptotic.SHIFT_DRAWS) -> tuple[float, float]:  # fmt: skip
    """(b̂, v) of q: ``draws`` copies of the sliding runs (Ψ_in, Ψ_out, e folded, their
    (5.8) ``inputs`` and ``stated`` = (B, stated u) as ``walton_bootstrap.stated_inputs``
    gives them, all for these runs), every speed drawn again from its stated u
    (``walton_bootstrap.perturbed_runs``: v_N,in's factor shared by Ψ_in, Ψ_out and e),
    μ_f (2.9) and g of (5.8) (v_N,in and U = Ψ_in v_N,in perturbed) recomputed and q
    refitted, the sliding runs held; b̂ the mean of q_copy − q̂, v their variance."""
    b, u = stated
    rng = np.random.default_rng(seed)
    x_b, y_b, e_b, f = resampling.perturbed_runs(rng, draws, sliding_x, sliding_y, e, u)
    at = {name: np.broadcast_to(value, x_b.shape) for name, value in inputs.items()}
    at["vn"] = at["vn"] * f
    at["u"] = x_b * at["vn"]
    g = friction_of(at, 1.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        measured = (x_b - y_b) / ((1.0 + e_b) * b)
        ok = np.isfinite(g) & np.isfinite(measured)
        copies = np.sum(np.where(ok, measured * g, 0.0), axis=1) / np.sum(
            np.where(ok, g * g, 0.0), axis=1
        )
    shifts = copies - q
    return float(np.mean(shifts)), float(np.var(shifts, ddof=1))


def _fit_group(
    key: tuple,
    group: Any,
    model: Any,
    asked: int | None,
    seed: int,
    switch: int = asymptotic.ASYMPTOTIC_FROM,
    scale: tuple[float, str] | None = None,
    curve: Callable[[float], float] | None = None,
) -> dict:
    """One group's row (``gap_viscosity``); ``scale``: the catalogue's share of its g;
    ``curve``: the relative u of the fluid's μ(T) at a temperature (°C)."""
    nan = math.nan
    row: dict[str, Any] = {**dict(zip(GROUP, key, strict=True))}
    row.update(gap_viscosity_pa_s=nan, gap_viscosity_low_pa_s=nan, gap_viscosity_high_pa_s=nan)
    row.update(gap_viscosity_std_pa_s=nan, gap_temperature_c=nan)
    row.update(gap_temperature_low_c=nan, gap_temperature_high_c=nan, n_runs=0)
    row["shared_scale_u"] = nan  # the catalogue's share of g, where stated
    row["temperature_curve_u"] = nan  # μ(T)'s relative u at the gap temperature, where stated
    row.update(confidence_level=LEVEL, bootstrap_seed=seed, interval_reason="")
    row["interval_method"] = intervals.METHOD + ", the sliding runs re-decided in each"
    stated = resampling.stated_inputs(group, walton_arrays(group))
    if stated is not None:
        row["interval_method"] += resampling.STATED_WALTON_METHOD
    ambient = group["viscosity_pa_s"].to_numpy(float)
    ambient = ambient[np.isfinite(ambient)]  # rows without a fluid state have none
    row["ambient_viscosity_pa_s"] = float(np.mean(ambient)) if ambient.size else nan
    row["method"] = METHOD
    sliding, measured, reason, everything, held = _sliding_runs(group)
    count = len(measured)
    row["bootstrap_resamples"] = asked if asked is not None else resampling.resample_count(count)
    row["bootstrap_rule"] = "as asked" if asked is not None else resampling.RESAMPLE_RULE
    if sliding is None:
        row["reason"] = row["note"] = reason
        return row
    viscosity, g = _least_squares(measured, sliding)
    row.update(n_runs=len(measured), gap_viscosity_pa_s=viscosity)
    resamples = row["bootstrap_resamples"]
    if not math.isfinite(viscosity):
        row["reason"] = row["note"] = "the sliding runs' μ_f give no positive μ₀"
        return row
    interval_reason = ""
    large = g is not None and asymptotic.uses(len(measured), asked, switch)
    if large and g is not None:
        q = viscosity ** (2 / 7)
        se = asymptotic.line_se(g, measured - q * g)
        centre = q
        row["interval_method"] = asymptotic.method(switch, False, ASYMPTOTIC_OF_Q)
        if stated is not None:  # the errors-in-variables bias, from perturbed copies
            x, y, c, e, order, smooth = everything
            shift, spread = stated_shift(
                x[held], y[held], e[held], model_inputs(sliding), _take(stated, held), q, seed
            )
            centre = q - shift
            se = asymptotic.stated_se(se, spread)
            row["interval_method"] += STATED_SHIFT.format(draws=asymptotic.SHIFT_DRAWS)
            if math.isfinite(shift):  # μ₀ = q̂^(7/2), not corrected
                row["interval_method"] += asymptotic.shift_words(shift, value="q̂^(7/2)", of=" in q")
        found = asymptotic.interval(centre, se, bounds=(0.0, math.inf), level=LEVEL)
        interval_reason = found.reason
        if stated is None and not interval_reason:
            interval_reason = _unstated_bias(
                _held_runs(everything, held), measured, g, model_inputs(sliding), q, seed
            )
            if interval_reason:
                found = intervals.Interval(nan, nan, 0.0, interval_reason)
        row.update(bootstrap_resamples=0, bootstrap_rule=asymptotic.rule(switch))
        if not interval_reason:
            row.update(gap_viscosity_low_pa_s=found.low**3.5)
            row.update(gap_viscosity_high_pa_s=found.high**3.5)
            row["gap_viscosity_std_pa_s"] = 3.5 * q**2.5 * se
    elif g is not None and len(measured) < MIN_RUNS_FOR_INTERVAL:
        # few runs: μ_f,i = q g_i is a line through the origin, so q's t-interval on the
        # sliding runs is exact under normal scatter; mapped to μ₀ = q^{7/2} (monotone)
        q = viscosity ** (2 / 7)
        residual = float(np.sum((measured - q * g) ** 2))
        se = float(core.standard_error(residual, len(g), float(g @ g)))
        # the scatter of μ_f grows with Ψ (speeds measured to a relative u): the larger of
        # the least-squares and the sandwich (HC1) standard error
        m = len(g)
        sandwich = math.sqrt(m / (m - 1) * float(np.sum((g * (measured - q * g)) ** 2))) / float(
            g @ g
        )
        se = max(se, sandwich)
        found = intervals.t_interval(q, se, len(g), bounds=(0.0, math.inf), level=LEVEL)
        interval_reason = found.reason
        row["interval_method"] = SMALL_N_METHOD + (STATED_SMALL_N if stated is not None else "")
        if not interval_reason:
            row.update(gap_viscosity_low_pa_s=found.low**3.5)
            row.update(gap_viscosity_high_pa_s=found.high**3.5)
            row["gap_viscosity_std_pa_s"] = 3.5 * q**2.5 * se
    elif (
        g is not None
        and stated is None
        and (
            biased := _unstated_bias(
                _held_runs(everything, held),
                measured,
                g,
                model_inputs(sliding),
                viscosity ** (2 / 7),
                seed,
                bootstrap=True,
            )
        )
    ):
        # without stated u the errors-in-variables bias outgrows the bootstrap's interval
        interval_reason = biased
        row["bootstrap_resamples"] = 0
    elif g is not None:
        x, y, c, e, order, smooth = everything
        if stated is None:
            g_all = model_friction(group.iloc[order], 1.0)
            q_boot, se_boot = _bootstrap((x, y, c, e), g_all, smooth, resamples, seed)
        else:
            inputs = model_inputs(group.iloc[order])
            q_boot, se_boot = _bootstrap_stated((x, y, c, e), inputs, smooth, stated,
                                                resamples, seed)  # fmt: skip
        q = viscosity ** (2 / 7)
        residual = float(np.sum((measured - q * g) ** 2))
        se = float(core.standard_error(residual, len(g), float(g @ g)))
        found = intervals.studentized(q, se, q_boot, se_boot, bounds=(0.0, math.inf), level=LEVEL)
        interval_reason = found.reason
        row.update(gap_viscosity_low_pa_s=found.low**3.5, gap_viscosity_high_pa_s=found.high**3.5)
        row["gap_viscosity_std_pa_s"] = 3.5 * q**2.5 * se  # the delta method from q's
    elif g is None:
        interval_reason = "interval not determined: (5.8) is not a power law of μ₀ here"
    if scale is not None and not interval_reason:  # the catalogue's share of g
        low, high = row["gap_viscosity_low_pa_s"], row["gap_viscosity_high_pa_s"]
        row["gap_viscosity_low_pa_s"], row["gap_viscosity_high_pa_s"] = shared_scale.widened(
            low, high, viscosity, 3.5 * scale[0], LEVEL
        )
        row["interval_method"] += shared_scale.words(scale[0], scale[1], shared_scale.GAP)
        row["shared_scale_u"] = scale[0]
    row["interval_reason"] = interval_reason
    row["gap_temperature_c"], reason = _temperature(model, viscosity)
    if not reason and not interval_reason:
        low, high = row["gap_viscosity_low_pa_s"], row["gap_viscosity_high_pa_s"]
        share = math.nan if curve is None else curve(row["gap_temperature_c"])
        if share > 0:  # the curve's error: one for every run, on μ's log scale
            low, high = shared_scale.widened(low, high, viscosity, share, LEVEL)
            row["interval_method"] += shared_scale.CURVE_WORDS.format(share=share)
            row["temperature_curve_u"] = share
        # μ(T) falls with T: the high viscosity is the low temperature
        t_low, t_high = _temperature(model, high)[0], _temperature(model, low)[0]
        if math.isfinite(t_low) and math.isfinite(t_high):
            row["gap_temperature_low_c"], row["gap_temperature_high_c"] = t_low, t_high
        else:  # an end beyond the fluid's data: no interval, and the reason why
            outside = high if not math.isfinite(t_low) else low
            reason = (
                f"interval of temperature not determined: μ₀'s interval reaches "
                f"{outside * 1e3:.3g} mPa·s, outside the fluid's μ(T) data "
                f"({model.low_c:g}–{model.high_c:g} °C)"
            )
    row["reason"] = row["note"] = reason
    return row


def gap_viscosity(
    frame: Any,
    fluids: dict[str, Any],
    *,
    resamples: int | None = None,
    seed: int = SEED,
    asymptotic_from: int = asymptotic.ASYMPTOTIC_FROM,
    gap_scale: dict[tuple, tuple[float, str]] | None = None,
    curves: dict[str, Callable[[float], float]] | None = None,
) -> list[dict[str, Any]]:
    """μ₀ and the gap temperature per immersed group (figure 14, table 2).

    ``fluids`` maps a fluid name to its viscosity model (``temperature_for_viscosity``) or
    None. Keys: the group; ``gap_viscosity_pa_s`` and its ``_low_pa_s``/``_high_pa_s``
    bootstrap percentile interval and ``_std_pa_s``; ``gap_temperature_c`` with
    ``_low_c``/``_high_c``; ``ambient_viscosity_pa_s``; ``n_runs`` (sliding runs used);
    ``confidence_level``, ``bootstrap_resamples``, ``bootstrap_seed``, ``bootstrap_rule``
    (``resamples`` None follows ``walton_bootstrap.RESAMPLE_RULE`` on the sliding runs);
    ``method``;
    ``reason`` (one line whenever μ₀ or the temperature is missing, else '') and ``note``
    (the same text, the older name). ``asymptotic_from``: the number of sliding runs from
    which, with no count asked for, the interval is asymptotic (``granudb.analysis.asymptotic``;
    ``bootstrap_resamples`` 0). ``gap_scale``: {(dataset, particle, wall, fluid): (u_r,
    sources)}, the catalogue's share of each group's g of (5.8) where it states one
    (``granudb.scenario.plug_ins.gap_scale``): an error shared by every run, which widens
    μ₀'s interval and the gap temperature's with it (``granudb.analysis.shared_scale``;
    ``shared_scale_u`` gives u_r: NaN where nothing is stated or no interval was given).
    ``curves``: {fluid: the relative u of its μ(T) at a temperature} where the catalogue
    states one (``granudb.scenario.plug_ins.fluid_curves``): the curve that turns μ₀ into
    the gap temperature is an error shared by every run too, so the temperature's
    interval maps μ₀'s widened by it (``temperature_curve_u``; NaN where not stated).
    """
    scales, curves = gap_scale or {}, curves or {}
    if "normal_speed_m_s" not in frame:  # a table of wall impacts only: the particle's own
        frame = frame.assign(normal_speed_m_s=frame["v_n_in_m_s"])
    inputs = dict.fromkeys(
        [
            *WALTON_INPUTS,
            *_MODEL_INPUTS,
            "viscosity_pa_s",
            "roughness_exceeds_gap",
            *resampling.STATED_COLUMNS,
        ]  # fmt: skip
    )
    with resampling.one_thread():
        return [  # dry runs (no fluid) are in no group
            _fit_group(
                key,
                group,
                fluids.get(key[3]),
                resamples,
                seed,
                asymptotic_from,
                scales.get(tuple(key)),
                curves.get(key[3]),
            )  # fmt: skip
            for key, group in group_frames(frame, GROUP, [c for c in inputs if c not in GROUP])
        ]
