"""The exported C follows the warned air of a one-campaign training (stop 94, quiet94c;
follow-up of bench_quiet94): quiet94 (KEPT) marks the ambient sensors of a served monitor
fitted on ONE campaign ``drift_warn_only`` -- their drift error is judged and warned but neither
excludes them, nor names them as explaining the others, nor vetoes / holds another's exclusion.
The C kept main's drift rule, so on the short one-campaign swiss records where main excluded a
healthy ``T_amb`` the C excluded the air and the served monitor did not (``not_in_code`` named
it, the check pack stopped where they parted).  The rule: the export writes a fixed per-sensor
array ``warn_only`` (``MON_WARN_ONLY``), and the C's drift judgement (stream.c's
``mon_judging``, its numpy mirror ``CodeMonitor._judging``) leaves those sensors' errors out of
its evidence exactly where the served ``_judging`` does: the trigger, the culprit, the lone fault,
the explaining sensor (neither a candidate nor judged), the veto's and the resolve's sets, the
blind partner, the excursion's hover, the field that follows, the end of a new state.  Their
bands still flag (``TC_MON_BAND``) and every fault signature (jump, freeze, dropout, range,
stepped error) still excludes them, as served.  ``not_in_code`` no longer names the rule.

Usage (from ``benchmarks/``, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_quiet94c.py swiss ROOT SEEDS [HOURS]    # C = served, pack
    python benchmarks/bench_quiet94c.py lr ROOT SEEDS              # multi-campaign: C = main's

``swiss``: per seed bench_quiet93's record (``simulate`` 3 campaigns of HOURS (4) to HOURS + 1 h
at 300 s, the longest one the lab's one-file record, ROOT/SEED-<HOURS>h), written as one CSV and
run as a lab runs it (``data.path=<csv> data.test_fraction=0.25 model=mlr``: ONE train
campaign, the test part continuing it), deployed as ``replay`` deploys it (adaptive monitor);
then the whole test part (after its lead-in) stepped by the served model, the NEW mirror (the
export as written) and the BASE mirror (the same arrays without ``warn_only``: main's drift
rule): per mirror the largest |C - served| over every row, the first NOT_IN_CODE (row, rule),
the rows parting by more than 1e-9 µm; the compiled C (``-Werror``) of the NEW export fed the
same rows, its largest |C - served|, the conformance pack's cut and ``check.sh``'s exit status;
the served exclusions and ``not_in_code``.  ``lr``: bench_cmon93's long records (``sim=
long_record``, 3 days, R1b the last fifth continuing R1a), mlr deployed adaptive
(``data.reference=none``): the arrays' ``warn_only``, and NEW against BASE on R1b row by row
(identical flags, rules and corrections: the rule does not act).

BAR (written and committed BEFORE the fresh seeds 9714-9718 were simulated; the seen 9559 /
9646 and the lr records measured first, said below).  KEPT only if all hold:
(1) on FRESH 9714-9718 (4 h) and SEEN 9559 / 9646 (4 h): the NEW mirror and the compiled C =
    served to 1e-9 µm on every test row, no NOT_IN_CODE for a drift (DRIFT) on any of them,
    ``not_in_code`` naming no drift of an ambient, and ``check.sh`` exit 0 with the pack whole
    (no cut);
(2) on the seen lr records (bench_cmon93's seen lr9212 and its lr9526 / lr9529): NEW =
    BASE on every row (corrections to 0 µm, flags and rules identical) -- the C's behaviour
    there main's;
(3) the C-export / monitor suites the brief names pass (test_export_cmon9*, bent93, st9*,
    monitor76, spike54, check61, tests/apps/test_monitor_ambient_one_campaign94.py).
Otherwise REFUSED (src reverted, the rule as benchmarks/quiet94c_rule.patch).

Measured (2026-12-05, this tree; SEEN 9559 / 9646 and the lr records first, the bar committed
(ad3febbc) before FRESH 9714-9718 were simulated, then fresh once; the bar unchanged)
--------------------------------------------------------------------------------------------
``swiss`` (BASE = main's drift rule in the same arrays; the served monitor excluded nothing on
any record; ``warn_only`` = [T_amb] on every one; rows: the lead-in and the test part)::

    record     rows  BASE max|C-served|  BASE rows parted  NEW mirror  compiled C  pack  check.sh
    9559 seen    58        3.7 µm               9           4.3e-14     6.4e-14    whole    0
    9646 seen    56        1.7 µm               4           0           1.8e-14    whole    0
    9714 fresh   58        4.4 µm               8           1.8e-14     5.0e-14    whole    0
    9715 fresh   59        0                    0           0           5.0e-14    whole    0
    9716 fresh   55        1.4 µm               9           7.1e-15     4.3e-14    whole    0
    9717 fresh   57        2.1e-14              0           2.1e-14     3.7e-14    whole    0
    9718 fresh   60        8.9e-16              0           8.9e-16     2.1e-14    whole    0

No NOT_IN_CODE on any row (NEW nor BASE: main's C took the healthy air out by a drift it holds,
silently), the stream said nothing "not in the code", ``not_in_code`` one entry naming no
ambient drift (main's: two, the second "a drift of T_amb").  Clause (1): HOLDS (7 of 7).
``lr`` (lr9212 seen by bench_cmon93, lr9526 / lr9529 its fresh ones, now seen; 4321 rows each):
their training is ONE campaign too (R1a; R1b continues it), so ``warn_only`` = [T_amb] there as
well -- the brief's "more than one campaign" does not describe them, said plainly -- yet NEW =
BASE on every row of all three (corrections, flags, rules, missed rules identical; NEW = served
to 0 µm; lr9212's one NOT_IN_CODE, a DRIFT at row 682, the same in both).  Clause (2): HOLDS.
Clause (3): HOLDS -- test_export_cmon91 / cmon92b / cmon93, bent93, st93 / st94, monitor76,
spike54, check61, cmon82 / 82b / 82c / 85, mon85b, mon86, rounding83, the new
test_export_quiet94c, tests/apps/test_monitor_ambient_one_campaign94.py and test_lint: 53
passed; cmon80 / 83 / 84 / 86 / 88 / 89 / 89b, freeze84, mon88, cdrop77, test_export.py: 60
passed; cmon87 (its helper shared), test_docs, test_benchmarks_cli, test_lint: 615 passed.
Tests failing on 6c291de8 (its src, these tests): 3 of the 8 new / changed (test_export_quiet94c's
arrays and compiled-C cases, test_monitor_ambient_one_campaign94's not_in_code case).
VERDICT: KEPT (all three clauses; the fresh seeds scored once, the bar unchanged).
CPU: ``swiss`` ~4 s per record (its C build included), ``lr`` ~6 s per record after its
simulation.
"""

from __future__ import annotations

import dataclasses
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_quiet93 as quiet93  # noqa: E402
from _cli import run_commands, seed_list  # noqa: E402
from bench_cmon93 import FRESH as CMON93_FRESH  # noqa: E402

from test_export_cmon87 import deployed_mlr  # noqa: E402

LR = {"lr9212": ["sim=long_record", "seed=9212", "sim.generator.duration_days=3.0",
                 "sim.generator.test_fraction=0.2"],
      **{k: v for k, v in CMON93_FRESH.items() if k.startswith("lr")}}
TOL = 1e-9


def _deployed(data: str, *words: str):
    """``(deployed, system with its monitor, the test part after its lead-in, tests, leads)``
    of ``data`` run with ``words``, as ``replay`` deploys it (the tests' helper)."""
    deployed, ss, frame, _, tests, leads = deployed_mlr(f"data.path={data}", *words)
    return deployed, ss, frame, tests, leads


def _stepped(deployed, ss, frame) -> dict:
    """Per row the served corrections and, per mirror (NEW: the arrays as exported; BASE: without
    ``warn_only``), the code's corrections, flags and the rule it missed."""
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.pack import corrections

    base = dataclasses.replace(ss, monitor={k: v for k, v in ss.monitor.items() if k != "warn_only"})
    sims = {"NEW": Simulator(ss), "BASE": Simulator(base)}
    for sim in sims.values():
        sim.reset()
    deployed.reset()
    X = frame[deployed.columns_].to_numpy(float)
    U, t = frame[ss.inputs].to_numpy(float), frame["time"].to_numpy(float)
    out = {"served": [], **{m: {"c": [], "flags": [], "rule": [], "missed": []} for m in sims}}
    for i in range(len(frame)):
        out["served"].append(corrections(ss, deployed._step(X[i], t[i])[0][None, :])[0])
        for m, sim in sims.items():
            out[m]["c"].append(sim.step(U[i], t[i]))
            out[m]["flags"].append(sim.watch.flags)
            out[m]["rule"].append(sim.watch.rule)
            out[m]["missed"].append(sim.watch.missed)
    return {k: ({kk: np.asarray(vv) for kk, vv in v.items()} if isinstance(v, dict) else np.asarray(v))
            for k, v in out.items()}


def _first_missed(run: dict) -> tuple | None:
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE, RULES

    rows = np.flatnonzero(run["flags"] & NOT_IN_CODE)
    return None if not len(rows) else (int(rows[0]) + 1, RULES[int(run["missed"][rows[0]])])


def _compiled(folder: Path, deployed, ss, frame, tests, leads) -> tuple[np.ndarray, dict, int, str]:
    """The NEW export compiled in ``folder`` with its pack: ``(C per row, summary, check.sh's
    exit status, stream's stderr lines 'not in the code')``."""
    import pandas as pd

    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.export.pack import conformance_pack

    files, summary = conformance_pack(deployed, ss, tests, leads)
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in {**exported_files(deployed, "c"), **files}.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=folder, check=True, capture_output=True)
    run = subprocess.run([str(folder / "stream")], capture_output=True, text=True, check=True,
                         input=frame[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g"))
    check = subprocess.run(["sh", "check/check.sh"], cwd=folder, capture_output=True, text=True)
    said = [line for line in run.stderr.splitlines() if "not in the code" in line]
    return (pd.read_csv(pd.io.common.StringIO(run.stdout)).to_numpy(float), summary,
            check.returncode, "; ".join(said[:2]))


def swiss(root: str, seeds: str, hours: str = "4") -> None:
    """The ``swiss`` rows (module doc)."""
    from thermocomp.apps.deploy.export import not_in_code
    from thermocomp.apps.deploy.report import stream_rows

    h = float(hours)
    for seed in seed_list(seeds):
        rows, _ = quiet93._record(root, seed, h)
        base = Path(root).resolve() / f"{seed}-{h:g}h"
        csv = base / "record.csv"
        if not csv.exists():
            rows.to_csv(csv, index=False)
        deployed, ss, frame, tests, leads = _deployed(str(csv), "data.test_fraction=0.25")
        (test, _), = tests.items()
        warned = [ss.inputs[i] for i, w in zip(ss.monitor["inputs"], ss.monitor.get("warn_only", []))
                  if w]
        served_out = [(e["sensor"], e["reason"][:5]) for e in
                      stream_rows(deployed, frame, test).events if e["to"] == "excluded"]
        run = _stepped(deployed, ss, frame)
        parts = []
        for m in ("BASE", "NEW"):
            gap = np.abs(run[m]["c"] - run["served"]).max(axis=1)
            parts.append(f"{m} max|C-served| {gap.max():.2g} µm, rows parted {int((gap > TOL).sum())}"
                         f", first NOT_IN_CODE {_first_missed(run[m])}")
        c, summary, rc, said = _compiled(base / "c", deployed, ss, frame, tests, leads)
        left = not_in_code(deployed, "c")
        print(f"swiss{seed} {h:g}h: rows {len(frame)}, warn_only {warned}, served exclusions "
              f"{served_out}; " + "; ".join(parts) + f"; compiled C max|C-served| "
              f"{np.abs(c - run['served']).max():.2g} µm, pack cut "
              f"{[e['cut'] for e in summary['campaigns']]}, check.sh exit {rc}; not_in_code "
              f"entries {len(left)}, names an ambient drift: {any('a drift of' in s for s in left)}"
              f"; stream said: {said or 'nothing'}")


def lr(root: str, seeds: str) -> None:
    """The ``lr`` rows (module doc): SEEDS names bench_cmon93's records (lr9212,lr9526,...)."""
    from thermocomp.shell.cli import main

    for record in seeds.split(","):
        data = Path(root).resolve() / "lr" / record
        if not (data / "campaigns.csv").exists():
            assert main(["-q", "simulate", *LR[record], f"data.path={data}", "track=false"]) == 0
        deployed, ss, frame, _, _ = _deployed(str(data), "data.reference=none")
        run = _stepped(deployed, ss, frame)
        same = {k: bool(np.array_equal(run["NEW"][k], run["BASE"][k]))
                for k in ("c", "flags", "rule", "missed")}
        gap = np.abs(run["NEW"]["c"] - run["served"]).max(axis=1)
        print(f"{record}: rows {len(frame)}, warn_only {ss.monitor.get('warn_only')}; NEW = BASE "
              f"{same}; NEW max|C-served| {gap.max():.2g} µm, first NOT_IN_CODE "
              f"{_first_missed(run['NEW'])}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"swiss": swiss, "lr": lr}, argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
