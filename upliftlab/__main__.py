"""``python -m upliftlab``: the command line."""

from .cli import main
from .cli.exits import EXIT_INTERRUPTED, forget_handled_interrupt

code = main()
if code == EXIT_INTERRUPTED:
    forget_handled_interrupt(code)
raise SystemExit(code)
