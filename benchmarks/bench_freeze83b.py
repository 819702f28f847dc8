"""A healthy column sensor taken out as frozen when an unseen heat source sets in (freeze83b,
issue 34): trace and cost.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_freeze83b.py trace [ROOT] [SEED] [SENSOR] [FIRST] [LAST]
    python benchmarks/bench_freeze83b.py cost [ROOT] [SEEDS] [SENSOR]
    python benchmarks/bench_freeze83b.py census [ROOT] [SEEDS]
    python benchmarks/bench_freeze83b.py probe [ROOT] [SEEDS]

Both build bench_mon83c's record (``column_moving_source``, MLR on the train split, deployed
adaptive with ``monitor.fallbacks=unobservable``) into ``ROOT`` (default ``/tmp/freeze83b-bench``),
and the same seed three times more: noise-free readings (``temp_noise_c=0``, ``temp_quantum_c=0``:
the generator still draws the same noise, so every other draw is the same), without the unseen
source (``q3=false``), and both.  ``trace`` (default seed 8613, ``T_left1``, rows 718-735,
1-based): per row the reading, its noise-free value, the sensor's constant run, and the field's
prediction of it (from the others, under the monitor's operator: ``d - e``) on the record and the
three variants, and the reading without Q3; the sensor's training run limit and warning band.
``cost``: per record the E_* test RMSE of the fixed model, the served adaptive one, and the
served one with the freeze check off for ``SENSOR`` only (its ``_seen_run`` infinite).
``census`` (default this task's fresh seeds 8631-8640): every freeze exclusion on the healthy
record, and on the record with bench_cmon82's sensor held at its middle row's reading from there
(a frozen fault) the row it goes out.  ``probe`` (default s8613): E_* fixed / served / served
with What remains (a) patched into this process's monitor, healthy and frozen as ``census``.

Traced (2026-12-04, main 61e8e75f, ``trace``; test_cycle of s8613, 1441 rows of 100 s)
------------------------------------------------------------------------------------
Why the healthy reading stands still: noise and the logger's step at the top of a slow hump, not
the sensor model's lag and not Q3.  ``T_left1`` reads 26.12 °C on rows 724-729 (6 samples); its
noise-free reading there is 26.103, 26.110, 26.116, 26.1165 (its peak, row 727), 26.111, 26.099:
0.017 K between its extremes, under two quanta (0.01 °C) against noise of s.d. 0.02 °C (read
minus noise-free over the record: 0.0201).  Its lag (60 s) is shorter than a sample (100 s)
and holds nothing.  Without Q3 (``q3=false``, the same draws) the reading is the same 26.12 x 6:
Q3 (on ``right_7``) does not reach it in these rows.  Training's longest run of ``T_left1`` is 5
samples (the monitor's count of repeats 4 = ``_seen_run``, the window 10 being larger); this
test record's longest runs pass training's on 5 of its 20 sensors (``T_left1`` 6 vs 5 samples,
``T_front1`` 6 vs 4, ``T_right1`` 6 vs 5, ``T_left3`` 5 vs 4, ``T_edge1`` 5 vs 4: the
small-sample maximum of bench_freeze83); only ``T_left1``'s met a moving field.

The field's move is Q3.  The others' prediction of ``T_left1`` (the monitor's operator) from the
run's start (row 725) to row 729: 26.243 -> 25.702 °C, moved 0.54 against its warning band 0.512
(row 728: 0.42, so the freeze is raised at 729, 1.05 x the band).  On the noise-free record it
moves 0.47 (26.203 -> 25.738), without Q3 0.20 (26.358 -> 26.163), noise-free without Q3 0.13
(26.328 -> 26.200), while the true reading moved 0.011 K (26.1103 -> 26.0994).  So about
0.34-0.41 K of the 0.54 is Q3: the training modes, which never saw it, read its heat on the right
face as the left face cooling, and the prediction goes on falling (24.965 at row 735 against a
reading of 25.92) -- the error of mon83c's s8546.  "The field moved" is no evidence here that
the reading should have: the prediction left the truth, not the sensor.

What it costs (``cost``; E_* test RMSE in µm, fixed / served adaptive on main / served with
``T_left1``'s freeze check off): E_X 22.316 / 11.441 / 22.316, E_Y 12.356 / 20.102 / 12.352,
E_Z 5.826 / 11.005 / 5.826, E_X_mid 0.916 / 4.790 / 0.916, E_Y_mid 2.424 / 3.298 / 2.424, E_Z_mid
2.100 / 4.040 / 2.098; out ``T_left1`` 729-1224 and ``T_left3`` 737-742 on main, ``T_amb``
732-736 alone without the freeze (the judgement keeps ``T_left1`` in: Q3 is named a new thermal
state).  E_Y +63 % above the fixed model, E_Z +89 %, E_X_mid x5.2 (E_X better by accident).
It stays out because its return is judged against the field (within ``READMIT`` of its band for a
window): under Q3 that field is 1 K off it, so not before 1224.  ``bench_mon83d.py bound
/tmp/freeze83b-bench 8613 729 745`` (main's served on rows 729..k, fixed elsewhere): every target
within 2 % of the fixed model only if back by row 735 (E_X_mid +1.6 %; 736 +2.0 %); back after a
window's dwell (739) E_Y +3.9 %, E_X_mid +12.1 %; at 745 E_Y +12.1 %, E_X_mid +49.7 %.

The catch cannot tell it from a frozen fault (``census`` on this task's fresh seeds 8631-8640,
seen once, nothing tuned on them): no healthy record raises a freeze; ``T_front1`` held from row
721 goes out at 756, 740, 732, 732, 727, 732, 734, 740, 730, 725 (8631..8640); by the field's
move on 7, at 1.03-1.28 x its band 0.400 (0.41-0.51 °C), and by the blind path (12 samples over
a run limit of 2-3) on 8633, 8634, 8636.  The run limit binds on 8640 (5 samples, limit 3) and
8635 (7, limit 4), the band on the rest: a run limit raised to the window delays 8640 to 730 and
8635 to 730; a move required beyond 1.05 x the band (s8613's) delays 8635 (1.03) and 8639 (1.08).
Either fails "frozen faults out no later than main" by construction.

No rule (the brief: one only if a principled one shows and can be scored by the deadline).  At
row 729 nothing the monitor holds separates s8613's run from a frozen fault's (a run within two of
training's, a field move just beyond the band, every other sensor within band); the cost is in
the return, and ``bound`` says a return must come within 6 rows.  Bar, had a rule been tried: s8613
no worse than fixed by 2 %; fresh healthy column 8631-8640 no adaptive RMSE > 2 % above main's;
frozen faults on 8631-8635 out no later than main; tests/shell/test_monitor*.py,
tests/apps/test_monitor*.py, tests/shell/test_export*.py pass.

What remains.  (a) A return rule: a sensor out for a freeze alone whose reading changes again is
no longer frozen by the freeze's own evidence; it could go back to the judgement's hands (re-
admitted and judged as an active one, the new-state veto with it) on its first changed reading
rather than after a window against the field.  A frozen fault as simulated (held exactly) never
changes, so never returns; a real stuck logger toggling one step would flap (out again only by
the freeze's run).  ``probe`` measures it without a source change (``_probe_return``: this
process's monitor patched, the quiet path handed to the full one while such a sensor is out,
which re-admits nobody before a window's calm; not the exported C): s8613 healthy ``T_left1`` out
729 only (main 729-1224), fixed / main / probe E_X 22.316 / 11.441 / 22.315, E_Y 12.356 / 20.102
/ 12.352, E_Z 5.826 / 11.005 / 5.826, E_X_mid 0.916 / 4.790 / 0.916, E_Y_mid 2.424 / 3.298 /
2.424, E_Z_mid 2.100 / 4.040 / 2.098 (out: ``T_amb`` 732-736 as with the freeze off); s8613 with
``T_front1`` frozen from row 721: out at 747 (main 767), E_Y 34.418 / 18.952 / 12.776, E_Y_mid
10.795 / 3.321 / 5.908, E_X 20.839 / 11.468 / 21.009; fresh 8641-8645 healthy and frozen: the
same digits and spans as main on all ten (no healthy freeze; the frozen ``T_front1`` never reads
again), 13.0 s CPU.  Not a scored rule: it needs the served monitor (a freeze-out flag, the
``_fast`` hand-over), watch.py and watch_c.py (``mon_returning``) to follow, and the bar above
(8631-8640 healthy, 8631-8635 frozen; unused by it) scored on the sources before the deadline.
(b) The freeze's evidence is a field prediction the monitor cannot yet doubt at row 729 (every
sensor in band); a freeze *flagged* but not excluded until the run passes the window where the
field's move is within 1.1 x the band would cost 8635 / 8639 / 8640 up to 5 rows of a frozen
sensor in the fit.  CPU (user + sys): ``trace`` 3.2 s, ``cost`` 2.1 s, ``census`` 10.9 s,
``probe`` 8613,8641-8645 13.0 s.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import bench_mon83c  # noqa: E402
from _ccode import rmse  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

VARIANTS = {"noise-free": ("sim.generator.temp_noise_c=0", "sim.generator.temp_quantum_c=0"),
            "no-Q3": ("sim.generator.q3=false",),
            "noise-free-no-Q3": ("sim.generator.temp_noise_c=0", "sim.generator.temp_quantum_c=0",
                                 "sim.generator.q3=false")}


def _variant(root: Path, seed: int, name: str):
    """The test frame of ``seed`` simulated with the variant's overrides."""
    from thermocomp.core.io.read import read_dataset
    from thermocomp.shell.cli import main

    data = root / f"{name}-{seed}"
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false",
                     f"sim={bench_mon83c.SIM}", *VARIANTS[name]]) == 0
    return read_dataset(data)[0]


def _field(deployed, frame, j: int) -> tuple[np.ndarray, np.ndarray]:
    """Per row: sensor ``j``'s field prediction (absolute °C, from the others under the monitor's
    operator of the moment) and whether it is active."""
    mon = deployed.monitor
    X = frame[deployed.columns_].to_numpy(float)
    deployed.reset()
    field, active = [], []
    for x, t in zip(X, frame["time"].to_numpy(float)):
        deployed._step(x, t)
        d = (x if deployed._mon_all else x[deployed._mon]) - mon._ref
        _, e = mon._errors(d)
        field.append(d[j] - e[j] + mon._ref[j])
        active.append(bool(mon._active[j]))
    deployed.reset()
    return np.array(field), np.array(active)


def _runs(x: np.ndarray) -> np.ndarray:
    """Length of the constant run each sample ends (1 = changed)."""
    run = np.ones(len(x), dtype=int)
    for i in range(1, len(x)):
        run[i] = run[i - 1] + 1 if x[i] == x[i - 1] else 1
    return run


def trace(root: str = "/tmp/freeze83b-bench", seed: str = "8613", sensor: str = "T_left1",
          first: str = "718", last: str = "735") -> None:
    folder = made_folder(root)
    deployed, ds, test_ids = bench_mon83c._deployed(folder, int(seed))
    mon = deployed.monitor
    j = mon.names.index(sensor)
    print(f"{sensor}: longest constant run in training {mon.longest_run[j]:.0f}, run limit "
          f"(_seen_run) {mon._seen_run[j]:.0f}, warning band {mon.warning_c[j]:.3f} °C")
    frames = {"record": ds.campaigns[test_ids[0]].reset_index(drop=True)}
    for name in VARIANTS:
        frames[name] = _variant(folder, int(seed), name).campaigns[test_ids[0]].reset_index(drop=True)
    fields = {k: _field(deployed, f, j) for k, f in frames.items()}
    x = frames["record"][sensor].to_numpy(float)
    run = _runs(x)
    print("row reading noise-free run | field: record (active) noise-free no-Q3 noise-free-no-Q3 "
          "| no-Q3 reading")
    for i in range(int(first) - 1, int(last)):
        f = {k: v[0][i] for k, v in fields.items()}
        print(f"{i + 1} {x[i]:.2f} {frames['noise-free'][sensor].iloc[i]:.4f} {run[i]} | "
              f"{f['record']:.3f} ({'in' if fields['record'][1][i] else 'OUT'}) "
              f"{f['noise-free']:.3f} {f['no-Q3']:.3f} {f['noise-free-no-Q3']:.3f} | "
              f"{frames['no-Q3'][sensor].iloc[i]:.2f}")


def cost(root: str = "/tmp/freeze83b-bench", seeds: str = "8613", sensor: str = "T_left1") -> None:
    from thermocomp.apps.deploy.streaming import replay

    folder = made_folder(root)
    for seed in seed_list(seeds):
        deployed, ds, test_ids = bench_mon83c._deployed(folder, seed)
        mon, targets = deployed.monitor, deployed.targets_
        frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
        errors = frame[targets].to_numpy(float)
        fixed = rmse([errors], [-replay(deployed.streaming, frame)[targets].to_numpy(float)])
        s = bench_mon83c._streamed(deployed, frame)
        served = rmse([errors], [-s["y"]])
        mon._seen_run[mon.names.index(sensor)] = np.inf
        q = bench_mon83c._streamed(deployed, frame)
        quiet = rmse([errors], [-q["y"]])
        print(f"s{seed} fixed / served / no {sensor} freeze: " + "  ".join(
            f"{t} {a:.3f} / {b:.3f} / {c:.3f}" for t, a, b, c in zip(targets, fixed, served, quiet)))
        print(f"  out: {bench_mon83c._spans(s['active'], mon.names)}")
        print(f"  out without the freeze: {bench_mon83c._spans(q['active'], mon.names)}")


def census(root: str = "/tmp/freeze83b-bench", seeds: str = "8631-8640") -> None:
    """Every freeze exclusion on each healthy record and, with bench_cmon82's sensor held at its
    reading of the middle row from there (a frozen fault), the row it goes out (docstring)."""
    from bench_cmon82 import _sensor

    from thermocomp.apps.deploy.export import state_space

    folder = made_folder(root)
    for seed in seed_list(seeds):
        deployed, ds, test_ids = bench_mon83c._deployed(folder, seed)
        mon = deployed.monitor
        sensor = _sensor(state_space(deployed, monitor=True))
        frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
        frozen = frame.copy()
        half = len(frame) // 2
        frozen.loc[half:, sensor] = frame[sensor].iloc[half]
        for kind, f in (("healthy", frame), ("frozen", frozen)):
            s = bench_mon83c._streamed(deployed, f)
            said = [f"row {row} {e['sensor']}: {e['reason']}" for row, e in s["events"]
                    if e.get("to") == "excluded" and e["reason"].startswith("freeze")]
            line = f"{kind} s{seed}: freezes {'; '.join(said) or 'none'}"
            if kind == "frozen":
                j = mon.names.index(sensor)
                gone = np.flatnonzero(~s["active"][half:, j])
                line += (f" | {sensor} (run limit {mon._seen_run[j]:.0f}, band "
                         f"{mon.warning_c[j]:.3f}) held from row {half + 1}, out at "
                         f"{half + 1 + gone[0] if len(gone) else 'never'}")
            print(line, flush=True)


def _probe_return(mon) -> None:
    """Patch ``mon`` (this process only, no source change): a sensor out for a freeze alone is
    re-admitted on its first changed reading (What remains (a))."""
    from thermocomp.apps.deploy.surveillance.states import OK

    frozen: set[int] = set()
    check, readmit, fast = mon._check_freeze, mon._readmit, mon._fast

    def _fast(x):   # the quiet path re-admits nobody before a window's calm: the full one
        return None if frozen else fast(x)

    def _check_freeze(*args):
        before = mon._active.copy()
        check(*args)
        frozen.update(np.flatnonzero(before & ~mon._active).tolist())

    def _readmit(d, finite, instant, time, events):
        back = False
        for j in sorted(frozen):
            if mon._active[j] or mon._by_field[j] or mon._jumps[j] or mon._dropped[j]:
                frozen.discard(j)
            elif mon._run[j] == 0 and finite[j] and j not in instant:
                mon._set_state(j, OK, time, "re-admitted: reading again after a freeze", events)
                mon._active[j], back = True, True
                mon._explains[j] = mon._ranged[j] = False
                mon._set_operator()
                frozen.discard(j)
        return readmit(d, finite, instant, time, events) or back

    mon._check_freeze, mon._readmit, mon._fast = _check_freeze, _readmit, _fast


def probe(root: str = "/tmp/freeze83b-bench", seeds: str = "8613") -> None:
    """E_* fixed / served / served with :func:`_probe_return`, healthy and with bench_cmon82's
    sensor frozen from the middle row (as ``census``); the sensors out."""
    from bench_cmon82 import _sensor

    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.streaming import replay

    folder = made_folder(root)
    for seed in seed_list(seeds):
        deployed, ds, test_ids = bench_mon83c._deployed(folder, seed)
        mon, targets = deployed.monitor, deployed.targets_
        sensor = _sensor(state_space(deployed, monitor=True))
        frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
        frozen = frame.copy()
        frozen.loc[len(frame) // 2:, sensor] = frame[sensor].iloc[len(frame) // 2]
        for kind, f in (("healthy", frame), ("frozen", frozen)):
            errors = f[targets].to_numpy(float)
            fixed = rmse([errors], [-replay(deployed.streaming, f)[targets].to_numpy(float)])
            s = bench_mon83c._streamed(deployed, f)
            patched = bench_mon83c._deployed(folder, seed)[0]
            _probe_return(patched.monitor)
            q = bench_mon83c._streamed(patched, f)
            print(f"{kind} s{seed} fixed / served / probe: " + "  ".join(
                f"{t} {a:.3f} / {b:.3f} / {c:.3f}" for t, a, b, c in
                zip(targets, fixed, rmse([errors], [-s["y"]]), rmse([errors], [-q["y"]]))))
            print(f"  out: {bench_mon83c._spans(s['active'], mon.names)} | probe: "
                  f"{bench_mon83c._spans(q['active'], mon.names)}", flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"trace": trace, "cost": cost, "census": census,
                         "probe": probe},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
