"""A drift exclusion and a freeze with TWO or more sensors already out: the C as served (issue
34; stop 100, dep100).

SEEN (step99's probes on test_export_dep99b's eight-sensor machine, measured again here on
9bbbb214's src with ``machine``' faults): ``T_e`` and ``T_f`` in kelvin from row 20 (both out
by range), then a third sensor, one the others predict, faulted while they are out.  Served's
drift judgement excludes while more than ``min_active`` are in (``Judgement._exclude_by_judgement``)
and its freeze check (``InstantFaults._check_freeze``) has no cap on the count out; the C
(``CodeMonitor._exclude`` -> ``_second_held``, C ``mon_exclude`` -> ``mon_second_held``) holds a
drift exclusion (``DRIFT_OUT``) or a freeze beside those out only where a place is free
(``out2 < 0``, cmon85's two-slot cap; dep99 / dep99b / step99 lifted it for a range reading, a
jump and a stepped error):

* ``drift_d``: ``T_d`` +0.85 °C for good from row 35: served takes it out by drift at 36 as the
  third; the C flags ``SECOND`` at 36-39, 1.37 µm, 4 rows apart;
* ``drift_c``: ``T_c`` +0.6 °C from 35: served out by drift at 36; the C ``SECOND`` 36-38, 0.153
  µm, 44 rows apart (it judges on with the stepped reading in);
* ``freeze_a``: ``T_e`` / ``T_f`` in kelvin 30 rows (20-49), ``T_a`` held at its row-35 reading
  from 35: served out by freeze at 46 as the third; the C ``SECOND`` at 55-59, 0.940 µm, 14 rows
  (step99 said 1.09 µm / 24 rows for it; this is 9bbbb214's number, the same faults).

The C's blind-out drift path (``_drift``: ``self.out < 0 or _second_held(u, DRIFT_OUT)``, C
``mon_drift``: ``mon_nout > 0 && !mon_second_held(s, u, TC_MON_DRIFT_OUT)``) reads the same
clause.  The ST's static freeze pairs (``MON_OUT_FREEZE_HELD``, st_watch.blind_constants) hold a
freeze beside ONE sensor out (its ``BLIND_OUT``), where the cap never binds (``out2 < 0``): they
read ``mon.solve`` and the pair's operator, not the cap.  Measured (``machine``, 9bbbb214): in
all these cases the block flags ``OFF_RANGE`` of ``T_e`` on every kelvin row (20-29, 20-49) and
names nothing at the third's drift or freeze; it holds no out set (dep99: that needs the set, the
operator's solve and the re-admission), so it is apart from served from the first kelvin row on
(3.24 µm / 60 rows for the drifts, 6.29 / 60 for ``freeze_a``): the ST has no third place to lift.
The rule below was built and D1 measured on it before this bar was committed (seen cases only).

RULE (dep100; mirror ``CodeMonitor._second_held``, C ``mon_second_held``): the cap kept for a
dropout alone (``rule != DROPOUT`` / ``rule == TC_MON_DROPOUT``): a drift exclusion (its
blind-out too) and a freeze join a range reading, a jump and a stepped error, held beside ANY
number out where the set's operator solves and the sensor is one ``_second_kind`` admits
(unchanged: a freeze of one no other predicts beside two out stays ``SECOND``).  No key.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep100.py machine SCRATCH           # the seen cases above (D1)
    python benchmarks/bench_dep100.py planted ROOT RECORD [...]  # D3 / D4 on a record

``machine``: the eight-sensor machine built and deployed under SCRATCH (test_export_dep99b's),
each case (and ``freeze_u``: ``T_u``, no other predicts it, frozen as ``freeze_a``, not in the
bar) stepped through served, the numpy mirror, the compiled C (``gcc -O2 -Werror``, stream.c)
and the ST block (test_export's ``StructuredText``): max|C - served| µm and rows > 1e-9 for the
mirror and the compiled C, the mirror's rules from row 35, the ST's flagged rows and rules.
``planted``: RECORD's mlr-none cell (bench_dep98's ``stepped_cell``: simulated and run into ROOT
where missing), the served model and the mirror stepped over the lead-in and the campaign to its
fault row (a quarter in), then over :data:`ROWS` rows from it in four cases fixed before any
fresh record was drawn: ``healthy`` (nothing planted); ``two_out`` (the first two monitored
sensors the others predict, not the air, in kelvin from the fault row to the end); ``drift``
(``two_out`` and the third such sensor ramped +1 K/h from fault row + :data:`LATE`); ``freeze``
(``two_out`` and the third held at its reading at fault row + :data:`LATE` to the end).  Per case:
max|C - served| µm, rows > 1e-9, the first parting row (from the fault row) and the mirror's rule
there, served's exclusions from the fault row (row, sensor, reason), the count out at the end
(served / mirror).

Records.  SEEN: the machine above.  FRESH (never simulated before this bar's commit): dl9913
(bench_cmon91's dl9377 generator, 14 sensors, ``min_active`` 9 on dl9902), sw9914 (the Swiss
lathe, 12 temperatures), cr9915 (the climate room).  The trunnion is left out: 9 sensors,
``min_active`` 8, two out already leave the set below it (swap99's tr9876: the C holds no such
set), not this rule's.

BAR (written and committed BEFORE any of 9913-9915 is simulated; scored once; main = 9bbbb214's
src via ``git archive``, the rule this branch's; the fresh records simulated and run by main's
tree, the same ROOT copied and read by the rule's)
---
D1. ``machine``, rule: drift_d, drift_c, freeze_a: max|C - served| <= 1e-9 µm and 0 rows > 1e-9,
    the mirror and the compiled C alike, nothing "not in the code" (main: 1.37 µm / 4, 0.153 /
    44, 0.940 / 14).
D2. every line of ``bench_step99.py cases`` (dl9902 dl9901 dl9903 dl9878 tr9876 tr9877 dl9907
    tr9908 dl9909: bench_step99's, bench_dep99b's and swap99's seen and fresh) and ``bench_dep99.py
    card`` (tr9828 tr9873) identical main / rule (``diff``, CPU lines aside).
D3. ``planted`` healthy lines and bench_step99's healthy lines: as main's (0 rows apart, the same
    served events).
D4. fresh dl9913 / sw9914 / cr9915 ``planted``, scored once: on the rule, every ``drift`` and
    ``freeze`` case max|C - served| <= 1e-9 µm, 0 rows > 1e-9.  A case apart on main for a
    reason other than the cap (``two_out`` apart too, or its first parting rule not ``SECOND``)
    is said, and still counts against the bar if apart on the rule.
D5. a test (tests/shell/test_export_dep100.py, < 5 s) that fails on 9bbbb214 (``SECOND`` at the
    drift row) and passes on the rule; the C monitor export suites touched, test_export.py
    (PARSED_DIGEST: the ST text unchanged), test_lint, test_benchmarks_cli pass.
KEPT if D1-D5 hold (src + C + test + docs); else REFUSED (benchmarks/dep100_rule.patch, src as
9bbbb214), the numbers kept here.

Scored (bar 97c6d14a, the rule b52fdfe9 committed after it, before any of 9913-9915 was
simulated; 2026-12-06 15:33-15:36 UTC under a load of 15-27 on 2 cores; main = ``git archive
9bbbb214 src``, which simulated and ran the fresh records into one ROOT, the rule's tree then read
a copy of it).  CPU (user + sys): ``planted`` 16.6 / 14.0 s main / rule, ``machine`` 3.4 / 3.5 s::

    case                    main: max|C - served|, rows apart (first, rule)   rule (b52fdfe9)
    machine drift_d         1.37 µm, 4 (36 SECOND); compiled the same          1.42e-14, 0 (compiled too)
    machine drift_c         0.153, 44 (36 SECOND)                              7.11e-15, 0
    machine freeze_a        0.940, 14 (46 SECOND)                              1.78e-14, 0
    machine freeze_u        0.177, 16 (46 SECOND: one no other predicts)       the same (not in the bar)
    dl9913 healthy/two_out  0 / 2.84e-14, 0                                    the same
    dl9913 drift            18.2, 294 (66 SECOND)                              5.68e-14, 0
    dl9913 freeze           3.74, 329 (31 SECOND)                              8.53e-14, 0
    sw9914 healthy/two_out  0 / 8.53e-14, 0                                    the same
    sw9914 drift            39.4, 295 (65 SECOND)                              64.9, 295 (65 DRIFT_OUT)
    sw9914 freeze           11.1, 329 (31 SECOND)                              3.84e-13, 0
    cr9915 healthy/two_out  0 / 7.11e-14, 0                                    the same
    cr9915 drift            3.81, 114 (44 SECOND)                              7.82e-14, 0
    cr9915 freeze           14.3, 128 (31 SECOND)                              1.71e-13, 0

(dl9913: n 14, 8 modes, ``min_active`` 9, kelvin ``T_spindle_rear`` / ``T_head_left``, third
``T_head_right``; sw9914 and cr9915: n 12, 7 modes, ``min_active`` 8, kelvin ``T_headstock`` /
``T_guidebush``, third ``T_toolholder1``.)  The ST, ``machine``: the same main / rule (flags
``OFF_RANGE`` on the kelvin rows, nothing at the third; 3.24 / 6.29 µm, 60 rows apart).

Traced after the score (sw9914 drift, fed rows 63-68 from the fault row, the rule's tree): at 65
served takes ``T_toolholder2`` out by drift (-0.67 °C, the culprit) and, in the same judgement,
the drifting ``T_toolholder1`` (+0.82 °C, "no other sensor predicts it once T_toolholder2 is
out", ``_exclude_by_judgement``'s blind loop, no cap) as the fourth.  The rule takes the culprit
out as the third (``DRIFT_OUT``) and flags the partner: ``_drift``'s partner loop keeps its own
cap (``self.out2 >= 0``, C ``mon_drift``'s ``s->mon_nout >= 2``), a second clause of the drift
path this rule did not lift; the drifting sensor stays in the C, 64.9 µm (main refused both,
``SECOND``, 39.4 µm).  The rule lifting that clause too (after the score; in
benchmarks/dep100_rule.patch, measured, NOT scored): sw9914 drift 4.54e-12 µm, 0 rows; every
other fresh line as the rule's; ``machine`` as the rule's.

D2 (2026-12-06 15:27-16:13 UTC, load 13-30; the ROOT step99's and dep99b's seen and fresh,
copied per src; CPU ``cases`` 249.5 / 249.0 s, ``card`` 17.2 / 16.2 s main / rule): the 81 lines
of ``bench_step99.py cases`` on the nine records and the 6 of ``bench_dep99.py card`` tr9828 /
tr9873 identical (``diff``), every drift / ambient case there <= 6.22e-12 µm, 0 rows apart on
both.  The partner-clause variant: its first 29 lines (dl9902, dl9901) the same; the rest not run.

D1 MET (mirror and compiled C <= 1.78e-14 µm, 0 rows, nothing "not in the code").  D2 MET.  D3
MET (the nine records' healthy lines and the three ``planted`` healthy lines as main's: 0 µm, the
same served events; 0 on the fresh).  D4 NOT MET: sw9914 drift apart on the rule (64.9 µm, 295
rows, the partner's cap), the other five planted cases <= 3.84e-13 µm, 0 rows (main 3.74-18.2
µm).  D5: test_export_dep100 (2 cases, in the patch) fails on 9bbbb214 (``SECOND`` at rows 36 /
46), passes on the rule; with the partner clause, it and test_export_dep99b / step99 / dep99 /
cmon85 / cmon86 / cmon88 / cmon82c / st99: 15 passed.  PARSED_DIGEST: the ST text untouched.
VERDICT: REFUSED (D4).  benchmarks/dep100_rule.patch (``git apply`` on 9bbbb214): the rule, the
partner clause (after the score) and the test; src as 9bbbb214.  Next: the two clauses together
(one cap for the drift path: the culprit, its blind-out and its partner), scored on new fresh
seeds with the same ``planted`` cases; a freeze of one no other predicts beside two out
(``freeze_u``, ``_second_kind``) stays ``SECOND`` either way.
"""

from __future__ import annotations

import copy
import shutil
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_mon97 import CR, SW  # noqa: E402
from bench_mon98b import _dl  # noqa: E402

FRESH = {"dl9913": _dl(9913), "sw9914": [*SW, "seed=9914"], "cr9915": [*CR, "seed=9915"]}
ROWS, LATE, KELVIN, DRIFT_K_PER_H = 360, 20, 273.15, 1.0
#: the machine's faults (module doc): ``{case: (sensor, size °C or None: held, rows in kelvin)}``
MACHINE = {"drift_d": ("T_d", 0.85, 10), "drift_c": ("T_c", 0.6, 10), "freeze_a": ("T_a", None, 30),
           "freeze_u": ("T_u", None, 30)}


def _tests_on_path() -> None:
    root = HERE.parent / "tests"
    sys.path[:0] = [str(root / "shell"), str(root)]


def _machine_frames(scratch: Path):
    """``(deployed, ss, {case: faulted frame})`` of test_export_dep99b's machine (module doc)."""
    _tests_on_path()
    import test_export
    from conftest import deployed_as_replay
    from test_export_dep99b import ONSET, SPIKE, _machine
    from thermocomp.apps.deploy.export import state_space

    folder = scratch / "data"
    shutil.rmtree(folder, ignore_errors=True)
    deployed, ds, test_ids = deployed_as_replay(test_export._compose(
        f"data.path={_machine(folder)}", "track=false", "monitor.adaptive=true",
        "monitor.fallbacks=none"))
    base = ds.campaigns[test_ids[-1]].reset_index(drop=True)
    frames = {}
    for case, (sensor, size, kelvin_rows) in MACHINE.items():
        frame = base.copy()
        frame.loc[ONSET:ONSET + kelvin_rows - 1, ["T_e", "T_f"]] += KELVIN
        if size is None:
            frame.loc[SPIKE:, sensor] = frame.loc[SPIKE, sensor]
        else:
            frame.loc[SPIKE:, sensor] += size
        frames[case] = frame
    return deployed, state_space(deployed, monitor=True), frames


def _apart(got, want) -> str:
    d = np.max(np.abs(np.asarray(got) - want), axis=1)
    return f"{d.max():.3g} µm, {int((d > 1e-9).sum())} rows"


def machine(scratch: str) -> None:
    """The ``machine`` lines (module doc)."""
    _tests_on_path()
    from test_export import StructuredText, built_stream
    from test_export_cmon80 import _streamed
    from test_export_dep99b import SPIKE
    from thermocomp.apps.deploy.export import Simulator, exported_files
    from thermocomp.apps.deploy.export.pack import corrections
    from thermocomp.apps.deploy.export.watch import RULES
    from thermocomp.apps.deploy.report import stream_rows

    root = Path(scratch).resolve()
    deployed, ss, frames = _machine_frames(root)
    code = root / "c"
    code.mkdir(parents=True, exist_ok=True)
    binary = built_stream(code, exported_files(deployed, "c"))
    block = exported_files(deployed, "st")["compensator.st"]
    for case, frame in frames.items():
        run = stream_rows(deployed, frame, "K06")
        want = corrections(ss, run.y)
        times = frame["time"].to_numpy(float) - frame["time"].iloc[0]
        outs = [(int(np.searchsorted(times, e["time"])), e["sensor"], e["reason"][:24])
                for e in run.events if e.get("sensor") and e["to"] == "excluded"]
        sim, fb = Simulator(ss), StructuredText(block)
        sim.reset()
        mirror, st, rules, st_said = [], [], [], []
        for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
            mirror.append(sim.step(u, t))
            st.append(fb(u, t, i == 0))
            w, v = sim.watch, fb.vars
            if w.rule and i >= SPIKE:
                rules.append((i, RULES[w.rule], ss.inputs[ss.monitor["inputs"][w.sensor]], len(w.gone)))
            if v["mon_flag"]:
                st_said.append((i, RULES[int(v["mon_rule"])], int(v["mon_sensor"])))
        got, said = _streamed(binary, frame, ss.inputs)
        print(f"{case} ({MACHINE[case]}): served out {outs}; mirror |C - served| {_apart(mirror, want)}; "
              f"compiled C {_apart(got, want)}, not in the code "
              f"{sum('not in the code' in line for line in said.splitlines())} lines; mirror rules "
              f"(row, rule, sensor, out) {rules[:5]}; ST flagged (rule, k, rows) {_runs(st_said)}, "
              f"|ST - served| {_apart(st, want)}", flush=True)


def _runs(said: list[tuple]) -> list[tuple]:
    """``(rule, sensor, 'first-last')`` of each run of rows the ST flags alike."""
    runs = []
    for i, rule, k in said:
        if runs and runs[-1][:2] == [rule, k] and runs[-1][3] == i - 1:
            runs[-1][3] = i
        else:
            runs.append([rule, k, i, i])
    return [(rule, k, f"{a}-{b}") for rule, k, a, b in runs]


def _planted_parts(frame, start: int, names: list[str], predictable) -> tuple[list[str], dict]:
    """``(the three sensors, {case: frame rows from start})`` (module doc)."""
    from thermocomp.core.io.contract import is_ambient

    chosen = [n for n, p in zip(names, predictable) if p and not is_ambient(n)][:3]
    part0 = frame.iloc[start:start + ROWS].copy()
    two = part0.copy()
    for s in chosen[:2]:
        two[s] += KELVIN
    drift, freeze = two.copy(), two.copy()
    col = two.columns.get_loc(chosen[2])
    period = float(np.median(np.diff(frame["time"].to_numpy(float))))
    ramp = DRIFT_K_PER_H * period / 3600.0 * np.arange(1, len(two) - LATE + 1)
    drift.iloc[LATE:, col] += ramp
    freeze.iloc[LATE:, col] = two.iloc[LATE, col]
    return chosen, {"healthy": part0, "two_out": two, "drift": drift, "freeze": freeze}


def planted(root: str, *records: str, table: dict | None = None, parts=None) -> None:
    """The ``planted`` lines (module doc); ``table``: the records' simulate arguments (:data:`FRESH`;
    bench_dep100b passes its own fresh seeds); ``parts``: the cases' maker (:func:`_planted_parts`;
    bench_freezeu100 passes its own)."""
    from bench_dep98 import stepped_cell

    from thermocomp.apps.deploy.export.watch import RULES

    for record in records:
        deployed, ss, frame, lead, start, cid, run = stepped_cell(root, record, table or FRESH)
        mon = deployed.monitor
        names = list(mon.names)
        before = max(float(np.max(np.abs(c - want))) for c, want, *_ in run.rows(frame.iloc[:start]))
        chosen, cases = (parts or _planted_parts)(frame, start, names, mon._predictable)
        print(f"{record} mlr-none, test campaign {cid}: fault row {start}, n {len(names)}, modes "
              f"{mon.pod.n_modes_}, min_active {mon.min_active_}; kelvin {chosen[:2]}, third "
              f"{chosen[2:]}; before the fault row max|C - served| {before:.3g} µm", flush=True)
        period = float(np.median(np.diff(frame["time"].to_numpy(float))))
        for case, part in cases.items():
            r = copy.deepcopy(run)
            dif, rules, events = [], [], []
            times = part["time"].to_numpy(float)
            for i, (c, want, *_) in enumerate(r.rows(part)):
                dif.append(float(np.max(np.abs(c - want))))
                rules.append(RULES[r.sim.watch.rule])
                events += [(i, e["sensor"], e["reason"][:24]) for e in r.served.last_events_
                           if e.get("sensor") and e["to"] == "excluded"]
            dif = np.array(dif)
            first = int(np.argmax(dif > 1e-9)) if (dif > 1e-9).any() else None
            out_end = (int((~r.served.monitor._active).sum()), len(r.sim.watch.gone))
            print(f"  {case:<8} {len(part)} rows ({period:.0f} s, to {times[-1] - times[0]:.0f} s): "
                  f"max|C - served| {dif.max():.3g} µm, {int((dif > 1e-9).sum())} rows > 1e-9, first "
                  f"{first if first is None else (first, rules[first])}; served out "
                  f"{events[:5]}{' ...' if len(events) > 5 else ''}; out at the end served / C "
                  f"{out_end}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"machine": machine, "planted": planted}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
