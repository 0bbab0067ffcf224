"""granudb: a materials-and-regime database for particle-wall collisions in liquids.

The library is the product; the ``granudb`` command is a thin layer over it.
Heavy dependencies (pandas, SQLAlchemy, matplotlib) are imported lazily so that
``granudb --help`` stays fast.
"""

__version__ = "0.1.0"
