"""A reading beyond its range and a common step in the exported C (cmon80, issue 34): a faulted
record's corrections from the compiled code with its sensor monitor, without it, and the served
adaptive model's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_cmon80.py faults [ROOT] [SEEDS] [MODEL]

For each seed (default 7996-8010, not used before) ``thermocomp simulate`` (the default
``yearround_spindle``, healthy) into ``ROOT`` (default ``/tmp/cmon80-bench``), MODEL (default
``mlr``) fitted on the
train split and deployed adaptive as ``replay`` deploys it, exported as C (``gcc -std=c99 -Wall
-Wextra -Werror -O2``) once with the monitor (``export.format=c``) and once without it.  Two
faults planted on every test campaign from its middle row (the train split untouched, one fit
per seed):

* ``range``: ``T_motor2`` reads ``+RANGE_C`` °C for ``RANGE_ROWS`` samples (a loose contact, an
  overload the logger does not mark), then healthy again;
* ``common``: every monitored ``T_`` sensor ``+STEP_C`` °C from there to the end (a logger's
  reference changed).

Prints per record the test RMSE (µm, pooled over the test campaigns) per target: fixed (the
plain stream), the served adaptive model, the C without and with its monitor, the largest |C
with monitor - served| over every row, the first row where the code's monitor flagged a rule it
does not hold (per campaign), the rows beyond the range limit (range) and the conformance pack's
rows kept of all, with the copies it plants on the first test campaign listed apart.

This changes no rule of auto / diagnose / monitor (the served monitor is as shipped): the code
is measured against it, so no bar is written.

Measured (2 cores shared with other jobs; 15 seeds, 30 records: 43.0 s user + 2.6 s sys of CPU,
gcc and ``stream`` included, the simulations cached; 47.5 + 2.2 s with 14 of them), E_Z test
RMSE in µm pooled over the 6-8 test campaigns of each record (543-638 rows); "before cmon80": the
same bench on the sources of main at 928bc89a (the C that flagged both rules), its pack's rows
in brackets:

| record | fixed | served adaptive | C no monitor | C before cmon80 | C with monitor | pack rows (before) |
|---|---|---|---|---|---|---|
| range s7996 | 14.927 | 5.662 | 11.655 | 10.334 | 5.662 | 616 / 616 (365) |
| range s7997 | 8.667 | 4.801 | 8.536 | 8.536 | 4.801 | 572 / 572 (284) |
| range s7998 | 7.026 | 6.783 | 7.026 | 7.085 | 6.783 | 607 / 607 (344) |
| range s7999 | 28.757 | 5.099 | 12.924 | 12.376 | 5.099 | 570 / 570 (318) |
| range s8000 | 36.855 | 4.296 | 11.698 | 10.572 | 4.296 | 543 / 543 (334) |
| range s8001 | 17.124 | 6.270 | 11.089 | 11.089 | 6.270 | 570 / 570 (283) |
| range s8002 | 11.685 | 4.319 | 8.744 | 8.744 | 4.319 | 592 / 592 (295) |
| range s8003 | 13.243 | 6.584 | 12.568 | 11.828 | 6.584 | 621 / 621 (342) |
| range s8004 | 15.330 | 5.096 | 11.428 | 11.428 | 5.096 | 584 / 584 (290) |
| range s8005 | 59.822 | 4.836 | 13.561 | 12.573 | 4.836 | 545 / 545 (303) |
| range s8006 | 37.410 | 4.545 | 12.128 | 12.128 | 4.545 | 609 / 609 (304) |
| range s8007 | 5.910 | 4.736 | 5.910 | 5.725 | 4.736 | 607 / 607 (336) |
| range s8008 | 12.045 | 4.003 | 11.460 | 10.209 | 4.003 | 638 / 638 (393) |
| range s8009 | 45.836 | 5.853 | 13.700 | 13.700 | 5.853 | 606 / 606 (301) |
| range s8010 | 30.232 | 6.488 | 11.522 | 11.522 | 6.488 | 615 / 615 (306) |
| common s7996 | 6.531 | 6.113 | 6.531 | 6.531 | 6.113 | 616 / 616 (306) |
| common s7997 | 11.583 | 4.903 | 11.583 | 11.583 | 4.903 | 572 / 572 (284) |
| common s7998 | 10.200 | 6.958 | 10.200 | 10.200 | 6.958 | 607 / 607 (303) |
| common s7999 | 7.916 | 5.462 | 7.916 | 7.916 | 5.462 | 570 / 570 (284) |
| common s8000 | 4.109 | 4.793 | 4.109 | 4.109 | 4.793 | 543 / 543 (271) |
| common s8001 | 8.439 | 6.465 | 8.439 | 8.439 | 6.465 | 570 / 570 (283) |
| common s8002 | 10.486 | 4.431 | 10.486 | 10.486 | 4.431 | 592 / 592 (295) |
| common s8003 | 11.960 | 6.543 | 11.960 | 11.960 | 6.543 | 621 / 621 (309) |
| common s8004 | 10.480 | 5.260 | 10.480 | 10.480 | 5.260 | 584 / 584 (290) |
| common s8005 | 9.034 | 4.951 | 9.034 | 9.034 | 4.951 | 545 / 545 (271) |
| common s8006 | 8.552 | 4.534 | 8.552 | 8.552 | 4.534 | 609 / 609 (304) |
| common s8007 | 9.317 | 4.671 | 9.317 | 9.317 | 4.671 | 607 / 607 (302) |
| common s8008 | 9.015 | 4.289 | 9.015 | 9.015 | 4.289 | 638 / 638 (316) |
| common s8009 | 9.772 | 6.237 | 9.772 | 9.772 | 6.237 | 606 / 606 (301) |
| common s8010 | 11.644 | 6.728 | 11.644 | 11.644 | 6.728 | 615 / 615 (306) |

The C with its monitor gives the served adaptive corrections on every row of every test
campaign of all 30 records (largest |difference| over the three targets 2.5e-13 µm; before: up
to 63.1 µm on a range fault, 17.6 µm on a common step) and no rule it does not hold fires; the
pack keeps every row (before: 4798 and 4425 of 8895).  Its copies planted on the first test
campaign (a jump, a freeze, a dropout, a range reading of ``T_bearing_f1`` and the common step)
are cut where the record's own range fault on ``T_motor2`` comes while the planted sensor is out
(a second sensor out: not in the code), all but the common step, which passes whole; on a
common-step record every copy passes whole but the freeze on 4 of 15 (its cut not traced here).
On s8000's common step the served monitor is worse than the fixed model (4.793 against 4.109
µm): the C follows it, as it should.

With ``lagbank`` (``faults /tmp/cmon80-bench 7996-8000 lagbank``, 19.8 s user + 1.2 s sys): the
same on all 10 records (largest |C with monitor - served| 3.6e-13 µm, no flag, every row kept),
E_Z served adaptive = C with monitor 3.64-7.78 µm against 5.97-20.84 for the C without it.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _ccode import built, built_without_monitor, deployed_on, rmse, streamed  # noqa: E402
from _cli import made_folder, run_commands, seed_list  # noqa: E402

SEEDS = "7996-8010"
KINDS = ("range", "common")
SENSOR = "T_motor2"
RANGE_C, RANGE_ROWS = 40.0, 6          # +40 degC for 6 samples (30 min of 300 s)
STEP_C = 3.0


def _planted(frame: pd.DataFrame, kind: str, monitored: list) -> pd.DataFrame:
    out = frame.copy()
    half = len(out) // 2
    if kind == "range":
        out.loc[half:half + RANGE_ROWS - 1, SENSOR] += RANGE_C
    else:
        out.loc[half:, monitored] += STEP_C
    return out


def _first_flag(ss, frame: pd.DataFrame) -> int | None:
    """The row (1-based) where the code's monitor first flags a rule it does not hold."""
    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.watch import NOT_IN_CODE

    sim = Simulator(ss)
    sim.reset()
    for i, (u, t) in enumerate(zip(frame[ss.inputs].to_numpy(float), frame["time"])):
        sim.step(u, t)
        if sim.watch.flags & NOT_IN_CODE or sim.refused:
            return i + 1
    return None


def record(root: Path, seed: int, model: str = "mlr") -> list[str]:
    from thermocomp.apps.deploy.export import exported_files, state_space
    from thermocomp.apps.deploy.export.pack import conformance_pack, corrections
    from thermocomp.apps.deploy.report import stream_rows
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.shell.cli import main

    data = root / f"healthy-{seed}"
    if not (data / "campaigns.csv").is_file():
        assert main(["-q", "simulate", f"seed={seed}", f"data.path={data}", "track=false"]) == 0
    deployed, ds, test_ids = deployed_on(data, model)
    targets = deployed.targets_
    monitored = list(deployed.monitor.names)
    ss = state_space(deployed, monitor=True)
    k = monitored.index(SENSOR)
    limit = ss.monitor["hi_lim"][k]
    out = []
    with tempfile.TemporaryDirectory(prefix="cmon80-") as tmp:
        with_mon = built(Path(tmp) / "with", exported_files(deployed, "c"))
        without = built_without_monitor(Path(tmp) / "without", deployed)
        cols = ["time", *ss.inputs]
        for kind in KINDS:
            tests = {t: _planted(ds.campaigns[t].reset_index(drop=True), kind, monitored)
                     for t in test_ids}
            errors, fixed, served, code0, code1, flags = [], [], [], [], [], []
            for t, df in tests.items():
                errors.append(df[targets].to_numpy(float))
                fixed.append(-replay(deployed.streaming, df)[targets].to_numpy(float))
                served.append(corrections(ss, stream_rows(deployed, df, t).y))
                code0.append(streamed(without, df[cols]))
                code1.append(streamed(with_mon, df[cols]))
                if (row := _first_flag(ss, df)) is not None:
                    flags.append(f"{t}@{row}")
            _, summary = conformance_pack(deployed, ss, tests)
            listed = [e for e in summary["campaigns"] if "planted" not in e]
            kept = sum(e["rows"] for e in listed)
            total = sum(len(df) for df in tests.values())
            plants = [f"{e['campaign'].split('.', 1)[1]} {e['rows']}"
                      f"{'' if e['cut'] is None else ' cut'}"
                      for e in summary["campaigns"] if "planted" in e]
            worst = max(float(np.max(np.abs(a - b))) for a, b in zip(code1, served))
            beyond = sum(int((df[SENSOR] > limit).sum()) for df in tests.values())
            out.append(f"{kind} s{seed} {model}: pack rows {kept}/{total}; max|C monitor - served| "
                       f"{worst:.2e} um; flags {', '.join(flags) or 'none'}"
                       + (f"; {beyond} rows beyond {SENSOR}'s limit {limit:.2f}"
                          if kind == "range" else "")
                       + f"; planted: {', '.join(plants)}")
            for i, t in enumerate(targets):
                f, s, c0, c1 = (rmse(errors, x)[i] for x in (fixed, served, code0, code1))
                out.append(f"  {t}: fixed {f:.3f}  served adaptive {s:.3f}  C without monitor "
                           f"{c0:.3f}  C with monitor {c1:.3f}")
    return out


def faults(root: str = "/tmp/cmon80-bench", seeds: str = SEEDS, model: str = "mlr") -> None:
    folder = made_folder(root)
    for seed in seed_list(seeds):
        print("\n".join(record(folder, seed, model)), flush=True)


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"faults": faults}, sys.argv[1:] if argv is None else argv,
                        cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
