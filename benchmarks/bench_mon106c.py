"""Which rule moves replay off run on the long healthy records (issue 34; stop 106, mon106c: TRACED).

Issue 34 wants replay of a record cut in two = ``run`` to 1 %.  This stop found replay off run on
lw10088 (bench_ati106b: -1.39 % on ``ati=days``, -1.47 % on BASE's ``ati=cmeans`` model) and on the
lab record of bench_audit106 (lagbank +5.5 %); mon106 (REFUSED) traced ed10035's +5.2 % to
``Judgement._explaining`` blaming T_hall / T_cabinet on a machine-off weekend training never saw.

``trace`` replays one model as ``thermocomp replay`` does (the stage itself, monitor and guard on,
warmed on the lead-in) and reads, per test campaign and target, the rows where the deployed
correction leaves the batch one (run's), the largest gap, and what those rows add to the squared
error (dSSE, µm², stream minus batch; < 0: replay nearer the truth), and the events by reason.

Usage (repository root, ``PYTHONPATH=<tree>/src``; the records as their benches made them)::

    python benchmarks/bench_mon106c.py trace DATA MODEL [OVERRIDE ...]

e.g. DATA ``/tmp/ati106b/root/data/lw10088``, MODEL ``/tmp/ati106b/root/reports/lw10088/base/model.pkl``
(``bench_ati106b.py cells ROOT lw10088 base`` on 1707a192); la10087 the same; lr10060 from
``bench_ati106.py``; ed10035 ``/tmp/mon106/root`` (``bench_mon106.py seen``, mlr / lagbank); the lab:
DATA ``L/contract.csv``, MODEL ``L/contract-lagbank/model.pkl``, overrides
``hydra.searchpath=[file://L/contract-init/conf] data=contract data.test_fraction=0.25``
(``bench_audit106.py lab``, L = ROOT/L/lab10068).

MEASURED (c668e59b's src, 2026-12-07, 2 cores shared; CPU user+sys 2.3-5.1 s a trace)::

  record    model        replay/run-1  rows moved  rule (reason)                    dSSE µm²
  lw10088   mlr cmeans   -1.47 %       21 of 4032  _check_stepped (jump: self-pred.  -128.07
            (BASE)                     (R1b 2600-2620) error stepped -2.27 °C)      (-127.80 on 3 rows)
  lw10088   mlr ati=days -1.39 %       21 (the same) _check_stepped                   -106.17
  la10087   mlr cmeans   -1.5e-05      20 of 4032  _check_stepped (-1.05 °C)         -0.16
  lr10060   mlr cmeans   0             0           none (0 events)                  0
  ed10035   mlr          +5.7 / +3.9 % 429 D7 + 738 D8  Judgement._explaining        +1770 +3539 (E_X)
            lagbank      +11.7 / +1.8 %  982 + 1440    (T_hall, T_cabinet; 9 out)   +5436 +5622 (E_X)
  lab10068  lagbank      +5.5 / +6.5 % 16 / 11 of 361  CorrectionGuard (correction    +134.1 / +38.7
                                                     bounded; 0 monitor events)

lw10088: ``sim=long_record`` plants ``n_temperature_outliers: 4`` spikes (1-3 samples, ±1-5 °C).
One is T_bed_right at R1b rows 2600-2602 (18.91 -> 16.65, 16.63, 16.68 -> 19.06 °C).
``InstantFaults._check_stepped`` (faults.py) excludes it there.  The field's prediction stands in
for 21 rows, until ``re-admitted: within ±0.2 °C for 21 samples``.  Run's batch prediction takes the
spike: it corrects 5.2-5.3 µm too far on those 3 rows (residual -6.6..-6.7 µm; replay's
-1.4..-1.6).  On the 18 rows after it, the gap is ±0.14 µm.  The lead-in's two exclusions
(R1a spikes: T_col_front_low +3.81, T_bed_right -4.5 °C) leave no row of R1b moved.  Replay is
nearer the truth than run: the monitor does its job.  The same holds for la10087 (T_head_right
18.77 -> 17.72 for 2 rows).

lab10068: the CorrectionGuard (guard.py), not the sensor monitor.  The test run's error reaches
-13.9 µm.  Training's range, widened by the margin and the inputs' allowance, bounds the correction
at -8.31 µm, and from there it widens by only 0.05-0.34 µm a row.  Run's batch follows the truth.
ed10035: mon106's mechanism (a healthy slow state training never saw), 9 exclusions.

So three mechanisms, none shared, none general: a sensor spike the monitor rightly removes (no
rule should quiet it: run is the worse figure), a correction bound past training's error range,
and the machine-off weekend mon105e / mon106 refused.  No rule built; fresh 10115-10117 not drawn.
"""

from __future__ import annotations

import contextlib
import io
import json
import sys
from collections import Counter
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests")]
from _cli import run_commands  # noqa: E402


def _replayed(data: str, model: str, overrides: tuple[str, ...]) -> tuple[dict, dict]:
    """``thermocomp replay`` of MODEL on DATA: (its report, per test campaign the adaptive stream's
    (deployed, campaign frame, streamed rows, lead-in))."""
    from hydra import compose, initialize_config_dir

    import thermocomp.shell.cli  # noqa: F401  (the config's resolvers)
    from thermocomp.apps.deploy import report
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.stages import replay

    caught, streamed = {}, report.stream_rows

    def keeping(deployed, campaign, cid="", file=None, lead_in=None):
        out = streamed(deployed, campaign, cid, file, lead_in)
        if deployed is not report.plain(deployed):     # the deployed stream, not replay's plain one
            caught[cid] = (deployed, campaign, out, lead_in)
        return out

    out_dir = Path(model).resolve().parent.parent / f"{Path(model).parent.name}-mon106c"
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["track=false", "plots=none", f"data.path={data}",
                                                       f"replay.model={model}", f"out={out_dir}",
                                                       *overrides])
    report.stream_rows = keeping
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            rep = replay.replay(cfg)
    finally:
        report.stream_rows = streamed
    return rep, caught


def trace(data: str, model: str, *overrides: str) -> None:
    """Per test campaign and target: the rows the deployed correction leaves run's, and why."""
    from thermocomp.apps.deploy import report

    rep, caught = _replayed(data, model, overrides)
    for cid, (deployed, frame, out, lead) in caught.items():
        comp, targets = report.plain(deployed).compensator, list(deployed.targets_)
        batch = report.batch_prediction(comp, frame, lead)[targets].to_numpy()
        measured = comp.measured({cid: frame})[cid][targets].to_numpy(float)
        for k, target in enumerate(targets):
            gap = np.abs(out.y[:, k] - batch[:, k])
            moved = np.flatnonzero(gap > 1e-6)
            ok = np.isfinite(measured[:, k])
            dsse = np.where(ok, (measured[:, k] - out.y[:, k]) ** 2 - (measured[:, k] - batch[:, k]) ** 2, 0)
            top = np.argsort(gap)[-3:]
            where = f" rows {moved[0]}-{moved[-1]}, largest gap {gap.max():.3f} µm" if len(moved) else ""
            print(f"{cid} {target}: {len(moved)} of {len(frame)} rows moved{where}; dSSE {dsse.sum():+.2f} "
                  f"µm² ({dsse[top].sum():+.2f} on the 3 largest gaps)", flush=True)
        reasons = Counter(e["reason"].split(":")[0][:40] + " -> " + e["to"] for e in out.events)
        print(f"{cid} events {len(out.events)}: {dict(reasons)}", flush=True)
    print("replay/run-1 " + json.dumps({t: round(v["rmse"] / v["rmse_batch"] - 1, 6)
                                        for t, v in rep["targets"].items()}), flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"trace": trace}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
