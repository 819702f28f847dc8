"""The Structured Text block's sensor-fault flag against the served monitor (st93, issue 34).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_st93.py trace ROOT RECORD
    python benchmarks/bench_st93.py fresh ROOT [RECORD ...]

(The block measured is the rule's: on a tree with ``benchmarks/st93_rule.patch`` applied; since
st93b, KEPT on fresh seeds by ``bench_st93b.py``, main's block is that rule.)

``trace``: the cell ``ROOT/reports/RECORD/mlr-none`` (its ``model.pkl``; ``ROOT/data/RECORD`` the
record, as bench_cmon92's ``made`` leaves them) deployed as ``export`` deploys it (bench_cmon91's
``deployed_cell``), its ST block (``FB_ThermoComp``, run by the tests' interpreter
``StructuredText``) and the served model stepped together from a reset over the fed rows of its
first test campaign (its lead-in, then the campaign), healthy; then from a quarter of the
campaign on, per monitored sensor and per kind, copies of both stepped over the next rows with a
fault planted on that sensor: ``spike`` (read :data:`SPIKE_C` high for :data:`ROWS` samples:
bench_cmon92's spike), ``freeze`` (held at its first planted reading for :data:`FREEZE_ROWS`:
bench_cmon92's freeze), ``dropout`` (no reading, NaN, for :data:`ROWS`) and ``range`` (reading its
range's limit past its training edge by the margin again, ``2 hi_lim - hi_c``, for :data:`ROWS`),
each :data:`AFTER` rows past the fault's end.  Per kind: ``served`` the served monitor's
exclusions of a detection kind (its reason ``jump`` / ``dropout`` / ``out of range``), ``hits``
those the block flagged at their row with the sensor and the rule of that kind (the C's codes:
``JUMP``, ``GLITCH``, ``DROPOUT``, ``OFF_RANGE``), ``misses`` the others, ``other`` the served
exclusions of other kinds (freeze, drift ...: not in the ST), ``false`` the block's flags at a row
with no served exclusion of the sensor flagged, on another sensor than the planted one or on it
outside the fault's rows and the row after them (a spike's return, a dropout's or a range's
first reading again, is a jump of the reading the block re-references: not false).  The healthy
run: the same counts, every flag false where the served monitor excluded nothing there; and the
block's corrections against the numpy mirror of the C (:class:`Simulator`) on the rows before the
mirror's first monitor event (``max |ST - C|``).

``fresh``: ``trace`` on fresh records (bench_cmon92's generators, bench_cmon91's lr / dl / cr /
lr / dl, seeds of :data:`FRESH`), each simulated and ``run model=mlr`` once under ``ROOT`` by
bench_cmon92's ``made``.

The bar (written and committed before any fresh record was simulated; seeds 9581-9585 never run
before)::

1. Healthy, every fresh record: 0 false flags, and ST = C mirror to 1e-6 µm before the mirror's
   first event.
2. Planted spike, dropout and range on every monitored sensor of every fresh record: misses 0
   (every served jump / dropout / out-of-range exclusion flagged by the block at its row, with the
   sensor and the rule) and false 0.
3. Freeze: reported, not scored for hits (the ST holds no POD; a frozen sensor is judged by the
   others' prediction of it), false 0 as in 2.
KEPT if 1-3 hold on all five.  Else REFUSED with the cases named (src as on main, the rule's diff
in benchmarks/st93_rule.patch), unless a miss is a served rule the block declares it does not
hold (said plainly, then TRACED).

Changed after the bar was committed (fe8745d8), both before any fresh record: the block's rule
that a jump back within its limit of the reference before it ends the fault (``SPIKE``, not
flagged; found on the seen lr9496, cmon92's spent seed: T_xdrive's one-sample spike, its return
flagged with no served event, a false flag).  After the fresh scoring, measurement only: the
``stepped`` column (the served exclusions whose reason is ``jump: self-prediction error stepped
...``, ``InstantFaults._check_stepped``, counted apart from ``served``; the first fresh run
counted them as jumps, and every miss it found was one of them: below).

Results (2026-12-05; 2 cores shared by 8 helpers; ``fresh /tmp/st93/fresh``: 30 s of this
process's CPU for the five, each record's simulation and ``run model=mlr`` a few seconds more).

Seen, lr9496 (before the fresh seeds, the SPIKE rule in): healthy 1 served jump, hit, 0 false,
ST = C to 1.2e-13 µm; spike 11 of 11 hit, dropout 14 / 14, range 14 / 14, freeze 0 served
jumps; false 0 everywhere.

Fresh 9581-9585, the first run (served ``jump`` of both kinds): healthy false 0 on all five,
ST = C before the C's first event to 9.9e-14 / 1.4e-13 / 1.4e-14 / 8.5e-14 / 1.1e-13 µm; misses
healthy 2 / 2 / 0 / 2 / 3 and spike 0 / 2 / 0 / 2 / 2, every one a served stepped-error
exclusion (the second run's ``stepped``); dropout, range: every served exclusion hit.
The second run (``stepped`` apart; the same models)::

    record  healthy: served hits misses stepped false   max|ST-C| µm
    lr9581           1      1    0      2       0       9.95e-14
    dl9582           2      2    0      2       0       1.35e-13
    cr9583           0      0    0      0       0       1.42e-14
    lr9584           1      1    0      2       0       8.53e-14
    dl9585           0      0    0      3       0       1.07e-13

    kind     (cases per record 14 / 14 / 12 / 14 / 14)
             served      hits        misses  stepped     other       false
    spike    13/12/12/11/11  = served    0   0/2/0/2/2   1/2/0/0/1   0
    dropout  14/14/12/14/14  = served    0   0           0           0
    range    14/14/12/14/14  = served    0   0           0           0
    freeze   0/14/0/0/0      = served    0   0           5/9/10/9/13 0

(dl9582's freeze: the reading's return after 60 held rows is a jump, served and flagged; the
freezes themselves, ``other``, are not in the ST.)

Verdict, by the bar as written: 1 and 3 hold; 2 holds for every served instant jump, dropout and
range (hits = served, false 0), but the served monitor's stepped self-prediction-error
exclusions (reason ``jump: ...``, the C's ``STEP_OUT``, judged by the POD) are 15 misses of the
first run (9 healthy, 6 spike) -- a served rule the block does not hold (its doc says the rules
judged by the others' prediction are not in the ST, the stepped error not named there before
the scoring): TRACED, src as on main, the rule (src, its test, docs) in
benchmarks/st93_rule.patch.  Next: the patch scored on new seeds with the bar restated before
scoring (the stepped-error exclusions outside the ST's rules, counted apart), or the stepped
error added to the ST (the full set's ``M`` row and the alarm band: exact only with every sensor
in; the ST tracks no sensor out).
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_cmon92  # noqa: E402
from _cli import run_commands  # noqa: E402
from bench_cmon91 import FRESH as CMON91_FRESH  # noqa: E402
from bench_cmon91 import deployed_cell  # noqa: E402

# bench_cmon91's generators (lr / dl / cr / lr / dl) on the seeds given, chosen before any was simulated
FRESH = {f"{record[:2]}{seed}": [f"seed={seed}" if w.startswith("seed=") else w for w in words]
         for (record, words), seed in zip(CMON91_FRESH.items(), range(9581, 9586))}
SPIKE_C = bench_cmon92.SPIKE_C
ROWS, FREEZE_ROWS, AFTER = bench_cmon92.SPIKE_ROWS, bench_cmon92.FREEZE_ROWS, bench_cmon92.AFTER
KINDS = ("spike", "dropout", "range", "freeze")
DETECTED = {"jump": ("JUMP", "GLITCH"), "dropout": ("DROPOUT",), "out of range": ("OFF_RANGE",)}


def planted(frame, start: int, sensor: str, kind: str, ss, k: int):
    """``frame``'s rows from ``start`` with ``sensor`` (monitored ``k``) faulted (module doc)."""
    m = ss.monitor
    rows = FREEZE_ROWS if kind == "freeze" else ROWS
    part = frame.iloc[start:start + rows + AFTER].copy()
    col = part.columns.get_loc(sensor)
    if kind == "spike":
        part.iloc[:rows, col] += SPIKE_C
    elif kind == "freeze":
        part.iloc[:rows, col] = part.iloc[0, col]
    elif kind == "dropout":
        part.iloc[:rows, col] = np.nan
    else:
        part.iloc[:rows, col] = 2.0 * m["hi_lim"][k] - m["hi_c"][k]
    return part, rows


class Stepped:
    """The served model and the ST block stepped together (rows from the states they are in)."""

    def __init__(self, deployed, ss, block: str):
        from test_export import StructuredText

        self.served, self.ss, self.fb = deployed, ss, StructuredText(block)
        self.names = [ss.inputs[i] for i in ss.monitor["inputs"]]
        self.first = True
        deployed.reset()

    def rows(self, part):
        """Per row ``(ST corrections, the block's flag (sensor, rule name) or None, the served
        exclusions [(sensor, reason's kind)])``."""
        from thermocomp.apps.deploy.export.watch import RULES

        served, fb = self.served, self.fb
        X, U = part[served.columns_].to_numpy(float), part[self.ss.inputs].to_numpy(float)
        t = part["time"].to_numpy(float)
        for i in range(len(part)):
            served._step(X[i], t[i])
            out = [(e["sensor"], _kind(e["reason"])) for e in served.last_events_
                   if e.get("sensor") and e["to"] == "excluded"]
            c = fb(U[i], t[i], self.first)
            self.first = False
            v = fb.vars
            flag = (self.names[int(v["mon_sensor"])], RULES[int(v["mon_rule"])]) if v["mon_flag"] else None
            yield c, flag, out


def _kind(reason: str) -> str:
    """A served exclusion's kind: its reason's head, ``stepped`` for the jump of a self-prediction
    error (``InstantFaults._check_stepped``: judged by the others' prediction, the POD, not in the
    ST; its reason also begins ``jump``)."""
    return "stepped" if "self-prediction error stepped" in reason else reason.split(":")[0]


def scored(rows, planted_sensor=None, fault_rows=0) -> dict:
    """The counts of the module doc over ``rows`` (``Stepped.rows``'s)."""
    tally = {"served": 0, "hits": 0, "misses": 0, "stepped": 0, "other": 0, "false": 0}
    cases = []
    for i, (_, flag, out) in enumerate(rows):
        for sensor, why in out:
            if why in DETECTED:
                tally["served"] += 1
                hit = flag is not None and flag[0] == sensor and flag[1] in DETECTED[why]
                tally["hits" if hit else "misses"] += 1
                if not hit:
                    cases.append(f"miss row {i + 1} {sensor} {why} (block {flag})")
            else:
                tally["stepped" if why == "stepped" else "other"] += 1
        if flag is not None and flag[0] not in [s for s, _ in out]:
            ours = flag[0] == planted_sensor and i <= fault_rows
            if not ours:
                tally["false"] += 1
                cases.append(f"false row {i + 1} {flag}")
    return tally, cases


def trace(root: str, record: str) -> None:
    """The ``trace`` table (module doc)."""
    from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
    from thermocomp.apps.deploy.export.pack import fed
    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.stages.export import lead_ins

    root = Path(root).resolve()
    model = root / "reports" / record / "mlr-none" / "model.pkl"
    deployed, ds, _, test_ids = deployed_cell(root, record, model)
    ss = state_space(deployed, monitor=True)
    block = exported_files(deployed, "st")["compensator.st"]
    cid = test_ids[0]
    frame = fed(ds.campaigns[cid], lead_ins(plain(deployed).compensator, ds, [cid]).get(cid))
    lead = len(frame) - len(ds.campaigns[cid])
    start = lead + (len(frame) - lead) // 4
    # healthy: the whole fed frame, and the block against the C's mirror before its first event
    whole = Stepped(copy.deepcopy(deployed), ss, block)
    rows = list(whole.rows(frame))
    tally, cases = scored(rows)
    sim = Simulator(ss)
    sim.reset()
    diff = 0.0
    for (c, *_), u, t in zip(rows, frame[ss.inputs].to_numpy(float), frame["time"]):
        want = sim.step(u, t)
        if sim.watch.flags:
            break
        diff = max(diff, float(np.max(np.abs(c - want))))
    print(f"{record} {cid}: {len(frame)} fed rows ({lead} lead-in), {len(whole.names)} monitored; "
          f"healthy {tally}, max |ST - C| before the C's first event {diff:.3g} µm "
          f"{'; '.join(cases)}", flush=True)
    base = Stepped(deployed, ss, block)
    for _ in base.rows(frame.iloc[:start]):
        pass
    print(f"{'kind':<9}{'cases':>6}" + "".join(f"{k:>8}" for k in tally), flush=True)
    for kind in KINDS:
        total = dict.fromkeys(tally, 0)
        said = []
        for k, sensor in enumerate(base.names):
            run = copy.deepcopy(base)
            part, rows_faulted = planted(frame, start, sensor, kind, ss, k)
            got, cases = scored(list(run.rows(part)), sensor, rows_faulted)
            for key in total:
                total[key] += got[key]
            said += [f"{sensor}: {c}" for c in cases]
        print(f"{kind:<9}{len(base.names):>6}" + "".join(f"{total[k]:>8}" for k in total), flush=True)
        for line in said:
            print(f"    {line}", flush=True)


def fresh(root: str, *chosen: str, records: dict | None = None, traced=None) -> None:
    """The ``fresh`` tables (module doc); ``records`` / ``traced`` (bench_st94): other generators
    and another ``trace`` (default :data:`FRESH`, :func:`trace`)."""
    records, traced = records or FRESH, traced or trace
    bench_cmon92.FRESH.update(records)       # its made() simulates and runs the records it names
    for record in [r for r in records if r in chosen] or list(records):
        bench_cmon92.made(Path(root).resolve(), record, "mlr")
        print(f"== {record}", flush=True)
        traced(root, record)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "fresh": fresh}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
