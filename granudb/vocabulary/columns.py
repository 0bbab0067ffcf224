"""The column lists of the catalogue: what a listing shows, what a user may set.

Generated lists elsewhere (Data Package schemas, Datasette metadata) come from the terms;
these say which of them the catalogue commands show and accept, in order.
"""

from __future__ import annotations

MATERIAL_COLUMNS = [
    "name",
    "description",
    "density_kg_m3",
    "youngs_modulus_pa",
    "poisson_ratio",
    "roughness_rms_m",
    "correlation_length_m",
    "shear_modulus_pa",
    "shear_modulus_derived",
    "yield_stress_pa",
    "source",
    "source_locator",
]
MATERIAL_TABLE_COLUMNS = [
    "name",
    "density_kg_m3",
    "youngs_modulus_pa",
    "poisson_ratio",
    "roughness_rms_m",
    "shear_modulus_pa",
    "source",
]
FLUID_COLUMNS = [
    "name",
    "description",
    "glycerol_mass_fraction",
    "reference_density_kg_m3",
    "reference_viscosity_pa_s",
    "reference_temperature_c",
    "pressure_viscosity_pa_inv",
    "source",
    "source_locator",
    "density_source",
    "pressure_viscosity_source",
    "points",
]
FLUID_TABLE_COLUMNS = [
    "name",
    "glycerol_mass_fraction",
    "reference_density_kg_m3",
    "reference_viscosity_pa_s",
    "reference_temperature_c",
    "pressure_viscosity_pa_inv",
    "points",
    "source",
]
POINT_COLUMNS = ["temperature_c", "viscosity_pa_s", "density_kg_m3", "source"]

MATERIAL_FIELDS = {
    "description",
    "density_kg_m3",
    "youngs_modulus_pa",
    "poisson_ratio",
    "roughness_rms_m",
    "correlation_length_m",
    "shear_modulus_pa",
    "yield_stress_pa",
    "source_locator",
}
FLUID_FIELDS = {
    "description",
    "glycerol_mass_fraction",
    "reference_density_kg_m3",
    "reference_viscosity_pa_s",
    "reference_temperature_c",
    "pressure_viscosity_pa_inv",
    "source_locator",
}


# --- materials -------------------------------------------------------------------------
