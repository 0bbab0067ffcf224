"""Measured collisions to DEM inputs, checked by running the real codes (issue 16).

Pure Python on top of ``granudb.physics``: build a :class:`~granudb.dem.spec.DemModel`
from plain values, write it for a code with ``liggghts.write``, ``lammps.write``,
``yade.write`` or ``mercurydpm.write`` (each ``write(model, *, clamp=False) -> str``), and
check it with :func:`granudb.dem.verify.verify`, which runs LIGGGHTS, LAMMPS and Yade on
real collisions where they are installed.
"""

from granudb.dem.spec import (
    PARAMETER_SETS,
    ContactScales,
    DemModel,
    PairParameters,
    ParticleType,
    Value,
    WetParameters,
    predicted_wet_restitution,
)

WRITER_NAMES = ("liggghts", "lammps", "yade", "mercurydpm")

__all__ = [
    "PARAMETER_SETS",
    "WRITER_NAMES",
    "ContactScales",
    "DemModel",
    "PairParameters",
    "ParticleType",
    "Value",
    "WetParameters",
    "predicted_wet_restitution",
]
