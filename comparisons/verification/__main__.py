"""``python -m upliftlab.comparisons.verification``: the study's command line."""

import sys

from .workflow import main

sys.exit(main())
