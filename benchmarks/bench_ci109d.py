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

Change tried (benchmarks/ci109d_rule.patch, applies to 2811aa7c; not in tests/): in
tests/hydra_cache.py, each override text parsed once (``OverridesParser.parse_overrides``: a copy
of the cached Override per call; a ``shuffle(`` text parsed every time), the root's own
``hydra.searchpath`` read once per (search path's contents, root) with Hydra's code after the read
(``_process_config_searchpath``, source sha256 pinned), a conf/ file hashed again only when its
stat (size, mtime, ctime, inode, device) changed or its ctime was within 2 s of the last hash
(a write sets ctime to the clock; ``os.utime`` cannot set it back), the search path's key read once
per composition.  tests/test_hydra_cache.py (11 tests, plain Hydra's configs and errors, an edited
file with size and mtime kept) passes with it.

Measured (2026-12-07 18:51-18:53, ``hits TREE 3``, base = ``git archive`` of 2811aa7c, after =
this worktree with the patch, one after the other per round; ms of CPU per hit)::

  round  base   after  ratio
  1      20.5   17.6   0.86
  2      25.5   21.8   0.85
  3      23.5   15.8   0.67

  (ROUNDS 6)
  4      21.3   20.1   0.95
  5      21.7   22.2   1.02
  6      20.9   17.3   0.83

``ab TREE`` (TREE with the patch applied; one process, the patch's wrappers switched on and off
per block of the 12 commands, 8 blocks each, order alternated): 24.0 -> 19.5 (0.81),
26.6 -> 23.7 (0.89), 23.8 -> 21.9 (0.92) ms per hit.

Bar (1) not met in any round: REFUSED.  Why (cProfile of the after tree's hits): the suite's value
overrides name fresh folders (``tmp_path``), so their texts are parsed anew on every command (the
parse cache hits only the constant ones); what is left is Hydra filling the ``hydra`` node and
applying the value overrides (OmegaConf ``_set_item_impl``, ~35 %: ``config_sources``,
``overrides.task`` appends, ``choices``) and the cache's unpickle (~16 %), which no wrapper of the
cache's kind removes without re-implementing ``_load_configuration_impl``.

Usage (TREE: the checkout measured, its src/, tests/ and conf/)::

    python benchmarks/bench_ci109d.py hits TREE [ROUNDS]
    python benchmarks/bench_ci109d.py loop TREE
    python benchmarks/bench_ci109d.py ab TREE        # TREE with ci109d_rule.patch applied
"""

from __future__ import annotations

import hashlib
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


def ab(tree: str, blocks: str = "8") -> None:
    _tree(tree)
    import bench_ci109a
    from hydra._internal.config_loader_impl import ConfigLoaderImpl
    from hydra.core.override_parser.overrides_parser import OverridesParser

    import conftest  # noqa: F401
    import hydra_cache as cache
    from thermocomp.shell.config import overrides

    new = (cache._parse_overrides, cache._process_config_searchpath, cache._file_digest,
           cache._sources_key)

    def read_digest(file: str) -> bytes:       # 2811aa7c's rule: the bytes on every call
        with open(file, "rb") as f:
            return hashlib.blake2b(f.read()).digest()

    def switch(on: bool) -> None:
        OverridesParser.parse_overrides = new[0] if on else cache._original["parse"]
        ConfigLoaderImpl._process_config_searchpath = new[1] if on else cache._original["searchpath"]
        cache._file_digest = new[2] if on else read_digest
        cache._sources_key = new[3] if on else cache._read_sources_key

    base = Path(tempfile.mkdtemp(prefix="ci109d-"))
    spent = {False: 0.0, True: 0.0}
    for on in (False, True):
        switch(on)
        for args in bench_ci109a._commands(base / f"first{on}"):
            overrides.compose_checked(list(args[1:]), args[0])
    for n in range(int(blocks)):
        for on in (n % 2 == 0, n % 2 == 1):
            switch(on)
            for args in bench_ci109a._commands(base / f"{n}{on}"):
                start = time.process_time()
                overrides.compose_checked(list(args[1:]), args[0])
                spent[on] += time.process_time() - start
    hits = 12 * int(blocks)
    off, on = spent[False] / hits * 1e3, spent[True] / hits * 1e3
    print(f"CPU per hit: wrappers off {off:.2f} ms, on {on:.2f} ms, ratio {on / off:.2f}")


def loop(tree: str) -> None:
    import bench_ci109a

    bench_ci109a.loop(tree)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"hits": hits, "loop": loop, "ab": ab}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
