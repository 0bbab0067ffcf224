"""Reading stored collisions as plain columns (not ORM objects) into a DataFrame.

One joined select gives each run with its dataset, its particle's and wall's names and
properties, and its fluid id: 100,000 rows load in a fraction of a second.
"""

from __future__ import annotations

from typing import Any

from sqlalchemy import select
from sqlalchemy.orm import Session, aliased

from granudb.db import catalog
from granudb.db import datasets as dataset_queries
from granudb.db.models import Collision, Dataset, Material
from granudb.vocabulary import COLLISION_MEASURED, MATERIAL_PROPERTIES


def load_collisions(
    session: Session,
    *,
    dataset: str | None = None,
    version: str | None = None,
    particle: str | None = None,
    wall: str | None = None,
    fluid: str | None = None,
) -> Any:
    """The stored collisions matching the filters (names case-insensitive; ``fluid``
    "dry" for dry runs), ordered by dataset, version and run label, as a DataFrame with
    ``particle_<property>`` and ``wall_<property>`` columns."""
    import pandas as pd

    first, second = aliased(Material), aliased(Material)
    query = (
        select(
            Dataset.name.label("dataset"),
            Dataset.version.label("version"),
            Collision.run,
            first.name.label("particle"),
            second.name.label("wall"),
            Collision.fluid_id,
            *(getattr(Collision, name) for name in COLLISION_MEASURED),
            Collision.notes,
            *(getattr(first, n).label(f"particle_{n}") for n in MATERIAL_PROPERTIES),
            *(getattr(second, n).label(f"wall_{n}") for n in MATERIAL_PROPERTIES),
        )
        .join(Dataset, Collision.dataset_id == Dataset.id)
        .join(first, Collision.particle_id == first.id)
        .join(second, Collision.wall_id == second.id)
    )
    if dataset is not None:
        chosen = dataset_queries.get_dataset(session, dataset, version)
        query = query.where(Collision.dataset_id == chosen.id)
    if particle is not None:
        query = query.where(Collision.particle_id == catalog.get_material(session, particle).id)
    if wall is not None:
        query = query.where(Collision.wall_id == catalog.get_material(session, wall).id)
    if fluid is not None:
        if fluid.strip().casefold() == "dry":
            query = query.where(Collision.fluid_id.is_(None))
        else:
            query = query.where(Collision.fluid_id == catalog.get_fluid(session, fluid).id)
    query = query.order_by(Dataset.name, Dataset.version, Collision.run)
    result = session.connection().execute(query)
    return pd.DataFrame(result.fetchall(), columns=list(result.keys()))
