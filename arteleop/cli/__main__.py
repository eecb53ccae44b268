"""``python -m arteleop.cli``: the `arteleop` command."""

import sys

from arteleop.cli.main import main

sys.exit(main())
