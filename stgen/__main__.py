"""`python -m stgen ...` runs the same CLI as the `stgen` script."""

import sys

from .cli import main

sys.exit(main())
