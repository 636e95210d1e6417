"""``python -m praxicon build|draw|generate ...``: the same commands as ``psgs praxicon``."""

import sys

from .cli import main

sys.exit(main())
