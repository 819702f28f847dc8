"""``python -m thermocomp <stage> ...``: the console command without the script on PATH."""

import sys

from .shell.cli import main

sys.exit(main())
