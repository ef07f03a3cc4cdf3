"""``python -m upliftlab.comparisons.winkler_vs_continuum``: the study's command line."""

import sys

from .workflow import main

sys.exit(main())
