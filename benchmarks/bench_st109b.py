"""The ST says ``mon_unsure`` where a monitored reading goes beyond its range after a campaign's first
sample and the C may read it on (st109b, issue 34 "deployed as scored").

Found by st109 (present on its BASE too): the seen model (test_export_lean107b's dep108 case,
diag107's ``_room`` record, MLR + ``ambient_scaled``), T_1 +30 on rows 0-39 of the first test
campaign.  T_1 + 30 is within range at the first sample and beyond it on rows 18-39; the ST is off
the C on rows 18-119 (max 21.1 um), rows 60-119 unflagged.

BAR (committed before the change is measured and before fresh 10207 is scored; not moved after).
BASE = 7d4346c5's src (``git archive``), RULE = this branch's.  A row *differs* where
max |ST - C| > 1e-9 um (C = the JSON mirror ``Simulator``); *unflagged* where it differs and
neither ``mon_flag``, ``mon_unsure`` nor ``refused`` is set.  A column is pushed +30 degC on rows
0 .. n // 3 - 1 of every test campaign (``back``).
* B1 seen (``seen``), T_1: unflagged differing rows 60 (BASE, measured) -> 0.
* B2 fresh 10207 (``bench_st107b.py simulate DATA 10207 room``, ``bench_diag107b.py chain``, once;
  ``fresh``): the sensor pushed is the first monitored one but T_amb, in the monitor's order,
  that is within range at the first sample and beyond it later in some test campaign (chosen by
  that rule, not by the score): 0 unflagged differing rows.
* B3 no other ST output changed: bench_st108b ``stream`` on the healthy lr/dl 9964-9967 (every
  saved array identical to BASE, ``same``); bench_st109 ``score`` on its seen chain (T_amb back /
  all: the same differing, unflagged, refused and unsure counts as BASE).
* B4 PARSED_DIGEST updated (blark parses), test_export_lean107b's dep108 case asserting no
  unflagged differing row, failing on BASE.
* KEPT where B1-B4 hold; else REFUSED (src at BASE, the change in benchmarks/st109b_rule.patch).

RULE (st_watch.py): ``mon_rlater``, a monitored reading measured and beyond its range after the
first sample (but the st109 followed one's before its return) sets ``mon_unsure`` to the
campaign's end.  Why: the C reads such a reading on where the others predict it beyond the same
training edge (cmon80 ``_beyond``, a machine hotter than training), so its last reading is the
last one beyond and the return (T_1 -30 at row 40) is a JUMP: excluded, re-referenced by its step
less the others' change, back at row 50; the block read it as OFF_RANGE (refused), stepped the
return from row 17 over the gap (no jump), kept T_1 on its first reference: 9.8-21.1 um off to the
end, its st108b flags ending at row 59.  Porting the C's read-on needs hi_c / lo_c and the set-
without-k rows for every sensor, and the return's jump would still part (below): flagged instead.

SCORED (2026-12-07, the bar 8c326703 unchanged; BASE /tmp/st109b/base = ``git archive 7d4346c5``).
* B1 met.  Seen T_1: campaign 0 beyond rows 18-39; BASE differing 102 (21.1 um), unflagged 60
  (rows 60-119); RULE differing 102, unflagged 0 (unsure 42 -> 102).  Campaigns 1-3 (beyond at
  the first sample: st109's rule) 0 differing, unchanged.  5.9 s CPU.
* B2 NOT met as worded.  Fresh 10207 (diagnose took the lean mean law + a lag on E_X), T_headstock
  (the rule's pick): campaign 3, beyond rows 19-168: unflagged 319 -> 0 (differing 489, 20.7 um,
  all flagged).  Campaigns 0 and 2 (never beyond: the -30 step at n // 3 a lone jump in range):
  unflagged 329 / 351 (max 0.13 / 0.12 um) on BASE and RULE alike: another class (below).
* B3 met.  bench_st108b ``stream`` lr/dl 9964-9967: every saved array (st, c, flag, rule, sensor,
  mon_unsure, stop) identical (BASE 94.7 s, RULE 110.0 s CPU, loaded machine).  bench_st109
  ``score`` on its seen chain: T_amb back / all 0 / 0 differing, unsure 240 / 480 on both.
* B4 met.  PARSED_DIGEST 10f59d5a (blark parsed, 44.1 s CPU once); lean107b's dep108 test fails
  on BASE (unflagged rows [60, 61, ...]), its added loop 0.09 s CPU.
* Found, on BASE too: a lone JUMP of a sensor the others predict (seen T_1 -3 from row 60): the C
  re-references by its step less the others' change (0.244 degC here), the block by its whole
  step: 0.52 um off to the end, unflagged from row 81 (39 rows).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st109b.py seen BASESRC
    python benchmarks/bench_st109b.py fresh ROOT DATA BASESRC
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests" / "apps"),
                str(HERE.parent / "tests")]
from _cli import project_root, run_commands  # noqa: E402

TOL = 1e-9     # um
PUSH = 30.0    # degC


def _pushed(df, column: str):
    """``df`` with ``column`` + PUSH on rows 0 .. n // 3 - 1 (bench_dep108's ``back``)."""
    from bench_dep108 import _changed

    return _changed(df, column, PUSH, "back")


def _beyond_later(ss, df, column: str) -> np.ndarray:
    """Rows where ``column`` is beyond its range, none at the first sample (else empty)."""
    m = ss.monitor
    k = [ss.inputs[i] for i in m["inputs"]].index(column)
    x = df[column].to_numpy(float)
    out = (x < m["lo_lim"][k]) | (x > m["hi_lim"][k])
    return np.flatnonzero(out) if not out[0] else np.array([], int)


def _score(deployed, campaigns: list, column: str, basesrc: str) -> None:
    """Per block (BASE, RULE): rows, differing (max), unflagged (their rows), refused, unsure."""
    from bench_st108d import _block, _run

    from thermocomp.apps.deploy.export import state_space

    ss = state_space(deployed, monitor=True)
    tests = [_pushed(df, column) for df in campaigns]
    for i, df in enumerate(tests):
        rows = _beyond_later(ss, df, column)
        print(f"{column} +{PUSH:g} campaign {i}: beyond later on rows "
              f"{f'{rows.min()}-{rows.max()} ({len(rows)})' if len(rows) else 'none (or at the first)'}")
    for who, block in (("BASE", _block(deployed, basesrc)), ("RULE", _block(deployed, None))):
        per = [_run(block, ss, df) for df in tests]
        for i, r in enumerate(per):
            gap = np.max(np.abs(r["c"] - r["st"]), axis=1)
            differ = gap > TOL
            lone = np.flatnonzero(differ & ~(r["flag"] | r["unsure"] | r["refused"]))
            where = f" rows {lone.min()}-{lone.max()}" if len(lone) else ""
            print(f"  {who} campaign {i}: {len(gap)} rows; differing {int(differ.sum())} (max "
                  f"{gap.max():.3g} um), unflagged {len(lone)}{where}; refused {int(r['refused'].sum())}, "
                  f"unsure {int(r['unsure'].sum())}", flush=True)


def seen(basesrc: str) -> None:
    """B1: test_export_lean107b's dep108 model (diag107's ``_room`` record), T_1 pushed."""
    import tempfile

    from test_diagnose_level107 import _room
    from test_export_lean107b import _deployed_scaled

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp) / "data"
        root.mkdir()
        ds = _room(7)
        for cid, df in ds.campaigns.items():
            df.to_csv(root / f"{cid}.csv", index=False)
        ds.manifest.reset_index().to_csv(root / "campaigns.csv", index=False)
        os.chdir(tmp)
        deployed, _ = _deployed_scaled(root)
        from test_export import _compose
        from thermocomp.shell.source import read_streamed

        ds, _, test_ids, _ = read_streamed(_compose(f"data.path={root}", "track=false"))
        _score(deployed, [ds.campaigns[c] for c in test_ids], "T_1", basesrc)


def fresh(root: str, data: str, basesrc: str) -> None:
    """B2: a chain's deployed model (bench_st109 ``score``'s), the sensor chosen by the bar's rule."""
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
    campaigns = [ds.campaigns[c] for c in test_ids]
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    column = next((c for c in names if c != "T_amb" and any(
        len(_beyond_later(ss, _pushed(df, c), c)) for df in campaigns)), None)
    if column is None:
        print("no monitored sensor but T_amb goes beyond its range only after the first sample")
        return
    _score(deployed, campaigns, column, basesrc)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": seen, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
