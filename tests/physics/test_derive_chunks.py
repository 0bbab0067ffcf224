"""``derive`` over large tables: blocks and threads change nothing but the time taken.

A table longer than ``CHUNK_ROWS`` is computed block by block (on several threads by
default); every row must equal what a small table holding that row alone gives, every
column must keep its dtype and shape, and bad input must be refused exactly as one pass
over the whole table refuses it (the first bad row of the first failing rule).
"""

from __future__ import annotations

import numpy as np
import pytest
from support import STEEL_ON_ZERODUR

from granudb.physics.derive import UNCERTAIN_INPUTS, derive
from granudb.physics.numeric import PhysicsInputError
from granudb.physics.row_chunks import CHUNK_ROWS, run_in_chunks

ROWS = 2 * CHUNK_ROWS + 123  # two full blocks and a partial one


def _mixed(n: int, seed: int = 5) -> dict[str, np.ndarray]:
    """Walls, fixed and free spheres, dry and immersed rows, known and unknown inputs."""
    rng = np.random.default_rng(seed)

    def some_nan(values: np.ndarray, share: float) -> np.ndarray:
        return np.where(rng.random(n) < share, np.nan, values)

    free = rng.random(n) < 0.3
    sphere = free | (rng.random(n) < 0.3)

    def target(low: float, high: float) -> np.ndarray:
        return np.where(free, some_nan(rng.uniform(low, high, n), 0.2), np.nan)

    tangential = rng.uniform(0, 2, n)
    tangential[rng.random(n) < 0.05] = 0.0
    return {
        "particle_density_kg_m3": rng.uniform(1000, 8000, n),
        "particle_youngs_modulus_pa": rng.uniform(1e9, 2e11, n),
        "particle_poisson_ratio": rng.uniform(0.1, 0.45, n),
        "particle_roughness_rms_m": rng.uniform(1e-9, 1e-6, n),
        "particle_yield_stress_pa": some_nan(rng.uniform(1e8, 3e9, n), 0.4),
        "wall_density_kg_m3": rng.uniform(1000, 8000, n),
        "wall_youngs_modulus_pa": rng.uniform(1e9, 2e11, n),
        "wall_poisson_ratio": rng.uniform(0.1, 0.45, n),
        "wall_roughness_rms_m": rng.uniform(1e-9, 1e-6, n),
        "wall_shear_modulus_pa": some_nan(rng.uniform(1e9, 8e10, n), 0.5),
        "wall_diameter_m": np.where(sphere, rng.uniform(1e-3, 3e-2, n), np.nan),
        "diameter_m": rng.uniform(1e-3, 3e-2, n),
        "v_n_in_m_s": rng.uniform(0.01, 2.0, n),
        "v_t_in_m_s": tangential,
        "omega_in_rad_s": rng.uniform(-100, 100, n),
        "fluid_density_kg_m3": some_nan(rng.uniform(990, 1260, n), 0.1),
        "viscosity_pa_s": some_nan(rng.uniform(5e-4, 0.5, n), 0.3),
        "pressure_viscosity_pa_inv": some_nan(np.full(n, 6e-9), 0.3),
        "v_n_out_m_s": some_nan(rng.uniform(0, 2, n), 0.3),
        "v_t_out_m_s": some_nan(rng.uniform(-2, 2, n), 0.3),
        "wall_v_n_in_m_s": np.where(free, rng.uniform(-1, 0.005, n), np.nan),
        "wall_v_t_in_m_s": target(-1, 1),
        "wall_omega_out_rad_s": target(-50, 50),
    }


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    if a.dtype.kind == "f":
        return bool(np.array_equal(a, b, equal_nan=True))
    return bool(np.array_equal(a, b))


@pytest.mark.parametrize("threads", [1, 2, None])
def test_blocked_derive_equals_small_tables_row_for_row(threads: int | None) -> None:
    table = _mixed(ROWS)
    whole = derive(**table, threads=threads)
    # slices of at most 1000 rows are one block each: the plain, unblocked computation
    for start in range(0, ROWS, 1000):
        part = derive(**{name: values[start : start + 1000] for name, values in table.items()})
        for name, values in part.items():
            assert whole[name].dtype == values.dtype, name
            assert _same(whole[name][start : start + 1000], values), (name, start)


def test_blocked_outputs_keep_shape_and_are_independent_writable_arrays() -> None:
    speeds = np.linspace(0.01, 1.0, 3 * (ROWS // 3)).reshape(ROWS // 3, 3)
    common = dict(
        STEEL_ON_ZERODUR,
        v_t_in_m_s=0.1,
        viscosity_pa_s=1e-3,
        fluid_density_kg_m3=998.0,
        pressure_viscosity_pa_inv=6e-9,
    )
    result = derive(**common, v_n_in_m_s=speeds)
    one_by_one = derive(**common, v_n_in_m_s=speeds[5, 1])
    for name, values in result.items():
        assert values.shape == speeds.shape, name
        assert _same(values[5, 1:2], np.asarray(one_by_one[name]).reshape(1)), name
    before = result["contact_radius_m"].copy()
    result["max_pressure_pa"][:] = 0.0  # columns share no elements
    assert np.array_equal(result["contact_radius_m"], before)


def test_bad_input_in_a_late_block_names_the_row_of_the_whole_table() -> None:
    table = _mixed(ROWS)
    late = 2 * CHUNK_ROWS + 7
    table["diameter_m"][late] = -1.0
    with pytest.raises(PhysicsInputError) as caught:
        derive(**table)
    assert (caught.value.field, caught.value.row) == ("diameter_m", late + 1)


def test_bad_input_is_refused_by_the_same_rule_as_one_pass() -> None:
    # An earlier row breaks a later rule (v_n_in); one pass checks diameter first over the
    # whole table, so the diameter row is named although it is in a later block.
    table = _mixed(ROWS)
    table["v_n_in_m_s"][3] = 0.0
    table["diameter_m"][CHUNK_ROWS + 50] = 0.0
    with pytest.raises(PhysicsInputError) as caught:
        derive(**table, threads=2)
    assert (caught.value.field, caught.value.row) == ("diameter_m", CHUNK_ROWS + 51)


def test_run_blocked_calls_compute_once_per_block_and_preserves_dtypes() -> None:
    seen: list[int] = []

    def compute(x: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
        seen.append(len(x["a"]))
        return {"twice": 2 * x["a"], "odd": x["a"] % 2 == 1, "name": x["a"].astype(object)}

    values = np.arange(25, dtype=float)
    out = run_in_chunks(compute, {"a": values}, threads=3, block_rows=10)
    assert sorted(seen) == [5, 10, 10]
    assert np.array_equal(out["twice"], 2 * values)
    assert out["odd"].dtype == bool and out["odd"].sum() == 12
    assert out["name"].dtype == object and out["name"][24] == 24.0


def test_blocked_derive_with_uncertainties_equals_small_tables_row_for_row() -> None:
    """With uncertainties the blocks after the first write their u, interval ends,
    probabilities and method straight into the table (``writes_into``); every row, every
    column, is what a one-block table of those rows gives, bit for bit."""
    table = _mixed(ROWS, seed=8)
    rng = np.random.default_rng(9)
    u = {f"u_{name}": 0.02 * np.abs(table[name]) for name in UNCERTAIN_INPUTS if name in table}
    u["u_viscosity_pa_s"] = np.where(rng.random(ROWS) < 0.1, np.nan, u["u_viscosity_pa_s"])
    flags = {"correlated_materials": rng.random(ROWS) < 0.3, "one_speed": rng.random(ROWS) < 0.3}
    whole = derive(**table, uncertainties=u, **flags, monte_carlo=False)
    assert len(whole) > 150  # the u, interval and method columns are there
    for start in (0, CHUNK_ROWS - 400, 2 * CHUNK_ROWS):
        rows = slice(start, start + 1000)
        part = derive(
            **{name: values[rows] for name, values in table.items()},
            uncertainties={name: values[rows] for name, values in u.items()},
            **{name: values[rows] for name, values in flags.items()},
            monte_carlo=False,
        )
        assert list(part) == list(whole)
        for name, values in part.items():
            assert whole[name].dtype == values.dtype, name
            assert _same(whole[name][rows], values), (name, start)


def test_a_compute_may_write_its_columns_into_the_table() -> None:
    """``writes_into``: blocks after the first get the table's rows; a column returned as
    that very array stays as written, any other is copied in; the first block (and a
    one-block table) gets none."""
    given: list[bool] = []

    def compute(x: dict[str, np.ndarray], into: dict | None = None) -> dict[str, np.ndarray]:
        given.append(into is not None)
        twice = np.multiply(x["a"], 2.0, out=None if into is None else into["twice"])
        return {"twice": twice, "square": x["a"] * x["a"]}

    values = np.arange(25, dtype=float)
    out = run_in_chunks(compute, {"a": values}, threads=1, block_rows=10, writes_into=True)
    assert given == [False, True, True]
    assert np.array_equal(out["twice"], 2 * values)
    assert np.array_equal(out["square"], values * values)
    given.clear()
    run_in_chunks(compute, {"a": values[:7]}, block_rows=10, writes_into=True)
    assert given == [False]
