"""``python -m upliftlab.comparisons.speed_vs_error``: the study's command line."""

import sys

from .workflow import main

sys.exit(main())
