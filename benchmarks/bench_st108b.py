"""The ST names every row after its stop where it may differ from the C (st108b, issue 34).

st108 (TRACED, bench_st108.py) found that after the block's own ``mon_stop`` the C may take sensors
out by ``DRIFT_OUT`` (with a partner), ``BLIND_OUT`` or ``STEP_OUT`` and rebuild them, where the
stopped block reads them as measured: dl10127 / dl10178 (fault windows, 3.9 .. 20 um) and the
healthy dl9965 (20 rows, 1.24 um, none flagged) and dl9967 (33 rows, 3.17 um, 1 flagged); lr9965
stops too and the C takes nothing out after.  The lead's decision: flags on rows where the block
really differs from the C are wanted; flags where it equals the C are the cost, kept small.

BAR (committed before the rule is scored and before fresh lr/dl 10189-10191 are made; fresh scored
once).  Tree = this branch's block, BASE = 4f56cd99's (its src ``git archive``d, the same bench run
with it on ``PYTHONPATH``), the C beside.  A row is *flagged* where ``mon_flag`` or the rule's new
output is TRUE; *differs* where max|C - ST| > 1e-9 um.

* B1 every differing row flagged: on ``window`` dl10127 T_amb, dl10178 T_amb, dl10178 T_col_back
  (st108's; bench_st103b's window, the whole window), ``stream`` dl9965 and dl9967 (the healthy
  stream whole) and the fresh ones' streams.
* B2 on the 8 healthy streams (bench_st105's lr/dl 9964-9967, no fault added): rows flagged and not
  differing <= 2 % of all their rows (count said, BASE's beside).
* B3 the rule only flags: on every row scored, c and (``mon_flag``, ``mon_rule``, ``mon_sensor``)
  byte-identical to BASE's (so no event of bench_st107's seen / fresh sets moves off the C or loses
  a flag: the rule writes its own output only, read by nothing else in the block).
* B4 the ST modules pass, ``PARSED_DIGEST`` re-asked (blark parses the block); a test (<= ~3 s CPU,
  test_export_st100's fixtures) that fails on BASE; docs/monitoring.md's ST section says it.
* Fresh lr/dl 10189-10191 (bench_st102b's words, seeds +225, made by bench_cmon92's ``made``),
  their healthy streams: B1, B2's count (<= 2 % of their rows) and B3; scored once, after this bar.
* KEPT where B1-B4 hold on seen and fresh; else REFUSED (src reverted, benchmarks/st108b_rule.patch).

RULE (st_watch.py, ``mon_unsure``; no key, no constant): TRUE while the block holds a ``STEP_OUT``
(the C rebuilds it); and, from the block's ``mon_stop`` or ``mon_lost``, on each row it flags or
where a judged sensor's error with every sensor in (``mon_e``) is at its warning band
(``MON_WARN``), and ``2 MON_WINDOW`` rows after.  Not st106c's (which named the C's DRIFT_OUT and
held one row): it tells nothing of the C's choice, it bounds where the C may act.  Built on seen
dl9965 / dl9967 / lr9964 (the STEP_OUT hold and a JUMP's 2 rows after were seen there).

MEASURED (2026-12-07, 2 cores shared, load 1-4; rule = ebb0bb1e's src, BAR e8e6ed03, unchanged;
BASE 4f56cd99 (``git archive`` src); records: st108's root copied (data and reports, made by
3a560e8f's src), fresh made here after ebb0bb1e (10.4 s); CPU user + sys as /usr/bin/time prints it).
VERDICT KEPT: B1-B4 met on seen and fresh.

* B1 seen: windows dl10127 T_amb 50 differing rows (max 4.41 um), dl10178 T_amb 50 (19.9 um),
  dl10178 T_col_back 104 (31 um): unflagged BASE 50 / 50 / 103 -> 0 / 0 / 0 (13.1 + 15.4 s);
  streams dl9965 31 rows (2.72 um: a STEP_OUT hold at 4113 and the DRIFT_OUT after the stop 5696)
  BASE 30 -> 0 unflagged, dl9967 33 (3.17 um) BASE 32 -> 0.  The other 6 healthy streams too:
  BASE 13 / 13 / 21 / 20 / 20 / 0 -> 0 (healthy 8: 42.1 + 40.1 s; BASE 74.5 s for all 8).
* B2 healthy 8 (46084 rows): flagged and not differing 131 rows (0.28 %; BASE 3): lr9964 19,
  dl9964 19, lr9966 18, dl9966 18, dl9965 2, dl9967 34, lr9965 21 (its stop, the C takes nothing
  out), lr9967 0.
* B3 ``same``: 0 c rows and 0 (flag, rule, sensor) rows differing from BASE on the 3 windows and 8
  streams (and fresh 6).
* Fresh lr/dl 10189-10191 (scored once; tree 28.2 + 34.3 s, BASE 25.9 + 29.2 s): differing rows 21 /
  32 / 23 / 23 / 3 / 3 (max 4.67 um), unflagged BASE 19 / 29 / 21 / 21 / 1 / 1 -> 0 on all; flagged
  and not differing 12 / 12 / 0 / 0 / 39 / 40 = 103 of 34563 rows (0.30 %; BASE 4); B3 0 / 0.
* B4: PARSED_DIGEST b4860421... (blark parsed the block: the 3 parse tests failed on the old digest
  only, 200 s wall); test_export_st97d's new case fails on 4f56cd99 (unflagged rows after the stop)
  and costs no measurable CPU (it reads the module's resumed pass; the module without / with it,
  paired, 2 reps: 5.31 / 4.93 -> 4.94 / 4.90 s); the ST modules: see the report (st108b.md).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st108b.py window ROOT OUT RECORD SENSOR [SENSOR ...]
    python benchmarks/bench_st108b.py stream ROOT OUT RECORD [RECORD ...]
    python benchmarks/bench_st108b.py same OUT_A OUT_B
    python benchmarks/bench_st108b.py make ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (:data:`MADE_BY`); OUT gets per run
the rows' c, flags, rule and sensor (``.npz``) and ``same`` compares two OUTs run by run (B3).
``window`` / ``stream`` print per run: rows, differing rows, of them unflagged, flagged and not
differing (all flags / the new output only), the block's ``mon_stop_row``.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st102  # noqa: E402
import bench_st102b  # noqa: E402
import bench_st103b  # noqa: E402
import bench_st107  # noqa: E402
import bench_st107c  # noqa: E402,F401  (its fresh records in bench_st107.MADE_BY)
from _cli import run_commands  # noqa: E402

TOL = 1e-9
NEW = "mon_unsure"     # the rule's output (absent on BASE: read FALSE)


def _fresh() -> dict:
    """bench_st102b's :data:`FRESH` words on seeds 10189-10191 (named before any was simulated)."""
    return {f"{r[:2]}{int(r[2:]) + 225}": [f"seed={int(w[5:]) + 225}" if w.startswith("seed=") else w
                                           for w in words]
            for r, words in bench_st102b.FRESH.items() if int(r[2:]) <= 9966}


FRESH = _fresh()     # lr10189, dl10189, ..., lr10191, dl10191
MADE_BY = {**bench_st107.MADE_BY, **FRESH}


def _cell(root: str, record: str):
    return bench_st103b._cell(root, record, MADE_BY, lambda _: "    N_LAWS : INT := 0;")


def _run(st, sim, ss, part, first: bool) -> dict:
    """Per row of ``part``: the block's c, flags, rule, sensor, new output; the C's c."""
    from test_export import StructuredText  # noqa: F401  (the block's interpreter)

    U, t = part[ss.inputs].to_numpy(float), part["time"].to_numpy(float)
    got = {k: [] for k in ("st", "c", "flag", "rule", "sensor", "new", "stop")}
    for i in range(len(part)):
        a, c = st(U[i], t[i], first and i == 0), sim.step(U[i], t[i])
        v = st.vars
        for key, x in (("st", np.array(a, float)), ("c", np.array(c, float)), ("flag", bool(v["mon_flag"])),
                       ("rule", int(v["mon_rule"])), ("sensor", int(v["mon_sensor"])),
                       ("new", bool(v.get(NEW, False))), ("stop", int(v["mon_stop_row"]))):
            got[key].append(x)
    return {k: np.array(x) for k, x in got.items()}


def _said(label: str, got: dict, out: str) -> None:
    gap = np.max(np.abs(got["c"] - got["st"]), axis=1)
    differ, flagged = gap > TOL, got["flag"] | got["new"]
    np.savez(Path(out) / f"{label}.npz", **got)
    print(f"  {label}: {len(gap)} rows; differing {int(differ.sum())} (max {gap.max():.3g} um), unflagged "
          f"{int((differ & ~flagged).sum())}; flagged not differing {int((flagged & ~differ).sum())} "
          f"(new output {int((got['new'] & ~differ).sum())}, new rows {int(got['new'].sum())}); "
          f"stop_row {int(got['stop'].max())}", flush=True)


def window(root: str, out: str, record: str, *sensors: str) -> None:
    """The ``window`` lines (module doc): the lead-in, then each sensor's window from it."""
    from test_export import StructuredText
    from thermocomp.apps.deploy.export import Simulator

    Path(out).mkdir(parents=True, exist_ok=True)
    _, ss, frame, start, names, tree, _ = _cell(root, record)
    st, sim = StructuredText(tree), Simulator(ss)
    sim.reset()
    _run(st, sim, ss, frame.iloc[:start], True)
    for sensor in sensors:
        df, back = bench_st102.dropped(frame, sensor, start)
        _said(f"{record}_{sensor}", _run(copy.deepcopy(st), copy.deepcopy(sim), ss,
                                         df.iloc[start:back + 61], False), out)


def stream(root: str, out: str, *records: str) -> None:
    """The ``stream`` lines (module doc): each record's stream whole, no fault added."""
    from test_export import StructuredText
    from thermocomp.apps.deploy.export import Simulator

    Path(out).mkdir(parents=True, exist_ok=True)
    for record in records:
        _, ss, frame, _, _, tree, _ = _cell(root, record)
        st, sim = StructuredText(tree), Simulator(ss)
        sim.reset()
        _said(record, _run(st, sim, ss, frame, True), out)


def same(a: str, b: str) -> None:
    """B3: per run in both OUTs, rows whose c or (flag, rule, sensor) differ."""
    for f in sorted(Path(a).glob("*.npz")):
        g = Path(b) / f.name
        if not g.exists():
            continue
        x, y = np.load(f), np.load(g)
        c = int(np.any(x["st"] != y["st"], axis=1).sum())
        said = int(((x["flag"] != y["flag"]) | (x["rule"] != y["rule"]) | (x["sensor"] != y["sensor"])).sum())
        print(f"  {f.stem}: {len(x['st'])} rows, c rows differing {c}, (flag, rule, sensor) rows "
              f"differing {said}", flush=True)


def make(root: str, *records: str) -> None:
    """The records, as bench_cmon92's ``made`` (model mlr)."""
    from bench_cmon92 import made

    for record in records:
        made(Path(root).resolve(), record, "mlr", MADE_BY)
        print("made", record, flush=True)


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"window": window, "stream": stream, "same": same, "make": make}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
