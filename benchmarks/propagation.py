"""Does each propagated u and 95 % interval agree with a 10⁶-draw Monte Carlo (issue 36)?

For μ_f of (5.8) (the dimensionless form (5.10) with A(η̂ p_max), every input uncertain:
μ₀, U, E*, R, η̂, ρ_p, V) and the predicted restitution e = e_dry exp(−35/St) above
St_c = 10 (0 below) near the threshold (St ≈ 11; inputs ρ_p, ρ_f, R, V, μ, e_dry), at
1, 5 and 10 % relative input u: ``granudb.physics.monte_carlo.propagate`` (first order
where its check allows, else a 2·10⁵-draw Monte Carlo) against an independent 10⁶-draw
Monte Carlo (another seed). PASS when both ends of the interval are within 5 % of the
reference interval's width of the reference's ends; the method is printed.

    nice -n 10 python benchmarks/propagation.py
"""

from __future__ import annotations

import sys

from granudb.physics import contact, flow, lubrication
from granudb.physics.monte_carlo import monte_carlo, propagate

REFERENCE_DRAWS, REFERENCE_SEED = 1_000_000, 12345


def friction(mu0, speed_t, e_star, radius, eta_hat, rho, speed_n):
    load = contact.hertz_impact_load(radius, e_star, rho, speed_n)
    a = contact.max_contact_radius(radius, load, e_star)
    integral = lubrication.friction_integral(eta_hat * contact.max_pressure(load, a))
    return lubrication.lubricated_friction_dimensionless(
        mu0, speed_t, e_star, radius, eta_hat, rho, speed_n, integral
    )


def restitution(rho_p, rho_f, radius, speed, mu, e_dry):
    st = flow.added_mass_stokes_number(rho_p, rho_f, radius, speed, mu)
    return flow.predicted_restitution(st, e_dry)


CASES = {
    "mu_f (5.8), glycerol 37 %": (
        friction,
        dict(
            mu0=3e-3,
            speed_t=0.17,
            e_star=65.6e9,
            radius=6.35e-3,
            eta_hat=375e-12,
            rho=7780.0,
            speed_n=0.3,
        ),
    ),  # fmt: skip
    "e_pred near St_c (St = 11)": (
        restitution,
        dict(rho_p=2540.0, rho_f=1112.0, radius=6.35e-3, speed=0.0, mu=0.045, e_dry=0.97),
    ),
}


def main() -> int:
    fails = 0
    # the speed giving an added-mass Stokes number of 11
    x = CASES["e_pred near St_c (St = 11)"][1]
    x["speed"] = 11.0 * 9 * x["mu"] / (2 * (x["rho_p"] + 0.5 * x["rho_f"]) * x["radius"])
    print(f"{'quantity':30} {'u_in':>5} {'value':>8} {'u':>8} {'MC sd':>8} "
          f"{'low':>8} {'MC low':>8} {'high':>8} {'MC high':>8} verdict  method")  # fmt: skip
    for name, (f, x) in CASES.items():
        for rel in (0.01, 0.05, 0.10):
            u = {k: rel * abs(v) for k, v in x.items()}
            got = propagate(f, x, u)
            _, sd, low, high, _ = monte_carlo(f, x, u, REFERENCE_DRAWS, REFERENCE_SEED)
            width = high - low
            ok = abs(got.low - low) <= 0.05 * width and abs(got.high - high) <= 0.05 * width
            fails += not ok
            print(
                f"{name:30} {rel:>5.0%} {got.value:>8.4g} {got.u:>8.3g} {sd:>8.3g} "
                f"{got.low:>8.4g} {low:>8.4g} {got.high:>8.4g} {high:>8.4g} "
                f"{'PASS' if ok else 'FAIL':7}  {got.method.split(',')[0]}"
                + (f" ({got.why})" if got.why else ""),
                flush=True,
            )
    print("PASS" if not fails else f"FAIL ({fails})")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
