"""The tests' one C build of the exported code (ci101): ``gcc -std=c99``, warnings as errors.

Most builds run at ``-O0`` (:data:`LEVEL`; ``THERMOCOMP_TEST_CC_OPT`` overrides it, e.g.
``THERMOCOMP_TEST_CC_OPT=-O2 make test``).  A control builds at ``-O2``, which costs gcc about
1.4 s of CPU a build here against 0.4 s at ``-O0``, and the suite builds some 250 streams.  The
level does not change the arithmetic on x86-64 with ``-std=c99`` (SSE doubles, no contraction
into FMA): test_export's ``test_optimization_levels_stream_the_same_bytes`` holds a monitored
export's pack to the same bytes at ``-O0`` and ``-O2``.  The warnings gcc finds only when
optimizing (``-Warray-bounds``, ``-Wmaybe-uninitialized``) are held by the builds that name
:data:`CONTROL` (test_export's proofs, every model family)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

WARNINGS = ("-Wall", "-Wextra", "-Werror")
CONTROL = "-O2"               # a control's build
LEVEL = os.environ.get("THERMOCOMP_TEST_CC_OPT", "-O0")


def compiled(folder: Path, sources=("compensator.c", "stream.c"), program: str = "stream",
             level: str | None = None, warnings: bool = True) -> Path:
    """``sources`` in ``folder`` compiled and linked into ``folder/program`` (``level``: the
    optimization, :data:`LEVEL` by default; ``warnings``: as errors), gcc's output in the
    failure's message."""
    command = ["gcc", "-std=c99", *(WARNINGS if warnings else ()), level or LEVEL, *sources,
               "-lm", "-o", program]
    done = subprocess.run(command, cwd=folder, capture_output=True, text=True)
    assert done.returncode == 0, f"{' '.join(command)} in {folder}:\n{done.stderr}"
    return Path(folder) / program
