"""After the block's own ``mon_lost``, a second sensor's fault: does the ST flag every row it differs
from the C (st111b, issue 34 "deployed as scored")?

The gap named at stop 109: after ``mon_lost`` (st_watch.py, a dropout or a jump the block does not
follow) the block judges no other sensor (``mon_e`` is no longer computed) while the C still does.

CASES (a rule, fixed before any was run).  The model: test_export_lean107b's dep108 model (MLR +
``ambient_scaled`` on E_X) on diag107's ``_room(7, seed=SEED)`` record (seen: seed 3, the module's;
fresh: 10211-10213, each drawn once).  In each test campaign (n rows), A = the first monitored
sensor but T_amb (monitor order), B = the next one:

* first fault on A at ``r1 = n // 4``: ``drop`` (NaN on rows r1 .. r1 + 2) or ``jump`` (-3 K from
  r1 to the end);
* second fault on B at ``r2 = n // 2``: ``jump`` (+3 K from r2 to the end), ``drop`` (NaN on rows
  r2 .. r2 + 4) or ``drift`` (+0.05 K per row from r2 on).

A row *differs* where max |ST - C| > 1e-9 um (C = the JSON mirror ``Simulator``), is *flagged*
where ``mon_flag``, ``mon_unsure`` or ``refused`` is TRUE.  Per case and block: rows from r2 that
differ unflagged (``late``), of them those not so in the first fault alone (``added``: the second
fault's), max |ST - C| there, and whether the block was ``mon_lost`` at row r2 - 1.

SCORED (2026-12-07, bar ac9a6a38 unchanged; BASE = 1a0fc91a's src, a second worktree; load 13-17 on
2 cores).  RULE (st_watch.py): after ``mon_lost`` the errors with every sensor in computed on for
st108b's ``mon_unsure`` test (stale before: the C's later DRIFT_OUT / STEP_OUT went unflagged),
and a jump after it of one the others predict (``MON_JUMP_HELD`` 0) sets ``mon_rjump``
(``mon_unsure`` to the campaign's end).  c, flag, rule, sensor untouched.
* seen seed 3: ``added`` 0 on all 8 cases, BASE and RULE alike (the room's T_2 is one no other
  predicts: the C's hold ends after 10 rows, all flagged); the T_1 jump-first runs keep st111's
  lone-jump rows (240 late unflagged, first fault alone).  12.5 s CPU.
* seen stream lr9964 (A T_spindle_front, B T_spindle_rear, ``MON_JUMP_HELD`` 1): drop then drift
  added 268 (0.193 um) -> 0; drop alone late 12 (1.28 um) -> 0; drop then jump 2119 (1.34 um) ->
  1521 (0.061 um): NOT met (the C's hold of a held sensor and its undoing at BACK, not followed
  after ``mon_lost``; not latched: this rule latches only sensors the others predict).
  dl9965 (BASE only): drop then jump added 3569 (4.54 um).
* fresh 10211-10213 (drawn once, after 83886f83's rule): 10212 drop then jump added 156
  (0.525 um) -> 0; 10211 jump then jump 1, jump then drift 2 added rows on BASE and RULE alike;
  every other case 0 on both.  25.6 s CPU.
* B3 bench_st108b ``stream`` lr/dl 9964-9967 (BASE 69.5 s, RULE 68.5 s CPU): st, c, flag, rule,
  sensor, stop identical on all 8 (``same``: 0 / 0); differing rows unchanged, all flagged on both;
  ``mon_unsure`` rows 291 -> 1527 of 46084 (lr9964 33 -> 170, dl9964 33 -> 272, lr9966 42 -> 360,
  dl9966 41 -> 583; the other 4 identical): the cost, flags on rows equal to the C.
* B4 test_export_st97d's new case fails on BASE (rows 692-789 unflagged, 3 K jump of T_head_left
  after a dropout), passes on RULE; module CPU without / with it 4.72 / 4.35 -> 4.72 / 4.45 s.
  PARSED_DIGEST 320772ec (blark parsed, 30.9 s CPU).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st111b.py score BASESRC SEED [SEED ...]
    python benchmarks/bench_st111b.py stream ROOT BASESRC RECORD [RECORD ...]

``stream``: the same rule on bench_st108b's healthy lr/dl streams (one campaign each), added after
the room's seen cases were run (more seen cases, not the bar's fresh ones).
"""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests" / "apps"),
                str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402

TOL = 1e-9      # um
FIRST = ("drop", "jump")
SECOND = ("none", "jump", "drop", "drift")


def faulted(df, a: str, b: str, first: str, second: str):
    """``df`` with A's ``first`` fault at n // 4 and B's ``second`` at n // 2 (module doc)."""
    df = df.reset_index(drop=True).copy()
    n = len(df)
    r1, r2 = n // 4, n // 2
    if first == "drop":
        df.loc[r1:r1 + 2, a] = np.nan
    else:
        df.loc[r1:, a] -= 3.0
    if second == "jump":
        df.loc[r2:, b] += 3.0
    elif second == "drop":
        df.loc[r2:r2 + 4, b] = np.nan
    elif second == "drift":
        df.loc[r2:, b] += 0.05 * (np.arange(r2, n) - r2 + 1)
    return df


def run(block: str, ss, df) -> dict:
    """Per row: the block's c, its flags (flag, unsure, refused), mon_lost; the mirror's c."""
    from test_export import StructuredText
    from thermocomp.apps.deploy.export import Simulator

    st, sim = StructuredText(block), Simulator(ss)
    sim.reset()
    U, t = df[ss.inputs].to_numpy(float), df["time"].to_numpy(float)
    got = {k: [] for k in ("st", "c", "flagged", "lost")}
    for i in range(len(df)):
        a, c = st(U[i], t[i], i == 0), sim.step(U[i], t[i])
        v = st.vars
        got["st"].append(np.array(a, float))
        got["c"].append(np.array(c, float))
        got["flagged"].append(bool(v["mon_flag"]) or bool(v.get("mon_unsure", False)) or bool(v["refused"]))
        got["lost"].append(bool(v["mon_lost"]))
    return {k: np.array(x) for k, x in got.items()}


def loose(r: dict) -> np.ndarray:
    """Rows differing from the C and not flagged."""
    return (np.max(np.abs(r["c"] - r["st"]), axis=1) > TOL) & ~r["flagged"]


def _deployed(seed: int, tmp: str):
    from test_diagnose_level107 import _room
    from test_export import _compose
    from test_export_lean107b import _deployed_scaled
    from thermocomp.shell.source import read_streamed

    root = Path(tmp) / "data"
    root.mkdir()
    ds = _room(7, seed=seed)
    for cid, df in ds.campaigns.items():
        df.to_csv(root / f"{cid}.csv", index=False)
    ds.manifest.reset_index().to_csv(root / "campaigns.csv", index=False)
    os.chdir(tmp)
    deployed, _ = _deployed_scaled(root)
    ds, _, test_ids, _ = read_streamed(_compose(f"data.path={root}", "track=false"))
    return deployed, [ds.campaigns[c] for c in test_ids]


def _cases(label: str, ss, campaigns: list, blocks: dict) -> None:
    """Per case and block: the module doc's counts, summed over ``campaigns``."""
    names = [ss.inputs[i] for i in ss.monitor["inputs"]]
    a, b = [c for c in names if c != "T_amb"][:2]
    for who, block in blocks.items():
        for first in FIRST:
            alone = [run(block, ss, faulted(df, a, b, first, "none")) for df in campaigns]
            for second in SECOND:
                late = added = lost = 0
                worst = 0.0
                for df, r0 in zip(campaigns, alone):
                    r = r0 if second == "none" else run(block, ss, faulted(df, a, b, first, second))
                    r2 = len(df) // 2
                    bad = loose(r)
                    bad[:r2] = False
                    late += int(bad.sum())
                    added += int((bad & ~loose(r0)).sum())
                    lost += int(r["lost"][r2 - 1])
                    if bad.any():
                        worst = max(worst, float(np.max(np.abs(r["c"] - r["st"])[bad])))
                print(f"{label} {who} {a} {first} then {b} {second}: late unflagged {late}, added {added} "
                      f"(max {worst:.3g} um); mon_lost at r2-1 in {lost} of {len(campaigns)} campaigns",
                      flush=True)


def score(basesrc: str, *seeds: str) -> None:
    """The room record's cases per seed (module doc), BASE's block and the tree's."""
    from bench_st108d import _block

    from thermocomp.apps.deploy.export import state_space

    for seed in map(int, seeds):
        with tempfile.TemporaryDirectory() as tmp:
            deployed, campaigns = _deployed(seed, tmp)
            blocks = {"BASE": _block(deployed, basesrc), "RULE": _block(deployed, None)}
            _cases(f"seed {seed}", state_space(deployed, monitor=True), campaigns, blocks)


def stream(root: str, basesrc: str, *records: str) -> None:
    """The same cases on bench_st108b's healthy streams (ROOT as its ``make`` makes them)."""
    import bench_st103b
    import bench_st108b
    from bench_st108d import _block

    for record in records:
        _, ss, frame, _, _, tree, base = bench_st103b._cell(root, record, bench_st108b.MADE_BY,
                                                            lambda d: _block(d, basesrc))
        _cases(record, ss, [frame], {"BASE": base, "RULE": tree})


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score, "stream": stream}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
