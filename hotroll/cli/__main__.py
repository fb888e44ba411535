"""``python -m hotroll.cli``: the ``hotroll`` command."""
from hotroll.cli import main

main()
