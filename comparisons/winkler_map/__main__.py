"""``python -m upliftlab.comparisons.winkler_map``: the study's command line."""

import sys

from .workflow import main

sys.exit(main())
