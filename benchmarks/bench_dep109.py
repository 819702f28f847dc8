"""The C equals replay where a sensor beyond range since the first sample returns on a row the C
skips, or on a row two other sensors jump together (dep109, issue 34 "deployed as scored").

Usage (from the repository root, ``PYTHONPATH=<tree>/src``)::

    python benchmarks/bench_dep109.py score ROOT DATA COLUMN PUSH MODE BASESRC
    python benchmarks/bench_dep109.py healthy ROOT BASESRC RECORD [RECORD ...]

bench_dep108's commands, with three MODEs more (the return row ``r = n // 3`` of each test campaign
of ``n`` rows; COLUMN +PUSH on rows ``0 .. r - 1`` as bench_dep108's ``back``):

* ``backfar``: and on row ``r`` alone :data:`OTHERS` [0] +PUSH (beyond its range: the row the C
  passes by, ``mon_beyond``);
* ``backpair``: and :data:`OTHERS` both +:data:`PAIR_STEP` degC from row ``r`` on (a pair jump on
  the return row);
* ``backspike``: and :data:`SPIKERS` +:data:`PAIR_STEP` on rows ``r - 6 .. r - 1`` / ``r - 5 .. r - 1``
  (each out for a lone jump while the air is beyond range), both back on the return row: a pair
  jump of two sensors out, where the C's and the mirror's ``mon_pair_jump`` try a spike's return
  first; served (monitor.py ``_update``) tries none on a row with a value not finite (the late one).

The sensors (fixed before any fresh record is scored): :data:`OTHERS` are the first two monitored
sensors after COLUMN in the model's input order, :data:`SPIKERS` the first two of them the others
predict (the monitor's ``predictable``: a spike's return is tried on those only); on the seen
record T_1, T_2 and T_1, T_3.

TRACE (BASE = 348af997, the seen record: bench_dep108f's, ``bench_st107b.py room`` +
``bench_diag107b.py chain`` in /tmp/dep109/droot; T_amb +30 on rows 0-39 of each of the 4 test
campaigns of 120 rows).  The C passes a row by (``mon_beyond`` -1, ``return`` before the late
reference) only where it flags ``TC_MON_NOT_IN_CODE``: every reading beyond range, one of a sensor
it does not hold out, or a set whose operator it has not.  On this record every sensor is held
(MON_SECOND_INSTANT / SECOND_RANGE 1, 8 sensors, min_active 7): T_1 +30 on row 40 (``backfar``),
T_2, T_1 + T_3, T_1 + T_2, all seven others +60, T_1 on rows 40-41: the C equals replay on every
row (<= 2.2e-13 um), no flag, the late reference taken on row 40 as served.  A pair jump on the
return row (T_1 + T_2 +3, T_1 + T_3 +3 or +1, T_3 + T_5 +3) likewise.  ``backspike``: equal too,
for want of a field: served tries a spike's return only where ``min_active`` sensors stay in
(``_rebuilds``), never with the air and two jumpers out of 8 here.  So where the C tries one on a
late row and served does not needs ``n - 3 >= min_active``: not on this record.

BAR (committed before fresh 10201-10203 are drawn; not moved after).  BASE = 348af997's src
(``git archive``), RULE = this branch's.
* H1 seen: ``backfar`` / ``backpair`` / ``backspike`` T_amb +30: RULE |C - replay| <= 1e-9 um on
  every row, 0 rows flagged ``mon_not_in_code``; |JSON - C| <= 1e-9 um.
* H2 fresh 10201, 10202, 10203 (each ``bench_st107b.py simulate DATA SEED room`` once, then
  ``bench_diag107b.py chain``): the same three modes, as H1 (a row the C flags: said, with why).
* H3 no other case changed: the seen ``back`` / ``all`` / ``step`` +30, ``ramp`` +10, ``step`` +5,
  C stdout (``--flags``) identical to BASE's; the 13 healthy records of bench_dep108 byte-identical.
  (The review's move of ``by_field`` after the ``continue`` in the late loop: no output change, H3.)
* H4 where src changes behaviour: a test in test_export_lean107b (< 2 s CPU) that fails on BASE.
* KEPT where a src rule changes a case and H1-H4 hold; TRACED where BASE already meets H1-H2 (the
  by_field move kept if H3 holds); REFUSED where a rule misses (src at BASE, the rule in
  benchmarks/dep109_rule.patch).

RULE (watch_c.py ``mon_pair_jump``, watch.py ``_pair_jump``, in step): no spike's return tried on
a sample with a value not finite (the late row), as served; ``by_field`` after the ``continue``.

SCORED (2026-12-07, the bar 4ffd5c68 / 7bc7f82f unchanged; BASE /tmp/dep109/basesrc = ``git
archive 348af997 src``; CPU user + sys of the bench with its children, ``/usr/bin/time``):
* H1 met.  Seen ``backfar`` / ``backpair`` / ``backspike``: BASE and RULE 8.0e-15 / 8.0e-15 /
  2.2e-13 um, stdout identical, 0 flag rows; |JSON - C| <= 1.4e-14 um (~10.5 s CPU each).
* H2 met.  Fresh 10201 / 10202 / 10203 (12 monitored, min_active 7; diagnose took a lean law on
  E_X and E_Z each; OTHERS = SPIKERS = T_headstock, T_guidebush): ``backfar`` 4.3e-14 / 2.8e-14 /
  1.1e-13 um and ``backpair`` 2.8e-14 / 3.6e-14 / 9.2e-14 um, BASE = RULE, stdout identical, 0 flag
  rows: the C passes no such row by (it does only where it flags ``TC_MON_NOT_IN_CODE``).
  ``backspike``: BASE 0.292 / 0.562 / 0.477 um off replay on 1443 / 1404 / 1477 rows, unflagged
  (the pair read back in as spikes on the return row); RULE 3.6e-14 / 4.6e-14 / 1.0e-13 um, 0
  flag rows; |JSON - C| <= 4.3e-14 um.  ~12-16 s CPU a score.
* H3 met.  Seen ``back`` / ``all`` / ``step`` +30, ``ramp`` +10, ``step`` +5: stdout identical
  (~10-13 s CPU each).  The 13 healthy records: C stdout byte-identical on each (121 s CPU).
* H4 met.  test_export_lean107b ``test_two_sensors_back_from_a_jump_on_the_air_s_return_row_are_no_
  spike_there`` (its record: diag107's with T_1, T_3, T_5 twinned, 6 campaigns): fails on BASE
  (1.44 um), passes; marginal CPU 0.83 / 0.72 / 1.18 s (3 paired runs).
* The ST (not changed) on the test's case: off the C on all 120 rows (<= 8.0 um), every one
  flagged (``mon_unsure``, st108d's first-sample rule, or refused).
"""

from __future__ import annotations

import sys
from pathlib import Path

import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_dep108  # noqa: E402
from _cli import run_commands  # noqa: E402

OTHERS = ["T_1", "T_2"]     # (set per record by :func:`score`)
SPIKERS = ["T_1", "T_3"]
PAIR_STEP = 3.0     # degC: past each one's jump limit, within range
_back = bench_dep108._changed


def _changed(df: pd.DataFrame, column: str, push: float, mode: str) -> pd.DataFrame:
    if mode not in ("backfar", "backpair", "backspike"):
        return _back(df, column, push, mode)
    df = _back(df, column, push, "back")
    r = len(df) // 3
    if mode == "backfar":
        df.loc[r, OTHERS[0]] += push
    elif mode == "backspike":
        df.loc[r - 6:r - 1, SPIKERS[0]] += PAIR_STEP
        df.loc[r - 5:r - 1, SPIKERS[1]] += PAIR_STEP
    else:
        df.loc[r:, list(OTHERS)] += PAIR_STEP
    return df


bench_dep108._changed = _changed


def score(root: str, data: str, column: str, push: str, mode: str, basesrc: str) -> None:
    """bench_dep108's ``score``, :data:`OTHERS` and :data:`SPIKERS` of this record's monitor."""
    import os

    from hydra import compose, initialize_config_dir

    from thermocomp.apps.deploy.export import state_space
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    base, here = bench_dep108.project_root(root), os.getcwd()
    os.chdir(base)
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[f"data.path={Path(data).resolve()}", "track=false"])
    ds, train_ids, _, _ = read_streamed(cfg)
    deployed = deployable_model(cfg, ds, train_ids, str(base / "run" / "model.pkl"), "export.model")[0]
    ss = state_space(deployed, monitor=True)
    m = ss.monitor
    names = [ss.inputs[i] for i in m["inputs"]]
    after = [k for k, name in enumerate(names) if name != column]
    OTHERS[:] = [names[k] for k in after[:2]]
    SPIKERS[:] = [names[k] for k in after if m["predictable"][k]][:2]
    print(f"OTHERS {OTHERS}, SPIKERS {SPIKERS}; {len(names)} monitored, min_active {m['min_active']}")
    os.chdir(here)
    bench_dep108.score(root, data, column, push, mode, basesrc)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"score": score, "healthy": bench_dep108.healthy}, argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
