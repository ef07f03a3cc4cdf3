"""``python -m upliftlab.comparisons.fixed_vs_uplift``: the study's command line."""

import sys

from .workflow import main

sys.exit(main())
