"""Regenerate the correlated numbers in seed_data/ for the water–glycerol fluids.

- ``fluids.csv``: the density column, from Volk & Kähler (2018) at each fluid's
  reference temperature (the viscosities stay as Joseph & Hunt printed them).
- ``fluid_points.csv``: viscosity (Cheng 2008) and density (Volk & Kähler 2018) every 5 °C
  from 10 to 60 °C for each fluid, so viscosity can be evaluated (and inverted to a gap
  temperature) anywhere in that range.

Run from the repository root: ``python tools/make_fluid_seed.py``. The output is
deterministic; the seed loader reports any value that changed.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from granudb.physics.viscosity import glycerol_water_density, glycerol_water_viscosity

SEED = Path(__file__).resolve().parent.parent / "seed_data"
TEMPERATURES = np.arange(10.0, 60.0 + 1e-9, 5.0)


def main() -> None:
    path = SEED / "fluids.csv"
    rows = list(csv.DictReader(path.open(encoding="utf-8")))
    header = list(rows[0])
    for row in rows:
        fraction = float(row["glycerol_mass_fraction"])
        temperature = float(row["reference_temperature [degC]"])
        row["density [kg/m^3]"] = f"{float(glycerol_water_density(fraction, temperature)):.1f}"
    with path.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=header, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)

    points = SEED / "fluid_points.csv"
    with points.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(
            [
                "fluid",
                "temperature [degC]",
                "viscosity [mPa*s]",
                "density [kg/m^3]",
                "source",
                "source_locator",
            ]
        )
        for row in rows:
            fraction = float(row["glycerol_mass_fraction"])
            for t in TEMPERATURES:
                mu = float(glycerol_water_viscosity(fraction, t)) * 1e3
                rho = float(glycerol_water_density(fraction, t))
                writer.writerow(
                    [
                        row["name"],
                        f"{t:g}",
                        f"{mu:.4g}",
                        f"{rho:.1f}",
                        "cheng-2008",
                        "eqs. 6, 21, 22 (viscosity); density: Volk & Kähler 2018",
                    ]
                )
    print(f"wrote {path.name} densities and {len(rows) * len(TEMPERATURES)} points")


if __name__ == "__main__":
    main()
