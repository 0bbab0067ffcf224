"""The columns each listing shows, in order: collisions, datasets, fits, sources.

A listing shows the same columns in every format (a table, JSON, CSV, a DataFrame);
``--wide`` (``wide=True``) shows every column. These lists, like the catalogue's
(``granudb.vocabulary.catalog``), are the one place a listing's columns are named.
"""

from __future__ import annotations

from collections.abc import Iterable

from granudb.vocabulary.derived import term
from granudb.vocabulary.terms import COLLISION_ANGLE, COLLISION_LISTED, COLLISION_MEASURED

#: The particle's size, shown first of the measurements.
_SIZE = COLLISION_MEASURED[0]

#: What ``collisions list`` shows by default, in every format: one line per run.
COLLISION_NARROW = [
    "run",
    "particle",
    "wall",
    "fluid",
    *COLLISION_LISTED,
    "normal_restitution",
    "rotational_restitution",
    "effective_incidence",
    "sliding_friction",
    "normal_stokes_number",
    "film_parameter",
    "tangential_regime",
]
#: Every column, in presentation order (``--wide``); derived ones not named here follow.
COLLISION_WIDE = [
    "dataset",
    "version",
    "run",
    "particle",
    "wall",
    "fluid",
    _SIZE,
    "incidence_angle_rad",
    *COLLISION_ANGLE,
    *[c for c in COLLISION_MEASURED if c not in (_SIZE, *COLLISION_ANGLE)],
    "viscosity_pa_s",
    "normal_restitution",
    "rotational_restitution",
    "effective_incidence",
    "effective_rebound",
    "sliding_friction",
    "normal_stokes_number",
    "reynolds_number",
    "min_gap_m",
    "composite_roughness_m",
    "film_parameter",
    "roughness_exceeds_gap",
    "rebound_expected",
    "tangential_regime",
    "quasi_static_valid",
    "shear_strain",
    "tangential_speed_m_s",
    "lubricated_friction",
    "effective_radius_m",
    "reduced_modulus_pa",
    "notes",
    "derivation_note",
]
#: What a read of stored collisions selects by: names (case-insensitive), ``fluid``
#: "dry" for dry runs (``granudb.db.collision_queries``).
STORED_FILTERS = ("dataset", "version", "particle", "wall", "fluid")
#: A dataset report's table of its runs (and the CSV beside it): what a reader needs to
#: check the figures and fits run by run, with each run's Walton branch and assumptions.
REPORT_RUN_COLUMNS = [
    "run",
    "particle",
    "wall",
    "fluid",
    *COLLISION_LISTED,
    "effective_incidence",
    "normal_restitution",
    "rotational_restitution",
    "effective_rebound",
    "walton_branch",
    "derivation_note",
]
#: A dataset in ``granudb dataset list`` (and ``granudb.datasets()``).
DATASET_COLUMNS = ["name", "version", "state", "title", "runs", "content_hash", "license", "source"]
#: The descriptive fields a dataset's record starts with, as stored (``dataset show`` and
#: the metadata of a package export).
DATASET_DESCRIPTION = ["name", "version", "title", "description", "license"]
#: A dataset's runs counted by pair and fluid (``dataset show``).
DATASET_GROUP_COLUMNS = ["particle", "wall", "fluid", "runs"]
#: A difference between two datasets (``dataset diff``).
DIFF_COLUMNS = ["change", "run", "fields"]
#: A published value as a table of a source shows it (``sources show``).
PUBLISHED_NARROW = ["source_locator", "label", "quantity", "value_as_printed"]

#: The group a fit's row is for.
FIT_GROUP = ["dataset", "particle", "wall", "fluid"]
#: What a table of each fit shows (JSON and CSV show every key the fit returns).
#: What a table of a Bayesian fit adds (a bootstrap fit's rows have none of these; the
#: priors, likelihood and sampler settings are in every row of JSON and CSV).
FIT_BAYES = ["converged"]
FIT_NARROW = {
    "walton": [
        *FIT_GROUP,
        "model",
        "rotational_restitution",
        "sliding_friction",
        "normal_restitution_mean",
        "n_sticking",
        "n_sliding",
        *FIT_BAYES,
    ],
    "restitution": [
        *FIT_GROUP,
        "model",
        "e_dry",
        "parameter_name",
        "parameter",
        "n_runs",
        "reason",
        *FIT_BAYES,
    ],
    "gap_viscosity": [
        *FIT_GROUP,
        "gap_viscosity_pa_s",
        "ambient_viscosity_pa_s",
        "gap_temperature_c",
        "n_runs",
        "reason",  # its older name "note" (the same text) only in --wide
    ],
}


def units_of(columns: Iterable[str]) -> dict[str, str]:
    """``{column: SI unit}`` for the columns that have one (a DataFrame's ``attrs``)."""
    return {c: unit for c in columns if (unit := term(c).unit)}
