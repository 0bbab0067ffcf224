"""Paper values (Joseph & Hunt 2004, table 1) as DEM models: the cases of
``benchmarks/dem_verify.py`` and of the tests of granudb.dem (``tests/dem/dem_cases.py``
re-exports them; a benchmark imports no test module, issue 36)."""

from __future__ import annotations

from dataclasses import replace

from granudb.dem.spec import (
    DemModel,
    PairParameters,
    ParticleType,
    Value,
    predicted_wet_restitution,
)

TABLE_1 = "Joseph & Hunt 2004 table 1"
GLASS = ParticleType("glass", 60e9, 0.23, 2540.0, 12.7e-3)
STEEL = ParticleType("steel", 190e9, 0.27, 7780.0, 12.7e-3)
ZERODUR = ParticleType("zerodur", 91e9, 0.24, 2540.0, None, is_wall=True)
E_DRY = Value(0.97, "Joseph & Hunt 2004 §3, mean dry e = 0.97 +- 0.02")
MU_STEEL = Value(0.11, "Joseph & Hunt 2004 §3, steel on Zerodur 0.11 +- 0.003")
MU_GLASS = Value(0.106, "Joseph & Hunt 2004 §3, glass on Zerodur 0.106 +- 0.008")
#: 37 % and 78 % glycerol at 20 °C: viscosity [Pa s] (fluid densities ~1090 and ~1200 kg/m³).
FLUIDS = {"glycerol37": 3e-3, "glycerol78": 48e-3}
FLUID_DENSITIES = {"glycerol37": 1090.0, "glycerol78": 1200.0}
BINARIES = {"liggghts": "liggghts", "lammps": "lmp", "yade": "yade"}


BETA_STEEL = Value(0.34, "Joseph & Hunt 2004 §3, steel on Zerodur beta = 0.34 +- 0.07")
BETA_GLASS = Value(0.39, "Joseph & Hunt 2004 §3, glass on Zerodur beta = 0.39 +- 0.06")

#: The one immersed beta the paper gives (steel in water and 37 % glycerol, figure 10).
WET_BETA = {("steel", "glycerol37"): Value(0.6, "Joseph & Hunt 2004 §4 figure 10, beta ~ 0.6")}


def dry_model() -> DemModel:
    pairs = [
        PairParameters("glass", "glass", E_DRY, MU_GLASS),
        PairParameters("glass", "steel", E_DRY, MU_STEEL),
        PairParameters("steel", "steel", E_DRY, MU_STEEL),
        PairParameters("glass", "zerodur", E_DRY, MU_GLASS, rotational_restitution=BETA_GLASS),
        PairParameters("steel", "zerodur", E_DRY, MU_STEEL, rotational_restitution=BETA_STEEL),
    ]
    return DemModel([GLASS, STEEL, ZERODUR], pairs, 0.3)


def wet_model(fluid: str, speed: float = 0.3) -> DemModel:
    """Immersed pairs: e predicted by e_dry exp(-35/St) at ``speed`` (Legendre et al. 2006)."""
    mu, rho_f = FLUIDS[fluid], FLUID_DENSITIES[fluid]
    pairs = []
    for particle, friction in ((GLASS, MU_GLASS), (STEEL, MU_STEEL)):
        e, law = predicted_wet_restitution(E_DRY, particle, mu, speed, rho_f)
        beta = WET_BETA.get((particle.name, fluid))
        pairs.append(
            PairParameters(
                particle.name, "zerodur", e, friction, wet=law, rotational_restitution=beta
            )
        )
    e_gs, law_gs = predicted_wet_restitution(E_DRY, GLASS, mu, speed, rho_f)
    pairs += [
        PairParameters("glass", "glass", e_gs, MU_GLASS, wet=law_gs),
        PairParameters("glass", "steel", e_gs, MU_STEEL, wet=law_gs),
        PairParameters(
            "steel", "steel", predicted_wet_restitution(E_DRY, STEEL, mu, speed, rho_f)[0], MU_STEEL
        ),
    ]
    return DemModel([GLASS, STEEL, ZERODUR], pairs, speed)


def with_restitution(model: DemModel, restitution: float) -> DemModel:
    """``model`` with every pair's e replaced: a deliberately wrong deck."""
    pairs = [replace(p, restitution=Value(restitution, "deliberately wrong")) for p in model.pairs]
    return DemModel(list(model.types), pairs, model.characteristic_velocity_m_s)
