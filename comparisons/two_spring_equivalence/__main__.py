"""``python -m upliftlab.comparisons.two_spring_equivalence``: the study's command line."""

import sys

from .workflow import main

sys.exit(main())
