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

Scored: (filled in after the sweep; nothing above changed after any fresh number was seen).
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
from bench_audit86b import stage, test_frames  # noqa: E402
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


def pack_cold(c_dir: Path, data: Path) -> dict:
    """The pack's cold figure (``Pcold``), its ``.cold`` entries (``ncold``) and those cut."""
    pack = json.loads((c_dir / "check" / "check.json").read_text())
    entries = {e["campaign"]: e for e in pack["campaigns"]}
    colds = {e["cold_start"]: e for e in pack["campaigns"] if "cold_start" in e}
    residuals = []
    for cid, (_, df) in test_frames(data).items():
        entry = colds.get(cid, entries[cid])
        if entry["lead_in_rows"]:            # a continuing campaign with no cold entry: none to score
            return {"ncold": len(colds), "cut": -1}
        expected = pd.read_csv(c_dir / entry["folder"] / "expected.csv")
        measured = df[[f"E_{c[2:]}" for c in expected.columns]].to_numpy(float)[:len(expected)]
        residuals.append(measured + expected.to_numpy(float))
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
        row.update(pack_cold(c_dir, data))
        row.update({k: v for k, v in monitored(out, out / "model.pkl", data, extra_of(record)).items()
                    if k != "note" or not row.get("note")})
    return {**row, "cpu": cpu_seconds() - start}


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {
        "sweep": lambda root, *chosen: sweep(Path(root).resolve(), list(chosen), RECORDS, cell89, COLUMNS),
    }, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
