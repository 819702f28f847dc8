"""A lone JUMP of a sensor the others predict, in range, re-referenced as the C does (st111, issue 34
"deployed as scored").

Found by st109b (on its BASE too): the C re-references such a jump by its step less the change the
others predict for it since the last row (watch_c.py ``other[k] - mon_prev_other[k]``), the block
by its whole step: T_1 -3 from row 60 on the seen model, 0.52 um off the C to the campaign's end,
unflagged from row 81; fresh 10207's +30 returns (bench_st109b ``fresh``), 680 rows unflagged.

The bar is benchmarks/st111_bar.md (committed first).  A row *differs* where max |ST - C| > 1e-9
um (C = the JSON mirror ``Simulator``), *unflagged* where it differs and neither ``mon_flag``,
``mon_unsure`` nor ``refused`` is set.  B2 / B3 are bench_st109b ``fresh``; B4 bench_st108b.

RULE (st_watch.py): while the C's set is whole as far as the block knows (``mon_whole``: nothing
flagged, held or followed late, no reading beyond range, the others' last prediction known), a
lone jump of a judged sensor the C holds out (``MON_STEP_HELD``) is re-referenced by its step less
``(d - e) - mon_other`` (``e`` with every sensor in, ``MON_SELF`` / ``MON_SCALE``: the C's
``other``, which does not read its own ``d``); any other lone jump of a judged sensor sets
``mon_junsure`` (``mon_unsure`` to the campaign's end).

SCORED (2026-12-07, the bar fc0afaf3 unchanged, the rule b78456d8; BASE /tmp/base-st111 = a worktree
of 1a0fc91a; CPU user + sys by /usr/bin/time, 2 cores shared).
* B1 seen T_1 -3 from row 60: per test campaign differing BASE 60 (max 1.4-6.5 um), unflagged 39
  (rows 81-119) -> RULE differing 10 / 10 / 11 / 10, unflagged 0; the rows left are the jump's row
  and the C's hold after it (the C rebuilds the excluded sensor, the block reads it: flagged
  unsure), none after the C's BACK.  Bar's "differing after the jump's row -> 0": not met (9-10).
  6.6 s CPU (both blocks).
* B2 fresh 10207 (T_headstock): campaigns 0 / 2 unflagged 329 / 351 -> 0 / 0 (differing 350 / 372
  -> 10 / 10); campaigns 1 / 3 unchanged (0 / 0 unflagged).  9.5 s CPU.
* B3 fresh 10208 (T_headstock), 10209, 10210 (T_nc_spindle_motor), each scored once after b78456d8:
  unflagged 0 on every campaign (BASE: 377 on 10208's campaign 1, differing 398 -> 10).
* B4 bench_st108b ``stream`` lr/dl 9964-9967 (46084 rows; BASE 69.9 s, RULE 65.9 s CPU): flag,
  rule, sensor, new output, stop identical; c changed on 12 rows (3 each of lr/dl9964 and lr/dl9966:
  a spike's jump and the 2 rows of the C's hold before its return), every one flagged and off the C
  in both (BASE 0.01-1.34 um, RULE 0.15-1.41 um: the C rebuilds the sensor there, the block reads
  it); every other row identical.  Bar's "identical, or only flags": not met as worded.
* B5 tests/shell/test_export_st111.py: fails on 1a0fc91a (0.41 um off the C from its BACK), adds
  <= 0.2 s CPU to test_export_st94's run (paired, 2 reps); PARSED_DIGEST re-asked (blark parsed).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st111.py seen BASESRC
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests" / "apps"),
                str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402

TOL = 1e-9      # um
STEP = -3.0     # degC, from FROM on
FROM = 60


def _jumped(df, column: str):
    """``df`` with ``column`` + STEP from row FROM to the end."""
    df = df.reset_index(drop=True).copy()
    df.loc[FROM:, column] += STEP
    return df


def _said(who: str, i: int, r: dict) -> None:
    gap = np.max(np.abs(r["c"] - r["st"]), axis=1)
    differ = gap > TOL
    lone = np.flatnonzero(differ & ~(r["flag"] | r["unsure"] | r["refused"]))
    where = f" rows {lone.min()}-{lone.max()}" if len(lone) else ""
    late = np.flatnonzero(differ[FROM + 1:]) + FROM + 1
    print(f"  {who} campaign {i}: {len(gap)} rows; differing {int(differ.sum())} (max {gap.max():.3g} um; "
          f"after row {FROM} {len(late)}, max {gap[FROM + 1:].max():.3g}), unflagged {len(lone)}{where}; "
          f"unsure {int(r['unsure'].sum())}", flush=True)


def seen(basesrc: str) -> None:
    """B1: test_export_lean107b's dep108 model (diag107's ``_room``), T_1 - 3 from row 60."""
    import tempfile

    from bench_st108d import _block, _run

    from test_diagnose_level107 import _room
    from test_export import _compose
    from test_export_lean107b import _deployed_scaled
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.shell.source import read_streamed

    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp) / "data"
        root.mkdir()
        ds = _room(7)
        for cid, df in ds.campaigns.items():
            df.to_csv(root / f"{cid}.csv", index=False)
        ds.manifest.reset_index().to_csv(root / "campaigns.csv", index=False)
        os.chdir(tmp)
        deployed, _ = _deployed_scaled(root)
        ds, _, test_ids, _ = read_streamed(_compose(f"data.path={root}", "track=false"))
    ss = state_space(deployed, monitor=True)
    tests = [_jumped(ds.campaigns[c], "T_1") for c in test_ids]
    for who, block in (("BASE", _block(deployed, basesrc)), ("RULE", _block(deployed, None))):
        for i, df in enumerate(tests):
            _said(who, i, _run(block, ss, df))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"seen": seen}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
