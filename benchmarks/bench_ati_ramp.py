"""ATI when some training runs ramp the room: why ``model=auto`` lost rig40, and the mend.

    .venv/bin/python benchmarks/bench_ati_ramp.py DIR [--only 'rig40 s0' lathe43m]   # the table

``rig40`` (``benchmarks/bench_other_machine.py``, seed 0): 9 runs, 6 train (run_1 and run_5 ramp
the room 20 -> 30 °C, the others held at 20 / 25 / 30 / 15 °C), test run_7 (held 20), run_8 (25),
run_9 (ramp).  ``model=auto`` tested E_X 0.72 µm against MLR's 0.56.

Diagnosis (test RMSE µm, E_X unless said; numbers of this session):

* ATI (``mlr ati=cmeans``) chose 4 intervals for E_X (boundaries 17.5 / 22.5 / 27.5 °C); run_7
  was predicted by the 20 °C interval's model, fitted on run_1, run_2, run_5, which started at
  19.97 / 19.99 / 19.98 °C.  ATI counted three distinct ambients there (to 1e-6 °C) and gave that
  model the interaction ``x (A0 - 20 °C)``, a slope fitted on 0.02 K; run_7 started at 20.08 °C:
  0.91 against MLR's 0.37 (run_8 0.34 vs 0.65, run_9 0.45 vs 0.85).  E_Z: 1 interval, 0.66 / 0.58
  / 0.55 against MLR's 0.86 / 0.79 / 0.85.
* Not the ramp: MLR fitted on the same three runs (two ramped, one held) without the interaction
  predicts run_7 at 0.32 (E_Z 0.65), better than MLR on all six (0.37 / 0.86).
* The folds: auto's 3 blocked forward folds (E_X) (fit run_1..3 -> run_4, run_1..4 -> run_5, run_1..5
  -> run_6) had ATI choose one interval with the interaction (0.54 / 0.32 / 0.36 against MLR's
  1.02 / 0.46 / 0.93): a fair win of a model that the refit on six runs did not keep.  On E_Z the
  same bug gave ATI 221 µm in the last fold (run_6 at 14.9 °C through an interval of the three
  20 °C runs): its E_Z validation RMSE 136 µm (bench_other_machine's note).
* The elbow: its leave-one-campaign-out never saw the bogus slope of the final 20 °C interval
  (each fold leaves two of its runs: two ambients, no interaction), and SM + SD 0.52 (4 intervals)
  beat 0.65 (1).

Mend (adopted): an interval takes the interaction only with three ambient *levels*, initial
ambients 0.5 °C apart (``thermocomp.core.models.ati.ambient_levels``), the count ``model=auto``
already used (by rounding) to try ``ati`` at all.  Written down before scoring, also tried:
the number of intervals capped by the levels too (``V2``): the same figures but lathe43 E_dZ
0.729 against 0.711: not adopted.  The ramp remedies (key rows on the current ambient; the
interaction with A(t); ramped runs training every interval they cross) were not tried: the ramp
was not the cause.

Test RMSE (µm, per target) before -> after, ``thermocomp run`` defaults (``track=false
plots=none``), 2 shared cores; records as below (``sim=climate_room seed=S`` /
``sim=yearround_spindle`` written by ``thermocomp simulate``; rig40 seeds by
``bench_other_machine.py write --seed``, fixed before running)::

    record        mlr                 mlr ati=cmeans                       auto
    rig40 s0      0.558 / 0.837       0.715 / 0.620 -> 0.371 / 0.620       0.715 / 0.804 -> 0.365 / 0.609
    rig40 s1      0.572 / 0.944       0.563 / 0.674    (same)              0.563 / 0.830 -> 0.561 / 0.756
    rig40 s2      0.371 / 0.618       0.324 / 0.990 -> 0.346 / 0.578       0.329 / 0.615 -> 0.331 / 0.599
    lathe43       0.416 / 1.229       0.375 / 0.755 -> 0.375 / 0.711       0.396 / 0.755 -> 0.391 / 0.711
    lathe43m      0.426 / 1.048       0.408 / 0.582    (same)              0.413 / 0.551    (same)
    yearround     0.750/1.424/5.802   0.780/0.910/0.994 (same)             0.651/0.793/0.994 (same)
    climate 5501  1.625 / 2.938       0.427 / 0.828    (same)              0.427 / 0.828    (same)
    climate 5502  1.505 / 2.499       0.639 / 0.920    (same)              0.639 / 0.920    (same)
    climate 5601  0.992 / 2.088       0.372 / 1.125    (same)              0.372 / 1.125    (same)
    climate 5602  2.117 / 3.171       0.629 / 0.975    (same)              0.629 / 0.975    (same)
    vendor5       (not run)           0.315 / 0.599    (same)              0.509 / 0.842    (same)

One figure got worse: rig40 s2 ``mlr ati=cmeans`` E_X +0.022 (per test run +0.069 / +0.054 /
-0.015: E_X now 2 intervals, before 1 with the interaction), within the noise: the three rig40
seeds' MLR E_X spread 0.37 .. 0.57, and that record's E_Z fell 0.99 -> 0.58.  CPU (user + sys)
unchanged: rig40 auto 8.7 -> 8.6 s, lathe43 auto 54 -> 50 s, climate auto 31-36 s either way.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from bench_other_machine import QUIET, thermocomp, write  # noqa: E402

MODELS = {"mlr": ("model=mlr",), "mlr ati=cmeans": ("model=mlr", "ati=cmeans"), "auto": ("model=auto",)}
CLIMATE_SEEDS = (5501, 5502, 5601, 5602)
RIG_SEEDS = (0, 1, 2)


def records(root: Path) -> dict:
    """Name -> the ``run`` overrides that read it; writes every record under ``root``."""
    out = {}
    for seed in RIG_SEEDS:
        write(root / f"om{seed}", seed)
        out[f"rig40 s{seed}"] = [f"data.path={root / f'om{seed}' / 'rig40'}"]
    status, *_ = thermocomp("init", str(root / "om0" / "lathe43"), "data.max_gap_samples=2",
                            f"out={root}/init")
    assert status == 0, "init refused the lathe's folder"
    out["lathe43"] = [f"hydra.searchpath=[file://{root}/init/conf]", "data=lathe43"]
    out["lathe43m"] = [f"data.path={root / 'om0' / 'lathe43m'}"]
    sims = {"yearround": ["sim=yearround_spindle"]}
    sims.update({f"climate {s}": ["sim=climate_room", f"seed={s}"] for s in CLIMATE_SEEDS})
    for name, args in sims.items():
        path = root / name.replace(" ", "_")
        if not (path / "campaigns.csv").exists():
            status, *_ = thermocomp("simulate", *args, f"data.path={path}", "track=false")
            assert status == 0, f"simulate {args} failed"
        out[name] = [*args, f"data.path={path}"]
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("root")
    parser.add_argument("--only", nargs="+", help="record names, e.g. 'rig40 s0' (default: all)")
    args = parser.parse_args(argv)
    root = Path(args.root).resolve()
    for name, data in records(root).items():
        if args.only and name not in args.only:
            continue
        cells = []
        for model, overrides in MODELS.items():
            out = root / "out" / f"{name}-{model}".replace(" ", "_")
            status, cpu, _, err = thermocomp("run", *data, *overrides, *QUIET, f"out={out}")
            if status:
                cells.append(f"exit {status}")
                continue
            targets = json.loads((out / "metrics.json").read_text())["targets"]
            cells.append("/".join(f"{t['test']['rmse']:.3f}" for t in targets.values()) + f" ({cpu:.0f} s)")
        print(f"{name:13s} " + "   ".join(f"{m}: {c}" for m, c in zip(MODELS, cells)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
