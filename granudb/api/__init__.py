"""The public Python API: what ``import granudb`` offers, and what the command line calls.

Every function takes ``db=`` (an opened database from ``connect``, a URL, a SQLite path,
or nothing for the default) and accepts quantities as numbers in SI or as strings with
units (``"12.7 mm"``), like the command line.
"""
