"""``python -m upliftlab.comparisons.paper``: the study's command line."""

import sys

from .workflow import main

sys.exit(main())
