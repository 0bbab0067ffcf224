"""Two-sphere collisions import when they are physical in relative velocities (issue 23):
the equal-sphere impact with the target at rest leaves the particle moving forward
(v_n_out < 0 on the particle's own axis) and a heavier target hitting a resting particle
starts it from v_n_in = 0; both import, and e comes back from the relative velocities.
Rows where the two would not approach, or would not separate, are refused in one line."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

import granudb
from granudb.errors import ValidationError

HEADER = ["run", "particle", "wall", "fluid", "diameter [mm]", "wall_diameter [mm]",
          "v_n_in [mm/s]", "v_t_in [mm/s]", "v_n_out [mm/s]", "v_t_out [mm/s]",
          "wall_v_n_in [mm/s]", "wall_v_n_out [mm/s]"]  # fmt: skip


def _equal_spheres(e: float, speeds: list[float]) -> list[list[str]]:
    """Equal masses, target at rest: after impact the particle moves on at (1 − e)/2 V
    (stored as −(1 − e)/2 V, away from the target being positive) and the target at
    (1 + e)/2 V along the normal."""
    return [
        [f"eq-{i}", "steel", "steel", "", "12.7", "12.7", f"{v:.3f}", "0",
         f"{-(1 - e) / 2 * v:.5f}", "0", "0", f"{(1 + e) / 2 * v:.5f}"]
        for i, v in enumerate(speeds, start=1)
    ]  # fmt: skip


def _write(path: Path, rows: list[list[str]]) -> Path:
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(HEADER)
        writer.writerows(rows)
    return path


def test_equal_spheres_with_the_target_at_rest_import_and_give_e(opened, tmp_path) -> None:
    source = _write(tmp_path / "eq.csv", _equal_spheres(0.9, [200.0, 300.0, 400.0]))
    granudb.import_collisions(source, dataset="eq", db=opened)
    runs = granudb.collisions(dataset="eq", db=opened, as_frame=False, wide=True)
    assert len(runs) == 3
    np.testing.assert_allclose([r["normal_restitution"] for r in runs], 0.9, rtol=1e-4)


def test_a_heavier_target_hitting_a_resting_particle_imports(opened, tmp_path) -> None:
    # particle at rest; the target comes at 0.3 m/s (−300 mm/s along n, from particle to
    # target); afterwards the particle leaves at 0.2 and the target moves back at −0.07.
    rows = [["hit-1", "glass", "steel", "", "12.7", "25.4", "0", "0", "200", "0", "-300",
             "-70"]]  # fmt: skip
    granudb.import_collisions(_write(tmp_path / "hit.csv", rows), dataset="hit", db=opened)
    (run,) = granudb.collisions(dataset="hit", db=opened, as_frame=False, wide=True)
    assert run["normal_restitution"] == pytest.approx((200 - 70) / 300, rel=1e-6)


@pytest.mark.parametrize(
    ("row", "words"),
    [
        (["x", "steel", "steel", "", "12.7", "12.7", "100", "0", "0", "0", "200", "100"],
         "must approach"),
        (["x", "steel", "steel", "", "12.7", "12.7", "300", "0", "-200", "0", "0", "100"],
         "separate"),
        (["x", "steel", "steel", "", "12.7", "12.7", "300", "0", "-10", "0", "0", "400"],
         "≤ 1.05"),
    ],
)  # fmt: skip
def test_unphysical_relative_velocities_are_refused(opened, tmp_path, row, words) -> None:
    with pytest.raises(ValidationError, match=words):
        granudb.import_collisions(_write(tmp_path / "bad.csv", [row]), dataset="bad", db=opened)
    assert granudb.datasets(db=opened, as_frame=False) == []
