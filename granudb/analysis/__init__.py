"""The service layer the command line, the reports and the Python API share.

Fluid state at a temperature, the derivation of one pair or of stored collisions, the
collision queries that return DataFrames, and the fits. It reads through ``granudb.db``
and computes through ``granudb.physics``; it never parses files or prints.
"""
