"""The C's single-sensor spike and its return on a row where another sensor is missing (c111,
issue 34 "deployed as scored"): C against the served model per row.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_c111.py score ROOT BASESRC RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (:data:`MADE_BY`: bench_st105's
words, and :data:`FRESH`); BASESRC a ``git archive`` (or worktree) of BASE's src.  Per RECORD and
model (:data:`CELLS`) bench_cmon92's ``faulted_cell`` frame (lead-in + first test campaign; onset
``s`` a quarter into the campaign) and the cases of :func:`cases` (the rule, fixed in
benchmarks/c111_bar.md before any case was measured): spiker S (the first monitored sensor the
others predict, the first they do not) read +:data:`SPIKE_C` on rows ``s .. s+L-1`` (L = 1, 2,
3; the return ``r = s+L``), the other O (the first monitored sensor not S) missing (an empty
cell) on ONE row of ``s-1``, ``s``, ``r-1``, ``r``; the frame cut :data:`AFTER` rows past ``r``.
The served model (export's ``corrections`` of its ``y``, from the state its lead-in left: the
rows before ``s-1``) against the C (``stream --flags``, cc -O2) of the tree's and of BASE's
export on the same rows.  Per case: max |C - served|, the rows past :data:`TOL` and of those the
ones not flagged ``mon_not_in_code`` on that row or earlier from ``s`` on (silent), per tree, and
whether the two trees' stdout is identical.

TRACE (why they agree).  Served (monitor.py ``_update``) tries a spike's return (faults.py
``_spike_back``) only where every reading of the row is finite, referenced and in range; the C
(watch_c.py, the single-jump branch) only where ``lost < 0 && far < 0 && !nlate``: no missing cell,
none beyond range, none awaiting its late reference: the same condition.  On a row with a missing
cell neither tries it: the spiker is re-referenced by the return's step and waits out a window,
the missing sensor is out for a dropout, both back by the window rule on the same row.  Missing
on an earlier row (s-1, s, r-1), the other is still out on the return row and both try the return
against the set without it (C ``n >= MON_MIN_ACTIVE``, served ``_rebuilds``): e.g. lr9964 mlr,
T_head_left L2, T_amb empty on row s: T_head_left back as a spike on row r in both; with
min_active 13 of 14 (lr10216) neither tries it.

SCORED (2026-12-07, the bar afdd8a03 unchanged; BASE = 1a0fc91a in a detached worktree, TREE =
this branch, src unchanged; CPU user + sys of the bench with its children, ``/usr/bin/time``).
* Seen lr9964 (mlr, lagbank; 14 monitored, min_active 10; spikers T_head_left (predicted) and
  T_amb (not), others T_amb / T_spindle_front): 44 cases, max |C - served| 6.5e-13 um (= the
  healthy cut's), 0 rows > 1e-9 um, 0 flags, BASE stdout = TREE's (24.4 s CPU, making the record
  and both models included).
* Fresh lr10214 / lr10215 / lr10216 (bench_st105's lr9964 words, seed replaced; each simulated,
  run and scored once; min_active 10 / 8 / 13): 132 cases, max |C - served| 1.25e-12 um, 0 rows
  > 1e-9 um, 0 flags, BASE stdout = TREE's on every case (72.0 s CPU).
"""

from __future__ import annotations

import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402

TOL = 1e-9        # um
SPIKE_C = 5.0     # degC: bench_cmon92's planted spike
AFTER = 60        # rows past the return: a re-admission window (10) several times
CELLS = ("mlr", "lagbank")
BUILD = ["cc", "-std=c99", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"]


def _made_by() -> dict:
    from bench_st105 import MADE_BY

    lr = MADE_BY["lr9964"]
    fresh = {f"lr{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in lr]
             for seed in (10214, 10215, 10216)}
    return {**MADE_BY, **fresh}


def cases(names: list[str], predictable: list[bool], s: int) -> list[tuple[str, str, int, str, int]]:
    """``(spiker, other, L, where, missing row)`` per case (module doc)."""
    spikers = [next((n for n, p in zip(names, predictable) if p == want), None) for want in (True, False)]
    out = []
    for spiker in [n for n in spikers if n is not None]:
        other = next(n for n in names if n != spiker)
        for rows in (1, 2, 3):
            r = s + rows
            wheres = {"before": s - 1, "onset": s, "last": r - 1, "back": r}
            seen = set()
            for where, row in wheres.items():
                if row not in seen:
                    seen.add(row)
                    out.append((spiker, other, rows, where, row))
    return out


def _build(files: dict, folder: Path) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    for name, body in files.items():
        if name.endswith((".c", ".h")):
            (folder / name).write_text(body)
    subprocess.run(BUILD, cwd=folder, check=True)
    return folder / "stream"


def _run(stream: Path, inputs: list[str], df: pd.DataFrame) -> tuple[str, str]:
    text = df[["time", *inputs]].to_csv(index=False, float_format="%.17g")
    done = subprocess.run([str(stream), "--flags"], input=text, capture_output=True, text=True)
    return done.stdout, done.stderr


def _judge(out: str, want: np.ndarray, targets: list[str], s: int) -> tuple[float, int, int]:
    got = pd.read_csv(io.StringIO(out))
    c = got[[f"C_{t[2:]}" for t in targets]].to_numpy(float)
    gap = np.abs(c - want).max(axis=1)
    flag = got["mon_not_in_code"].to_numpy() > 0
    flagged = np.maximum.accumulate(np.where(np.arange(len(flag)) >= s, flag, False))
    part = gap > TOL
    return float(gap.max()), int(part.sum()), int((part & ~flagged).sum())


def score(root: str, basesrc: str, *records: str) -> None:
    """The per-case lines (module doc) and the totals."""
    from bench_cmon92 import faulted_cell, made
    from bench_dep108 import _files

    from thermocomp.apps.deploy.export import exported_files
    from thermocomp.apps.deploy.export.pack import corrections
    from thermocomp.apps.deploy.export.served import ServedLead
    from thermocomp.apps.deploy.streaming import OutOfEnvelopeError

    base, made_by = Path(root).resolve(), _made_by()
    totals = {"BASE": [0, 0, 0.0], "TREE": [0, 0, 0.0]}   # cases parting, cases silent, max gap
    for record in records:
        for family in CELLS:
            made(base, record, family, made_by)
            deployed, ss, frame, lead, s, cid = faulted_cell(base, record, f"{family}-none")
            m = ss.monitor
            names = [ss.inputs[i] for i in m["inputs"]]
            targets = list(deployed.targets_)
            streams = {}
            for who, src in (("BASE", basesrc), ("TREE", None)):
                files = _files(deployed, src) if src else exported_files(deployed, "c")
                inputs = json.loads(files["compensator.json"])["inputs"]
                streams[who] = (_build(files, base / "c111" / record / family / who), inputs)
            served = ServedLead(deployed, frame, s - 1)
            listed = cases(names, list(m["predictable"]), s)
            healthy = frame.iloc[:s + 3 + AFTER + 1].copy()
            want = corrections(ss, served.stream(healthy))
            sane = [_judge(_run(*streams[w], healthy)[0], want, targets, s)[0] for w in streams]
            print(f"== {record} {family} {cid}: {len(frame)} rows ({lead} lead-in), onset {s}; "
                  f"{len(names)} monitored, min_active {m['min_active']}; {len(listed)} cases; healthy "
                  f"cut |C - served| BASE {sane[0]:.3g} TREE {sane[1]:.3g} um", flush=True)
            for spiker, other, rows, where, row in listed:
                df = frame.iloc[:s + rows + AFTER + 1].copy()
                df.iloc[s:s + rows, df.columns.get_loc(spiker)] += SPIKE_C
                df.iloc[row, df.columns.get_loc(other)] = np.nan
                try:
                    want = corrections(ss, served.stream(df))
                except OutOfEnvelopeError as err:
                    print(f"  {spiker} L{rows} {other} {where}: served refused ({err})")
                    continue
                line, outs = [], {}
                for who, (stream, inputs) in streams.items():
                    outs[who], err = _run(stream, inputs, df)
                    worst, parted, silent = _judge(outs[who], want, targets, s)
                    said = [x for x in err.splitlines() if "not in the code" in x][:1]
                    line.append(f"{who} {worst:.2g} um {parted} rows > tol, {silent} silent"
                                + (f" [{said[0][:90]}]" if said else ""))
                    t = totals[who]
                    t[0] += parted > 0
                    t[1] += silent > 0
                    t[2] = max(t[2], worst)
                print(f"  {spiker} L{rows} {other} {where} (row {row}): " + "; ".join(line)
                      + f"; stdout identical {outs['BASE'] == outs['TREE']}", flush=True)
    for who, (parting, silent, worst) in totals.items():
        print(f"{who}: cases parting {parting}, silent {silent}; max |C - served| {worst:.3g} um")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
