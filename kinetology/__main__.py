"""``python -m kinetology``: the ``kinetology`` command."""

import sys

from .cli import main

sys.exit(main())
