"""A sensor out for a freeze alone returns to the judgement on its first changed reading
(freeze83c, issue 34): the rule and its bar.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's,
``/work/main/src`` shipped, the branch the rule)::

    python benchmarks/bench_freeze83c.py column ROOT LABEL [SEEDS]
    python benchmarks/bench_freeze83c.py stranger ROOT LABEL [SEEDS]
    python benchmarks/bench_freeze83c.py verdict ROOT SHIPPED RULE [UNCOUNTED]

``column`` (default 8613,8646-8655,8662-8665): bench_mon83c's record (``column_moving_source``, MLR
on the train split, served adaptive with ``monitor.fallbacks=unobservable``), a line per record and
kind in ``ROOT/<LABEL>.jsonl``: E_* test RMSE of the fixed and the served model, the sensors' spans
out, and for a fault the row the faulted sensor (bench_cmon82's ``_sensor``: ``T_front1``) first
goes out. Kinds: ``healthy`` on every seed; ``frozen`` (held at its middle row's reading from
there, bench_freeze83b's census fault) on 8646-8650; ``toggle`` on 8651-8655 and 8662-8665: a stuck
logger that from the middle row reads the held value, one sample in ``TOGGLE`` one logger step (the
sensor's smallest non-zero one-sample change on the record) above it. ``stranger`` (default
8656-8661): bench_mon83's harness, healthy only (trunnion 8656-8657, lathe 8658-8659, jig
8660-8661) into ``ROOT/<LABEL>-stranger.jsonl``. ``verdict``: the bar below, part by part, from the
two labels (the records of the seeds ``UNCOUNTED`` printed, not counted).

The rule (src, written and committed before scoring).  ``SensorMonitor``: a sensor excluded by
the freeze (``_check_freeze``) is marked out for a freeze alone (``_froze``); any other detector
firing on it (dropout, range, jump) clears the mark; a marked sensor whose reading is finite and
changed (its run 0), no detector firing, is re-admitted at once (``Readmission._thawed``) and
judged from there as an active sensor (its drift exclusion and the new-state veto with it).  The
quiet path (``_fast``) hands such a sample to the full one.  The exported monitor
(``export/watch.py``, C ``watch_c.py``) follows (rule ``THAWED``), or flags it.

The bar (written before scoring; fresh seeds 8646-8661, none tuned on; REFUSED if any part
fails, the src reverted, kept as ``benchmarks/freeze83c_rule.patch``):
1. s8613 healthy (the found case): every E_* of the rule within 2 % of the fixed model's.
2. Healthy column 8646-8655: no served RMSE more than 2 % above shipped's; no sensor out with
   the rule that is not out shipped (no new event).
3. Frozen ``T_front1`` on 8646-8650: out no later than shipped; served RMSE no more than 2 %
   above shipped's.
4. Toggling logger on 8651-8655: no E_* more than 2 % above shipped's.
5. trunnion / lathe / jig healthy 8656-8661: identical records to shipped.
6. tests/shell/test_monitor*.py, tests/apps/test_monitor*.py, tests/shell/test_export*.py pass.

Scored (2026-12-04, shipped = /work/main/src at 262ab787, the rule = 909baa27; ``column`` 13.8 s /
9.4 s CPU, ``stranger`` 20.6 s shipped; E_* served RMSE in µm, shipped -> rule):
1. s8613 healthy: passes.  ``T_left1`` out 729-1224 -> 729 only (``T_amb`` 732-736 then, as with
   the freeze off); fixed / shipped / rule E_X 22.316 / 11.441 / 22.315, E_Y 12.356 / 20.102 /
   12.352, E_Z 5.826 / 11.005 / 5.826, E_X_mid 0.916 / 4.790 / 0.916, E_Y_mid 2.424 / 3.298 /
   2.424, E_Z_mid 2.100 / 4.040 / 2.098: every target within 0.03 % of fixed.
2. Healthy 8646-8655: passes; the same digits and spans as shipped on all ten (no freeze on any).
3. Frozen ``T_front1`` 8646-8650: passes; out at 741, 726, 725, 728, 727 both, same digits (a held
   reading never changes: never back).
4. Toggling logger 8651-8655: FAILS on all five.  Shipped keeps ``T_front1`` out from its first
   freeze (766, 760, 728, 735, 773) to the end or nearly (the return against the field); the rule
   takes it back at each toggle and it stays in, stuck, until the field has moved a band within
   one run of 5 equal samples: 12, 13, 17, 14, 12 spans out instead of 1-3.  E_Y 21.632 -> 62.027
   (s8651), 24.282 -> 53.529, 16.064 -> 39.056, 20.983 -> 61.765, 21.087 -> 63.338; E_Y_mid 7.479
   -> 16.604, 7.979 -> 14.346, 6.097 -> 13.476, 8.257 -> 16.287, 8.202 -> 16.732 (x2-3).
5. trunnion / lathe / jig healthy 8656-8661: passes, records identical.
6. Passes: tests/apps/test_monitor*.py, tests/shell/test_monitor*.py 146 passed, 4 xfailed
   (64.7 s wall); tests/shell/test_export*.py 245 passed (145.2 s wall).

Verdict: REFUSED by part 4 (the src reverted, kept as ``benchmarks/freeze83c_rule.patch``).  A
change of reading is the freeze's evidence gone only for a sensor that then goes on reading; a
logger stuck but for one step every few samples changes as often, and the freeze's run (its
only catch under a field it follows) restarts at each step.

The second rule (src, written and committed before scoring; the first plus one line of state).
Once a campaign: a sensor back on a changed reading that the freeze takes out again is not
marked (``_thaws``), so it returns only by the window against the field, as shipped.  A healthy
sensor read still at a slow peak is one event; a stuck logger's second freeze is the evidence
that its change was no return.  The C and numpy mirror follow (``mon_thaws``).

Its bar (written before scoring; the toggles of 8651-8655 shaped it and are printed, not
counted; fresh: 8662-8665, never run before; REFUSED if any part fails):
1.-3. and 5. as the first rule's (s8613; healthy column 8646-8655; frozen 8646-8650; trunnion /
   lathe / jig healthy 8656-8661 identical to shipped).
4. Toggling logger on 8662-8665: no E_* more than 2 % above shipped's.
6. The same test files pass, with a test that fails on shipped.

Scored (2026-12-04, shipped = /work/main/src at 262ab787 as ``main2`` (its ``stranger`` file the
first scoring's: the same code and seeds), the second rule = 3838ee9d as ``rule2``; ``column``
12.7 s / 11.8 s CPU; ``verdict ROOT main2 rule2 8651-8655``; served E_* RMSE in µm):
1. s8613, 2. healthy 8646-8655 and 8662-8665, 3. frozen 8646-8650, 5. stranger 8656-8661: pass,
   the same numbers as the first rule's (nothing here is frozen twice).
4. Toggling logger on fresh 8662-8665: FAILS on three of four.  The first freeze now costs a
   few rows: ``T_front1`` out 724-905 shipped, with the rule out 724-725, back (a step), out again
   727-730, back, out 736-905; E_Y 16.788 -> 17.206 (+2.5 %), E_Y_mid 5.581 -> 5.703 (+2.2 %);
   s8664 (730-734, 736-1441 shipped; 730-734, 736-737, 749-1441) E_Y 12.982 -> 13.256 (+2.1 %);
   s8665 (856-1284 shipped; 856-857, 862-1284) E_Y 20.367 -> 21.097 (+3.6 %), E_Y_mid 8.767 ->
   8.994 (+2.6 %); s8663 (748-1441; 748-749, 755-1441) within 0.1 %.  Not counted (seen): 8651
   E_Y +3.5 %, 8653 +32.3 %, 8654 +96.0 % (back once, stuck in for 170 rows before the field
   moved a band within one of its runs), 8652 and 8655 within 2 %.
6. Not run (refused by part 4 before; the tests of the first rule passed).

Verdict: REFUSED by part 4 (src reverted; ``benchmarks/freeze83c_rule.patch`` is now the second
rule's diff, the first rule's is it less ``_thaws`` / ``thaws`` / ``mon_thaws``).  Between the
return and the next freeze a stuck sensor is in and read; nothing the monitor holds at the
return tells a healthy sensor that reads on from a logger that stepped once.  What remains: a
return judged on more than one changed reading (its changes agreeing with the field's over a few
samples, not a window against its level), or a toggle caught by its own signature (a run broken
by one sample that returns to the held value), each with its bar on seeds not yet drawn.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon83c  # noqa: E402
from _ccode import rmse  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

TOGGLE = 6        # the stuck logger's period (samples): one of them a step up
FROZEN, TOGGLED = range(8646, 8651), (*range(8651, 8656), *range(8662, 8666))


def _faulted(frame, kind: str, sensor: str):
    """``frame`` with ``sensor`` held from its middle row (``frozen``), or held and one sample in
    ``TOGGLE`` one logger step above (``toggle``)."""
    out = frame.copy()
    half = len(frame) // 2
    x = frame[sensor].to_numpy(float)
    held = np.full(len(frame) - half, x[half])
    if kind == "toggle":
        steps = np.abs(np.diff(x))
        held[TOGGLE - 1::TOGGLE] += steps[steps > 0].min()
    out.loc[half:, sensor] = held
    return out


def column(root: str, label: str, seeds: str = "8613,8646-8655,8662-8665") -> None:
    from bench_cmon82 import _sensor

    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.streaming import replay

    folder = made_folder(root)
    with open(folder / f"{label}.jsonl", "w") as out:
        for seed in seed_list(seeds):
            deployed, ds, test_ids = bench_mon83c._deployed(folder, seed)
            mon, targets = deployed.monitor, deployed.targets_
            sensor = _sensor(state_space(deployed, monitor=True))
            frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
            kinds = ["healthy"] + (["frozen"] if seed in FROZEN else []) + (
                ["toggle"] if seed in TOGGLED else [])
            for kind in kinds:
                f = frame if kind == "healthy" else _faulted(frame, kind, sensor)
                errors = f[targets].to_numpy(float)
                fixed = rmse([errors], [-replay(deployed.streaming, f)[targets].to_numpy(float)])
                s = bench_mon83c._streamed(deployed, f)
                gone = np.flatnonzero(~s["active"][len(f) // 2:, mon.names.index(sensor)])
                r = {"seed": seed, "kind": kind, "targets": list(targets),
                     "fixed": [float(v) for v in fixed],
                     "served": [float(v) for v in rmse([errors], [-s["y"]])],
                     "out": bench_mon83c._spans(s["active"], mon.names), "sensor": sensor,
                     "first_out": int(len(f) // 2 + 1 + gone[0]) if len(gone) else None}
                out.write(json.dumps(r) + "\n")
                print(f"{kind} s{seed}: " + "  ".join(
                    f"{t} {a:.3f}/{b:.3f}" for t, a, b in zip(targets, r["fixed"], r["served"]))
                    + f" | out {r['out']} | {sensor} first out {r['first_out']}", flush=True)


def stranger(root: str, label: str, seeds: str = "8656-8661") -> None:
    import bench_mon82c as m82c

    s = seed_list(seeds)
    m82c.trunnion(root, f"{label}-stranger", ",".join(map(str, s[0:2])), "healthy")
    m82c.lathe(root, f"{label}-stranger", ",".join(map(str, s[2:4])), "healthy")
    m82c.jig(root, f"{label}-stranger", ",".join(map(str, s[4:6])), "healthy")


def _lines(path: Path) -> dict:
    return {(r["seed"], r["kind"]): r for r in map(json.loads, path.read_text().splitlines())}


def verdict(root: str, shipped: str, rule: str, uncounted: str = "") -> None:
    """The bar, part by part (docstring); the last line KEPT or REFUSED by parts 1-5, the
    records of the seeds ``uncounted`` printed only."""
    skip = set(seed_list(uncounted)) if uncounted else set()
    folder = Path(root)
    a, b = _lines(folder / f"{shipped}.jsonl"), _lines(folder / f"{rule}.jsonl")
    fails, counted = [], []
    for key in sorted(a):
        p, q = a[key], b[key]
        worse = [f"{t} {100 * (y / x - 1):+.1f}%" for t, x, y in zip(p["targets"], p["served"],
                                                                       q["served"]) if y > 1.02 * x]
        said = (f"s{key[0]} {key[1]}: served shipped/rule " + "  ".join(
            f"{t} {x:.3f}/{y:.3f}" for t, x, y in zip(p["targets"], p["served"], q["served"]))
            + f" | out shipped {p['out']} | rule {q['out']}")
        if key == (8613, "healthy"):
            bad = [t for t, x, y in zip(q["targets"], q["fixed"], q["served"]) if y > 1.02 * x]
            said += f" | fixed {' '.join(f'{x:.3f}' for x in q['fixed'])}; >2 % of fixed: {bad}"
            fails += ["1"] if bad else []
        else:
            fails += [{"healthy": "2", "frozen": "3"}.get(key[1], "4") + " " + key[1]] if worse else []
            said += f" | >2 % above shipped: {worse or 'none'}"
        if key[1] == "healthy" and key[0] != 8613:
            names = [{w.split("@")[0] for w in r["out"].split()} for r in (p, q)]
            new = names[1] - names[0] - {"none"}
            fails += ["2 new event"] if new else []
        if key[1] == "frozen":
            late = q["first_out"] is None or (p["first_out"] is not None
                                              and q["first_out"] > p["first_out"])
            fails += ["3 later"] if late else []
            said += f" | first out {p['first_out']} -> {q['first_out']}"
        print(said + (" (not counted)" if key[0] in skip else ""))
        if key[0] in skip:
            fails = counted
        counted = list(fails)
    same = [(folder / f"{x}-stranger.jsonl").read_text() for x in (shipped, rule)]
    print(f"stranger healthy records identical: {same[0] == same[1]}")
    fails += [] if same[0] == same[1] else ["5"]
    print(f"verdict (parts 1-5): {'REFUSED ' + str(fails) if fails else 'KEPT'}")


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"column": column, "stranger": stranger, "verdict": verdict},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
