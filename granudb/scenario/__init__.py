"""What a collision is, before any fit: the pair scenario and the stored runs as frames.

The derivation of one pair (``pair``: every derived quantity and verdict of a particle
on a wall in a fluid), the fluid's state at a temperature (``fluid_state``), the dry e
and μ a pair uses with where each comes from (``dry_values``), the stored collisions
with their derived columns (``collisions``, ``collision_query``) and the physical
refusals (``refusals``). It reads through ``granudb.db`` and computes through
``granudb.physics``; the fits of those runs live in ``granudb.analysis``.
"""
