"""A healthy column record whose served monitor takes out a pair as a drift when an unseen heat
source sets in (mon83c, issue 34): trace, and the served monitor on fresh draws.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_mon83c.py trace [ROOT] [SEED] [FIRST] [LAST]
    python benchmarks/bench_mon83c.py score [ROOT] [SEEDS] [KINDS]

Both build bench_cmon83's record: ``thermocomp simulate sim=column_moving_source seed=SEED`` into
``ROOT`` (default ``/tmp/mon83c-bench``), MLR fitted on the train split, deployed adaptive as by
default with ``monitor.fallbacks=unobservable``.  ``trace`` (default seed 8546, rows 725-770):
the monitor's events, then per row (1-based) the sensors out, the readings of ``T_left1`` and
``T_left3`` against what the monitor feeds the model (rebuilt from the others while out), the
served E_Y correction less the fixed model's, and every judged sensor out of its warning band
(its error over the last ``confirm`` samples).  ``score`` (default seeds 8601-8610, kinds
``healthy,drift``; drift: bench_cmon82's ``+1 K/h`` from the middle row on the sensor
bench_cmon82's ``_sensor`` picks): per record the E_* test RMSE, fixed / served adaptive, the
sensors excluded (``sensor@first-last`` row spans), and for a drift the first row its sensor is
out.

Traced (2026-12-04, main b5aa4c93, ``trace``; test_cycle of s8546, 1441 rows of 100 s)
-------------------------------------------------------------------------------------
Q3 (200 W on ``right_7``, unmeasured, between ``T_right3`` and ``T_right4``) sets in at the test
half, row ~721.  Up to row 730 every sensor is within band (the monitor on its quiet path).
Row 731, before the judgement: ``T_left1`` (level 2 of the left face, far from Q3, leverage 0.82,
its band 0.611) at +0.82 °C over the last 2 samples, the only sensor out of band (``T_right4``
+0.41, one of its two samples within 0.4).  So (judgement.py): paper 002's culprit, the largest
``|E|(1-h)``, is ``T_right4`` (0.33; ``T_left1`` 0.15), whose exclusion leaves ``T_left1`` out:
no; ``_lone_fault`` then takes ``T_left1``: with it out every other judged sensor is within band
and its own deviation from the others' field is at least their largest error (0.41); the veto
sees 0 others out of band with it in (``new_state_others`` 2): no new thermal state, a drift.
With ``T_left1`` out, ``T_left3``'s leverage rises to 0.939 (> 0.9): no other predicts it, and
its ``|E|(1-h)`` 0.12 >= 0.7 x 0.15, so it goes out too as the blind partner.  A lone residual of
0.15 °C (0.82 x (1 - 0.82)) on a high-leverage sensor is the first sign of the new field, not a
fault: nothing in the judgement can tell it at the one row where it is alone.

The cost: the model is fed the pair rebuilt from the other 16 judged sensors under the training
modes, which have no Q3.  Rebuilt minus read, ``T_left1`` / ``T_left3``: -2.23 / -1.04 °C at row
731, -4.2 / -2.2 at 738, -10.2 / -5.4 at 760, -11.9 / -6.2 at 770 (the readings rise 24.0 ->
25.5 °C; the rebuild falls to 13.6: the modes put Q3's heat on the right face with a cold left
one).  The served E_Y correction less the fixed model's: -35.3 µm at row 731 (the guard's rate
limit; unguarded -54.1), -94.9 at 738, -131.2 at 760, -140.3 at 770.  Over the record served E_Y
RMSE 71.260 µm against the fixed model's 16.489 (E_X 23.236 / 25.685, E_Z 16.263 / 7.961).

Why no re-admission: ``_follow_field`` re-admits a drift-excluded sensor when ``new_state_others``
(2) other judged sensors leave the band *within a window (10 samples) of its exclusion*.  Rows
732-741 have one (``T_right4``, from 739); two (``T_right3`` and ``T_right4``) at row 744, 13
samples after it, then up to 7.  At row 761 (the alarm band, a sensor being out by the field)
``T_right4`` at +0.84 °C, whose exclusion leaves the others out: a new thermal state declared,
which stops further drift exclusions but leaves the pair out.  ``readmission.py`` then needs the
pair within band against the others' field for a whole window: their errors there +10 to +12 °C
while Q3 runs; back at row 1247 (the state ended at 1216).

A principle (the one tried): an exclusion the field follows was the first sign of the field, as
the window rule says; the window is only a stand-in for "the same excursion".  Rule: a drift
exclusion can be followed by the field (re-admitted, a new thermal state) until the field has
been calm (every judged sensor within its warning band) for a window since it, not only within a
window of it.  A true drift's exclusion leaves the field calm: its sensor stays out as before.
Changed: ``_follow_field``'s ``_since`` is cleared for an active sensor, or, more than a window
after the exclusion, once ``_calm_field >= window`` (the exported C's ``mon_since``, watch_c.py,
is not changed: kept, it would have to follow).

Bar (written before scoring the fresh draws; the brief's): s8546 quiet, or its served E_Y no worse
than the fixed model's; fresh healthy column_moving_source 8601-8610: no record with a served
adaptive E_* RMSE more than 2 % above the fixed model's where main's is not; drift on 8601-8605:
the drifting sensor out no later than on main; tests/shell/test_monitor*.py,
tests/apps/test_monitor*.py, tests/shell/test_export*.py pass.  Else REFUSED: the source
reverted, ``benchmarks/mon83c_rule.patch`` kept.

Scored (2026-12-04, ``score``; "main": the sources of b5aa4c93, "rule": this branch with the rule,
alternated; E_* test RMSE in µm, fixed / served adaptive)
-----------------------------------------------------------------------------------------------
s8546 healthy: E_Y 16.489 / 71.260 -> 16.489 / 17.518 (+6.2 % above fixed), E_X 23.236 -> 25.822
(fixed 25.685), E_Z 16.263 -> 7.993 (7.961), E_X_mid 7.465 -> 1.446 (1.210), E_Y_mid 13.647 ->
3.037 (2.729), E_Z_mid 5.044 -> 1.739 (1.681); the pair out 731-1246 -> 731-743, re-admitted at
row 744 as the field follows (``T_right3``, ``T_right4``: a new thermal state, ended at 1208).
The 6.2 % left are the 13 rows with the pair out: E_Y over rows 731-743 fixed 24.286, served
65.732; over the other rows 16.401 / 16.442 (the served equal to the fixed model's, 0.01 µm, from
row 748 on).  Judge only (``adaptive`` off, main): with the pair in, ``T_right4`` leaves the band
at row 732 and a new thermal state is named at 734 (``T_left1`` +1.1, ``T_left3`` -0.46,
``T_right3`` +0.44, ``T_right4`` +0.52 °C): the exclusion itself, changing the operator, held the
others within band (``T_right4`` to 739, ``T_right3`` to 744) and so hid the field's following.

Fresh healthy 8601-8610 and drift 8601-8605 (``T_front1`` +1 K/h from row 721): every line the
same digits on main and with the rule (the field never followed an exclusion after its window:
healthy exclusions of 2-7 rows, ``T_left1``/``T_left3`` on s8607 733-735; no healthy record with a
served E_* more than 2 % above fixed's but s8607's E_X_mid 1.011 / 1.086, +7.3 %, on both);
``T_front1`` first out at 1086, 1273, 1273, 1117, 1179 on both.  CPU of ``score`` (user + sys):
healthy 8601-8610 9.2 s main, 6.8 s rule (simulations cached by the first); drift 4.1 / 3.8 s;
s8546 2.2 / 1.6 s.  Tests with the rule: tests/shell/test_monitor*.py, tests/apps/test_monitor*.py,
tests/shell/test_export*.py 390 passed, 4 xfailed (236 s).

Verdict: REFUSED by its bar: s8546's served E_Y stays 6.2 % above the fixed model's (71.260 ->
17.518 against 16.489), neither quiet nor no worse; the rest of the bar held (fresh records
unchanged, drift exclusions at the same rows, the tests pass).  The source is reverted; the rule
is ``benchmarks/mon83c_rule.patch``.  Kept, it would also have needed the exported C's
``mon_since`` (watch_c.py) to follow, which it did not change.

What remains: the 13 rows.  The judge-only trace points at the next rule to try: the field's
following of a fresh drift exclusion judged with the excluded sensor back in the fit (the
others' errors under the operator it was excluded from, as ``_resolves`` judges with it out): on
s8546 ``T_right4`` at row 732 and 3 others at 734, within the window, so the pair back after 3
rows, not 13 (unmeasured; its bar as this one's, on seeds not used here, and the C to follow).
An upper bound of what it can give, main's served E_Y on rows 731..k and the fixed model's on
every other row: 16.480 (k = 731), 16.489 (732), 16.505 (733), 16.559 (734) against fixed's
16.489: back within 2 rows, or no exclusion at 731, to be "no worse" than fixed on s8546; after
3 rows +0.1 %, before the guard's rate limit on the way back.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _ccode import deployed_on, rmse  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402
from bench_cmon82 import _planted, _sensor  # noqa: E402

SIM = "column_moving_source"
PAIR = ("T_left1", "T_left3")


def _deployed(root: Path, seed: int) -> tuple:
    from thermocomp.shell.cli import main

    data = root / f"{SIM}-{seed}"
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false",
                     f"sim={SIM}"]) == 0
    return deployed_on(data, "mlr", ("monitor.fallbacks=unobservable",))


def _streamed(deployed, frame: pd.DataFrame) -> dict:
    """Per row: the served output, the monitor's field (absolute °C), active mask, level, error;
    and the events with their row (1-based)."""
    mon = deployed.monitor
    X = frame[deployed.columns_].to_numpy(float)
    t = frame["time"].to_numpy(float)
    deployed.reset()
    keep = {k: [] for k in ("y", "field", "active", "level", "err")}
    events = []
    for i, (x, tt) in enumerate(zip(X, t)):
        y, _ = deployed._step(x, tt)
        level, err = mon._judge()
        keep["y"].append(np.array(y))
        keep["field"].append(mon._clean + mon._ref)
        keep["active"].append(mon._active.copy())
        keep["level"].append(level)
        keep["err"].append(err)
        events += [(i + 1, e) for e in deployed.last_events_]
    deployed.reset()
    out = {k: np.array(v) for k, v in keep.items()}
    out["events"] = events
    return out


def _spans(active: np.ndarray, names: list) -> str:
    """``sensor@first-last`` (1-based) of every run of rows a sensor is out."""
    said = []
    for k, name in enumerate(names):
        out = np.flatnonzero(~active[:, k])
        if len(out):
            breaks = np.flatnonzero(np.diff(out) > 1)
            starts = np.r_[out[0], out[breaks + 1]]
            ends = np.r_[out[breaks], out[-1]]
            said += [f"{name}@{a + 1}-{b + 1}" for a, b in zip(starts, ends)]
    return " ".join(said) or "none"


def trace(root: str = "/tmp/mon83c-bench", seed: str = "8546", first: str = "725",
          last: str = "770") -> None:
    from thermocomp.apps.deploy.streaming import replay

    deployed, ds, test_ids = _deployed(made_folder(root), int(seed))
    names, targets = deployed.monitor.names, deployed.targets_
    frame = ds.campaigns[test_ids[0]].reset_index(drop=True)
    s = _streamed(deployed, frame)
    fixed = -replay(deployed.streaming, frame)[targets].to_numpy(float)
    errors = frame[targets].to_numpy(float)
    print("E_* RMSE fixed / served:", "  ".join(
        f"{t} {a:.3f} / {b:.3f}" for t, a, b in zip(targets, rmse([errors], [fixed]),
                                                     rmse([errors], [-s["y"]]))))
    for row, e in s["events"]:
        if {e.get("from"), e.get("to")} & {"excluded", "new thermal state"}:
            print(f"  row {row} {e.get('sensor')} {e.get('from')} -> {e.get('to')}: {e['reason']}")
    pair = [names.index(p) for p in PAIR]
    cols = [deployed.columns_.index(p) for p in PAIR]
    X = frame[deployed.columns_].to_numpy(float)
    iy = targets.index("E_Y")
    for i in range(int(first) - 1, int(last)):
        out = ",".join(names[k] for k in np.flatnonzero(~s["active"][i])) or "-"
        rebuilt = " ".join(f"{X[i, c]:.2f}/{s['field'][i, k]:.2f}" for c, k in zip(cols, pair))
        bad = " ".join(f"{names[k]} {s['err'][i, k]:+.2f}" for k in np.flatnonzero(s["level"][i] >= 1))
        print(f"{i + 1} out {out} | {' / '.join(PAIR)} read/fed {rebuilt} | served - fixed E_Y "
              f"{-s['y'][i, iy] - fixed[i, iy]:+.1f} um | out of band: {bad or '-'}")


def score(root: str = "/tmp/mon83c-bench", seeds: str = "8601-8610",
          kinds: str = "healthy,drift") -> None:
    from thermocomp.apps.deploy.export import state_space
    from thermocomp.apps.deploy.streaming import replay

    folder = made_folder(root)
    for seed in seed_list(seeds):
        deployed, ds, test_ids = _deployed(folder, seed)
        names, targets = deployed.monitor.names, deployed.targets_
        sensor = _sensor(state_space(deployed, monitor=True))
        for kind in kinds.split(","):
            for t in test_ids:
                frame = ds.campaigns[t].reset_index(drop=True)
                if kind != "healthy":
                    frame = _planted(frame, kind, sensor)
                s = _streamed(deployed, frame)
                fixed = -replay(deployed.streaming, frame)[targets].to_numpy(float)
                errors = frame[targets].to_numpy(float)
                a, b = rmse([errors], [fixed]), rmse([errors], [-s["y"]])
                worse = [f"{x} {100 * (q / p - 1):+.1f}%" for x, p, q in zip(targets, a, b)
                         if q > 1.02 * p]
                line = (f"{kind} s{seed} {t}: " + "  ".join(
                    f"{x} {p:.3f}/{q:.3f}" for x, p, q in zip(targets, a, b))
                    + f" | >2% worse: {', '.join(worse) or 'none'} | out: "
                    + _spans(s["active"], names))
                if kind != "healthy":
                    gone = np.flatnonzero(~s["active"][:, names.index(sensor)])
                    line += f" | {sensor} first out at {gone[0] + 1 if len(gone) else 'never'}"
                print(line, flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"trace": trace, "score": score},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
