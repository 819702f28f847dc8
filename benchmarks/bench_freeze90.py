"""A frozen sensor that other sensors predict: constant far longer than any constant run of its
training, taken for frozen whether or not its field moved by its warning band (issue 34; stop
90, lead90).  REFUSED (src as on main; the rule: ``benchmarks/freeze90_rule.patch``)

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_freeze90.py audit ROOT RECORDS    # bench_audit89: healthy, then faults
    python benchmarks/bench_freeze90.py climate ROOT SEEDS    # bench_mon88: fresh (planted T_amb)
    python benchmarks/bench_freeze90.py traced ROOT           # bench_mon88: lr9171 and cr9031
    python benchmarks/bench_freeze90.py truth ROOT SEEDS      # the climate rooms, no fault planted

Each command runs another bench's with this tree's code (run it twice: main's src, this tree's,
into two ROOTs): ``audit`` = ``bench_audit89.py healthy ROOT RECORDS`` then ``faults ROOT
RECORDS`` (healthy records' events, the six injected faults on the sensor whose fault costs most,
served and compiled C); ``climate`` = ``bench_mon88.py fresh ROOT SEEDS`` (climate rooms with
``T_amb`` frozen from a third of each test campaign and a spike; long records as drawn);
``traced`` = ``bench_mon88.py traced ROOT``.  ``truth``: the same climate rooms drawn as
``climate`` draws them, nothing planted (the model fed the true readings): replay RMSE per target
-> ``ROOT/truth.json``, the reference of the bar question below.

The rule (served ``InstantFaults._frozen``; the export's numpy mirror and C behind the
compensator.json key ``long_freeze``, absent in an export before it: the old rule)
---------------------------------------------------------------------------------------
A reading unchanged for more than ``blind_run`` samples (``freeze_factor`` 2 times its longest
constant run in training, at least the window) is frozen whatever its field did; before, that
held only for a sensor no other predicts, and a predicted one was frozen only where the others'
prediction of it moved by its warning band.  Why: audit89 froze fl_thermal's ``T_t11`` (the
shipped measured record) from the middle of its test part; its field moved 0.28 °C, within its
0.728 °C band, and it was never detected (error 4.06 -> 4.79 µm).  A noisy sensor's longest
constant run in training is 1-2 samples (every fl_thermal sensor: 1), so a healthy one does not
repeat itself for the window; a quantised one's longest run sets its own bar.

Bar (written after the fl_thermal and cr9031 traces below, before the healthy audit and the
climate rooms 9201-9205 were scored with the rule): detection of the frozen fl ``T_t11``; healthy
audit records (bench_audit89's 9316-9325, fl) event for event as main; on 9201-9205 the planted
frozen ``T_amb`` detected in no fewer test campaigns than main and no (record, target) more than
2 % worse than main; C = served wherever the key is set.  The seen cr9031 row below (E_Z +2.1 %)
is past that 2 % and is reported, not hidden: its frozen ``T_amb`` is now out in all three test
campaigns (main: C10 by a freeze, C11 by a drift after a healthy partner's false exclusion, C12
never), the model fed the field's estimate of the ambient where main fed it the frozen value.

Scored (2026-12-05; main ca338ef6 vs fix/lead90; 2 cores, ``OMP_NUM_THREADS=1``)
--------------------------------------------------------------------------------
* fl_thermal (``audit /tmp/lead90/aud fl``): frozen ``T_t11`` detected after 11 samples
  (``freeze: 25.88 °C for 12 samples (longest constant run in training 1)``); adaptive RMSE 4.787
  -> 3.605 µm (healthy 4.060); dropout / spike / step / drift / range rows as main; C = served,
  pack whole, check.sh exit 0 (with the rule served-only the pack was cut at the planted freeze
  copy's row 10571: hence the key).
* Healthy ``audit /tmp/lead90/audh 9316-9325``: every row as audit89's main table, events,
  exclusions (0), RMSE fixed / adaptive, C = served on 10 of 10 (133 s CPU).
* ``traced``: lr9171 identical (E_Z 0.7845 µm, the same three events); cr9031 (frozen T_amb):
  E_X 2.2061 -> 2.1905, E_Z 4.0247 -> 4.1111 µm (+2.1 %); events: T_amb out by a freeze at 4380 /
  4740 / 5400 s in C10 / C11 / C12 (main: C10 at 4560 s, C11 a drift at 5040 s with the healthy
  T_nc_cabinet excluded beside it, C12 never).
* ``climate 9201-9205`` (``bench_mon88.py compare``): the frozen ``T_amb`` out in all 15 test
  campaigns (main: out at the end on 2 of 5 records), but per (record, target) cr9201 E_X 0.7674
  -> 0.8181 (+6.6 %), E_Z 1.6949 -> 1.7463 (+3.0 %); cr9203 E_X 1.9704 -> 2.0485 (+4.0 %), E_Z
  3.6758 -> 3.7606 (+2.3 %); cr9202 +0.6 / -1.1 %; cr9204 -7.2 / -9.5 %; cr9205 -2.2 / -2.6 %.
  Bar FAILED (4 rows past 2 %): REFUSED, src reverted, the rule kept as
  ``benchmarks/freeze90_rule.patch`` (served ``_frozen``, the mirror and C behind ``long_freeze``);
  with it, tests/shell/test_export_freeze90.py (3 tests, failing on main) was written and dropped.
* Reading: the fourth rule (after mon88's rule A, mon89, mon89b) that reads the sensors right and
  loses to main on the error: a climate room's frozen ``T_amb`` replaced by the field's estimate
  (from the cabinet sensor) serves MLR worse on some rooms than the frozen value.  The bar question
  stands (stop 89's note): deployed against the model fed the true readings, or against main.
* The true readings (``truth /tmp/lead90/truth 9201-9205``, measured after the verdict; it does
  not change it), E_X / E_Z µm: cr9201 0.788 / 1.704, cr9202 1.831 / 2.600, cr9203 2.012 / 3.816,
  cr9204 1.391 / 3.275, cr9205 1.059 / 1.538.  Main with the faults is BELOW the truth on cr9201
  (0.767 / 1.695) and cr9203 (1.970 / 3.676): the two records the rule "loses" are ones where the
  frozen ambient happened to serve better than the true one.  Rows more than 2 % above the truth:
  main 4 (cr9204 E_X +2.4 %, E_Z +5.7 %; cr9205 E_X +8.2 %, E_Z +5.7 %), the rule 4 (cr9201 E_X
  +3.8 %, E_Z +2.5 %; cr9205 E_X +5.9 %, E_Z +2.9 %); geometric mean of RMSE / truth over the 10
  rows: main 1.012, the rule 1.004.  Against the truth neither passes a 2 % row bar; the rule is
  the nearer on average.  The next stop's bar (decided before its scoring) can be written against
  the truth.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_audit89 as audit89  # noqa: E402
import bench_mon88 as mon88  # noqa: E402
from _cli import run_commands  # noqa: E402


def audit(root: str, records: str) -> None:
    audit89.main(["healthy", root, records])
    audit89.main(["faults", root, records])


def climate(root: str, seeds: str) -> None:
    mon88.main(["fresh", root, seeds])


def traced(root: str) -> None:
    mon88.main(["traced", root])


def truth(root: str, seeds: str) -> None:
    folder, results = mon88._root(root), {}
    for seed in mon88.seed_list(seeds):
        _, sim, extra = mon88.FRESH[seed]
        name = f"cr{seed}"
        data = mon88._drawn(name, seed, sim, folder)            # (not planted)
        results[name] = mon88.replayed(folder, name, data, ("model=mlr",), extra)["rmse"]
        print(name, results[name], flush=True)
    (folder / "truth.json").write_text(json.dumps(results, indent=1))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"audit": audit, "climate": climate, "traced": traced,
                                   "truth": truth}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
