"""A plug-in error shared by every run of a fit: the catalogue's share of St_n or of g.

The restitution fit's runs stand on St_n = m* v_N,in / (6π μ R*²) as derived from the
catalogue: the particle's density and diameter, the fluid's viscosity at the run's
temperature (and the target's, for a sphere). The fit holds those values as exact, but a
lab that states their uncertainty says they are not: an error δ of them moves every run's
St_n by the same factor (1 + δ), and both forms of e(St_n) (``restitution_fit``) depend on
St_n only through St_n/St_c or k/St_n, so the fitted St_c or k moves by exactly that
factor, e_dry not at all. The parameter's interval from the runs' scatter (any method:
bootstrap-t, profile likelihood, asymptotic, Bayesian) therefore lacks a factor whose log
is normal with standard deviation u_r, the catalogue's relative u of St_n
(``granudb.scenario.plug_ins`` computes it with ``granudb.pair``'s propagation, the one
record of how u reaches St_n).

The gap-viscosity fit is the same with g of (5.8), μ_f = q g, q = μ₀^(2/7): g is built
from the catalogue's E*, R*, pressure–viscosity coefficient (not μ, which the fit
replaces), so an error of them moves every run's g by one factor s, q̂ by 1/s and μ₀ by
s^(−7/2): μ₀'s interval lacks a log-normal factor of standard deviation 3.5 u_r.

The two are independent (the catalogue's error is one draw for the fit, the runs' scatter
another), so on the log scale their half-widths add in quadrature, each side on its own
(GUM, JCGM 100:2008 §5.1.2 on ln θ): h' = √(h² + (z u_r)²), z the normal quantile of the
level, about the value θ̂ (about the interval's geometric centre where θ̂ lies outside it:
a centre moved by the stated speeds' bias, ``granudb.analysis.asymptotic``). The gap
temperature, read from μ₀ through the fluid's μ(T), takes the curve's own u the same way
on μ's log scale (``CURVE_WORDS``). Measured on 200 synthetic sets a cell with a 5 %
catalogue error of St_n drawn once per set (``benchmarks/shared_scale_coverage.py``;
docs/intervals.md, "What the catalogue states"): St_c's interval of the runs alone
covered 0.800, 0.700, 0.535 and 0.260 at 5, 10, 30 and 100 runs, widened 0.965, 0.925,
0.940 and 0.945; ``tests/analysis/test_shared_scale.py`` keeps a 40-set version.
"""

from __future__ import annotations

import math
from statistics import NormalDist

#: What a fit's interval method adds where the catalogue states a u of what its runs
#: stand on (St_n: St_c and k scale with it; g of (5.8): μ₀ with its −7/2 power).
WORDS = (
    "; widened by the catalogue's share of {of} (u_r = {share:.2%}: {sources}; one error "
    "shared by every run, {law}), on the log scale √(h² + (z·{power}u_r)²) each side"
)
#: ``words``' arguments for the restitution fit's St_n and the gap viscosity's g.
STOKES = {"of": "St_n", "law": "by which St_c and k scale", "power": ""}
GAP = {"of": "g of (5.8)", "law": "μ₀ = (μ_f/g)^(7/2) scales with its −7/2 power", "power": "3.5·"}


def widened(low: float, high: float, value: float, share: float, level: float) -> tuple:
    """(low, high) of an interval of a parameter proportional to a shared scale whose log
    has standard deviation ``share``, its half-widths h on the log scale about ``value``
    (the interval's geometric centre where ``value`` lies outside it) each grown to
    √(h² + (z share)²), z the normal quantile of ``level``. Unchanged where the interval
    is not given (NaN) or the share is 0 or NaN.

    >>> low, high = widened(9.0, 11.0, 10.0, 0.03, 0.95)
    >>> round(low, 3), round(high, 3)
    (8.863, 11.185)
    >>> widened(9.0, 11.0, 10.0, 0.0, 0.95)
    (9.0, 11.0)
    """
    if not (share > 0 and low > 0 and high > low and math.isfinite(high)):
        return low, high
    centre = value if low < value < high else math.sqrt(low * high)
    grow = (NormalDist().inv_cdf(0.5 + level / 2) * share) ** 2
    below = math.sqrt(math.log(centre / low) ** 2 + grow)
    above = math.sqrt(math.log(high / centre) ** 2 + grow)
    return centre * math.exp(-below), centre * math.exp(above)


#: What the gap-viscosity fit's method adds where the fluid's μ(T) states a u: the curve
#: that turns μ₀ into the gap temperature is one error for every run too.
CURVE_WORDS = (
    "; the gap temperature's interval maps μ₀'s widened by the fluid's μ(T) at that "
    "temperature (u_r = {share:.2%}: its stated u, the reference temperature's with it; "
    "one error shared by every run), on the log scale √(h² + (z·u_r)²) each side"
)


def words(share: float, sources: str, of: dict[str, str] = STOKES) -> str:
    """The method's words for a ``share`` of ``sources`` (``WORDS``; ``of``: ``STOKES``
    or ``GAP``)."""
    return WORDS.format(share=share, sources=sources, **of)
