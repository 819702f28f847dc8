"""A repeated row (same time, same values) is skipped, not judged as ten freezes: the served model,
the exported C (its numpy mirror) and the Structured Text alike (issue 34; stop 99, dup99;
audit98's finding 1).

audit98 (``bench_audit98.py faults ROOT pt9851 cold``, the ``repeat`` line): a logger re-sending
its last sample 30 times (same time stamp, same values).  The served stream takes each row as a
new sample one period on (the time rule: a time not after the last read is a missing one); the
monitor sees ten sensors not moving while the field it predicts moves on, and at the 12th row
excludes all ten ("freeze: ... for 12 samples") and holds its correction; the C flags FREEZE
``T_col_L``, then SECOND on every row: C - served 2.61 µm (16d3b58d), and the lag memory moves
as if the machine had stood still for 30 periods.

What the batch does with such rows (docs/data-format.md, the contract): a time that repeats is
refused, exit 2, "duplicate time ... (same as row N): two samples at one time; delete the row
written twice, or give it its own time" (``core/io/values.py``).  What was scored is therefore
the record with the repeated rows deleted; the served stream agrees with it only by skipping
them.

TRACE (seen, 4fafc59a's src; ``python benchmarks/bench_dup99.py repeats ROOT pt9851`` and
/tmp/dup99/identical.py).  pt9851 (portal64, W3 the test campaign, read as a restart since
restart98: no lead-in), the fault row 2520 repeated n times: n = 5, nothing (the MLR is
static, the monitor's freeze needs 12 samples); n = 12, 20 served sensor events (T_bed, T_col_L,
T_col_R, T_hall, T_motor, T_rail), 3 mirror flagged rows, max|C - served| 4.77 µm, |served -
healthy| 3.13 µm; n = 30, the same events, 20 flagged rows, 6.69 / 6.69 µm; n = 40, 30 flagged
rows, 6.69 / 6.69 µm; equal to healthy again 10 rows after each burst; the replay path
(``run_rows``) = the served steps to 3.4e-13 µm.  ``retime``: nothing (0 events, = healthy).  Identical
consecutive rows (every temperature equal) in the seen records, with or without their time:
fl_thermal 0 of 11115 (all 16 temperatures change on every row), pt9851 0 of 30240 (at least 4
of 10 change), cr9763 0 of 1725, lr9376 0 of 4321, sw9776 0 of 6242; time not after the last
with equal inputs: 0 everywhere (the contract refuses it).

RULE (``core/timerule.py`` ``repeats`` / ``C_REPEAT_RULE`` / ``ST_REPEAT_RULE``; the adaptive
compensator's ``_step`` and ``run_rows``, the Simulator, ``tc_step``, the ST block).  A sample
whose time is finite and not after the last time read, and whose inputs are every one measured
and equal to those of the last sample the stream stepped on in this campaign, is no new sample:
skipped before the time rule, the monitor, the model and the guard (nothing remembered changes),
the last corrections given again, counted (served ``n_repeated_``, one event ``time ->
repeated`` at a burst's first row; the C's ``n_repeated`` and ``repeated``; the ST's
``repeated`` output).  Exported where the deployed object is the adaptive compensator
(``skip_repeats`` in compensator.json; a plain stream, ``monitor.adaptive=false``, has no
monitor to misjudge it and steps it as before, one period on, in every form).  A repeated time
with OTHER values is a sample (the time rule: one period on), as before.  A stream without a
time cannot tell a re-sent row from a machine standing still, and ``run`` scores every row of a
file without a time column as a sample one period on: such rows are not skipped (none in the
seen records, above).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dup99.py repeats ROOT RECORD [RECORD ...]   # R1 / R3
    python benchmarks/bench_dup99.py healthy ROOT RECORD [RECORD ...]   # R2 (fl: fl_thermal)

``repeats``: per record (:data:`SEEN` or :data:`FRESH`, simulated into ``ROOT/data`` and ``run
model=mlr`` into ``ROOT/reports`` by this tree, each once; bench_cmon92's ``made`` /
``faulted_cell``: the first test campaign after its lead-in, the fault row a quarter in), the
served model (``_step``, as ``serve``) and the C's numpy mirror stepped together over the
healthy frame, then per burst of :data:`BURSTS` the fault row written that many times (time and
values), then the :data:`AFTER` rows after it; and ``retime`` (the row after the fault row
stamped with the fault row's time: a repeated time, other values).  Per case: the served
sensor events (a sensor other than ``time``), the mirror's flagged rows, max|C - served| (µm),
max|served - healthy| (the burst's rows against the healthy fault row, the rows after against
the same rows), the replay path (``run_rows``) against the served steps, the repeats counted.
``healthy``: per record the healthy frame's served corrections and events and the mirror's
(a sha1 of the bytes; fl: tests/conftest.py's fl_thermal_served) and its count of repeated rows.

Records.  SEEN (traced on, spent): pt9851 (audit98), cr9763, lr9376, sw9776 (bench_mon98's
seen).  FRESH (never simulated before this bench's bar): pt9879 (portal64), tr9880 (trunnion63),
cr9881 (the climate room of bench_mon97).

BAR (written and committed BEFORE any of 9879-9881 is simulated; scored once, on main =
4fafc59a's src and on this branch's rule, each tree in its own ROOT)
---
R1. repeat bursts (each fresh record x 5 / 12 / 30 / 40 rows): 0 served sensor events and 0
    mirror flagged rows over the burst and the rows after it (the healthy frame has none there);
    max|C - served| <= 1e-9 µm on every row; |served - healthy| <= 1e-9 µm on every row (a skipped
    row changes nothing); the replay path = the served steps <= 1e-9 µm; served and mirror count
    n - 1 repeated rows.  The compiled C and the ST = the mirror on a burst (the tests).
R2. healthy frames (pt9851, cr9763, lr9376, sw9776, fl_thermal): served corrections, events and
    the mirror's corrections bit for bit as main's (the digests equal), 0 repeated rows counted.
R3. fresh scored once (R1 and R2's healthy line on each fresh record), main -> rule.
Reported beside the bar: ``retime`` (a repeated time, other values), main -> rule.
KEPT if R1-R3 hold; else REFUSED (benchmarks/dup99_rule.patch, src as on 4fafc59a).

Status: the bar above was committed in 4666594a before any of 9879-9881 was simulated; unchanged.
After it: the rule (5665c093) and one function for a case's line (ec6956ef: the same text, checked
on pt9851 before the fresh run).  Fresh scored once on ec6956ef, main's tree first (4fafc59a's src,
``git archive``), each tree its own ROOT.

Seen (pt9851; main -> rule): burst 12 / 30 / 40: served sensor events 20 / 20 / 20 -> 0, mirror
flagged rows 3 / 20 / 30 -> 0, max|C - served| 4.77 / 6.69 / 6.69 -> 0 µm, |served - healthy|
3.13 / 6.69 / 6.69 -> 0 µm; burst 5: 0 on both; repeats counted 4 / 11 / 29 / 39 (served = C);
replay - served 3.4e-13 µm on both.  R2 healthy digests equal line for line (pt9851, cr9763,
lr9376 with its own 6 events / 35 flagged rows, sw9776, fl_thermal), 0 repeats counted.

Scored (2026-12-06 11:47-12:13 UTC, 2 cores shared by up to 8 helpers, load 10-14, ``nice``;
main -> rule; bursts 5 / 12 / 30 / 40; burst 5 is 0 on both everywhere)::

  record  burst  served sensor events  mirror flagged rows  max|C - served| µm  |served - healthy| µm
  pt9879  12     24 -> 0               6 -> 0               104 -> 0            96.2 -> 0
          30/40  20 -> 0               21/31 -> 0           2.7e-13 -> 0        5.96 -> 0
  tr9880  12     18 -> 0               4 -> 0               5.28 -> 0           4.58 -> 0
          30/40  18 -> 0               21/31 -> 0           0.319 -> 0          0.85 -> 0
  cr9881  12     24 -> 0               4 -> 0               0.739 -> 0          1.54 -> 0
          30/40  24 -> 0               21/31 -> 0           1.36 -> 0           1.36 -> 0

Every case equal to healthy again 10 rows after the burst on main too (the MLR is static: what
parts is the monitor's exclusion over the burst).  Rule: repeats counted 4 / 11 / 29 / 39, served
= mirror, on every record; the replay path (``run_rows``) = the served steps to 4.8e-13 /
5.7e-14 / 5.3e-15 µm on both trees.  ``retime`` (a repeated time, other values): 0 events, 0
flags, C = served = healthy on both trees (the time rule takes it one period on, where it was).
R2 on the fresh healthy frames: served, events and mirror digests equal main -> rule (pt9879
18bedd1f, tr9880 d4e383ff, cr9881 67abbf37), 0 events, 0 repeats counted.  The compiled C and the
ST (with the monitor) = the record without the copies to 1e-9 µm on a lag bank's burst:
tests/shell/test_repeat99.py (7.74 µm in every form on 4fafc59a).  CPU of the bench process
(simulate / run subprocesses not counted): repeats 28.9 -> 29.4 s, healthy 16.2 -> 16.6 s.

VERDICT: KEPT (R1-R3 hold).  Left alone: a plain stream (``monitor.adaptive=false``) steps a row
written again one period on in every form, as before (no monitor to misjudge it; a lag bank's
lags move: the test's 'plain' case); a stream without a time steps it too (``run`` scores every
row of such a file); a reference measurement on a row written again is still taken, by the
served ``adapt`` and by ``tc_reference`` after the skipped sample (not measured here).
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit97 import TRUNNION  # noqa: E402
from bench_audit98 import FAULTED, PORTAL  # noqa: E402
from bench_mon97 import CR  # noqa: E402
from bench_mon97 import SEEN as MON97  # noqa: E402

SEEN = {**FAULTED, **MON97}
FRESH = {"pt9879": [*PORTAL, "seed=9879"], "tr9880": [*TRUNNION[1:], "seed=9880"],
         "cr9881": [*CR, "seed=9881"]}
TARGETS = {"pt": "portal64.", "tr": TRUNNION[0].split("=", 1)[1]}
BURSTS = (5, 12, 30, 40)
AFTER = 120
TIME = "time"


def _targets_env(record: str) -> None:
    if record[:2] in TARGETS:
        os.environ["THERMOCOMP_TARGETS"] = TARGETS[record[:2]]
    else:
        os.environ.pop("THERMOCOMP_TARGETS", None)


def _cell(root: Path, record: str):
    """``(deployed, state space, frame, fault row)`` of ``record`` (module doc)."""
    from bench_cmon92 import faulted_cell, made

    _targets_env(record)
    made(root, record, "mlr", {**SEEN, **FRESH})
    deployed, ss, frame, _, start, _ = faulted_cell(root, record, "mlr-none")
    return deployed, ss, frame, start


def _stepped(deployed, ss, frame) -> dict:
    """The served model and the mirror over ``frame`` (bench_cmon92's ``Stepped``): per row the
    served correction, the mirror's, the served sensor events, the mirror's flags; the repeats
    each counted."""
    from bench_cmon92 import Stepped

    run = Stepped(deployed, ss)
    out: dict = {"served": [], "c": [], "events": [], "flags": []}
    for c, want, flags, *_ in run.rows(frame):
        out["served"].append(want)
        out["c"].append(c)
        out["events"].append([e for e in deployed.last_events_ if e.get("sensor") != TIME])
        out["flags"].append(int(flags))
    out = {k: np.array(v) if k != "events" else v for k, v in out.items()}
    out["n_served"] = getattr(deployed, "n_repeated_", None)
    out["n_c"] = getattr(run.sim, "n_repeated", None)
    return out


def _replayed(deployed, ss, frame) -> np.ndarray:
    """The replay path's corrections (``run_rows``, a reset first; ``ss``: the state space, for
    the served's sign)."""
    from thermocomp.apps.deploy.export.pack import corrections

    deployed.reset()
    y, _ = deployed.run_rows(frame[deployed.columns_].to_numpy(float), frame[TIME].to_numpy(float))
    return corrections(ss, y)


def burst(frame: pd.DataFrame, start: int, n: int) -> pd.DataFrame:
    """``frame`` to the fault row, that row ``n`` times (time and values), the :data:`AFTER`
    rows after it."""
    return pd.concat([frame.iloc[:start], frame.iloc[[start] * n],
                      frame.iloc[start + 1:start + 1 + AFTER]], ignore_index=True)


def retimed(frame: pd.DataFrame, start: int) -> pd.DataFrame:
    """``frame`` to the fault row and :data:`AFTER` rows after it, the row after the fault row
    stamped with the fault row's time (a repeated time, other values)."""
    part = frame.iloc[:start + 1 + AFTER].copy().reset_index(drop=True)
    part.loc[start + 1, TIME] = part.loc[start, TIME]
    return part


def _case(deployed, ss, part: pd.DataFrame, expected: np.ndarray, start: int, after: int | None
          ) -> str:
    """A case's line (module doc) from the fault row ``start`` (``expected``: the healthy
    correction each row should give; ``after``: the first row 10 after a burst, None: no burst)."""
    got = _stepped(deployed, ss, part)
    replay = _replayed(deployed, ss, part)
    events = got["events"][start:]
    named = sorted({e.get("sensor") or e.get("reason", "")[:30] for r in events for e in r})
    off = np.abs(got["served"] - expected)
    return (f"served sensor events {sum(map(len, events))}"
            f"{f' {named[:6]}' if after is not None else ''}; mirror flagged rows "
            f"{int((got['flags'][start:] != 0).sum())}; max|C - served| "
            f"{np.abs(got['c'] - got['served']).max():.3g} µm; |served - healthy| {off.max():.3g} µm"
            + (f", from 10 rows after the burst {off[after:].max():.3g} µm" if after is not None
               else "")
            + f"; replay - served {np.abs(replay - got['served']).max():.3g} µm"
            + (f"; repeats counted served {got['n_served']} C {got['n_c']}" if after is not None
               else ""))


def repeats(root: str, *records: str) -> None:
    """The ``repeats`` lines (module doc)."""
    base = Path(root).resolve()
    for record in records:
        deployed, ss, frame, start = _cell(base, record)
        frame = frame.iloc[:start + 1 + AFTER].reset_index(drop=True)
        healthy = _stepped(deployed, ss, frame)
        print(f"{record} mlr: {len(frame)} rows fed, fault row {start}; healthy: served sensor "
              f"events {sum(map(len, healthy['events']))}, mirror flagged rows "
              f"{int((healthy['flags'] != 0).sum())}, max|C - served| "
              f"{np.abs(healthy['c'] - healthy['served']).max():.3g} µm", flush=True)
        want = healthy["served"]
        for n in BURSTS:
            # the healthy correction each row should give: the fault row's over the burst
            expected = np.vstack([want[:start], want[[start] * n], want[start + 1:]])
            print(f"  burst {n:>2}: "
                  f"{_case(deployed, ss, burst(frame, start, n), expected, start, start + n + 10)}",
                  flush=True)
        print(f"  retime  : {_case(deployed, ss, retimed(frame, start), want, start, None)}",
              flush=True)


def _digest(*arrays) -> str:
    h = hashlib.sha1()
    for a in arrays:
        h.update(a if isinstance(a, bytes) else np.ascontiguousarray(a, dtype=float).tobytes())
    return h.hexdigest()[:16]


def healthy(root: str, *records: str) -> None:
    """The ``healthy`` lines (module doc)."""
    base = Path(root).resolve()
    for record in records:
        if record == "fl":
            sys.path[:0] = [str(HERE.parent / "tests"), str(HERE.parent / "tests" / "shell")]
            from conftest import fl_thermal_served

            os.environ.pop("THERMOCOMP_TARGETS", None)
            deployed, ss, frame = fl_thermal_served()
        else:
            deployed, ss, frame, _ = _cell(base, record)
        got = _stepped(deployed, ss, frame)
        events = json.dumps(got["events"], sort_keys=True, default=str).encode()
        print(f"{record}: {len(frame)} rows; served {_digest(got['served'])} events "
              f"{sum(map(len, got['events']))} {_digest(events)}; mirror {_digest(got['c'])} "
              f"flagged rows {int((got['flags'] != 0).sum())}; max|C - served| "
              f"{np.abs(got['c'] - got['served']).max():.3g} µm; repeats counted served "
              f"{got['n_served']} C {got['n_c']}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"repeats": repeats, "healthy": healthy}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
