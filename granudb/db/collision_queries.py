"""Reading stored collisions as plain columns (not ORM objects) into a DataFrame.

One select gives each run with the ids of its dataset, particle, wall and fluid; names
and properties are looked up per id: 100,000 rows load in a fraction of a second.
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
    ``particle_<property>`` and ``wall_<property>`` columns.

    Why columnar: the select returns each run's own columns and the ids of its dataset
    and materials; names and material properties are looked up once per id and spread
    with an index (not joined into every row), and the rows become columns in one
    transpose, so 100,000 runs read at the driver's pace (a DataFrame built from row
    objects cost twice the read itself)."""
    import numpy as np
    import pandas as pd

    query = select(
        Collision.dataset_id,
        Collision.run,
        Collision.particle_id,
        Collision.wall_id,
        Collision.fluid_id,
        *(getattr(Collision, name) for name in COLLISION_MEASURED),
        Collision.notes,
    )
    first, second = aliased(Material), aliased(Material)  # inner joins: as before, a run
    query = (  # whose dataset or material is missing is not read
        query.join(Dataset, Collision.dataset_id == Dataset.id)
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
    connection = session.connection()
    result = connection.execute(query)
    names = list(result.keys())
    rows = result.fetchall()
    columns = dict(zip(names, zip(*rows, strict=True), strict=True)) if rows else {}
    n = len(rows)

    def objects(name: str) -> np.ndarray:
        out = np.empty(n, dtype=object)
        out[:] = columns.get(name, ())
        return out

    def index_of(name: str, ids: list[int]) -> np.ndarray:
        """Each row's position in ``ids`` (one lookup per distinct id)."""
        where = {key: i for i, key in enumerate(ids)}
        return np.array([where[key] for key in columns.get(name, ())], dtype=np.intp)

    data: dict[str, Any] = {}
    sets = connection.execute(select(Dataset.id, Dataset.name, Dataset.version)).all()
    at = index_of("dataset_id", [r[0] for r in sets])
    data["dataset"] = np.array([r[1] for r in sets], dtype=object)[at]
    data["version"] = np.array([r[2] for r in sets], dtype=object)[at]
    data["run"] = objects("run")
    properties = [getattr(Material, name) for name in MATERIAL_PROPERTIES]
    materials = connection.execute(select(Material.id, Material.name, *properties)).all()
    ids = [r[0] for r in materials]
    table = np.stack([_floats([r[2 + i] for r in materials]) for i in range(len(properties))], 1)
    material_names = np.array([r[1] for r in materials], dtype=object)
    for role in ("particle", "wall"):
        data[role] = material_names[index_of(f"{role}_id", ids)]
    data["fluid_id"] = _floats(columns.get("fluid_id", ()))
    for name in COLLISION_MEASURED:
        data[name] = _floats(columns.get(name, ()))
    data["notes"] = objects("notes")
    for role in ("particle", "wall"):
        at = index_of(f"{role}_id", ids)
        for i, name in enumerate(MATERIAL_PROPERTIES):
            data[f"{role}_{name}"] = table[at, i]
    return pd.DataFrame(data)


def _floats(values: Any) -> Any:
    """A float array; a value that is not a number (a bad stored cell) becomes NaN, as
    ``pandas.to_numeric(errors="coerce")`` makes it."""
    import numpy as np

    try:
        return np.array(values, dtype=float)
    except (TypeError, ValueError):
        import pandas as pd

        return pd.to_numeric(pd.Series(list(values), dtype=object), errors="coerce").to_numpy(
            dtype=float
        )
