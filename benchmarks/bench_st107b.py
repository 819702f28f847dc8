"""The ST block 9.87 um off replay where the monitor takes out the air sensor (st107b, issue 34).

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_st107b.py room DATA                      # diag107's climate room (bench_diag107b)
    python benchmarks/bench_st107b.py plain ROOT DATA                # run model=mlr, export c and st
    python benchmarks/bench_st107b.py score ROOT DATA COLUMN PUSH MODE  # C - replay, ST - C per row
    python benchmarks/bench_st107b.py simulate DATA SEED KIND       # a fresh climate room (KIND room / lag)
    python benchmarks/bench_st107b.py paired BASE RULE COLUMN PUSH MODE  # two roots' scores, row by row

diag107b (KEPT, bench_diag107b.py's docstring) saw on diag107's climate room that pushing the air
sensor ``T_amb`` +30 degC from half-way made the ST differ from replay by 12.5 um (the diagnosed
``ambient_scaled`` model) and 9.87 um (a plain MLR), the C = replay to 7.1e-15.  This bench
reproduces it with a plain MLR, no diagnose (``plain``: ``thermocomp run model=mlr``, then
``export`` to ``c`` and ``st`` into ROOT/code; a ROOT ``bench_diag107b.py chain`` left works too),
and tells, row by row over the test campaigns, where the ST parts from the C and what the block
said there.  ``score``: COLUMN changed from half-way (MODE ``step``: +PUSH; ``ramp``: 0 -> PUSH
linearly; ``all``: +PUSH on every row, the campaign's first sample too); ``replay`` of the model
deployed as ``export`` deploys it (its monitor), ``stream --flags`` of the C (cc -O2), the ST
through the tests' transpiler (test_export's ``StructuredText``).  Printed: max |C - replay|, max
|ST - C|, the rows where |ST - C| > 1e-9 um against the rows the block flags (``mon_flag``),
refuses (``refused``) or stops on (``mon_stop``), and, per campaign, the C's out rows and the
block's flags, stop row and held sensor where it parts silently.

The question (brief st107b): which of the monitor's judgements on the air sensor does the ST not
follow, and does it name it (a flag the machine sees) or follow it wrongly (a break, to mend)?

Measured (2026-12-07, tree = fb46731b, no src change; ROOT /tmp/st107b/root (plain MLR) and
/tmp/st107b/droot (bench_diag107b chain: ``ambient_scaled`` on E_X); 4 test campaigns, 480 rows):

* step +30 (diag107b's push; T_amb beyond ``MON_HI_LIM`` 43.8 degC): C - replay 7.1e-15 both.
  |ST - C| 9.868 um (plain) / 12.503 um (diagnosed) on 240 rows = every pushed row; on all 240 the
  block says ``mon_flag`` TRUE, ``mon_rule`` 16 (``OFF_RANGE``), ``mon_sensor`` 0 (T_amb) and
  ``refused`` TRUE (``c`` held); 0.0 on every other row.  The C excludes T_amb on the same row (4
  events) and rebuilds it from the others to the campaign's end (``mon_out`` 240 rows).  NAMED:
  docs/monitoring.md (st93) "a reading ... beyond the range refuses the sample", "a machine hotter
  than training ... the ST flags it and holds ``c``".  No break.
* all +30 (out from the first sample, the A0 context): the block flags ``RANGE`` (4) and refuses
  all 480 rows (|ST - C| 18.23 plain / 11.36 diagnosed).  The C says ``TC_MON_NOT_IN_CODE``
  (reason 4) on each campaign's first row; C - replay 7.1e-15 plain but 11.5 um diagnosed (the
  lean law's campaign A0 read where the served monitor and the C part; cause not traced here,
  the C's own "not in the code" said).  Named on both sides; the C's gap is the lead's.
* step +5 (a jump in range): ``JUMP`` (1) on T_amb flagged at the jump row (4); |ST - C| <= 0.053 um
  on the 240 rows from it (the C rebuilds T_amb, out 10 rows, the block re-references by the
  whole step): named, "parts from the C after it, as after any jump of a sensor the others predict".
* ramp 0 -> +10 (a drift): campaign 0, the C takes T_amb out by drift (row 64), the block's
  ``mon_stop`` TRUE there (st97d; ``mon_stop_row`` 65): 56 rows <= 0.056 um, named.  Campaign 3,
  the drifting air makes the blind T_7 explain the bands: the C's ``BLIND_OUT`` of T_7 at row 64,
  flagged alike by the block and held as the C to row 74 (|ST - C| 0); at row 75 the block's own
  stop of a one-out hold (st96/st99: the set without T_7 at its warning band on
  ``MON_FOLLOW_OTHERS`` sensors) drops the hold silently (``mon_lost``, ``mon_held`` -1, no flag,
  no ``mon_stop``) and reads T_7 live while the C keeps it out to the campaign's end: 45 rows,
  up to 4.51 um (diagnosed 3.94).  Not the air sensor's judgement: the class st107 traced (dl10127
  T_bed_right 0.016-0.089 um, "the C's ``_follow_field`` test in place of that stop").

Candidate (benchmarks/st107b_rule.patch, src st_watch.py: 7 lines + PARSED_DIGEST; applies to
fb46731b): where that stop ends the judgement the hold is kept (``mon_kept``), the model reading
T_7 at its last reading in on the C's fallback set, as the C does to its ``BACK``, which needs the
band that row broke.  Risk: where the C lets the sensor back later the kept hold parts from it.

BAR for the candidate (st107b's mend; committed before any regression run of it and before fresh
10162-10164 are simulated; not moved after).  RULE = st107b_rule.patch applied, BASE = fb46731b.

* B1 seen room (the record the rule was built on), ramp +10: block = C <= 1e-9 um on campaign 3's
  rows 75-119, plain and diagnosed (BASE 4.51 / 3.94 um).
* B2 fresh 10162 (bench_diag107b's CLIMATE), 10163 (CLIMATE + KIND, climate_lag), 10164 (CLIMATE),
  each simulated once, ``plain`` in a BASE root and a RULE root, ``score`` of T_amb ``ramp`` +10 and
  ``step`` +30: every event (a row where BASE's hold ends unsaid with the C still out): RULE = C
  <= 1e-9 um from that row to the C's release of that sensor or the campaign's end; and no row
  where |RULE - C| > |BASE - C| + 1e-9 um.  No event: the first clause VOID, said.
* B3 bench_st107 ``score`` (st107's seen records and st105's fresh f105) and ``healthy`` (seen
  lr/dl 9964-9967) with its BASE set to fb46731b: no event and no healthy row worse than BASE by
  > 1e-9 um (its ``worse`` counts 0), B3 flag rows 0.
* B4 the ST modules (export, st93-st100, counters97, stwires100) pass with PARSED_DIGEST re-asked
  (blark parses); a test (<= ~3 s CPU) that fails on BASE.
* KEPT where B1-B4 hold; a clause not measured by 13:35 UTC is not met (REFUSED, src at BASE).

SCORED (2026-12-07, bar 601d8f2a unchanged; RULE = the patch on fb46731b, BASE = fb46731b's
src, ``git archive``; CPU user + sys as printed; load 3-10 on 2 cores):

* B1 met: ramp +10, campaign 3's 45 rows 4.51 -> 0 um (plain), 3.94 -> 0 (diagnosed); step +30
  unchanged (9.87 / 12.5, the named refusal); no row worse.
* B2 VOID (said): fresh 10162 / 10163 (lag) / 10164 simulated once, BASE and RULE roots, T_amb
  ramp +10 and step +30: no event (no hold of the block's ended unsaid), no row worse, RULE = BASE.
  Step +30: every row the ST parts from the C is flagged OFF_RANGE and refused (ST - C 0 on the
  rest; max 24.6 / 42.0 / 32.3 um): the trace holds on fresh.  Ramp +10: the C takes T_nc_cabinet
  and T_amb out together by drift; the block says ``mon_stop`` at (or 1-3 rows before) that row,
  every differing row after it (max 44.5 / 7.3 / 24.1 um, E_Z on 10162): named.
* B3 NOT met: bench_st107 ``score`` (its BASE set to fb46731b): seen 10 records, 62 windows, 31
  events, 0 worse, 0 rows moved (189.4 + 4.2 s); st105's f105 (97.9 + 6.7 s): dl10013 96 window
  rows moved, all 96 worse than BASE by > 1e-9 um (the bench prints no size), the other 5 records
  0.  ``healthy`` lr/dl 9964-9967 (153.5 + 3.3 s): 0 rows worse, 0 moved, 0 B3 rows.
* B4 half: the ST modules with the rule 53 passed + the 3 digest cases (blark parses, new digest
  b392c884..., in the patch; 107.6 + 3.2 s); no test written (none of the modules' fixtures was
  found to reach that stop in the time).
* VERDICT REFUSED: src back at fb46731b, the rule in benchmarks/st107b_rule.patch.

The question's answer stands as traced: the 9.87 / 12.5 um are the ST's named refusal of an out-of-
range reading; the air sensor's own exclusions are named (``OFF_RANGE``, ``RANGE``, ``JUMP``,
``mon_stop``); the one silent part seen is the one-out hold's stop above.  CPU: ``plain`` 9.0 s
(run + two exports), ``score`` 4.9-5.7 s each, ``simulate`` 1.4-1.9 s.
"""

from __future__ import annotations

import io
import json
import os
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from _cli import project_root, run_commands  # noqa: E402


def _tree() -> Path:
    import thermocomp

    return Path(thermocomp.__file__).resolve().parents[2]


def room(data: str) -> None:
    """diag107's test record as CSVs and a manifest in DATA (bench_diag107b's ``room``)."""
    from bench_diag107b import room as diag_room

    diag_room(data)


def plain(root: str, data: str) -> None:
    """``thermocomp run model=mlr`` on DATA in ROOT, then ``export`` of its model.pkl to c and st."""
    from bench_diag107b import _tc

    base, data = project_root(root), str(Path(data).resolve())
    status, out = _tc(base, "run", f"data.path={data}", "model=mlr", "out=run", "plots=none", "track=false")
    assert status == 0, out[-3000:]
    for fmt in ("c", "st"):
        status, out = _tc(base, "export", f"export.model={base / 'run' / 'model.pkl'}",
                          f"export.format={fmt}", f"data.path={data}", "out=code", "track=false")
        print(f"export {fmt}: exit {status}")


def _changed(df: pd.DataFrame, column: str, push: float, mode: str) -> pd.DataFrame:
    df = df.reset_index(drop=True).copy()
    half = len(df) // 2
    if mode == "all":
        df[column] += push
    elif mode == "step":
        df.loc[half:, column] += push
    else:                                   # ramp: 0 -> push over the second half
        df.loc[half:, column] += push * np.arange(len(df) - half) / (len(df) - half)
    return df


def score(root: str, data: str, column: str, push: str, mode: str) -> None:
    """C - replay and ST - C per row on ROOT's export, COLUMN changed by MODE / PUSH."""
    from hydra import compose, initialize_config_dir

    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    sys.path[:0] = [str(_tree() / "tests" / "shell"), str(_tree() / "tests")]
    from test_export import StructuredText

    base, data = project_root(root), str(Path(data).resolve())
    os.chdir(base)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={data}", "track=false"])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    tests = [_changed(ds.campaigns[c], column, float(push), mode) for c in test_ids]
    deployed = deployable_model(cfg, ds, train_ids, str(base / "run" / "model.pkl"), "export.model")[0]
    code = base / "code"
    inputs = json.loads((code / "compensator.json").read_text())["inputs"]
    rep = [replay(deployed, df) for df in tests]
    targets = [t for t in rep[0].columns if t.startswith("E_")]
    expected = np.vstack([-r[targets].to_numpy(float) for r in rep])
    subprocess.run(["cc", "-std=c99", "-O2", "compensator.c", "stream.c", "-lm", "-o", "stream"],
                   cwd=code, check=True)
    parts = [df[["time", *inputs]].to_csv(index=False, float_format="%.17g") for df in tests]
    text = parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])
    c_out = pd.read_csv(io.StringIO(subprocess.run([str(code / "stream"), "--flags"], input=text, check=True,
                                                   capture_output=True, text=True).stdout))
    got_c = c_out[[f"C_{t[2:]}" for t in targets]].to_numpy(float)
    fb = StructuredText((code / "compensator.st").read_text())
    st, said = [], []
    for df in tests:
        for k, (u, t) in enumerate(zip(df[inputs].to_numpy(float), df["time"])):
            st.append(fb(u, t, k == 0))
            v = fb.vars
            said.append((bool(v["mon_flag"]), int(v["mon_rule"]), int(v["mon_sensor"]), bool(v["mon_stop"]),
                         bool(v["refused"]), int(v["mon_held"]), int(v["mon_stop_row"])))
    st = np.array(st)
    np.savez(base / f"score_{column}_{mode}_{float(push):g}.npz", st=st, c=got_c,
             out=c_out["mon_out"].to_numpy(), excluded=c_out["excluded_inputs"].fillna("").to_numpy(str),
             said=np.array(said),
             edges=np.cumsum([0] + [len(df) for df in tests]))
    flag, stop, refused = (np.array([s[i] for s in said]) for i in (0, 3, 4))
    out = c_out["mon_out"].to_numpy() > 0
    print(f"{column} {mode} {float(push):+g} degC from half-way ({'row 0' if mode == 'all' else 'half'}): "
          f"{len(expected)} rows, {len(tests)} test campaigns")
    for i, t in enumerate(targets):
        gap = np.abs(st[:, i] - got_c[:, i])
        part = gap > 1e-9
        print(f"  {t}: max |C - replay| {np.max(np.abs(got_c[:, i] - expected[:, i])):.3g}, max |ST - C| "
              f"{gap.max():.4g} um; rows ST != C {part.sum()}: flagged {(part & flag).sum()}, refused "
              f"{(part & refused).sum()}, C out {(part & out).sum()}; max |ST - C| on rows not refused "
              f"{gap[~refused].max() if (~refused).any() else 0:.3g}")
    print(f"  block's rules (rule, sensor) on flagged rows {dict(Counter(s[1:3] for s in said if s[0]))}; "
          f"C's exclusions {dict(Counter(c_out.loc[c_out.mon_excluded > 0, 'excluded_inputs']))}")
    edges = np.cumsum([0] + [len(df) for df in tests])
    for c in range(len(tests)):
        rows = slice(edges[c], edges[c + 1])
        gap = np.abs(st[rows, 0] - got_c[rows, 0])
        apart, c_rows = np.flatnonzero(gap > 1e-9), np.flatnonzero(out[rows])
        ended = [k for k in range(1, edges[c + 1] - edges[c]) if said[edges[c] + k - 1][5] >= 0
                 and said[edges[c] + k][5] < 0 and not said[edges[c] + k][0] and not said[edges[c] + k][3]]
        print(f"  campaign {c}: ST != C on {len(apart)} rows (max {gap.max():.3g} um); C out "
              f"{len(c_rows)} rows from {c_rows[0] if len(c_rows) else '-'} "
              f"{list(c_out.excluded_inputs.iloc[rows].dropna().unique())}; block flags "
              f"{[(k, s[1], s[2]) for k, s in enumerate(said[rows]) if s[0]][:4]}, stop rows "
              f"{[k for k, s in enumerate(said[rows]) if s[3]]}; block's hold ended unsaid at "
              f"{[(k, 'C still out' if out[edges[c] + k] else 'C in') for k in ended]}")


def simulate(data: str, seed: str, kind: str) -> None:
    """``thermocomp simulate`` of bench_diag107b's climate room (``lag``: with its lag node) -> DATA."""
    from bench_diag107b import CLIMATE, KIND, _tc

    root = project_root(str(Path(data).resolve().parent))
    status, out = _tc(root, "simulate", *CLIMATE, *(KIND if kind == "lag" else []), f"seed={int(seed)}",
                      f"data.path={Path(data).resolve()}", "track=false")
    print(out.strip().splitlines()[-1] if out.strip() else "", f"(exit {status})")


def paired(base_root: str, rule_root: str, column: str, push: str, mode: str) -> None:
    """BASE's and RULE's ``score`` files of one fault: the events (BASE's hold ended unsaid, the C still
    out) with RULE - C from each to the C's release or the campaign's end; the rows RULE is worse."""
    name = f"score_{column}_{mode}_{float(push):g}.npz"
    b, r = (np.load(Path(root).resolve() / name) for root in (base_root, rule_root))
    assert np.array_equal(b["c"], r["c"]), "the two roots' C differ"
    gap_b, gap_r = np.abs(b["st"] - b["c"]).max(axis=1), np.abs(r["st"] - r["c"]).max(axis=1)
    said, out, edges = b["said"], b["out"] > 0, b["edges"]
    events = []
    for c in range(len(edges) - 1):
        for i in range(edges[c] + 1, edges[c + 1]):
            if said[i - 1][5] >= 0 and said[i][5] < 0 and not said[i][0] and not said[i][3] and out[i]:
                end = i
                while end + 1 < edges[c + 1] and out[end + 1] and b["excluded"][end + 1] == b["excluded"][i]:
                    end += 1
                events.append((c, i - edges[c], end - i + 1, gap_b[i:end + 1].max(), gap_r[i:end + 1].max()))
    worse = np.flatnonzero(gap_r > gap_b + 1e-9)
    print(f"{column} {mode} {float(push):+g}: {len(gap_b)} rows; events (campaign, row, rows, BASE, RULE um) "
          f"{[(c, k, n, float(f'{x:.3g}'), float(f'{y:.3g}')) for c, k, n, x, y in events]}; "
          f"rows RULE worse than BASE by > 1e-9 um {len(worse)}; max |ST - C| BASE {gap_b.max():.3g} "
          f"RULE {gap_r.max():.3g} um")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"room": room, "plain": plain, "score": score,
                                  "simulate": simulate, "paired": paired}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
