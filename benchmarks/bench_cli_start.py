"""CPU of an in-process ``thermocomp`` call, of its config composition (compose47), and of a new store.

Usage::

    python benchmarks/bench_cli_start.py [repeats]      # default 9

The tests call the CLI in this process (~450 call sites: ``tests/conftest.py``'s ``thermocomp``,
``cli.main``), so what counts is the median CPU (user + sys of this process) of a call made
again in a warm process, not a fresh interpreter's start.  On a small simulated dataset (9
campaigns of 2-3 h), three calls: ``run`` with the tests' FAST overrides, a ``run`` refused by
the schema check (``eval.mode=nonsense``, after composing) and one refused by Hydra (an unknown
key).  For each: the median CPU of the call, of its compose alone (``overrides.compose``), and
what one call does: Hydra composes (``load_configuration``), ``initialize_config_dir``, Hydra
package YAMLs read (``OmegaConf.load``), and our parses of an override (``overrides.parse``).

Measured on the shared 2-core machine (load 1.1-2.8), main (b30e560) -> fix/compose47, medians;
first interleaved in one process (25 repeats, the two cuts switched off and on in turn: the
fairest under a shared load), then this script run alternately on each tree (2 x 15 repeats)::

    call                 call CPU (ms)                       its compose    override parses
                         one process | scripts               one process    (a warm process)
    run (FAST)           428 -> 402  | 388-429 -> 344-373   160 -> 148  |  30 -> 0
    run eval.mode=bad    243 -> 214  | 194-359 -> 179-185   185 -> 169  |  12 -> 0
    run eval.nosuch=1    162 -> 143  | 148-150 -> 132-134   153 -> 141  |   9 -> 0

Per call, before and after: one Hydra compose (a run composes its config once and hands it to
Hydra's job runner; an unknown key composes the whole config once per process for its hint),
one ``initialize_config_dir`` (~1 ms: keeping GlobalHydra up would gain nothing), 24 config
loads (14 files of conf/, parsed once per text by hydra_plugins/thermocomp_conf; Hydra's 4
package YAMLs, parsed every time, ~4 ms; 6 structured configs).  The rest of a compose (~85 %
of its cProfile) is Hydra's defaults tree and merges, an OmegaConf.create/merge of every node,
which no cache outside Hydra can skip: Hydra pops and reparents the loaded nodes into its
result, so a loaded config cannot be handed to two composes.  A run also pays Hydra's job runner
(``run_job`` deep-copies the config and the hydra node: about a quarter of a compose), kept.
What went: three ANTLR parses of each override per call (``overrides.parse`` cached per text; 10
overrides ~11 ms -> ~3.5 ms the first time, 0 once seen). The figures above include a second cut
that was measured and NOT merged: Hydra's per-compose deep copy of the whole ConfigStore (~11 ms
of a compose), avoided only by patching a private Hydra class (``hydra._internal``'s structured
config source): too fragile across Hydra releases for ~3 % of a call. With the parse cache
alone, expect roughly half of the gains in the table.

First, what a new SQLite store costs the command that creates it (``new store``: the first
tracked command of a project, and every test or sweep on a store of its own), median CPU:
MLflow's ~70 Alembic migrations, run for every new store until overhead51, against a copy of the
migrated template (:func:`thermocomp.shell.store.schema_template`, made once per MLflow version
and user) that MLflow then opens and gives its Default experiment.  Measured on the shared
2-core machine (load 8-11), fix/overhead51::

    new store            64-74 ms from the template, 1711-1971 ms migrated (3 runs, 3-9 repeats)

As whole commands on the default dataset, each on a fresh store (/usr/bin/time user+sys, main
9cc6076 -> fix/overhead51, alternated twice): ``run`` 17.3, 11.4 -> 12.3, 14.4 s; the sweep of
docs/sweeps.md 59.1, 49.4 -> 45.3, 55.7 s.  The ~1.9 s saved is inside the load's noise there
(a command's CPU varied by 3-6 s between two runs of the same tree).
"""

from __future__ import annotations

import collections
import contextlib
import io
import statistics
import sys
import tempfile
from pathlib import Path

from cpu import cpu_seconds  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from conftest import FAST, SHORT, process_state  # noqa: E402  (the tests' own in-process state)

cpu = cpu_seconds


def call(args: list[str]) -> int:
    from thermocomp.shell.cli import main

    with process_state(ROOT, {}), contextlib.redirect_stdout(io.StringIO()), \
            contextlib.redirect_stderr(io.StringIO()):
        return main(list(args))


def median_cpu(fn, repeats: int) -> float:
    fn()
    fn()                        # warm: what a test suite's 400th call costs
    times = []
    for _ in range(repeats):
        start = cpu()
        fn()
        times.append(cpu() - start)
    return statistics.median(times)


def counted(args: list[str]) -> collections.Counter:
    """What one call does: each wrapped function's calls."""
    import hydra
    import omegaconf
    from hydra._internal.config_loader_impl import ConfigLoaderImpl

    from thermocomp.shell.config import overrides

    counts = collections.Counter()
    targets = [(ConfigLoaderImpl, "load_configuration", "composes"),
               (hydra, "initialize_config_dir", "initialize"),
               (omegaconf.OmegaConf, "load", "OmegaConf.load"),
               (overrides._parser(), "parse_override", "parses")]
    originals = [getattr(owner, name) for owner, name, _ in targets]

    def wrapped(f, label):
        def w(*a, **k):
            counts[label] += 1
            return f(*a, **k)
        return w

    for (owner, name, label), f in zip(targets, originals):
        setattr(owner, name, wrapped(f, label))
    try:
        call(args)
    finally:
        for (owner, name, _), f in zip(targets, originals):
            setattr(owner, name, f)
    return counts


def compose(args: list[str]) -> None:
    from thermocomp.shell.config import overrides

    with contextlib.suppress(Exception):     # an unknown key: Hydra refuses it composing
        overrides.compose(args[1:], args[0])


def new_store(root: Path, repeats: int) -> None:
    """CPU of creating a new SQLite store (what the first tracked command on it pays): a copy
    of the migrated template, and MLflow's migrations (a template folder empty every time)."""
    from unittest import mock

    from thermocomp.shell import store

    made = iter(range(10**6))

    def create(templates: Path | None) -> None:
        folder = root / f"store{next(made)}"
        folder.mkdir()
        where = (lambda: templates / folder.name) if templates is not None else store.template_folder
        with mock.patch.object(store, "template_folder", where):
            store.create_store(folder / "mlflow.db")

    copied = median_cpu(lambda: create(None), repeats)
    migrated = median_cpu(lambda: create(root / "templates"), max(3, repeats // 3))
    print(f"{'new store':<20} {copied * 1000:7.0f}ms from the template, "
          f"{migrated * 1000:.0f}ms migrated")


def main(repeats: int) -> None:
    with tempfile.TemporaryDirectory(prefix="bench-cli-start-") as tmp:
        new_store(Path(tmp), repeats)
        data = Path(tmp) / "data"
        assert call(["simulate", f"data.path={data}", "track=false", *SHORT]) == 0
        calls = {
            "run (FAST)": ["run", f"data.path={data}", f"out={tmp}/out", f"data.interim={tmp}/interim",
                           f"model_path={tmp}/model.pkl", *FAST],
            "run eval.mode=bad": ["run", f"data.path={data}", f"out={tmp}/out", "eval.mode=nonsense",
                                  "track=false"],
            "run eval.nosuch=1": ["run", f"data.path={data}", "eval.nosuch=1", "track=false"],
        }
        print(f"{'call':<20} {'call CPU':>9} {'compose':>8}  what one call does (a warm process)")
        for name, args in calls.items():
            whole = median_cpu(lambda: call(args), repeats)
            alone = median_cpu(lambda: compose(args), repeats)
            print(f"{name:<20} {whole * 1000:7.0f}ms {alone * 1000:6.0f}ms  {dict(counted(args))}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 9)
