"""``python -m granudb`` is the ``granudb`` command."""

from granudb.cli.main import main

main()
