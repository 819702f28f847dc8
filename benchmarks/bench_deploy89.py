"""Deployed as scored, cold and warm-up: the conformance pack's cold campaign and ``monitor``'s
own warm-up report, every family x wrapper on fresh records (stop 89, deploy89; issue 34's
"what is deployed = what was scored").

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_deploy89.py sweep ROOT [RECORD|FAMILY ...]   # the table below

``sweep``: bench_deploy88's cell (its docstring: ``run`` -> ``replay`` warm and cold -> the
plain replay -> ``promote`` -> ``export`` st / onnx / C with its pack -> the compiled C fed the
chain and the raw test file) on this stop's records (:data:`RECORDS`, chosen before any was
simulated), then, per cell: the pack's cold campaigns (``check.json``'s entries with
``cold_start``, each a continuing test campaign streamed from a reset) and ``monitor
monitor.model=<model.pkl> plots=none`` on the same record.  Columns added to deploy88's (µm,
mean over targets): ``Pcold`` the pack's cold figure: the RMSE of ``measured + expected.csv``
over each test campaign's ``.cold`` entry (its own entry where it continues nothing: then warm =
cold), where ``measured`` is the test file's error columns; ``ncold`` the ``.cold`` entries
(should be the continuing test campaigns); ``cut`` the cold entries cut (rows short of the
campaign); ``mon`` monitor.json's ``rmse_adaptive`` (the deployed stream monitor streams);
``mlead`` / ``rlead`` monitor.json's / replay.json's ``lead_in_events`` counts and ``same``
whether the two lists are equal (1) or not (0).

Records (fresh, seeds 9212 and 9306-9310 as given; the generators deploy88's, the choice below
written before any was simulated):

* ``lr9212``, ``lr9306``, ``lr9309``: ``long_record``, 3 days at 1 min, R1b (the last 20 %)
  continues R1a (one train campaign);
* ``dl9307``, ``dl9310``: ``long_record``, 5 days, R1a re-cut into day files D1..D4, R1b
  continues D4 (bench_deploy88.day_files);
* ``cr9308``: ``climate_room``, 12 runs of 3-4 h, the last 3 test: nothing continues (the pack
  has no ``.cold`` entry; warm = cold by construction).

The bar (written before scoring; the rules: the pack's ``<campaign>.cold`` and monitor's
``lead_in_events``, src of fix/deploy89 at 67b284a9, and the tests of tests/shell/test_deploy89.py,
which fail on a0d62dea)::

1. Deployed as scored, warm: in every cell that runs (auto + ati is refused by design, exit 2),
   ``batch`` = ``plain`` = ``run`` and ``replay`` = ``promo`` = ``C`` to 1e-6 relative (7
   digits); ``replay`` leaves ``run`` only where replay's events show the monitor acting (noted
   cell by cell, as deploy88).
2. Cold: ``cold`` = ``pcold`` = ``Craw`` = ``Pcold`` to 1e-6 relative in every cell; ``ncold``
   = the continuing test campaigns (1 on lr / dl, 0 on cr) and no cold entry cut; every pack
   (``check.sh``, the cold campaigns in it) exits 0.
3. monitor: ``same`` = 1 in every cell (monitor's ``lead_in_events`` = replay's, the list);
   ``mon`` = ``replay`` to 1e-6 relative (the same deployed stream), or the difference traced.
4. KEPT when 1-3 hold in every cell run and the tests fail on main; a cell failing 1-2 in the C
   is a defect to mend (or, past the deadline, reported); a cell failing 3 REFUSES monitor's
   part unless mended.

Scored (2026-12-05, fix/deploy89's src at 67b284a9-3ebb80ac: the rules as committed before the sweep;
2 cores shared by 7 helpers, ``cpu`` the cell's CPU s).  Two changes after numbers were seen,
both to the bench's measurement, none to the bar or the rules: (a) ``Pcold`` took the test
file's raw error columns as ``measured``; on cr9308 (read ``first_sample``) that is not what run
scores (0.8037 against 0.8482 on mlr-none, every cr cell), so it now takes them as run scores
them (bench_audit86b.batch, as deploy88's ``C`` column) and cr9308 / dl9307 / lr9212's
``Pcold`` were recomputed from the cells' packs (lr / dl unchanged to the digit: read absolute);
(b) bench_deploy88's ``sweep`` loop is shared (no copy).  A first sweep, meant to stop after
lr9212, ran on beside the second (SIGTERM ends one thermocomp stage, which the bench reads as
an exit 1: lr9306/mlr-none's ``plain`` replay, the one stage it hit); it was killed by PID.

Legend: ``run``, ``replay``, ``cold`` as deploy88 (µm, mean over targets); in every row below
``batch`` = ``plain`` = ``run``, ``promo`` = ``C`` = ``replay``, ``pcold`` = ``Craw`` =
``Pcold`` = ``cold`` to the 7 digits printed, ``mon`` = ``replay``, ``same`` = 1 and every
pack (``check.sh``, its cold campaign included) and ST export exit 0, onnx exit 2 -- except
where the row says; ``ncold`` the ``.cold`` entries, ``lead`` monitor's lead-in events (=
replay's), ``ev`` replay's events in the test campaigns.  ``-ati`` rows equal their ``-none``
row to the digit on lr / dl (one train interval) and are not repeated::

  cell                  run        replay     cold       ncold lead ev  cpu (none / ati)
  lr9212/mlr            1.089157   0.9531205  0.9537126  1     8    4   13.6 / 9.6
  lr9212/pcr            0.7466808  0.7391247  0.73903    1     8    4   9.8 / 9.7
  lr9212/arx            2.060892   0.9969718  1.000395   1     8    4   10.3 / 10.7
  lr9212/lagbank        0.8504522  0.7299449  1.187391   1     8    4   13.3 / 12.9
  lr9212/hammerstein    0.8017601  0.7867866  0.8125232  1     8    4   16.1 / 16.2
  lr9212/arx_rf         2.080488   1.037863   1.041456   1     8    4   26.0 / 26.7  (C, below)
  lr9212/lstm           1.086273   0.954307   0.9552062  1     8    4   52.2 / 46.6
  lr9212/auto-none      0.8256089  0.8100009  0.6924982  1     8    4   18.0; auto-ati exit 2
  dl9307/mlr            1.013143   0.8843581  0.8838452  1     2    4   17.9 / 13.9
  dl9307/pcr            6.008396   5.941834   5.941522   1     2    4   14.7 / 14.4
  dl9307/arx            1.187984   0.9039709  0.9033096  1     2    4   15.7 / 16.0
  dl9307/lagbank        0.663101   0.7542447  5.305391   1     2    4   20.2 / 19.5
  dl9307/hammerstein    0.5304734  0.5052465  4.562071   1     2    4   25.9 / 25.0
  dl9307/arx_rf         1.165275   0.8598465  0.8604102  1     2    4   49.9 / 48.9
  dl9307/lstm           1.076432   0.9433387  0.9427387  1     2    4   90.0 / 88.3
  dl9307/auto-none      0.4324383  0.4811818  4.802107   1     2    4   28.2; auto-ati exit 2
  lr9306/mlr            0.8849595  0.8849595  0.8849595  1     8    0   11.3 / 11.2
  lr9306/pcr            7.414623   7.414623   7.414623   1     8    0   10.6 / 12.2
  lr9306/arx            1.071432   1.071432   1.06976    1     8    0   20.8 / 21.1
  lr9306/lagbank        1.570381   1.557708   8.664031   1     8    0   15.3 / 16.1
  lr9306/hammerstein    2.309152   2.2973     20.34544   1     8    0   19.9 / 20.9
  lr9306/arx_rf         1.191719   1.191719   1.18705    1     8    0   48.1 / 48.6
  lr9306/lstm           0.9322771  0.9322771  0.9320648  1     8    0   58.9 / 54.7
  lr9306/auto-none      0.8849595  0.8849595  0.8849595  1     8    0   10.1; auto-ati exit 2
cr9308 (nothing continues: ``ncold`` 0, no lead-in; warm = cold = every column), none / ati::

  cr9308/mlr            0.8482046 / 0.6143747       cr9308/arx_rf   0.8595478 / 0.7623871
  cr9308/pcr            4.199408 / 1.008933         cr9308/lstm     0.8611862 / 0.6407802
  cr9308/arx            0.8447341 / 0.7713062       cr9308/auto     0.6143747; auto-ati exit 2
  cr9308/lagbank        0.9033184 / 0.549599        (cpu 6-45 s a cell)
  cr9308/hammerstein    0.8260081 / 0.549599

(lr9306 as a second whole sweep gave it, ``sweep ROOT lr9306``: every column equal to the first,
interrupted sweep's where both ran, and ``plain`` on mlr-none = ``run``.)

Not run by the deadline: lr9309 and dl9310 (seeds 9309, 9310 unspent); main's side
(the change adds pack entries and a monitor report only: no warm figure can move; the tests show
main has neither).

Against the bar
---------------
1. Warm: ``batch`` = ``plain`` = ``run`` and ``replay`` = ``promo`` = ``C`` in every cell but
   lr9212/arx_rf (none and ati): ``C`` 1.035993 against ``replay`` = ``promo`` 1.037863 (-0.18
   %).  Traced: R1b row 765 (45840 s) T_motor jumps +4.98 °C; no other sensor predicts it, so
   the served monitor excludes it and serves the arx_rf fallback (the forest refitted without
   T_motor, ``monitor.fallbacks``), which the code cannot hold (export/fallbacks.py: "an arx_rf
   forest ... left out: its exclusion stays flagged FALLBACK"); the C holds T_motor at its last
   reading instead.  The pack says so: both R1b and R1b.cold are cut at row 765 "(the correction
   of the model fitted without a sensor no other predicts (of a kind the code does not hold)
   ...)", 99 of 864 rows unchecked.  A known gap of the code's monitor, not mended here.
   ``replay`` leaves ``run`` where the monitor acted: lr9212 / dl9307 (4 events each: one-sample
   spikes read as jumps, deploy88's cause 1) and, with no test event, lr9306's lag families
   (lagbank 1.5704 -> 1.5577, hammerstein 2.3092 -> 2.2973): 8 lead-in events (deploy88's cause
   2), now reported by ``monitor`` too.
2. Cold: ``cold`` = ``pcold`` = ``Craw`` = ``Pcold`` in every cell but lr9212/arx_rf (the same
   fallback: ``Pcold`` 0.99966 over the 764 rows before the cut, ``Craw`` 1.039593 against
   ``cold`` 1.041456); ``ncold`` 1 on every lr / dl cell, 0 on cr9308; every pack exits 0
   including its cold campaign (60 cells); no cold entry cut but lr9212/arx_rf's.
3. monitor: ``same`` = 1 in every cell (its ``lead_in_events`` = replay's, 8 / 2 / 8 on lr9212 /
   dl9307 / lr9306, none on cr9308; on a0d62dea monitor.json has none) and ``mon`` = ``replay``
   to the digit in every cell.
4. The tests (tests/shell/test_deploy89.py, 3) fail on a0d62dea (KeyError 'B.cold', check.sh
   without it, KeyError 'lead_in_events') and pass on the branch.  By the bar as written: the
   pack's cold campaign and monitor's warm-up report KEPT (1-3 hold in every cell but
   lr9212/arx_rf, whose C gap -- a forest fallback the code does not hold -- is reported, as the
   bar allows past the deadline, and which the new cold campaign cuts and names as the warm one
   does); CPU: the pack streams each continuing test campaign once more (its own rows only).
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path[:0] = [str(HERE)]
from _cli import run_commands  # noqa: E402
from bench_audit86b import batch, stage, test_frames  # noqa: E402
from bench_deploy88 import COLUMNS as COLUMNS88  # noqa: E402
from bench_deploy88 import LONG, cell, extra_of, sweep  # noqa: E402
from cpu import cpu_seconds  # noqa: E402

RECORDS = {
    "lr9212": [*LONG, "seed=9212", "sim.generator.duration_days=3.0"],
    "lr9306": [*LONG, "seed=9306", "sim.generator.duration_days=3.0"],
    "dl9307": [*LONG, "seed=9307", "sim.generator.duration_days=5.0"],
    "cr9308": ["sim=climate_room", "seed=9308", "sim.generator.n_runs=12",
               "sim.generator.duration_h=[3.0,4.0]", "sim.generator.test_fraction=0.25"],
    "lr9309": [*LONG, "seed=9309", "sim.generator.duration_days=3.0"],
    "dl9310": [*LONG, "seed=9310", "sim.generator.duration_days=5.0"],
}
COLUMNS = [*COLUMNS88[:-2], "Pcold", "ncold", "cut", "mon", "mlead", "rlead", "same", "events", "cpu"]


def mean_rmse(residuals: list[np.ndarray]) -> float:
    """Mean over targets of the RMSE of the stacked residuals."""
    r = np.vstack(residuals)
    return float(np.mean(np.sqrt(np.nanmean(r ** 2, axis=0))))


def pack_cold(c_dir: Path, data: Path, measured: dict) -> dict:
    """The pack's cold figure (``Pcold``), its ``.cold`` entries (``ncold``) and those cut;
    ``measured``: the test campaigns' errors as run scores them (:func:`bench_audit86b.batch`)."""
    pack = json.loads((c_dir / "check" / "check.json").read_text())
    entries = {e["campaign"]: e for e in pack["campaigns"]}
    colds = {e["cold_start"]: e for e in pack["campaigns"] if "cold_start" in e}
    residuals = []
    for cid, (_, df) in test_frames(data).items():
        entry = colds.get(cid, entries[cid])
        if entry["lead_in_rows"]:            # a continuing campaign with no cold entry: none to score
            return {"ncold": len(colds), "cut": -1}
        expected = pd.read_csv(c_dir / entry["folder"] / "expected.csv")
        errors = measured[cid][[f"E_{c[2:]}" for c in expected.columns]].to_numpy(float)
        residuals.append(errors[:len(expected)] + expected.to_numpy(float))
    return {"Pcold": mean_rmse(residuals), "ncold": len(colds),
            "cut": sum(1 for e in colds.values() if e["cut"])}


def monitored(out: Path, model: Path, data: Path, extra: list[str]) -> dict:
    """monitor's deployed figure and its lead-in events against replay's (the cold-start replay)."""
    rc, said = stage("monitor", f"data.path={data}", f"out={out}-monitor", f"monitor.model={model}",
                     "plots=none", *extra)
    if rc:
        return {"note": f"monitor exit {rc}: {said[:150]}"}
    mon = json.loads((out.parent / f"{out.name}-monitor" / "monitor.json").read_text())
    rep = json.loads((out.parent / f"{out.name}-replay" / "replay.json").read_text())
    got, want = mon.get("lead_in_events", []), rep.get("lead_in_events", [])
    return {"mon": float(np.mean([r["rmse_adaptive"] for r in mon["targets"].values()])),
            "mlead": len(got), "rlead": len(want), "same": int(got == want)}


def cell89(root: Path, record: str, family: str, wrapper: str, data: Path) -> dict:
    start = cpu_seconds()
    row = cell(root, record, family, wrapper, data)
    out = root / "reports" / record / f"{family}-{wrapper}"
    c_dir = out.parent / f"{family}-{wrapper}-c"
    if "C" in row:                           # deploy88's cell went through to the compiled C
        row.update(pack_cold(c_dir, data, batch(root, out / "model.pkl", data, extra_of(record))[1]))
        row.update({k: v for k, v in monitored(out, out / "model.pkl", data, extra_of(record)).items()
                    if k != "note" or not row.get("note")})
    return {**row, "cpu": cpu_seconds() - start}


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "sweep": lambda root, *chosen: sweep(Path(root).resolve(), list(chosen), RECORDS, cell89, COLUMNS),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
