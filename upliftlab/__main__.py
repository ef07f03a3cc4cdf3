"""``python -m upliftlab``: the command line."""

from .cli import main

raise SystemExit(main())
