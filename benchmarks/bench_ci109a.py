"""CI time (issue 34; stop 109, ci109a): an in-process command's config path (compose + Hydra's
job runner outside the task) at half its CPU.

The suite's py-spy profile puts ~13 % in Hydra/OmegaConf config handling; 3.0 % is
``cli._run_job``'s ``hydra.core.utils.run_job``, which deep-copies the composed config (the task's
copy, ~490 lines of yaml) and HydraConfig's (after a second ``set_config``: another masked copy of
the ``hydra`` node), copies that nothing reads after the job but the task.

``loop TREE`` runs 12 in-process commands as the tests run them (tests/conftest.py's
``_in_process`` and its composition cache, FAST overrides, SHORT simulated dataset): simulate,
ingest, train, evaluate, replay, export, run, run model=pcr, diagnose, replay, evaluate one_step,
simulate; every one must exit 0.  It prints per command its CPU and the config path's
(``overrides.compose_checked`` + ``cli._run_job`` minus the task, ``time.process_time``
wrappers), then the totals.

BAR (written and committed before any measurement of a change; exact: same outputs):
(1) the config path's CPU per in-process command (composition-cache hits: the last 3 commands,
    whose roots are composed before in the loop, and every command's ``_run_job`` outside the
    task) <= 0.5 x base (0326e79e), base and change run one after the other, 3 paired rounds;
(2) the 12-command loop's total CPU down by what (1) implies (said with the numbers);
(3) the tests of shell/cli and config (tests/shell/test_cli*.py, tests/shell/test_config*.py,
    tests/test_hydra_cache.py that name hydra or compose) pass unchanged.
(1) not met: REFUSED (src reverted, the change kept as benchmarks/ci109a_rule.patch).

Change tried (benchmarks/ci109a_rule.patch, applies to 0326e79e; not in src): a run's job
(shell/job.py) is Hydra's ``run_job`` step by step without its copies nothing reads: HydraConfig set
once (the run folder written into its copy as the second ``set_config`` would), the task's copy
pickled (same nodes, metadata, flags, values and parents as the deepcopy on every command root,
checked), ``hydra_cfg`` not copied again; tests/shell/test_job.py (in the patch) holds it to Hydra's
``run_job`` (same task config, callbacks, HydraConfig in the task, ``.hydra/`` files, return) and
pins run_job's source digest.

Measured (2026-12-07 18:15-18:26, load from up to 7 other helpers; ``loop`` base = ``git archive``
of 0326e79e, after = the worktree with the patch, one after the other per round; ms of CPU)::

  round  cache-hit config path       (compose, run_job)          run_job outside task, all 12   loop s
  1      83.7 -> 45.8  (0.55)   33.8, 49.8 -> 25.5, 20.2         36.8 -> 28.3                   7.49 -> 7.27
  2      71.8 -> 44.3  (0.62)   30.6, 41.2 -> 24.5, 19.8         35.2 -> 32.3                   8.00 -> 8.03
  3      50.6 -> 32.2  (0.64)   20.5, 30.1 -> 17.6, 14.6         30.8 -> 25.8                   6.85 -> 7.23
  4      57.9 -> 37.6  (0.65)   25.6, 32.3 -> 21.5, 16.1         36.7 -> 24.7                   8.39 -> 6.64
  (a round 2 whose after run met a planted break in the tree was dropped and run again: 2)

run_job outside the task halves (0.41-0.50 on hits), but a hit's composition (Hydra's own
override parsing, search path, ``hydra`` node; the test cache's file digests) stays: the config
path is 0.55-0.65 x base, not <= 0.5.  Bar (1) not met: REFUSED.  The loop's total (6.6-8.6 s)
moves by noise; the implied cut is ~12 x 15 ms = 0.2 s (~2.5 %).

Usage (``PYTHONPATH=<tree>/src``; TREE: the checkout measured, its tests/ and conf/)::

    python benchmarks/bench_ci109a.py loop TREE      # 12 commands: CPU, config path's CPU
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import run_commands  # noqa: E402

STEPS = ("compose", "run_job", "task")


def _timed(spent: dict, name: str, fn):
    def wrap(*args, **kwargs):
        start = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            spent[name] += time.process_time() - start
    return wrap


def _commands(base: Path) -> list[tuple]:
    from conftest import FAST, SHORT, UNTRACKED

    data, model = base / "data", base / "m" / "model.pkl"
    common = (f"data.path={data}", *FAST)
    return [
        ("simulate", f"data.path={data}", *UNTRACKED, *SHORT),
        ("ingest", f"data.path={data}", "track=false", f"data.interim={base / 'i'}"),
        ("train", *common, f"out={base / 'tr'}", f"model_path={model}", f"data.interim={base / 'i'}"),
        ("evaluate", *common, f"out={base / 'ev'}", f"model_path={model}", f"data.interim={base / 'i'}"),
        ("replay", f"data.path={data}", "track=false", f"replay.model={model}", f"out={base / 'rp'}"),
        ("export", f"data.path={data}", "track=false", f"export.model={model}", f"out={base / 'ex'}"),
        ("run", *common, f"out={base / 'run'}", f"model_path={base / 'm1/model.pkl'}",
         f"data.interim={base / 'i1'}"),
        ("run", *common, "model=pcr", f"out={base / 'run2'}", f"model_path={base / 'm3/model.pkl'}",
         f"data.interim={base / 'i3'}"),
        ("diagnose", *common, f"out={base / 'dg'}", "monitor.adaptive=false"),
        ("replay", f"data.path={data}", "track=false", f"replay.model={model}", f"out={base / 'rp2'}",
         "monitor.adaptive=false"),
        ("evaluate", *common, f"out={base / 'ev2'}", f"model_path={model}", f"data.interim={base / 'i'}",
         "eval.mode=one_step"),
        ("simulate", f"data.path={base / 'data2'}", *UNTRACKED, *SHORT, "seed=3"),
    ]


def loop(tree: str) -> None:
    root = Path(tree).resolve()
    sys.path[:0] = [str(root / "src"), str(root / "tests")]
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    import conftest  # noqa: F401  (installs the composition cache as the suite does)
    from thermocomp.shell import cli
    from thermocomp.shell.config import overrides

    spent = dict.fromkeys(STEPS, 0.0)
    overrides.compose_checked = _timed(spent, "compose", overrides.compose_checked)
    cli._run_job = _timed(spent, "run_job", cli._run_job)
    task = cli._task
    cli._task = lambda *a: _timed(spent, "task", task(*a))
    base = Path(tempfile.mkdtemp(prefix="ci109a-"))
    rows, start = [], time.process_time()
    try:
        for args in _commands(base):
            before, t = dict(spent), time.process_time()
            proc = conftest._in_process(args, root, {})
            assert proc.returncode == 0, (args, proc.stderr[-2000:])
            d = {k: spent[k] - before[k] for k in STEPS}
            rows.append((args[0], time.process_time() - t, d["compose"], d["run_job"] - d["task"]))
    finally:
        shutil.rmtree(base, ignore_errors=True)
    total = time.process_time() - start
    print(f"{'command':9s} {'CPU s':>7s} {'compose':>8s} {'run_job':>8s}  (run_job: outside the task)")
    for name, cpu, comp, job in rows:
        print(f"{name:9s} {cpu:7.3f} {comp:8.4f} {job:8.4f}")
    hits = rows[-3:]
    hit_path = sum(c + j for _, _, c, j in hits) / len(hits)
    print(f"loop total CPU s: {total:.3f}")
    print(f"config path, all 12: {sum(c + j for _, _, c, j in rows):.4f} s "
          f"(compose {sum(r[2] for r in rows):.4f}, run_job outside the task {sum(r[3] for r in rows):.4f})")
    print(f"run_job outside the task per command: {sum(r[3] for r in rows) / len(rows) * 1e3:.1f} ms")
    compose, job = (sum(r[i] for r in hits) / len(hits) * 1e3 for i in (2, 3))
    print(f"config path per cache-hit command (last 3): {hit_path * 1e3:.1f} ms "
          f"(compose {compose:.1f}, run_job {job:.1f})")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"loop": loop}, argv, cpu=sys.stdout)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
