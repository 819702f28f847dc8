"""The ST computes what the C computes where a campaign's first sample has a monitored reading out
of range (st109, issue 34 "deployed as scored").

dep108 made the C start a sensor beyond its range at a campaign's first sample from the monitor's
``first_c`` (``MON_FIRST_C``: the model's A0 too), rebuilt from the others while it stays beyond;
dep108f made it reference that sensor late where it reads in range again (``d`` the others'
prediction, ``ref = x - d``), out to its ``BACK``.  The ST block (st_watch.py) refused those rows
and took the sensor afresh at its return; st108d only made it say ``mon_unsure`` on every row of
such a campaign (``mon_rfirst``).

RULE (st_watch.py, st.py): where the block's first sample has exactly one monitored reading beyond
its range, measured, of a sensor the others predict (the set without it solved, the sensor judged
with every sensor in, no fallback model, ``late`` exported; ``MON_LATE_OK``) and nothing else gone,
the block reads it as the C: ``MON_FIRST_C + pred`` (``pred`` the set-without-it operator's row,
``MON_LATE_FIELD``, times the others' readings on their references) while it is beyond and after
its return to the C's ``BACK`` (its error with every sensor in within ``MON_BACK_BAND`` over the
last ``MON_WINDOW`` rows since the return, at least a window on, its reading moving), referenced
late at the return (``mon_shift``: its ``d`` the prediction); the rows are no longer refused.
Anything else named or gone while it is followed ends that (``mon_rfirst``: ``mon_unsure`` to the
campaign's end, as st108d); a first sample the rule does not take keeps st108d's flag.

BAR (committed before the rule is scored and before fresh 10198-10200 are simulated; not moved
after).  BASE = 348af997's src (``git archive``), RULE = this branch's.  A row *differs* where
max |ST - C| > 1e-9 um (C = the JSON mirror ``Simulator``, = the C to 1e-9 um on these cases per
dep108 / dep108f); *unflagged* where also neither ``mon_flag``, ``mon_unsure`` nor ``refused``.
* R1 seen (bench_st107b ``room`` + bench_diag107b ``chain``, the chain's ``ambient_scaled``
  model), T_amb ``back`` +30 (rows 0 .. n // 3 - 1 of each test campaign): RULE 0 differing rows
  (BASE: measured by ``score``, expected 480: 160 refused rows 0-39, 320 rows 40-119 4.3-8.0 um
  off); ``all`` +30 no more differing nor unflagged rows than BASE.
* R2 fresh 10198, 10199, 10200 (each ``bench_st107b.py simulate DATA SEED room`` once, then
  ``bench_diag107b.py chain``), T_amb ``back`` +30: as R1 on every row; scored once.
* R3 no other ST set worse: bench_st108c's healthy streams (bench_st108b ``stream`` on lr/dl
  9964-9967) c and (flag, rule, sensor, mon_unsure) identical to BASE (``same``); as many of
  bench_st108c's ``sets`` as the time allows, no new differing nor unflagged rows (named in
  the scores, the rest said not run).
* R4 PARSED_DIGEST updated (blark parses), the ST / export modules that import st_watch pass, a
  test in test_export_lean107b (its dep108 case) failing on BASE.
* KEPT where R1-R4 hold; else REFUSED (src at BASE, the rule in benchmarks/st109_rule.patch).

SCORED (2026-12-07, the bar 9d4376da unchanged; BASE /tmp/st109/basesrc = ``git archive 348af997
src conf``; CPU user + sys by /usr/bin/time; the machine shared, load ~14).
* R1 met.  Seen ``back`` +30: 480 rows; BASE differing 480 (max 7.97 um; 160 refused, 480
  ``mon_unsure``), RULE 0 (max 7.1e-15 um; 0 refused, 240 ``mon_unsure``: st108b's rule, the
  block's OFF_RANGE flags on rows 0-39 and 2 MON_WINDOW after).  ``all`` +30: BASE 480 differing
  (21.5 um, all refused), RULE 0 (7.1e-15 um; 480 ``mon_unsure``, every row flagged OFF_RANGE).
  Unflagged 0 -> 0 in both.  ``score`` 9.4 + 0.8 s CPU.
* R2 met.  Fresh 10198 / 10199 / 10200 simulated once (room) and chained (diagnose took the lean
  law on E_X and E_Z each); ``back`` +30 (2177 / 2167 / 2178 rows): BASE differing on every row
  (23.9 / 24.8 / 51.2 um), RULE 0 (<= 2.8e-14 um), 0 refused; ``all`` +30: BASE every row (35.5 /
  35.6 / 40.2 um), RULE 0 (<= 2.1e-14 um).  Unflagged 0 -> 0.  ~17 s CPU each.
* R3 healthy streams: bench_st108b ``stream`` on lr/dl 9964-9967 (46084 rows; records made here
  by ``make``), BASE 92.8 s / RULE 82.4 s CPU: the saved st, c, flag, rule, sensor, mon_unsure and
  stop arrays identical on every row of the 8 runs (so 0 unflagged, as BASE).
* R3 bench_st108c ``sets`` on st107 fresh (lr/dl 10127-10129, made here by bench_st108c's
  MADE_BY; gate lr10128 dl10128 as st108c): 24 windows, 2664 rows, 704 differing, 0 unflagged on
  both; every saved array identical BASE / RULE (BASE 68.5 s, RULE 62.2 s CPU).  Not run (time):
  st107 seen (16 records), st103b seen / fresh.  The rule is entered only at a first sample with
  a monitored reading beyond range (st108d's ``mon_rfirst`` condition); elsewhere the healthy 8
  and these 24 windows show the block unchanged, not measured on those sets.
* R4 met.  PARSED_DIGEST 091f0ac4... (blark parsed the block, 51.3 s CPU once); test_export_st*,
  test_export.py, lean107b, monitor76, step99, test_benchmarks_cli: 1063 passed (143.5 + 7.0 s
  CPU, -n 2).  test_export_lean107b's dep108 case asserts |ST - mirror| <= 1e-9 um on every row:
  fails on BASE (7.97 um); that test 7.1 s CPU (BASE, failing at its last line, 7.9 s): no cost.
* Also tried on the seen model (a script, not a command): T_1 +30 on rows 0-39 (the others
  predict it): the 3 campaigns where it is beyond range at the first sample 120 / 120 / 120
  differing rows -> 0; T_2 +30 (none predicts it: not followed, st108d's flag) 0 unflagged.
  Found, not this rule's (BASE the same, not traced): the first test campaign, where T_1 + 30 is
  within range at the first sample (49.4 < 50.05) and beyond it later in rows 0-39, the ST is off
  the C on rows 18-119 (max 21.1 um), rows 60-119 unflagged (the C takes T_1 out at row 40's
  -30 step, back at row 50).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st109.py score ROOT DATA BASESRC
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
from _cli import project_root, run_commands  # noqa: E402

TOL = 1e-9     # um
CASES = [("T_amb", 30.0, "back"), ("T_amb", 30.0, "all")]


def score(root: str, data: str, basesrc: str) -> None:
    """R1 / R2 on a chain's root (module doc): per case and block, rows, differing (max), unflagged,
    refused and ``mon_unsure`` rows."""
    from bench_dep108 import _changed
    from bench_st108d import _block, _run
    from hydra import compose, initialize_config_dir

    from thermocomp.apps.deploy.export import state_space
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    base, data = project_root(root), str(Path(data).resolve())
    os.chdir(base)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={data}", "track=false"])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    deployed = deployable_model(cfg, ds, train_ids, str(base / "run" / "model.pkl"), "export.model")[0]
    ss = state_space(deployed, monitor=True)
    blocks = {"BASE": _block(deployed, basesrc), "RULE": _block(deployed, None)}
    for column, push, mode in CASES:
        tests = [_changed(ds.campaigns[c], column, push, mode) for c in test_ids]
        for who, b in blocks.items():
            per = [_run(b, ss, df) for df in tests]
            got = {k: np.concatenate([r[k] for r in per]) for k in per[0]}
            gap = np.max(np.abs(got["c"] - got["st"]), axis=1)
            differ, flagged = gap > TOL, got["flag"] | got["unsure"] | got["refused"]
            print(f"{column} {mode} {push:+g} {who}: {len(gap)} rows; differing {int(differ.sum())} (max "
                  f"{gap.max():.3g} um), unflagged {int((differ & ~flagged).sum())}; refused "
                  f"{int(got['refused'].sum())}, unsure {int(got['unsure'].sum())}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
