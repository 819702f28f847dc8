"""acc112's 8 (record, target) rows more than 2 % worse after ``thermocomp diagnose``, scored three
ways (stop 112, trace112; a trace, no src change).  The bar: ``benchmarks/trace112_bar.md``.

Usage (from the repository root, ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_trace112.py streams ROOT ACC NAME LABEL [OVERRIDE ...]  # diagnose again
    python benchmarks/bench_trace112.py table ROOT ACC      # the three-way table of the 8 rows

ACC is bench_acc112's ROOT (read only: its ``data/NAME`` where the record was simulated, else its
``root`` as bench_acc112's WRITTEN).  ``streams`` runs ``thermocomp diagnose`` of NAME in this
process (``out=ROOT/out/NAME-LABEL``, ``plots=none``, ``track=false``, OVERRIDEs added) with
``replay`` wrapped: each deployed test stream diagnose scores (the adaptive compensator: sensor
monitor + guard around the envelope-clamped stream) is saved beside its inner stream run on the
same campaign without monitor and guard (``ROOT/npz/NAME-LABEL-{0: before, 1: after}.npz``).
LABEL ``dep``: the defaults; ``off``: ``promote.envelope.policy=off`` (there is no key for the guard
alone: ``monitor.adaptive=false`` drops monitor and guard together, the inner stream); ``nogain``:
the defaults with no model's step gain, so that each streams on the clamped inputs alone, the
low-pass copy of the clamped inputs with no bound from the measured ones (a trace, not a config).  So per
model: ``deployed`` (clamp + monitor + guard, what diagnose reports), ``clamp`` alone (dep's inner
stream), ``adaptive`` alone (off's; monitor + guard, no clamp) and ``none`` (off's inner stream:
equal to run's batch ``*_as_run`` on every row here, checked by ``table``).

Scored (2026-12-08, 50e90778's src, each stream once; 2 shared cores; CPU user + sys per diagnose
4.5-6.7 s a column record, 13.4-13.9 s twin_lathe; ``table /tmp/trace112/b /tmp/acc112``), test RMSE
before -> after (um); ``none`` equals run's batch ``*_as_run`` on every row (checked)::

  row              batch = none        deployed            clamp alone         adaptive alone     clamped in.
  col1403 E_X      1.87 -> 50.0 x26.7  27.0 -> 32.0 x1.18  25.6 -> 36.4 x1.42  23.2 -> 32.2 x1.39  x1.18
  col1514 E_X      2.47 -> 32.8 x13.3  24.8 -> 29.5 x1.19  = deployed           3.98 -> 32.8 x8.25 x1.18
  col1514 E_Z_mid  2.47 -> 9.69 x3.93  1.69 -> 4.45 x2.62  = deployed           2.47 -> 9.69 x3.93 x2.38
  col5791 E_X      1.33 -> 17.4 x13.1  22.9 -> 25.9 x1.13  22.8 -> 25.9 x1.14  7.00 -> 17.4 x2.49  x1.14
  col6511 E_X      1.75 -> 47.5 x27.2  21.6 -> 36.0 x1.67  = deployed           9.49 -> 47.5 x5.01 x1.55
  col6512 E_Z_mid  9.19 -> 8.17 x0.89  3.23 -> 3.80 x1.18  = deployed           9.19 -> 8.17 x0.89 x1.14
  twin_lathe E_Z1  .377 -> .319 x0.85  .372 -> .398 x1.07  = batch (no clamp)   = deployed
  twin_lathe E_Z2  .374 -> .324 x0.87  .372 -> .388 x1.04  = batch (no clamp)   = deployed

(``clamped in.``: ``nogain``'s after / before.) Column records (one train campaign, the test cycle
past it: 418-457 rows clamped before and after). Five rows are the lag itself: the
``lowpass_inputs`` model extrapolates 4-27x worse in batch; the clamp takes most of that back but
costs the base too (col6511 E_X 1.75 -> 21.6), leaving x1.13-2.62. On col1514, col6511, col6512
monitor + guard change no row once clamped (deployed = clamp alone, to the bit); on col1403 the
monitor excludes T_right3 / T_right4 on 557 of 1441 rows, before and after (x1.42 clamped alone ->
x1.18), on col5791 T_right4 on 2 rows and the guard bounds 28 before rows. col6512 E_Z_mid is the
clamp: better in batch and unclamped (x0.89), worse only clamped: on the clamped inputs the base
gains more (9.19 -> 3.23) than the lagged model (8.17 -> 3.80). The measured twin's bound (the
copy's held-step gain, gain61) lets part of the lag's response to the excess through (3.80 against
3.68 on the clamped inputs alone), but with no bound every row stays > 2 % worse (x1.14-2.38): not
the cause. twin_lathe: no row clamped or guarded; the sensor monitor excludes T_amb on 180 test rows
(18 bursts of 10, rows 606-7397 of 8640) and re-admits it each time: after the last burst the
deployed correction departs from the inner stream's for good, before by a constant -0.147 um (E_Z1;
E_Z2 -0.108: an input offset, as surveillance/faults.py keeps a step on re-admission; not traced
further), after by +0.457 rising to +0.653 (E_Z2 +0.651): the same offset moves the lagged model the
other way and 4.4x as far, through its lag. From row 7398 on the after model is 0.694 deployed vs
0.307 (before 0.364 vs 0.385); before it, 0.323 vs 0.321. The deployed path feeds the low-pass copy
the inputs the base reads (clamp and monitor alike): nothing of the lag's is mishandled.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _cli import made_folder, run_commands  # noqa: E402

ROWS = [("col1403", "E_X"), ("col1514", "E_X"), ("col1514", "E_Z_mid"), ("col5791", "E_X"),
        ("col6511", "E_X"), ("col6512", "E_Z_mid"), ("twin_lathe", "E_Z1_error"),
        ("twin_lathe", "E_Z2_error")]


def _words(acc: Path, name: str) -> list[str]:
    data = acc / "data" / name
    if data.exists():
        return [f"data.path={data}"]
    from bench_acc112 import _seen_words

    return _seen_words(name, str(acc / "root"))


def streams(root: str, acc: str, name: str, label: str, *overrides: str) -> None:
    """NAME diagnosed again, each deployed test stream saved beside its inner stream (module doc)."""
    import thermocomp.apps.deploy.streaming as streaming_module
    from thermocomp.shell.cli import main as thermocomp

    folder, saved = made_folder(root), []
    made_folder(str(folder / "npz"))
    replay = streaming_module.replay

    def recorded(streaming, df, lead_in=None):
        deployed = replay(streaming, df, lead_in=lead_in)
        if type(streaming).__name__ == "AdaptiveCompensator":
            inner = replay(streaming.streaming, df, lead_in=lead_in)
            streaming.reset()
            targets = list(streaming.targets_)
            excluded = deployed["excluded_inputs"].fillna("").astype(str).to_numpy().astype(str)
            np.savez(folder / "npz" / f"{name}-{label}-{len(saved)}.npz", targets=targets,
                     deployed=deployed[targets].to_numpy(float), inner=inner[targets].to_numpy(float),
                     measured=df[targets].to_numpy(float), excluded=excluded)
            saved.append(len(df))
        return deployed

    streaming_module.replay = recorded
    step_gain = streaming_module.step_gain
    if label == "nogain":     # every model streamed on the clamped inputs alone (no measured twin)
        streaming_module.step_gain = lambda *args, **kwargs: None
    try:
        argv, sys.argv = sys.argv, ["thermocomp", "diagnose", *_words(Path(acc).resolve(), name),
                                    f"out={folder / 'out' / f'{name}-{label}'}", "plots=none",
                                    "track=false", *overrides]
        status = thermocomp()
    finally:
        streaming_module.replay, streaming_module.step_gain, sys.argv = replay, step_gain, argv
    print(f"{name}-{label}: diagnose exit {status}, {len(saved)} deployed streams saved")


def _rmse(npz: Path, target: str, which: str) -> tuple[float, np.ndarray]:
    d = np.load(npz, allow_pickle=True)      # (excluded: strings)
    k = list(d["targets"]).index(target)
    y = d["measured"][:, k] - d["measured"][0, k]        # first_sample, as diagnose scores it
    return float(np.sqrt(np.nanmean((y - d[which][:, k]) ** 2))), d


def table(root: str, acc: str) -> None:
    folder, acc_dir = Path(root).resolve(), Path(acc).resolve()
    for name, target in ROWS:
        j = json.loads((acc_dir / "out" / name / "diagnosis" / f"diagnosis_{target}.json").read_text())
        ways = {"batch": [j[w]["test_rmse_as_run"] for w in ("before", "after")]}
        for label, which, way in (("dep", "deployed", "deployed"), ("dep", "inner", "clamp"),
                                  ("off", "deployed", "adaptive"), ("off", "inner", "none")):
            ways[way] = [_rmse(folder / "npz" / f"{name}-{label}-{i}.npz", target, which)[0] for i in (0, 1)]
        if (folder / "npz" / f"{name}-nogain-1.npz").exists():
            ways["clamped inputs alone"] = [_rmse(folder / "npz" / f"{name}-nogain-{i}.npz", target,
                                                  "deployed")[0] for i in (0, 1)]
        assert np.allclose(ways["none"], ways["batch"], rtol=1e-6), (name, target, ways)
        assert np.allclose(ways["deployed"], [j[w]["test_rmse"] for w in ("before", "after")], rtol=1e-9)
        _, d = _rmse(folder / "npz" / f"{name}-dep-1.npz", target, "inner")
        print(f"{name} {target}: " + "; ".join(f"{w} {b:.3f} -> {a:.3f} x{a / b:.3f}"
                                                for w, (b, a) in ways.items())
              + f"; rows clamped {j['after']['test_rows_clamped']}, guarded "
                f"{j['before']['test_rows_guarded']}/{j['after']['test_rows_guarded']}, "
                f"monitor-excluded {int((d['excluded'] != '').sum())}")
        if (d["excluded"] != "").any():
            _after_last_exclusion(folder, name, target)


def _after_last_exclusion(folder: Path, name: str, target: str) -> None:
    """Deployed vs inner stream before / after the monitor's last excluded row (twin_lathe)."""
    for i, model in ((0, "before"), (1, "after")):
        d = np.load(folder / "npz" / f"{name}-dep-{i}.npz", allow_pickle=True)
        k = list(d["targets"]).index(target)
        last = int(np.flatnonzero(d["excluded"] != "")[-1]) + 1
        y = d["measured"][:, k] - d["measured"][0, k]
        part = {w: [float(np.sqrt(np.nanmean((y[s] - d[w][s, k]) ** 2)))
                    for s in (slice(0, last), slice(last, None))] for w in ("deployed", "inner")}
        gap = d["deployed"][:, k] - d["inner"][:, k]
        print(f"  {model}: rows < {last} deployed {part['deployed'][0]:.3f} inner {part['inner'][0]:.3f};"
              f" rows >= {last} deployed {part['deployed'][1]:.3f} inner {part['inner'][1]:.3f}; "
              f"deployed - inner at row {last + 2} {gap[last + 2]:+.3f}, at the end {gap[-1]:+.3f}")


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"streams": streams, "table": table}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
