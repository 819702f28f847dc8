"""The C takes a predicted sensor's range reading as the only one out where served's re-admission
brings the first back in the same sample: the swap (issue 34; stop 99, swap99; mon98c's TRACED).

mon98c traced bench_mon98's seen tr9828 drift case (a +1 K/h drift of ``T_ram``, trunnion63, mlr,
from a quarter into test campaign W3): the blind ``T_coolant_return`` (no other predicts it) goes
out as explaining at drift row 130, served and C alike; at row 817 ``T_ram`` (the others predict
it) reads 34.85 °C, beyond its range [17.8, 24.8] ± 10 °C.  Served takes ``T_ram`` out and, in
the same sample, ``T_coolant_return`` back; the C (``CodeMonitor._beyond`` ->
``_second_kind(T_ram, OFF_RANGE)``, C ``mon_beyond`` / ``mon_second_kind``) refuses ``T_ram`` as
the second (8 in, 8 - 1 < ``min_active`` 8: the field not rebuilt without both), flags ``RANGE``,
passes the sample by and keeps ``T_coolant_return`` out for good.  Measured again here on
4fafc59a (``bench_mon98.py cases ROOT tr9828``, CPU 32.7 s): drift max|C - served| 22.7 µm, 6743
rows apart; healthy 0 µm, ambient 1.78e-15 µm, 0 rows.

TRACE (seen tr9828, ``trace``: served's sample 817 instrumented, 4fafc59a's src).  What served
judges in its in-between set (``T_ram`` out, then ``T_coolant_return`` back): after the range
exclusion 7 sensors are in, ``T_coolant_return`` and ``T_ram`` out; the POD has 7 modes, so every
leverage in that set is 1: NO sensor is judged there (``_judged`` empty, ``_rebuilds`` false).
The freeze check reads the rule for one no other predicts (``T_spindle_front`` the only unchanged
reading, its run short of ``blind_run``), the stepped check has nothing to judge, the drift
judgement is not entered (7 active, not more than ``min_active`` 8), the field's follower finds no
recent drift exclusion.  The re-admission: ``T_coolant_return`` due (calm 687 >= its wait 10),
trial = the 8 without ``T_ram``, judged there ``T_column``, ``T_bed``, ``T_table`` (``T_trunnion``
is blind without ``T_ram``, its partner): worst leave-one-out error over the window 0.101, 0.101,
0.095 of their warning bands, so ``T_coolant_return`` passes (one out as explaining: every judged
sensor within its band with it in) and comes back; then 8 in, ``T_ram`` the only one out.  So
nothing served does in between changes what it decides but the re-admission, judged in the set
without ``T_ram`` on the window with the sample's row (``T_ram`` read as missing).

RULE (in benchmarks/swap99_rule.patch; mirror ``CodeMonitor._swapped``, called by ``_beyond`` where
the count refuses; C ``mon_swapped`` called by ``mon_beyond``; compensator.json
``monitor.range_swap`` = 1, absent: 0, flagged ``RANGE`` as before). With one sensor out and a
range reading of a sensor the code would hold as the second but for the count (one the others
predict, or mon98b's blind one), the set of the two out solved and ``out2`` free: where nothing
else fires in the sample (every reading there, no other beyond its range, no step past its jump
limit) and the first is due as the re-admission asks (its reading moved, its wait out, the window
full), the code's own ``_returning`` / ``mon_returning`` judges it on the window as the
re-admission will read it (the sample's row in place, the range sensor read as missing and out as
the second, its within-band mark cleared, the runs stepped), then restores it. Where the first
passes, the range sensor goes out as the second (``_second_kind`` / ``mon_second_kind`` take the
sample's swap for the count) and the sample runs its ordinary course: the re-admission brings the
first back and the range sensor is the only one out. One mechanism: the re-admission's rules are
not copied. Should the first not come back after all (something in the sample the judgement did not
see), ``RANGE`` is flagged there. The ST block lags (it flags ``OFF_RANGE`` and holds no
re-admission).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_swap99.py trace ROOT [ROW]          # served's in-between set
    python benchmarks/bench_swap99.py cases ROOT RECORD [...]   # bench_mon98's cases, swaps said
    python benchmarks/bench_swap99.py compiled ROOT RECORD      # the compiled C on the drifts

``trace``: tr9828 (bench_mon98's SEEN) simulated into ``ROOT/data`` and ``run model=mlr`` into
``ROOT/reports`` once (bench_mon98's ``cases`` builds the same ROOT); its drift case stepped to
drift row ROW (default 817), served's monitor instrumented in that sample (the sets out, what is
judged, the re-admission's trial and each judged sensor's worst error / warning band), then
bench_mon98c's ``trace`` of rows ROW - 2 .. ROW + 2 (served and the mirror, |C - served|).
``cases``: bench_mon98's ``cases`` on :data:`FRESH` and the seen records (bench_mon98's and
bench_mon98b's), each fed row where the mirror takes a swap said before its case's line (``swap``:
fed row, the sensor out, the one back).  ``compiled``: RECORD's drift and ambient cases through
the compiled C (``gcc -O2 -Werror``, stream.c): max|compiled C - served| and |mirror - served|
(µm), rows apart, stream.c's "not in the code" lines.

Records.  SEEN: tr9828 (audit97's, mon98c's), bench_mon98's sw9776 / cr9763 / lr9376, bench_mon98b's
dl9845 / dl9870 / dl9871 / sw9872.  FRESH (never simulated before this bar's commit): tr9876,
tr9877 (trunnion63 as tr9828: 9 sensors, 7 modes, ``min_active`` 8, the kind where the count binds
with one out) and dl9878 (bench_cmon91's dl9377 generator, as mon98b's dl9870: a blind ``T_amb``
beyond range while a blind sensor is out, mon98b's path).

BAR (written and committed BEFORE any of 9876-9878 is simulated; scored once; main = 4fafc59a's
src via ``git archive``, the rule this branch's; the fresh records simulated and run by main's
tree, the same ROOT then read by the rule's: the rule changes the export only)
---
S1. seen tr9828 drift: max|C - served| <= 1e-9 µm on every row, 0 rows mirror != served (main:
    22.7 µm, 6743 rows); the compiled C = served <= 1e-9 µm on every row of it, nothing "not in
    the code" said.
S2. bench_mon98 ``cases`` tr9828 / sw9776 / cr9763 / lr9376 (but S1's line), bench_mon98b ``cases``
    dl9845 / dl9870 / dl9871 / sw9872, bench_dep98 ``back`` tr9828: every line as main's (CPU
    lines aside); every healthy frame 0 rows apart, max|C - served| as main's.
S3. fresh tr9876, tr9877, dl9878, every case (healthy, drift, ambient), scored once: max|C - served|
    <= 1e-9 µm and 0 rows mirror != served on the rule; where main is apart, it was flagged; the
    compiled C = the mirror (<= 1e-9 µm) on their drift and ambient cases.
S4. a new test (tests/shell/test_export_swap99.py) fails on 4fafc59a and passes on the rule; the C
    monitor export suites touched, test_lint, test_benchmarks_cli pass; PARSED_DIGEST unchanged
    (the ST text does not change).
KEPT if S1-S4 hold (src + C + test + docs/monitoring.md, docs/cli.md's key); else REFUSED
(benchmarks/swap99_rule.patch, src as 4fafc59a), the numbers kept here.

Seen (before the bar, the rule's tree, ROOT built by 4fafc59a's ``cases tr9828``): bench_mon98c's
``trace`` rows 815-821: C = served from 817 on (0 µm; main 2.02 µm at 817, growing);
``compiled ROOT tr9828``: drift max|compiled C - served| 5.68e-14 µm, 0 rows > 1e-9, nothing "not
in the code" (ambient 5.68e-14), CPU 26.4 s.  tests/shell/test_export_swap99.py (the six-sensor
machine, 4 modes): served swaps at its row 114; the mirror and the compiled C = served on every
row; on 4fafc59a the mirror flags ``RANGE`` at rows 115-117 (1 of 4 cases fails there).

Scored (fresh 9876-9878, once, after the bar's commit c9d0070f; the rule unchanged since but for
``_beyond``'s ``gap`` default, 2026-12-06 11:58-12:27 UTC under a load of 11-17 on 2 cores; main =
``git archive 4fafc59a src``, which simulated and ran the records into one ROOT, the rule's tree
then read it; ``cases`` CPU 110.2 s main, 97.5 s rule; ``compiled`` 22.6 / 29.5 / 10.9 s)::

    record  case     main: max|C - served|, rows apart   rule                 compiled C (rule)
    tr9876  healthy  0 µm, 0                              the same
    tr9876  drift    2.84e-14, 0 (T_ram named 823)        the same             5.68e-14
    tr9876  ambient  49.2, 6836 (T_amb 724)               the same             49.2, RANGE at 724
    tr9877  healthy  0, 0                                 the same
    tr9877  drift    7.11e-14, 0 (T_ram 826)              the same             1.71e-13
    tr9877  ambient  24.6, 6842 (T_amb 718)               the same             24.6, RANGE at 718
    dl9878  healthy  0, 0 (6 events, the generator's)     the same
    dl9878  drift    1.42e-13, 0                          the same             1.46e-13
    dl9878  ambient  19.3, 254 (T_amb 827)                the same             19.3, SECOND at 824

No fresh case took the swap (no ``swap`` line): the fresh drifts of ``T_ram`` pass through a new
thermal state, no blind sensor out when it leaves its range.  The three ambient partings are
main's, line for line, and the C flags each at its first parting row.  Traced after the score
(tr9876 ambient, the rule unchanged): at drift row 724 ``T_amb`` (blind) leaves its range while
the healthy ``T_column`` is out (since 693); served takes ``T_amb`` out and does NOT bring
``T_column`` back (7 in, below ``min_active`` 8: served then serves a field it does not rebuild),
so the rule's judgement refuses the swap and ``RANGE`` is flagged, as on main: another defect
(the C holds no set below ``min_active``, dep98b's), not this rule's.  dl9878's parting starts at a
jump of ``T_bed_right`` with ``T_col_back`` out (``SECOND``, 824), then ``T_amb``'s range at 827.

S1 MET: tr9828 drift max|C - served| 22.7 µm, 6743 rows -> 2.84e-14 µm, 0 rows (mirror, bench_mon98
``cases``); compiled C 5.68e-14 µm, nothing said.  S2 MET: every other bench_mon98 (tr9828 ambient,
sw9776, cr9763, lr9376), bench_mon98b (dl9845, dl9870, dl9871, sw9872) and bench_dep98 ``back`` line
identical, main / rule (``diff`` of the outputs but the CPU lines: S1's line only); healthy frames
0 rows apart.  S3 NOT MET as written: 3 of 9 fresh cases are apart on the rule (49.2, 24.6, 19.3
µm), as on main, each flagged, none on the swap's path.  S4 in part: test_export_swap99 4 passed
(1 fails on 4fafc59a); the export suites (test_export.py, 20 C monitor modules, mirror98) in one
run: 84 passed, test_export_cmon80's ``_beyond`` call failed (a TypeError: ``gap`` then defaulted,
cmon80 + mon98b 7 passed) and test_export_mon98b's fixture errored 3 times ("assignment destination
is read-only", pandas) in that run only (alone, and with cmon85: passed; not traced).

VERDICT: REFUSED (S3 not met as written).  The rule, its test and its docs are in
benchmarks/swap99_rule.patch (``git apply`` on 4fafc59a); src as on 4fafc59a.  What stands: served
judges nothing in the in-between set of the swap (7 modes, 7 sensors: every leverage 1) but the
re-admission, and the rule gives C = served on tr9828 and on the test's machine; the fresh
partings are served below ``min_active`` (T_amb out, T_column not back), which the C cannot hold.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit97 import TRUNNION  # noqa: E402
from bench_mon98 import FRESH as MON98  # noqa: E402
from bench_mon98 import SEEN as MON98_SEEN  # noqa: E402
from bench_mon98b import FRESH as MON98B  # noqa: E402
from bench_mon98b import _dl  # noqa: E402

FRESH = {"tr9876": [*TRUNNION[1:], "seed=9876"], "tr9877": [*TRUNNION[1:], "seed=9877"],
         "dl9878": _dl(9878)}
RECORDS = {**MON98_SEEN, "dl9845": MON98["dl9845"], **MON98B, **FRESH}


def _targets(record: str) -> None:
    """The trunnion's targets for a ``tr`` record (bench_mon98's ``cases``), else none set."""
    if record.startswith("tr"):
        os.environ["THERMOCOMP_TARGETS"] = TRUNNION[0].split("=", 1)[1]
    else:
        os.environ.pop("THERMOCOMP_TARGETS", None)


def _cell(root: str, record: str):
    """``(deployed, ss, frame, start, names, {case: the frame with its drift})`` of RECORD's
    mlr-none cell under ROOT (simulated and run where missing)."""
    from bench_cmon92 import faulted_cell, made
    from bench_mon98 import _drifts

    _targets(record)
    base = Path(root).resolve()
    made(base, record, "mlr", RECORDS)
    deployed, ss, frame, _lead, start, _cid = faulted_cell(base, record, "mlr-none")
    names = list(deployed.monitor.names)
    drifts = _drifts(frame, start, names, deployed.monitor._predictable)
    return deployed, ss, frame, start, names, {
        case: (sensor, pd.concat([frame.iloc[:start], part])) for case, (sensor, part) in drifts.items()}


def _served_sample(mon, names) -> None:
    """Served's monitor instrumented for one sample (module doc): each check's set and verdict."""
    said = lambda m: [names[k] for k in np.flatnonzero(m)]     # noqa: E731

    def wrapped(name, show):
        inner = getattr(mon, name)

        def call(*args, **kwargs):
            got = inner(*args, **kwargs)
            show(args, got)
            return got
        setattr(mon, name, call)

    wrapped("_exclude", lambda a, r: print(
        f"  out of range: {names[a[0]]} excluded; out {said(~mon._active)}, {int(mon._active.sum())} "
        f"in (min_active {mon.min_active_}), rebuilds {mon._rebuilds}"))
    wrapped("_check_freeze", lambda a, r: print(
        f"  freeze check in that set: unchanged readings {said(a[6])}, runs "
        f"{[int(mon._run[k]) for k in np.flatnonzero(a[6])]}, blind_run "
        f"{[float(mon._blind_run[k]) for k in np.flatnonzero(a[6])]}"))
    wrapped("_check_stepped", lambda a, r: print(
        f"  stepped check: judged {said(mon._judged)} (leverages {np.round(mon._lev, 6).tolist()})"))
    wrapped("_exclude_by_judgement", lambda a, r: print(
        f"  drift judgement: entered {bool(mon._active.sum() > mon.min_active_)}; recent drift "
        f"exclusions {said(mon._since >= 0)}; new state {mon._novel}"))

    def trial(a, r):
        M, lev = mon._operator(a[0])
        warn = mon._bands_of(a[0] | mon._hid)[0]
        judged = a[0] & (lev < mon.pod.max_leverage)
        print(f"  re-admission trial {said(a[0])}: passes {said(r[0])}; judged, worst / warning band: "
              + ", ".join(f"{names[k]} {r[1][k] / warn[k]:.3f}" for k in np.flatnonzero(judged)))
    wrapped("_pass_once_back", trial)
    wrapped("_returning", lambda a, r: print(f"  due {said(a[0])} -> back {said(r)}"))


def trace(root: str, row: str = "817") -> None:
    """The ``trace`` lines (module doc)."""
    from bench_cmon92 import Stepped
    from bench_mon98c import trace as rows

    deployed, ss, frame, start, names, drifts = _cell(root, "tr9828")
    mon, at = deployed.monitor, start + int(row)
    sensor, full = drifts["drift"]
    print(f"tr9828 drift of {sensor} from fed row {start}: n {len(names)}, modes "
          f"{mon.pod.n_modes_}, min_active {mon.min_active_}, window {mon.window}")
    for i, (c, want, *_) in enumerate(Stepped(deployed, ss).rows(full.iloc[:at + 1])):
        if i == at - 1:
            print(f"drift row {int(row) - 1}: served out {[n for n, a in zip(names, mon._active) if not a]}, "
                  f"calm {dict(zip(names, mon._calm.tolist()))}")
            print(f"drift row {row} (served's sample):")
            _served_sample(mon, names)
        if i == at:
            print(f"  events {[(e.get('sensor'), e.get('to')) for e in deployed.last_events_]}")
    rows(root, str(int(row) - 2), str(int(row) + 3))


def cases(root: str, *records: str) -> None:
    """bench_mon98's ``cases`` on RECORDS, the mirror's swaps said (module doc)."""
    import bench_cmon92
    from bench_mon98 import cases as mon98_cases

    plain = bench_cmon92.Stepped.rows

    def said(self, part):
        names = list(self.served.monitor.names)
        for i, r in enumerate(plain(self, part)):
            w = self.sim.watch
            if getattr(w, "swap", -1) >= 0:
                print(f"    swap at fed row {i}: {names[w.swap]} out, "
                      f"{[names[k] for k in (w.out, w.out2) if k >= 0]} out after", flush=True)
            yield r

    bench_cmon92.Stepped.rows = said
    try:
        mon98_cases(root, *records, generators=RECORDS)
    finally:
        bench_cmon92.Stepped.rows = plain


def compiled(root: str, record: str) -> None:
    """The ``compiled`` lines (module doc)."""
    from bench_cmon92 import Stepped

    from thermocomp.apps.deploy.export import exported_files

    deployed, ss, frame, start, names, drifts = _cell(root, record)
    folder = Path(root).resolve() / "c" / record
    folder.mkdir(parents=True, exist_ok=True)
    for name, text in exported_files(deployed, "c").items():
        (folder / name).write_text(text)
    subprocess.run(["gcc", "-std=c99", "-Wall", "-Wextra", "-Werror", "-O2", "compensator.c",
                    "stream.c", "-lm", "-o", "stream"], cwd=folder, check=True, capture_output=True)
    for case, (sensor, full) in drifts.items():
        run = subprocess.run([str(folder / "stream")], capture_output=True, text=True, check=True,
                             input=full[["time", *ss.inputs]].to_csv(index=False, float_format="%.17g"))
        got = pd.read_csv(pd.io.common.StringIO(run.stdout)).to_numpy(float)
        rows = list(Stepped(deployed, ss).rows(full))
        mirror, want = np.array([r[0] for r in rows]), np.array([r[1] for r in rows])
        apart = np.abs(got - want).max(axis=1)
        said = [line for line in run.stderr.splitlines() if "not in the code" in line]
        print(f"{record} {case} ({sensor}): {len(full)} rows; max|compiled C - served| "
              f"{apart.max():.3g} µm ({int((apart > 1e-9).sum())} rows > 1e-9, first "
              f"{int(np.argmax(apart > 1e-9)) - start if (apart > 1e-9).any() else '-'} of the drift); "
              f"max|mirror - served| {np.abs(mirror - want).max():.3g}, |compiled - mirror| "
              f"{np.abs(got - mirror).max():.3g} µm; not in the code: {len(said)} lines "
              f"{said[:2]}", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace, "cases": cases, "compiled": compiled}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
