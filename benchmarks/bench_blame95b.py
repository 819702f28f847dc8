"""The drift culprit picked by the fault's share, the errors' change since the last calm sample
(stop 95, blame95b; issue 34, mend (a) of bench_blame95): a measured prototype.  TRACED: the
prototype is ``benchmarks/blame95b_rule.patch`` (src of the served monitor only, no C, no ST);
src stays main 98f46c1a.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``, the tree main or main with the patch
applied: ``git apply benchmarks/blame95b_rule.patch``)::

    python benchmarks/bench_blame95b.py cell ROOT [FRAC]
    python benchmarks/bench_blame95b.py fl CASE [FRAC]
    python benchmarks/bench_blame95b.py mon85b [FRAC]

``cell``: bench_blame95's ``trace`` (audit95's spent cr9763, C07, T_frame1 frozen from row 55;
``ROOT`` a copy of its root).  ``fl``: bench_mon87's ``fl`` (fl_thermal, ``drift`` or ``clean``).
``mon85b``: bench_mon87's ``mon85b`` (fl_thermal, T_t12 1 K/h and T_t14 2.7 K/h from row 240).
``FRAC`` sets the patch's ``CALM_FRAC`` (default: the patch's 0.5); on main (no ``CALM_FRAC``)
the commands run as main and say so.

The prototype (the patch): after every sample, on the fast path and the full one, the judged
errors (mean of the last ``confirm``) are kept as the calm ones when every judged ``|error|`` is
below ``CALM_FRAC`` x its warning band (a change of operator forgets them: zeros, the pick on
levels as main).  The drift pick (``Judgement._exclude_by_judgement``: paper 002's
``|E|(1-h)``) and ``_lone_fault``'s likelier single fault (``|E| sqrt(1-h)``) then read
``share = error - calm errors`` instead of the error; the bands, ``_resolves``, the veto and the
regime check read the errors as before.  Not built: the non-adaptive ``_name_state``, the C
(``watch_c``), the ST, ``update_block``'s path (its rows are not kept as calm ones).

No bar and no fresh seed (TRACED, as briefed): every number is on SEEN records.

Measured (2026-12-06, stop 95, 2 cores shared, ``nice``; main = 98f46c1a's src):

(1) ``cell`` (window 10, confirm 2).  Main: row 25 T_frame2 excluded (drift +0.43 °C), row 60
    T_frame1 "jump +0.99 °C", row 84 T_frame2 back; residual RMS E_X / E_Z over 120 rows 3.521 /
    3.369 µm (healthy 0.943 / 1.731).  The literal mend (``CALM_FRAC`` 1.0, calm = no judged
    sensor out of band) keeps row 24 as calm (T_frame2 +0.395 within 0.400): the share at row 25
    is one sample's change, the pick falls on T_nc_cabinet (z 0.029), its exclusion does not
    resolve the bands and a NEW THERMAL STATE is declared at row 25 (ended row 39); T_frame2
    warned only, T_frame1 out by its own freeze check at row 30; RMS 0.923 / 1.726.  A calm
    sample searched only in the window (10 rows) finds none at 0.5 (T_frame2 > 0.2 from row 5):
    the pick on levels, as main -- hence the kept calm errors.  ``CALM_FRAC`` 0.5: calm errors
    T_frame1 +0.015 / T_frame2 +0.193; row 25 shares give z 0.227 / 0.153 -> T_frame1, its
    exclusion resolves the bands, but the regime check holds it (within its band, the excursion
    hovers): T_frame2 warned only, T_frame1 out by its freeze check at row 30 (5 rows after
    main's wrong exclusion), T_frame2 ok at row 30; RMS 0.923 / 1.726 (freeze 60 rows 0.935 /
    1.444, after 0.911 / 1.968), max |C - C_healthy| 0.824 / 1.646 µm (main 8.336 / 5.673).
    CALM_FRAC 0.5 is chosen on this seen cell: a tuned constant, not a measured one.
(2) ``fl drift`` (0.5): main takes T_t14 out at 10294 (-0.40 °C); the prototype takes the
    drifting T_t12 out first at 10294 (+0.32, within its 0.453 band), re-admits it at 10304
    (within band 10 samples), T_t9 warned at 10304, T_t14 out at 10305; from 10498 the same as
    main (T_t12 out by +0.93, T_t14 back).  ``fl clean``: no change.
(3) ``mon85b`` (0.5): main T_t14 warned at row 306, out at 313; the prototype out at 306 (7 rows
    earlier), the rest the same events; served RMSE ch1-ch5 5.61 4.51 4.89 5.53 4.37 -> 5.55
    4.44 4.87 5.50 4.36 µm.
(4) tests/apps/test_monitor_*.py + tests/shell/test_monitor.py with the patch (0.5): 5 failed, 92
    passed, 6 xfailed (main: the three files of the 5, 48 passed 2 xfailed).  test_monitor_lone84:
    the served monitor now excludes the high-leverage T_5 alone at a new source's onset (142 s;
    the mon84 regression back), and the C, unchanged, does not; test_monitor_rounding83: with
    ``rounding_c`` 0 the healthy offset T_0 is no longer excluded (the share of a standing offset
    is small: the pre-mon83 failure the test pins is gone) and the C still excludes it at 12180 s;
    test_monitor.py's column: the first sensor out is T_left1, not the nearest T_right3/T_right4
    (mon84's case).  Why the shares undo mon84's picks: not traced (time).
(5) bench_mon87's ``trace`` (healthy53 column record, seed 5305): the same events (T_left1
    warned 63100-63200 s, nothing out), served RMSE unchanged.  bench_mon85b's ``trace`` (drift):
    as (2).  bench_mon84's ``column`` on its spent seeds 8686-8693 (healthy + 4 faults, 40
    records; ``ctable``): served RMSE within 2 % of main on every record, T_front1's first row
    out the same on all 32 faulted; T_right4 (healthy) briefly out at the unseen Q3's onset
    (rows 730-734): main 19 of 40 records (seeds 8686, 8688, 8689, 8693), the prototype 18
    (8688, 8689, 8692, 8693: 8686 spared, 8692 new, 8688's drift spared).  ``trunnion``
    8694-8695 and ``lathe`` 8696-8697 (10 records each, 0.1 K logger; ``table``): the same
    sensors out at the same hours, the same RMSE.  Run as ``bench_mon84.py column ROOT LABEL
    8686-8693`` / ``trunnion`` / ``lathe ROOT LABEL SEEDS`` with ``PYTHONPATH`` main's src or
    the patched one.  Not run: ``jig`` 8698-8700, mon83-mon86b's own ``score``/column seeds.
CPU: ``cell`` 1.3-2.9 s, ``fl`` 3.3-4.1 s, ``mon85b`` 2.9-3.2 s (user + sys); mon84 ``column``
8686-8693 37 s user (82 s wall, two at once), ``trunnion`` / ``lathe`` 92-96 s user each
(201-208 s wall).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402


def _frac(frac: str | None) -> None:
    """Set the patch's ``CALM_FRAC`` (say so on main, where there is none)."""
    from thermocomp.apps.deploy.surveillance import judgement

    if not hasattr(judgement, "CALM_FRAC"):
        print("this tree has no CALM_FRAC (main): the culprit picked on error levels")
    elif frac is not None:
        judgement.CALM_FRAC = float(frac)
    if hasattr(judgement, "CALM_FRAC"):
        print(f"CALM_FRAC {judgement.CALM_FRAC}")


def cell(root: str, frac: str | None = None) -> None:
    """bench_blame95's ``trace`` on ``root`` (module doc)."""
    from bench_blame95 import trace

    _frac(frac)
    trace(root)


def fl(case: str, frac: str | None = None) -> None:
    """bench_mon87's ``fl`` (module doc)."""
    import bench_mon87

    _frac(frac)
    bench_mon87.main(["fl", case])


def mon85b(frac: str | None = None) -> None:
    """bench_mon87's ``mon85b`` (module doc)."""
    import bench_mon87

    _frac(frac)
    bench_mon87.main(["mon85b"])


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"cell": cell, "fl": fl, "mon85b": mon85b}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
