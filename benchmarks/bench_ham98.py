"""Why hammerstein's warm start scores worse than its cold one on tr9827 (stop 98, ham98; issue 34;
audit97's finding 4: warm, as scored, 1.900 µm against 1.384 cold; the C fed W3 alone = cold).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_ham98.py warmcold ROOT RECORD [FAMILY ...]   # warm / cold / first_sample
    python benchmarks/bench_ham98.py parts ROOT RECORD FAMILY            # warm - cold, by input
    python benchmarks/bench_ham98.py junctions ROOT RECORD               # each link's steps, errors
    python benchmarks/bench_ham98.py weekly ROOT                         # weekly lab files' errors

RECORD: ``tr<seed>`` (trunnion63, stranger63's machine, bench_audit97's ``RECORDS``: weeks W1, W2
train, W3 test, errors every 10th row), ``lr<seed>`` (``long_record``, 3 days, R1b the last 20 %,
bench_deploy88's ``lr9211``) -- simulated into ROOT/data/RECORD where missing -- or ``fl`` (the
shipped fl_thermal, ``data=fl_thermal``: its last 10 % a test part that continues the rest).
FAMILY: default ``hammerstein lagbank mlr``.  ``warmcold``: per family the configured model
fitted as ``run`` fits it (:func:`thermocomp.core.continuation.fit_joined`) with
``data.reference=auto`` -- test RMSE per target (µm, measured rows) warm (the state carried over
from the campaigns the test continues: what ``run`` scores, ``replay`` and the export's check
pack stream) and cold (the test campaign alone, streamed from a reset at its first row: what
the compiled C fed the test file alone gives) -- then refitted with ``data.reference=first_sample``
(each campaign from its own first sample; nothing carried over).  ``parts``: warm - cold of the
test campaign split by input: the lead-in with one column held at the test campaign's first
value (that column's lags start as cold), RMS of each part.  ``junctions``: for each link
:func:`~thermocomp.core.continuation.predecessors` finds, every temperature's step at the
junction over the largest one-sample step inside the two files (the reader warns at 3x), and
each error's last value before / first after.  ``weekly``: the weekly files of two seen benches,
written into ROOT where missing (bench_stranger64's ``pm12``, one record cut at each Monday, and
``pm12_restarts``, its weeks simulated apart; bench_probe61's ``grinder``, one record), each
week's first and last measured error (µm) as the lab's file has it.

TRACE (seen: tr9827 rebuilt into /tmp/ham98 = audit97's files byte for byte, tr9828, tr6301;
before any fresh seed; numbers in "Measured" below).  Warm is not stale by a gap (the weeks'
``start`` instants abut: W1 + 604740 s + 60 s = W2), nor a bug of the carried state (replay = run,
the check pack's C = the served warm stream, audit97).  It is the reading of the record:
trunnion63 simulates each week as its own campaign after a 2-day rest from equilibrium with its
own hall (``cooldown_s``), and its errors are the rises from that week's first sample
(``ThermoelasticMap.errors``: E(0) = 0 in every week), while the manifest's abutting ``start``s
make :func:`predecessors` chain W1 -> W2 -> W3 by time and ``data.reference=auto`` resolve to
``none``: the model is fitted on W1 + W2 joined as one absolute record and W3 is scored after it.
The W2 <- W1 junction steps T_bed -0.56 °C (3.3x the largest step inside; the reader warns: "a
restart rather than one record?"); W3 <- W2 steps no temperature more than 0.6x (nothing in the
temperatures tells that W3 restarts); the errors restart at 0 (E_Z -1.9 -> +0.1 µm).

BAR (a prediction of the trace, written and committed before FRESH trunnion63 seeds 9846-9848 are
simulated; scored ONCE with ``warmcold`` on tr9846, tr9847, tr9848; no src change is proposed, so
it decides whether the explanation holds, not whether a rule is kept; figures the mean over
E_X / E_Y / E_Z of the test RMSE, µm):
(1) on each fresh record, for hammerstein AND lagbank: cold below warm, and first_sample at least
    10 % below the better of the two (the weeks are separate campaigns, each zeroed at its start:
    the first-sample frame is the record's own; seen: 17-72 % below);
(2) mlr (no state): warm = cold to 1e-9 µm (the carried state is the lag families' alone);
(3) seen genuine continuations (``lr9211``, ``fl``), measured before the bar: warm below cold for
    hammerstein and lagbank (the carried state is right where the record is one experiment), so
    no rule that drops the warm start is proposed.
If (1) or (2) fails on a fresh record, the explanation is incomplete and is said so.

Measured, seen (2026-12-06, 16d3b58d's src, ``warmcold``; nice, OMP_NUM_THREADS=1, load ~2-3;
CPU 4-6 s a record; warm / cold / first_sample)::

  tr9827 hammerstein 1.9002 / 1.3842 / 0.3830   lagbank 1.9386 / 1.4299 / 0.5238   mlr 1.9457 x2 / 1.2753
  tr9828 hammerstein 1.2764 / 0.7392 / 0.3633   lagbank 1.1086 / 1.0380 / 0.5574   mlr 1.1832 x2 / 1.2238
  tr6301 hammerstein 0.9913 / 0.6488 / 0.3504   lagbank 1.0034 / 0.6678 / 0.5555   mlr 1.1482 x2 / 1.1251
  lr9211 hammerstein 0.9344 / 2.9700 / 5.4619   lagbank 0.8560 / 2.0517 / 4.6723   mlr 0.7718 x2 / 0.6975
  fl     hammerstein 2.9486 / 6.9151 / 5.8146   lagbank 4.7829 / 23.1812 / 4.4299  mlr 4.0600 x2 / 3.8335

tr9827 = audit97's (run 1.900243, C / cold 1.384218, mlr 1.945723); its three files = audit97's
byte for byte.  ``parts`` (tr9827, hammerstein, E_Z): rms(warm - cold) 1.851 µm,
day by day 3.47 2.67 1.73 1.07 0.66 0.40 0.24 (the long lags dying away over the week); by
input T_bed 2.27, T_coolant_return 1.45, T_trunnion 0.95, S_spindle_rpm 0.94, T_table 0.83,
T_amb 0.62 (parts that partly cancel: no one input, the whole carried history).  ``junctions``:
W2 <- W1 T_bed -0.56 (3.3x), T_column -0.50 (2.6x); W3 <- W2 at most 0.6x (T_bed -0.11, T_amb
+0.38); errors W2 -> W3 E_X +0.40 -> +0.10, E_Y +0.70 -> +0.10, E_Z -1.90 -> +0.10 µm.
bench_auto97's rows (the 22 seen records of bench_auto96b, /tmp/auto96/seen/automore.jsonl): every
one ``reference`` first_sample (their new campaigns continue none): warm = cold by construction.

Scored ONCE (2026-12-06 09:15 UTC, after the bar's commit 0b0d8a59, bar unchanged; 16d3b58d's src;
``warmcold /tmp/ham98/fresh tr9846|tr9847|tr9848``, 19.4 s CPU, 68 s wall for the three; no
junction of the three records warned; warm / cold / first_sample)::

  tr9846 hammerstein 0.8900 / 1.9697 / 0.2630   lagbank 0.8282 / 1.8692 / 0.4886   mlr 1.2068 x2 / 1.0931
  tr9847 hammerstein 3.8729 / 2.3912 / 0.9404   lagbank 3.6034 / 2.2142 / 0.6253   mlr 2.7857 x2 / 1.3871
  tr9848 hammerstein 1.4596 / 2.8896 / 0.5596   lagbank 1.3595 / 2.7571 / 0.7095   mlr 1.3793 x2 / 1.2745

(1) FAILS in its first half: cold is below warm on tr9847 only; on tr9846 and tr9848 warm is
    below cold by about 2x (hammerstein 0.890 vs 1.970, 1.460 vs 2.890).  Its second half holds on
    all three: first_sample 41-72 % below the better of warm and cold (hammerstein 70 / 61 / 62 %,
    lagbank 41 / 72 / 48 %).
(2) holds: mlr warm = cold to 0.0 µm on each (the carried state is the lag families' alone).
(3) held before the bar (lr9211 hammerstein 0.934 warm vs 2.970 cold; fl 2.949 vs 6.915).

VERDICT: TRACED, no src change.  What the trace explains: on trunnion63's weekly records neither
start is right -- both read three separately simulated weeks, each zeroed at its start, as one
absolute record, and which of warm or cold lands nearer is a matter of the seed (cold better on
4 of 6, warm on 2); the frame the record has (``first_sample``) is 17-72 % below both on all
six (41-72 % on the fresh three).  audit97's "the warm start is worse" is that frame's symptom,
not a wrong carried state: dropping the warm start would have made tr9846 / tr9848 2.0-2.2x
worse and lr9211 / fl 2.3-4.8x.
What the record shows that the reader does not use (``junctions``, seen): at each trunnion
junction every error restarts at 0 (E_Z -2.70 / -1.90 / -4.30 / +2.50 / -3.90 / +1.70 -> each
error within 0.3 µm of 0) while no temperature steps more than 3.3x the inside steps (W3 <- W2
at most 1.4x); where the record is one experiment the errors run on (lr9211 E_Z +12.66 ->
+13.35; fl E_ch1 +7.81 -> +7.82).  ``weekly /tmp/ham98/wk`` (after the fresh run, seen benches
only): pm12's weeks, one record, start where the week before ended (dX +5.8 -> +5.7, dY +8.1 ->
+8.9; +10.8 -> +10.4, +18.5 -> +17.9 µm), pm12_restarts' weeks, simulated apart, at 0 (every
first error within 0.5 µm of 0; the week before ended 1.9-13.5 µm from 0); the grinder's
weekly files (one record) first probe hours in (row 741-775), +14.8 .. +20.6 µm.  A rule reading
a link found by time as a restart where every error of the later file starts at 0 on its first
row is the next step; it was not built (the fresh seeds are spent, and it would move
``data.reference=auto`` and every stage that joins campaigns).
tr9827 scored = deployed: as on main, the scored (warm) figure is replay's and the check pack's
C's (audit97: C = served warm to 1e-9 µm); the C fed W3 alone is the cold start, which replay
and promote report beside it (deploy88).  Nothing here changes which the lab deploys.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
from _cli import made_folder, project_root, run_commands  # noqa: E402

TRUNNION = ["THERMOCOMP_TARGETS=trunnion63.", f"hydra.searchpath=[file://{HERE / 'conf63'}]",
            "sim=trunnion63"]
LONG = ["sim=long_record", "sim.generator.test_fraction=0.2", "sim.generator.duration_days=3.0"]
FAMILIES = ("hammerstein", "lagbank", "mlr")
LIGHT = ["track=false", "plots=none"]


def _simulated(root: Path, record: str) -> list[str]:
    """The ``run`` overrides that read RECORD (simulated into ROOT/data/RECORD where missing)."""
    if record == "fl":      # (the shipped file, not ROOT's)
        return ["data=fl_thermal", f"data.path={HERE.parent / 'datasets/fl_thermal/spindle_test.csv'}"]
    kind, seed = record[:2], record[2:]
    folder = root / "data" / record
    if not (folder / "campaigns.csv").is_file():
        words = (TRUNNION[1:] if kind == "tr" else LONG) + [f"seed={seed}", f"data.path={folder}"]
        env = dict(os.environ, THERMOCOMP_TARGETS="trunnion63.",
                   PYTHONPATH=os.pathsep.join([os.environ.get("PYTHONPATH", ""), str(HERE)]))
        subprocess.run([sys.executable, "-m", "thermocomp", "simulate", *words], check=True, env=env,
                       cwd=root)
    return [f"data.path={folder}"]


def _setup(root: Path, record: str, family: str, reference: str):
    """``(compensator fitted as run fits it, dataset, test ids)`` of RECORD with ``family``."""
    from hydra import compose, initialize_config_dir

    import thermocomp.shell.cli  # noqa: F401  (registers the config's resolvers)
    from thermocomp.base.paths import conf_dir
    from thermocomp.core.continuation import fit_joined
    from thermocomp.core.scoring.evaluation import require_split
    from thermocomp.shell.builders import build_compensator
    from thermocomp.shell.source import open_source

    overrides = [*LIGHT, f"model={family}", f"data.reference={reference}",
                 *_simulated(root, record)]
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=overrides)
    ds = open_source(cfg)
    comp = fit_joined(build_compensator(cfg, ds=ds), ds, require_split(ds, "train"))
    return comp, ds, require_split(ds, "test")


def _rmse(comp, ds, ids, carried) -> dict[str, float]:
    """Test RMSE per target over the measured rows of ``ids`` (``carried``: the chains)."""
    from thermocomp.core import continuation

    pred, meas = continuation.predict(comp, ds, ids, "simulation", carried)
    out = {}
    for t in comp.targets_:
        y = np.concatenate([meas[c][t].to_numpy(float) for c in ids])
        p = np.concatenate([pred[c][t].to_numpy(float) for c in ids])
        ok = np.isfinite(y)
        out[t] = float(np.sqrt(np.mean((y[ok] - p[ok]) ** 2)))
    return out


def _mean(d: dict) -> float:
    return float(np.mean(list(d.values())))


def warmcold(root: str, record: str, *families: str) -> None:
    """Per family warm / cold (reference auto) and first_sample test RMSE -> ROOT/RECORD.json."""
    from thermocomp.core import continuation

    folder = project_root(root)
    report = {}
    for family in families or FAMILIES:
        comp, ds, ids = _setup(folder, record, family, "auto")
        carried = continuation.carry_over(comp, ds)
        warm, cold = _rmse(comp, ds, ids, carried), _rmse(comp, ds, ids, {})
        fs_comp, fs_ds, _ = _setup(folder, record, family, "first_sample")
        first = _rmse(fs_comp, fs_ds, ids, {})
        chains = {c: carried[c] for c in ids if c in carried}
        report[family] = {"reference": comp.reference, "carried": chains, "warm": warm,
                          "cold": cold, "first_sample": first}
        print(f"{record} {family:12s} ref={comp.reference:12s} warm {_mean(warm):.4f} cold "
              f"{_mean(cold):.4f} first_sample {_mean(first):.4f}  per target warm/cold/fs "
              + " ".join(f"{t} {warm[t]:.3f}/{cold[t]:.3f}/{first[t]:.3f}" for t in warm), flush=True)
    Path(folder, f"{record}.json").write_text(json.dumps(report, indent=1))


def parts(root: str, record: str, family: str) -> None:
    """warm - cold of the (first) test campaign, split by input (RMS of each part, µm)."""
    from thermocomp.core import continuation

    comp, ds, ids = _setup(project_root(root), record, family, "auto")
    carried = continuation.carry_over(comp, ds)
    cid = next(c for c in ids if c in carried)
    n = len(ds.campaigns[cid])
    whole = continuation.joined(ds, carried[cid])
    lead = slice(0, len(whole) - n)

    def tail(frame):
        return comp.predict({cid: frame}, mode="simulation")[cid].iloc[-n:].reset_index(drop=True)

    warm = tail(whole)
    cold = comp.predict({cid: ds.campaigns[cid]}, mode="simulation")[cid]
    columns = [k for k in whole.columns if k.startswith(("T_", "S_"))]
    held = {}
    for k in columns:
        frame = whole.copy()
        frame.iloc[lead, frame.columns.get_loc(k)] = whole[k].iloc[len(whole) - n]
        held[k] = warm - tail(frame)
    days = (ds.campaigns[cid]["time"].to_numpy(float) - float(ds.campaigns[cid]["time"].iloc[0])) // 86400
    for t in comp.targets_:
        diff = (warm[t] - cold[t]).to_numpy()
        by_day = " ".join(f"{np.sqrt(np.mean(diff[days == d] ** 2)):.3f}" for d in np.unique(days)[:7])
        print(f"{record} {family} {t}: rms(warm - cold) {np.sqrt(np.mean(diff ** 2)):.3f} (day by day "
              f"{by_day}); parts: " + ", ".join(f"{k} {np.sqrt(np.mean(held[k][t] ** 2)):.3f}"
                                                for k in columns))


def junctions(root: str, record: str) -> None:
    """Each link's temperature steps (x the largest step inside the two) and errors around it."""
    from thermocomp.core import continuation
    from thermocomp.core.io.contract import role

    comp, ds, _ = _setup(project_root(root), record, "mlr", "auto")
    for cid, prev in continuation.predecessors(ds).items():
        a, b = ds.campaigns[prev], ds.campaigns[cid]
        steps = []
        for col in (c for c in b.columns if role(c) == "T" and c in a.columns):
            x, y = a[col].to_numpy(float), b[col].to_numpy(float)
            inside = max(np.nanmax(np.abs(np.diff(x))), np.nanmax(np.abs(np.diff(y))))
            steps.append(f"{col} {y[0] - x[-1]:+.2f} ({abs(y[0] - x[-1]) / inside:.1f}x)")
        errors = [f"{t} {a[t].dropna().iloc[-1]:+.2f} -> {b[t].dropna().iloc[0]:+.2f}"
                  for t in comp.targets_]
        print(f"{record} {cid} <- {prev}: " + ", ".join(steps) + "; errors " + ", ".join(errors))


def weekly(root: str) -> None:
    """Each weekly file's first and last measured error (µm) of pm12, pm12_restarts, grinder."""
    import bench_probe61
    import bench_stranger64
    import pandas as pd

    folder = made_folder(root)
    if not (folder / "pm12").is_dir():
        bench_stranger64.write(folder)
    if not (folder / "grinder").is_dir():
        bench_probe61.write(folder)
    files = {name: sorted((folder / name).glob("PM12_week*.txt")) for name in ("pm12", "pm12_restarts")}
    files["grinder"] = sorted((folder / "grinder").glob("PG31_KW*.csv"))
    for name, paths in files.items():
        for path in paths:
            lab = path.suffix == ".txt"      # (TAB, decimal commas, four preamble lines, mm)
            frame = (pd.read_csv(path, sep="\t", skiprows=4, decimal=",") if lab else pd.read_csv(path))
            errors = [c for c in frame.columns if c.startswith(("dX", "dY", "dZ", "Probe"))]
            scale = 1000.0 if lab else 1.0
            ends = [(c, frame[c].dropna()) for c in errors]
            print(f"{name} {path.name}: " + ", ".join(
                f"{c} {v.iloc[0] * scale:+.1f} .. {v.iloc[-1] * scale:+.1f} (first at row {v.index[0]})"
                for c, v in ends))


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"warmcold": warmcold, "parts": parts, "junctions": junctions,
                                  "weekly": weekly}, argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
