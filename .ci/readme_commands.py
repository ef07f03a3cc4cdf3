"""Print the first N commands of a README's ``bash`` code blocks, one per line (CI runs them
exactly as written). Usage: ``python3 .ci/readme_commands.py README.md N``. Standard library
only: it runs before anything is installed."""

import re
import sys
from pathlib import Path


def commands(text: str) -> list[str]:
    """Each non-comment line of each ```bash block, in order."""
    found = []
    for block in re.findall(r"```bash\n(.*?)```", text, flags=re.S):
        found += [line.strip() for line in block.splitlines()
                  if line.strip() and not line.lstrip().startswith("#")]
    return found


if __name__ == "__main__":
    path, count = sys.argv[1], int(sys.argv[2])
    print("\n".join(commands(Path(path).read_text())[:count]))
