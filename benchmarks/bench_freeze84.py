"""A sensor out for a freeze alone back once two readings in a row are off its held value
(freeze84, issue 34): trace, the rule and its bar.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's,
``/work/main/src`` shipped, the branch the rule)::

    python benchmarks/bench_freeze84.py trace ROOT [SEED] [KIND] [SENSOR] [FIRST] [LAST]
    python benchmarks/bench_freeze84.py column ROOT LABEL [SEEDS]
    python benchmarks/bench_freeze84.py stranger ROOT LABEL [SEEDS]
    python benchmarks/bench_freeze84.py verdict ROOT SHIPPED RULE

``trace`` (default s8613 ``healthy`` ``T_left1`` rows 724-745, 1-based): bench_mon83c's record
(``column_moving_source``, MLR, served adaptive with ``monitor.fallbacks=unobservable``), healthy
or with bench_freeze83c's fault (``frozen``, ``toggle``) on the sensor; per row its reading,
whether it is the value it held when it first went out (``=held``), the readings in a row off
that value, and whether it is in.  ``column`` (default 8613,8701-8708): bench_freeze83c's
``column`` (a line per record and kind in ``ROOT/<LABEL>.jsonl``) with ``healthy`` on every seed
and ``frozen`` and ``toggle`` (its stuck logger: held, one sample in 6 one logger step above) on
``T_front1`` of 8701-8708.  ``stranger`` (default 8709-8715): healthy trunnion 8709-8711, lathe
8712-8713, jig 8714-8715 (bench_mon82c's harness) into ``ROOT/<LABEL>-stranger.jsonl``.
``verdict``: the bar below, part by part, from the two labels.

Traced (2026-12-04, main bf78019c, ``trace``; 1441 rows of 100 s)
------------------------------------------------------------------
s8613 healthy ``T_left1`` (out 729-1224 on main, ``T_left3`` 737-742): 26.12 °C on rows 724-729,
out at 729 as frozen, then 26.08, 26.06, 26.01, 26.02, 25.99, 25.92 (rows 730-735): from row 730
every reading is off the held 26.12, 16 in a row by row 745 (the field it follows falls away
under Q3, which the field's prediction overshoots: a return judged against it waits to 1225).
bench_freeze83b's ``bound``: every target within 2 % of the fixed model only if back by 735.
freeze83c's toggling logger (s8651, spent, ``trace 8651 toggle T_front1 760 790``): held 25.33,
25.34 on every sixth row (762, 768, 774, ...), each followed by 25.33 again: off the held value
never more than one reading in a row.  A held fault (``frozen``) is never off it.  So two
readings in a row off the held value tell s8613's return from both stuck kinds at row 731, 2 rows
after its freeze; one (freeze83c's rule 1) does not.

The rule (src, written and committed before scoring; one rule).  A sensor excluded by the freeze
(``_check_freeze``) is marked out for a freeze alone with the reading it held (``_froze``,
``_held``); any other detector firing on it clears the mark.  On each sample a marked sensor's
readings in a row off its held value are counted (``_off``; a reading at the held value, a
missing one, sets it to 0): at ``THAW`` = 2 (readmission.py) it is re-admitted at once and judged
from there as an active sensor.  A held run broken by one sample that returns to the held value
is still a hold.  The quiet path (``_fast``) hands such a sensor's off-held reading (or its return
to the held value) to the full one.  The exported monitor (``export/watch.py``, C ``watch_c.py``)
follows (rule ``THAWED``), or flags it (``NO_THAW``, an export before it).

The bar (written before scoring; fresh seeds 8701-8715, none run before the scoring; REFUSED if
any part fails: the src reverted, kept as ``benchmarks/freeze84_rule.patch``):
1. s8613 healthy (the found case): every E_* of the rule no more than 2 % above the fixed model's.
2. Healthy column 8701-8708: no served RMSE more than 2 % above shipped's; no sensor out with the
   rule that is not out shipped (no new event).
3. Frozen ``T_front1`` on 8701-8708: its spans out the same in number as shipped's, each end
   within ``SLACK`` = 2 samples of shipped's; no served RMSE more than 2 % above shipped's.
4. Toggling logger (freeze83c's) ``T_front1`` on 8701-8708: as 3.
5. trunnion / lathe / jig healthy 8709-8715: records identical to shipped (no new event).
6. tests/shell/test_monitor*.py, tests/apps/test_monitor*.py, tests/shell/test_export*.py pass;
   kept: a test that fails on shipped, docs/monitoring.md.

Scored (2026-12-04, shipped = /work/main/src at bf78019c as ``main``, the rule = 4a980d93 as
``rule``, run one after the other; ``column`` 14.8 s / 11.9 s CPU, ``stranger`` 26.1 s shipped
(its data written then; the rule's 0.0 in-process); ``verdict /tmp/freeze84-bench main rule``;
served E_* RMSE in µm, shipped -> rule):
1. s8613 healthy: passes.  ``T_left1`` out 729-1224 -> 729-730 (back at 731 on its second
   reading off 26.12; ``T_amb`` 732-736 then, as with the freeze off); fixed / shipped / rule
   E_X 22.316 / 11.441 / 22.314, E_Y 12.356 / 20.102 / 12.352, E_Z 5.826 / 11.005 / 5.826,
   E_X_mid 0.916 / 4.790 / 0.917, E_Y_mid 2.424 / 3.298 / 2.424, E_Z_mid 2.100 / 4.040 / 2.098:
   every target within 0.1 % of fixed.
2. Healthy 8701-8708: passes; the same digits and spans as shipped on all eight.  No freeze on
   any: their exclusions (8701 ``T_amb`` 731-740, 8702 ``T_left1`` 729-733, 8703 ``T_left1`` /
   ``T_left3`` 732-1294, 8704 ``T_left1`` 732-735, 8706 ``T_right4`` 731-732, 8707 the pair
   731-739, 8708 ``T_amb`` 730-734) are drift exclusions at Q3's onset, untouched by the rule.
3. Frozen ``T_front1`` 8701-8708: passes; out 728, 732, 732, 730, 727, 730, 743, 729 to the end
   both, the same digits (a held reading is never off its value).
4. Toggling logger 8701-8708: passes; the same spans and digits as shipped on all eight (out
   from 736, 851, 928, 736, 727, 820, 755, 737; back only by the window against the field where
   shipped is: 8701 1200-1231, 8705 733-831, 8706 1164-1312, 8707 990-994 and 1332-1441, 8708
   996-999): its one reading in six off the held value never makes two in a row.
5. trunnion 8709-8711, lathe 8712-8713, jig 8714-8715 healthy: passes, records identical.
6. Passes: tests/shell/test_monitor*.py, tests/apps/test_monitor*.py 146 passed, 4 xfailed
   (71.3 s wall; 148 with test_monitor_freeze84, 116.4 s); tests/shell/test_export*.py 245
   passed (1298.7 s wall, the machine shared); the new tests/apps/test_monitor_freeze84.py (its
   first test fails on shipped: back at sample 175, a window against the field, for 163) and
   tests/shell/test_export_freeze84.py (served, numpy mirror and compiled C re-admit on the same
   row, every correction within 1e-9; an export without ``thawed`` flags ``NO_THAW``).

Verdict: KEPT.  A freeze's evidence is a held value; a sensor reading two values in a row off it
is reading again, and a stuck logger that steps once and returns is still holding.  What remains:
a logger stuck but for steps of two samples or more would be taken back (not seen on these
records, not scored); s8703 healthy keeps ``T_left1`` / ``T_left3`` out 732-1294 as a drift at
Q3's onset (E_Y 93.091 served against 15.275 fixed on shipped and the rule alike): mon83c's
case on a fresh draw, the field-follow window missing it, not the freeze's.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_freeze83c as f83c  # noqa: E402
import bench_mon83c  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

FAULTED = tuple(range(8701, 8709))     # frozen and toggling T_front1 on each
SLACK = 2                              # samples: an exclusion "at main's rows"


def trace(root: str, seed: str = "8613", kind: str = "healthy", sensor: str = "T_left1",
          first: str = "724", last: str = "745") -> None:
    deployed, ds, test_ids = bench_mon83c._deployed(made_folder(root), int(seed))
    frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
    if kind != "healthy":
        frame = f83c._faulted(frame, kind, sensor)
    j = deployed.monitor.names.index(sensor)
    s = bench_mon83c._streamed(deployed, frame)
    x, active = frame[sensor].to_numpy(float), s["active"][:, j]
    gone = np.flatnonzero(~active)
    held = x[gone[0]] if len(gone) else np.nan
    print(f"s{seed} {kind} {sensor}: out {bench_mon83c._spans(s['active'], deployed.monitor.names)}"
          f"; held {held:.2f}")
    off = 0
    for i in range(len(x)):
        off = off + 1 if (len(gone) and i > gone[0] and x[i] != held) else 0
        if int(first) - 1 <= i < int(last):
            print(f"{i + 1} {x[i]:.2f} {'=held' if x[i] == held else '     '} off {off} "
                  f"{'in' if active[i] else 'OUT'}")


def column(root: str, label: str, seeds: str = "8613,8701-8708") -> None:
    f83c.FROZEN = f83c.TOGGLED = FAULTED
    f83c.column(root, label, seeds)


def stranger(root: str, label: str, seeds: str = "8709-8715") -> None:
    import bench_mon82c as m82c

    s = seed_list(seeds)
    m82c.trunnion(root, f"{label}-stranger", ",".join(map(str, s[0:3])), "healthy")
    m82c.lathe(root, f"{label}-stranger", ",".join(map(str, s[3:5])), "healthy")
    m82c.jig(root, f"{label}-stranger", ",".join(map(str, s[5:7])), "healthy")


def _spans(out: str, sensor: str) -> list[tuple[int, int]]:
    return [tuple(int(v) for v in w.split("@")[1].split("-")) for w in out.split()
            if w.split("@")[0] == sensor]


def verdict(root: str, shipped: str, rule: str) -> None:
    """The bar, part by part (docstring); the last line KEPT or REFUSED."""
    folder = Path(root)
    a, b = f83c._lines(folder / f"{shipped}.jsonl"), f83c._lines(folder / f"{rule}.jsonl")
    fails = []
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
            part = {"healthy": "2", "frozen": "3", "toggle": "4"}[key[1]]
            fails += [f"{part} {key[1]} s{key[0]} RMSE"] if worse else []
            said += f" | >2 % above shipped: {worse or 'none'}"
        if key[1] == "healthy" and key[0] != 8613:
            names = [{w.split("@")[0] for w in r["out"].split()} for r in (p, q)]
            fails += [f"2 new event s{key[0]}"] if names[1] - names[0] - {"none"} else []
        if key[1] != "healthy":
            u, v = _spans(p["out"], p["sensor"]), _spans(q["out"], q["sensor"])
            moved = len(u) != len(v) or any(abs(m - n) > SLACK for s, t in zip(u, v)
                                            for m, n in zip(s, t))
            fails += [f"{'3' if key[1] == 'frozen' else '4'} rows s{key[0]}"] if moved else []
            said += f" | {p['sensor']} out {u} -> {v}"
        print(said)
    same = [(folder / f"{x}-stranger.jsonl").read_text() for x in (shipped, rule)]
    print(f"stranger healthy records identical: {same[0] == same[1]}")
    fails += [] if same[0] == same[1] else ["5"]
    print(f"verdict (parts 1-5): {'REFUSED ' + str(fails) if fails else 'KEPT'}")


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"trace": trace, "column": column, "stranger": stranger,
                                  "verdict": verdict},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
