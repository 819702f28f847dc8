"""Why the ST's held JUMPs are off the C where the C holds another sensor out: traced (st106, issue 34).

st105 (bench_st105.py, KEPT) made the block hold the C's JUMPs past its judgement's pause / stop;
its "A" events (the C holds another sensor out beside the jumped one) stayed 0.18 .. 2.0 um off
the C on the hold rows (seen 10, fresh 8).  The brief read it as the C rebuilding the sensor it
takes out with its POD, an arithmetic the ST could copy (the operators are export constants).

TRACE (898240b4's src; the records as st105 made them at 4b70457f, copied; bench_st103b.windows
with bench_st105's MADE_BY: seen lr9985 dl9964 lr9964 lr9966 lr9967 dl9966 dl10007 lr10007 lr10008,
st105's fresh lr/dl 10013-10015 (scored there, seen here), st105b's dl9975 (made alike); 2026-12-07, 2 cores
shared, CPU user + sys of each command as it prints it):

* ``oracle`` (seen 101.2 s, st105's fresh 69.0 s): a scratch copy of the block whose model reads,
  on each row, the C's own read (statespace.Simulator's ``watch.step``) of every sensor the C holds
  out and the block does not hold, and sums the C's served law set (8 ST lines before the FIR).
  The 18 events where the C holds another sensor out beside the JUMP (seen 10, st105's fresh 8):
  hold rows block 0.18 .. 2.0 um, oracle <= 8.2e-14; after rows block <= 5.1, oracle <= 8.5e-14;
  the row before the JUMP block 0.0022 .. 4.7, oracle <= 5.7e-14.  fresh dl10014 T_spindle_front
  (st105's "not traced", the C's other out let back on the JUMP's row): 1.6 -> 4.3e-14.  So the
  whole gap is that one input; the block's own hold of the jumped sensor is the C's already.
* ``timeline`` (seen 96.7 s, fresh 66.6 s): on all 18 that sensor is one the others predict
  (T_col_back 16, T_head_right, T_col_front_top) that the C takes out by ``DRIFT_OUT`` (its
  ``_lone_fault`` returns the z culprit, resolving) on the very row the block's ``mon_stop_row``
  names, 1 .. 41 rows before the JUMP; kept out to the window's end on 17 (lr10007 T_table: back
  3691, inside the hold).  The set served is the C's on those rows (that sensor has no fallback
  set; the jumped one's is served).  The two-out operator: held on 15, solved at run time (QR) on 3.
* The C's rebuild (watch_c ``mon_rebuilt`` / ``mon_errors``, watch.py ``_rebuilt``): one line for
  every sensor out that the others predict, ``pred[k] = sum_m mon_M[k][m] d[m]``, ``mon_M`` the
  operator of the C's out set (``mon_recompute`` -> ``mon_operator``: held for none, one out and a
  held pair, else solved by QR).  The jumped sensors here are ones no other predict: held at their
  last reading, not rebuilt.  The brief's second class, a second out beside a ``BLIND_OUT``
  (dl9975 T_col_back 6129; oracle 17.8 s, timeline 17.1 s): the second is one no other predicts
  too, held, not rebuilt; the block, holding T_table, does not hold it (block 7.3 um on the hold
  rows, oracle 3.6e-14): st105b's "two held at once", not the POD; so are dl9975's two JUMPs the
  block does not hold at 6170 (T_amb 2.3, T_col_back 4.8 um; oracle <= 3.6e-14).
* So the ST lacks the out set, not the arithmetic: from its ``mon_stop`` it cannot tell whether the
  C took a sensor out (lone fault), vetoed or declared a new state, nor when it lets it back.  That
  is st105b's item (REFUSED; its L1 failed on this very case, ``JUMP T_amb`` beside T_col_back),
  which this task was not to redo; a rebuild alone on the block's hold rows has no out set to read.

VERDICT TRACED (no src change; no bar; fresh 10054-10056 NOT drawn, unspent).  Holding these rows
to 1e-9 um needs, in the ST: the C's lone-fault choice (``_lone_fault``, ``_resolves`` with each
one-out operator, the veto count, ``_within_rounding`` / ``_hovers`` with the memory ``slow``),
the set's bands (mon86), the out sensor's re-admission (``_returning`` / ``_pass_once_back``, the
doubled wait, ``FOLLOWED``), then the rebuild over the one-out and two-out operators (QR or per-pair
constants).  Seen in passing, not traced: lr9985 T_head_right and lr9964 T_xdrive, the C serving a
``BLIND_OUT``'s set on 72 / 59 rows where the block serves the model's (lr9985: 1.2 um from 3712).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_st106.py oracle ROOT RECORD [RECORD ...]
    python benchmarks/bench_st106.py timeline ROOT RECORD [RECORD ...]

ROOT holds the records as bench_cmon92's ``made`` makes them (bench_st105's :data:`MADE_BY`).
``oracle``: per C JUMP of a window, the sensors out beside it and max|C - ST| on the row before,
the hold rows and the after rows, the block (the oracle block); rows where the C's served set is
not the block's.  ``timeline``: per window the rows where the C's out set changes or it names a
JUMP: its out set, rule, served set (C, block), the block's ``mon_stop_row``, the C's drift steps.
"""

from __future__ import annotations

import copy
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "shell"), str(HERE.parent / "tests")]
import bench_st102  # noqa: E402
import bench_st103b  # noqa: E402
import bench_st105  # noqa: E402
from _cli import run_commands  # noqa: E402

# the oracle: before the FIR, the C's reads of the inputs oracle_mask names, the C's served set
ORACLE = ("    IF oracle_on THEN\n        FOR j := 0 TO N_INPUTS - 1 DO\n"
          "            IF oracle_mask[j] THEN\n                uu[j] := oracle_uu[j];\n"
          "            END_IF;\n        END_FOR;\n        serving := oracle_set;\n    END_IF;\n")
FIR = "    (* causal FIR denoiser: newest raw sample first *)\n"


def oracle_block(deployed) -> str:
    """``deployed``'s block with :data:`ORACLE` before its FIR and its inputs declared."""
    from thermocomp.apps.deploy.export import exported_files

    st = exported_files(deployed, "st")["compensator.st"]
    assert st.count(FIR) == 1
    n = int(next(x for x in st.splitlines() if "N_INPUTS : INT" in x).split(":= ")[1].rstrip(";"))
    head, body = st.replace(FIR, ORACLE + FIR).split("END_VAR\nVAR CONSTANT", 1)
    return (head + f"    oracle_on : BOOL;\n    oracle_set : INT;\n    oracle_mask : ARRAY[0..{n - 1}] OF "
            f"BOOL;\n    oracle_uu : ARRAY[0..{n - 1}] OF LREAL;\n" + "END_VAR\nVAR CONSTANT" + body)


def _stepped(kept, df, start: int, back: int) -> list[dict]:
    """The window's rows: the block (``kept.tree``), the oracle block (``kept.main``), the C."""
    sim, st, orc = kept.sim, kept.tree, kept.main
    idx, real, got = np.asarray(kept.ss.monitor["inputs"]), sim.watch.step, {}

    def read(u, first, dt, now=np.nan):
        got["v"] = real(u, first, dt, now)
        return got["v"]

    sim.watch.step = read
    part = df.iloc[start:back + 61]
    U, t = part[kept.ss.inputs].to_numpy(float), part["time"].to_numpy(float)
    rows = []
    for i in range(len(part)):
        a = st(U[i], t[i], False)
        got.clear()
        c = sim.step(U[i], t[i])
        gone, held = list(sim.watch.gone), {int(st.vars["mon_held"]), int(st.vars["mon_jheld"])}
        mask = np.zeros(len(kept.ss.inputs), bool)
        mask[[idx[g] for g in gone if g not in held]] = True
        v = orc.vars
        v["oracle_on"], v["oracle_set"] = bool(mask.any() and got), int(sim.serving)
        v["oracle_mask"][:] = mask
        v["oracle_uu"][:] = got.get("v", v["oracle_uu"])
        b = orc(U[i], t[i], False)
        rows.append({"st": a, "oracle": b, "c": c, "rule": (int(sim.watch.rule), int(sim.watch.sensor)),
                     "gone": gone, "sets": (int(sim.serving), int(st.vars["serving"]))})
    sim.watch.step = real
    return rows


def _gap(r, of: str) -> float:
    return float(np.max(np.abs(r["c"] - r[of])))


def _top(rows, of: str) -> str:
    return f"{max(_gap(r, of) for r in rows):.2g}" if rows else "-"


def _oracle_window(kept, names, sensor: str, frame, start: int) -> dict | None:
    from thermocomp.apps.deploy.export.watch import JUMP

    df, back = bench_st102.dropped(frame, sensor, start)
    if back + 61 >= len(df):
        return None
    rows, events = _stepped(copy.deepcopy(kept), df, start, back), []
    for n, r in enumerate(rows):
        rule, s = r["rule"]
        if rule != JUMP:
            continue
        ends = next((m for m in range(n + 1, len(rows)) if rows[m]["rule"][1] == s and rows[m]["rule"][0]),
                    len(rows))
        stop = next((m for m in range(ends + 1, len(rows)) if rows[m]["rule"] == (JUMP, s)), len(rows))
        hold, after, others = rows[n:ends], rows[ends:stop], [names[k] for k in r["gone"] if k != s]
        print(f"  window {sensor}: C JUMP {start + n} {names[s]}, out beside it {others or '-'}: row "
              f"before {_top(rows[n - 1:n], 'st')} (oracle {_top(rows[n - 1:n], 'oracle')}); hold rows "
              f"{len(hold)} {_top(hold, 'st')} ({_top(hold, 'oracle')}); after rows {len(after)} "
              f"{_top(after, 'st')} ({_top(after, 'oracle')}) um", flush=True)
        events.append({"beside": bool(others),
                       "hold": [max(_gap(x, k) for x in hold) for k in ("st", "oracle")],
                       "after": [max([_gap(x, k) for x in after], default=0.0) for k in ("st", "oracle")]})
    sets = sum(r["sets"][0] != r["sets"][1] for r in rows)
    print(f"  window {sensor}: rows whose C served set is not the block's {sets}", flush=True)
    return {"events": events, "sets": sets}


def oracle(root: str, *records: str) -> None:
    """The ``oracle`` lines and totals (module doc)."""
    wins = list(bench_st103b.windows(root, records, _oracle_window, bench_st105.MADE_BY, oracle_block))
    beside = [e for w in wins for e in w["events"] if e["beside"]]

    def top(key, i):
        return f"{max((e[key][i] for e in beside), default=0.0):.2g}"

    print(f"total: {len(wins)} windows; C JUMPs with another out {len(beside)}: hold rows block <= "
          f"{top('hold', 0)}, oracle <= {top('hold', 1)} um; after rows block <= {top('after', 0)}, "
          f"oracle <= {top('after', 1)} um; rows with another served set {sum(w['sets'] for w in wins)}",
          flush=True)


def _timeline_window(kept, names, sensor: str, frame, start: int) -> dict | None:
    from thermocomp.apps.deploy.export import watch
    from thermocomp.apps.deploy.export.watch import JUMP, RULES

    df, back = bench_st102.dropped(frame, sensor, start)
    if back + 61 >= len(df):
        return None
    k, said = copy.deepcopy(kept), []
    plain = {n: getattr(watch.CodeMonitor, n) for n in ("_lone_fault", "_exclude", "_readmit", "_solved")}

    def logged(name):
        def call(self, *args):
            got = plain[name](self, *args)
            said.append(f"{name}{tuple(int(a) if np.ndim(a) == 0 else '...' for a in args)} -> {got}"
                        if name != "_solved" else "_solved")
            return got
        return call

    for name in plain:
        setattr(watch.CodeMonitor, name, logged(name))
    try:
        sim, st, was = k.sim, k.tree, []
        part = df.iloc[start:back + 61]
        U, t = part[k.ss.inputs].to_numpy(float), part["time"].to_numpy(float)
        for i in range(len(part)):
            said.clear()
            a, c = st(U[i], t[i], False), sim.step(U[i], t[i])
            w, gone = sim.watch, list(sim.watch.gone)
            if gone != was or w.rule == JUMP:
                held = w._op_of(np.isin(np.arange(w.n), gone)) is not None
                who = names[w.sensor] if w.sensor >= 0 else "-"
                print(f"  window {sensor}: row {start + i} C out {[names[g] for g in gone]} "
                      f"({'held' if held else 'solved'} operator), {RULES[int(w.rule)] or '-'} {who}; "
                      f"served set C {sim.serving} block {int(st.vars['serving'])}; block mon_stop_row "
                      f"{int(st.vars['mon_stop_row'])}; |C - ST| {float(np.max(np.abs(c - a))):.2g} um; "
                      f"{'; '.join(said) or '-'}", flush=True)
            was = gone
    finally:
        for name, f in plain.items():
            setattr(watch.CodeMonitor, name, f)
    return {}


def timeline(root: str, *records: str) -> None:
    """The ``timeline`` lines (module doc)."""
    for _ in bench_st103b.windows(root, records, _timeline_window, bench_st105.MADE_BY, oracle_block):
        pass


def main(argv: list[str]) -> int:
    """The command ``argv`` names (module doc; none: the usage, status 2)."""
    return run_commands(__doc__, {"oracle": oracle, "timeline": timeline}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
