"""``python -m topostore.cli``: the ``topostore`` command."""

import sys

from .group import main

sys.exit(main())
