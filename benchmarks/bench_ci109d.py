"""CI time (issue 34; stop 109, ci109d): a cache hit of the tests' Hydra composition
(tests/hydra_cache.py) at half its CPU.

ci109a measured a hit at 18-34 ms of CPU: Hydra's ``_process_config_searchpath`` (the root loaded
from the ConfigStore to read its ``hydra.searchpath``), the overrides parsed again by Hydra's ANTLR
grammar, the ``hydra`` node filled, and the cache's own key (every conf/ file read and hashed on
every call) and unpickle.

``hits TREE`` composes, with TREE's tests/conftest.py (its cache installed as the suite has it),
the overrides of bench_ci109a's 12 in-process commands once (misses), then ROUNDS passes of the
same commands with other output folders (``out=``, ``data.path=``: value overrides, so cache hits),
and prints the CPU (``time.process_time``) per hit composition (``overrides.compose_checked``).
``loop TREE`` is bench_ci109a's loop (its per-command compose column).

BAR (written and committed before any measurement of the change):
(1) ``hits``: CPU per cache-hit composition <= 0.5 x base (2811aa7c, ``git archive`` of it), base
    and change one after the other, 3 paired rounds, every round;
(2) same composed configs and errors as plain Hydra: tests/test_hydra_cache.py (with its new
    tests, which fail on 2811aa7c's cache) and the config/cli test modules pass.
(1) not met: REFUSED (the change kept as benchmarks/ci109d_rule.patch, tests/hydra_cache.py as at
2811aa7c).

Usage (TREE: the checkout measured, its src/, tests/ and conf/)::

    python benchmarks/bench_ci109d.py hits TREE [ROUNDS]
    python benchmarks/bench_ci109d.py loop TREE
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402


def _tree(tree: str) -> Path:
    root = Path(tree).resolve()
    sys.path[:0] = [str(root / "src"), str(root / "tests")]
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    os.chdir(root)
    return root


def hits(tree: str, rounds: str = "10") -> None:
    _tree(tree)
    import bench_ci109a
    import conftest  # noqa: F401  (installs the composition cache as the suite does)
    from thermocomp.shell.config import overrides

    base = Path(tempfile.mkdtemp(prefix="ci109d-"))
    for args in bench_ci109a._commands(base / "first"):      # misses: each root and its groups kept
        overrides.compose_checked(list(args[1:]), args[0])
    spent, count = 0.0, 0
    for n in range(int(rounds)):
        for args in bench_ci109a._commands(base / str(n)):
            start = time.process_time()
            overrides.compose_checked(list(args[1:]), args[0])
            spent += time.process_time() - start
            count += 1
    print(f"cache-hit compositions: {count}, CPU per hit: {spent / count * 1e3:.2f} ms")


def loop(tree: str) -> None:
    import bench_ci109a

    bench_ci109a.loop(tree)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"hits": hits, "loop": loop}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
