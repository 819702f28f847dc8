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
