"""The ``granudb`` command line: a face over ``granudb.api``.

Each module here parses one command group's options, calls one ``granudb.api`` function
and prints what it returns (tables for people, JSON or CSV for scripts). Nothing here
computes, reads a database or writes a file itself (import-linter's "one door" contract).
"""
