"""Does the deployed compensator say when the machine meets a heat source training never saw?
The column records auto loses to MLR (col5791, col1403, col1514, col6512; col6511 beside them, a
column record auto does not lose) streamed through the deployed monitor over the 12 new campaigns
auto106 scored them on (issue 34; stop 106, mon106b).

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the monitor measured is that tree's)::

    python benchmarks/bench_mon106b.py flags WORK STORE22 [RECORD ...]     # stream, keep the flags
    python benchmarks/bench_mon106b.py trace WORK STORE22 STOREONE [RECORD ...]  # flags vs errors
    python benchmarks/bench_mon106b.py healthy WORK SEED ...               # the kind without Q3
    python benchmarks/bench_mon106b.py rooms RECORD ...                    # bench_auto91's rooms
    python benchmarks/bench_mon106b.py fresh SEED ...                      # the bar's fresh records

``flags``: per record (``column_moving_source`` at the record's seed: its 40 h train campaign),
MLR fitted on the train split and deployed as ``thermocomp monitor`` / ``replay`` deploy it
(``deploy_stream`` + ``build_adaptive``, conf defaults: new_state on, adaptive), then the record's
own test and the 12 new campaigns (STORE22's ``draws/column-6911..6922.pkl``, bench_automore69's,
the campaigns auto106 scored) streamed row by row from a reset; per row kept in
``WORK/RECORD.flags.npz``: the new thermal state raised (``monitor.new_state_``), sensors excluded,
sensors beyond their warning band (``states``), in the order of STORE22's ``pred`` arrays.  The
monitor reads the ``T_`` readings only (no model output), so MLR's stream raises the flags
auto's would.  ``trace``: per record, where the flags sit against Q3 (on from 50 % to 75 % of the
test cycle: rows 720-1080 of 1441; the first half is the campaign before Q3) -- the first row of
the new state after Q3's onset (samples of 100 s), rows flagged in the first halves (false flags
before Q3) and in the second; then per target with a blend (auto106's deployed weights, stored
``pred_*``, run's scoring) each member's and the deployed blend's RMSE over MLR's on the new
campaigns' rows flagged vs not flagged, and the probe "MLR while the new state is raised" (the
record figure, mean over targets of RMSE over MLR's mean, as auto106's).  ``healthy``: the same
stream on ``column_moving_source`` with ``sim.generator.q3=false`` at SEED (its own train and test
campaign): the flags where no unseen source runs.  ``rooms``: bench_auto91's climate rooms (auto
and MLR fitted, each test campaign as ``run`` scores it) with the flags and the probe.  ``fresh``:
per SEED a column record (its 40 h train, its own 40 h test cycle with Q3) with auto and MLR fitted
as ``run`` fits them and scored as ``run`` scores them, the flags of MLR deployed on it, the probe,
and the same SEED without Q3 (``sim.generator.q3=false``) streamed for its flags.

The probe "MLR while the new state is raised" replaces, per row, the deployed blend's prediction by
MLR's where the deployed monitor has the new thermal state raised.  It reads the monitor's flag (the
temperature field off the training's POD subspace: several judged sensors past their band together),
not the inputs' range (auto91's refused guard: MLR out of the train range, which cost year6_5411's
ATI win 0.518 -> 0.744 and six climate rooms 7-114 %).  It is a probe, not src: a rule would put it
in the served blend, in ``run``'s scoring (deployed = scored) and in the C or not_in_code.

TRACE (2026-12-07, 2b836d65's src, ``OMP_NUM_THREADS=1``, 2 shared cores; stores of auto105b:
``/tmp/auto105b/main``'s rows and draws; CPU user + sys: ``flags`` 5.9 s col5791, 20.1 s the other
four, 14.8 s the six others; ``trace`` 2.5 s; ``healthy`` 14 seeds 12.4 s; ``rooms`` 13 rooms 31.0 s)
(seen records and seeds only; the four losers' figures reproduce auto106's within 0.001).

(1) Where the flag sits (the 12 new campaigns; Q3 on rows 720-1080 of 1441, 100 s a row):
  col5791, col1514, col6512, col6511: the new state raised 9-14 samples (15-23 min) after Q3's
  onset on all 48 campaigns, on 346-351 of Q3's 360 rows and 105-164 rows after it (Q3's heat
  decaying), never before Q3 (0 rows new state, 0 rows excluded in the 48 first halves).
  col1403: onset +12..+20 on 9, +103 / +106 / +123 on three campaigns (campaigns 0, 5, 10 of the
  13: a sensor excluded first, 472-557 rows, the new state only after it); in the first halves 20
  rows of new state (one campaign) and 98 rows with a sensor excluded (four campaigns).
(2) The same stream where no unseen source runs (healthy, seen): column without Q3 at 5305, 2718
  (bench_monitor_healthy's, docs' healthy column seeds) and 6911-6922 (the draws' seeds): 0 rows
  of new state on 14 x 1441 rows (3 records with an exclusion, 10 / 12 / 252 rows).  The 22
  table's swiss303, swiss5454, mill1514, year6511, year6512, year6_5411 (their new campaigns,
  98,788 rows): 0 rows of new state, 0 excluded.  bench_auto91's 13 climate rooms (cr9031 cr9076
  cr9079 cr9081 cr9083 cr9088 cr9089 cr9181 cr9182 cr9183 cr9244 cr9248 cr9245): 0 rows.
(3) Each member's error while flagged vs not (RMSE over MLR's on those rows, new campaigns)::

  col5791 E_Z_mid (lagbank .81)  flagged W 3.156 (lagbank 3.605)  not 1.090  (2nd half not 1.464)
  col5791 E_X_mid (arx .50)      flagged W 1.049 (arx 1.098)      not 0.996
  col5791 E_Z     (hamm .10)     flagged W 0.989 (hamm 0.748)     not 0.962
  col1403 E_Y     (lagbank .84)  flagged W 2.196 (lagbank 2.498)  not 1.620
  col1403 E_Y_mid (hamm .64)     flagged W 2.294 (hamm 2.494)     not 1.679
  col1403 E_Z_mid (arx .39)      flagged W 0.867 (arx 0.528)      not 0.839
  col1514 E_Z_mid (hamm .41)     flagged W 1.600 (hamm 3.271)     not 1.600  (2nd half not 3.093)
  col1514 E_Y_mid (arx .04)      flagged W 0.943                  not 0.997
  col6512 E_X_mid (arx .62)      flagged W 1.063 (arx 1.102)      not 0.996
  col6512 E_Z_mid (lstm .87)     flagged W 1.010                  not 1.038
  col6511 E_X     (arx .57)      flagged W 1.166 (arx 1.763)      not 1.056
  col6511 E_Z_mid (lagbank .12)  flagged W 0.953 (lagbank 0.395)  not 0.966

  Flagged, the blend loses to MLR on 8 of 13 blended targets, by up to 3.2x; it wins on 5 (by
  1-13 %).  col1403's loss lies outside the flag too (not flagged 1.62-1.68: auto91's fresh start).
(4) The probe, record figure auto / MLR -> MLR while raised (second halves in brackets):
  col5791 1.246 -> 1.001 (1.275 -> 1.004), col1403 1.312 -> 1.144 (1.318 -> 1.070), col1514 1.018
  -> 1.007 (1.022 -> 1.010), col6512 1.005 -> 1.000 (1.005 -> 1.000); col6511 0.994 -> 1.001 (its
  win lost); every record of (2) unchanged (no row raised).

BAR (written and committed before the fresh seeds 10079-10081 are drawn; scored once; the probe as
defined above; no src change this stop, so the verdict is TRACED either way -- the bar says whether
the rule is worth building served + scored + C):
F1 each fresh test cycle: the new state raised within 20 samples of Q3's onset (row 720), on >= 90 %
   of Q3's 360 rows, and no row of new state before row 720.
F2 the same three seeds without Q3: no row of new state in their test cycles.
F3 per fresh record, the probe's figure (mean over targets of test RMSE over MLR's) <= 1.01 x auto's;
   and where auto's second half loses to MLR (> 1.000), the probe's excess there at most half of
   auto's (if no fresh record's second half loses, this clause is vacuous and said so).

FRESH (2026-12-07, scored once after the bar's commit 43737304; ``fresh 10079 10080 10081``, CPU
user + sys 30.6 s): F1 MET (onset +11 / +14 / +16 samples, 349 / 346 / 344 of Q3's 360 rows, 0 rows
before Q3), F2 MET (0 rows of new state without Q3 on all three), F3 NOT MET: record auto / MLR ->
probe (probe / auto): s10079 0.898 -> 0.999 (1.112), s10080 0.968 -> 0.999 (1.032), s10081 1.001 ->
1.000 (0.999); second halves 0.895 -> 1.002, 0.966 -> 0.999, 1.002 -> 1.000 (the one losing half's
excess 0.002 -> 0.000).  On the fresh records the blends WIN while flagged: s10079 E_Z (lagbank .88)
0.778 flagged (1.299 not), E_Y (lagbank .11) 0.871, E_Y_mid (lstm .68) 0.941; s10080 E_Z_mid
(lagbank .18) 0.894, E_Z (hammerstein .09) 0.961; only s10079 E_X_mid 1.018 and s10081 E_Z_mid
1.016 lose there.

VERDICT: TRACED (no src).  The monitor does say it: the new thermal state is raised on 68 of 68
test cycles with Q3 (65 seen, 3 fresh), 9-20 samples (15-33 min) after the source starts on 65,
103-123 on three of col1403's (a sensor excluded first); before it only on col1403 (20 rows of one
campaign); never where no unseen source runs (17 column records without Q3, 6 other simulated
records, 13 climate rooms).  But the flag marks the unseen source, not the blend's loss in it: the
same lag families that lose 3x in col5791's Q3 rows win 22 % in s10079's.  Falling back to MLR while
raised mends the seen losers and costs the fresh winners 3-11 % (F3): the rule was not built, and
fresh 10079-10081 are spent.
"""

from __future__ import annotations

import json
import pickle
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE), str(HERE.parent / "tests" / "apps")]
from _cli import run_commands  # noqa: E402

RECORDS = ("col5791", "col1403", "col1514", "col6512", "col6511")
Q3_ON, Q3_OFF = 720, 1080              # rows of the 1441-row test cycle (ColumnMovingSource: 50-75 %)
MLR = {"mlr": 1.0}


def _deployed(overrides: list[str]):
    """``(adaptive compensator, dataset)``: MLR fitted on the train split, deployed as monitor does."""
    from hydra import compose, initialize_config_dir
    from hydra.utils import instantiate

    import thermocomp.shell.cli  # noqa: F401  (the config's resolvers)
    from thermocomp.base.paths import conf_dir
    from thermocomp.shell.builders import build_adaptive, build_compensator, deploy_stream
    from thermocomp.shell.source import resolve_reference

    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=["track=false", "plots=none", "model=mlr", *overrides])
    ds = instantiate(cfg.sim.generator).generate()[0]
    resolve_reference(cfg, ds)
    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    comp = build_compensator(cfg, ds=ds).fit(train)
    return build_adaptive(cfg, deploy_stream(cfg, comp, train), train, ds), ds


def _stream(adaptive, frame) -> dict:
    """Per row of ``frame`` (one campaign, from a reset): new state raised, sensors out, sensors
    beyond their warning band."""
    from thermocomp.apps.deploy.surveillance.states import STATES

    ok = STATES.index("ok") if isinstance(STATES, (list, tuple)) else 0
    X = frame[adaptive.columns_].to_numpy(float)
    t = frame["time"].to_numpy(float)
    adaptive.reset()
    mon = adaptive.monitor
    novel, out, warn = (np.zeros(len(X), bool), np.zeros(len(X), int), np.zeros(len(X), int))
    for i in range(len(X)):
        adaptive.step(X[i], t[i])
        novel[i] = mon.new_state_
        out[i] = len(mon.excluded)
        warn[i] = int(np.sum(mon.states != ok))
    return {"novel": novel, "out": out, "warn": warn}


def _overrides(name: str) -> list[str]:
    import bench_automore69 as automore

    return automore.OVERRIDES[name]


def _campaigns(ds, store22: Path, name: str) -> list:
    """The record's own test campaigns, then its machine's new ones, in the stored arrays' order."""
    import bench_automore69 as automore

    machine = automore.OF[name]
    frames = [ds.campaigns[c] for c in ds.ids("test")]
    for seed in automore.MACHINES[machine][2]:
        new = pickle.loads((store22 / "draws" / f"{machine}-{seed}.pkl").read_bytes())
        frames += [new.campaigns[c] for c in new.ids()]
    return frames


def flags(work: str, store22: str, *records: str) -> None:
    out = Path(work)
    out.mkdir(parents=True, exist_ok=True)
    for name in records or RECORDS:
        adaptive, ds = _deployed(_overrides(name))
        rows = [_stream(adaptive, f) for f in _campaigns(ds, Path(store22), name)]
        np.savez(out / f"{name}.flags.npz", own=len(ds.ids("test")), campaign=np.concatenate(
            [np.full(len(r["novel"]), k) for k, r in enumerate(rows)]),
            **{k: np.concatenate([r[k] for r in rows]) for k in ("novel", "out", "warn")})
        print(name, "streamed", len(rows), "campaigns")


def healthy(work: str, *seeds: str) -> None:
    out = Path(work)
    out.mkdir(parents=True, exist_ok=True)
    for seed in seeds:
        adaptive, ds = _deployed(["sim=column_moving_source", f"seed={seed}", "sim.generator.q3=false"])
        for c in ds.ids("test"):
            r = _stream(adaptive, ds.campaigns[c])
            print(f"column no Q3 s{seed} {c}: rows {len(r['novel'])}, new state {int(r['novel'].sum())}, "
                  f"excluded rows {int((r['out'] > 0).sum())}, rows with a sensor past its warning band "
                  f"{int((r['warn'] > 0).sum())}")


def _rmse(e) -> float:
    return float(np.sqrt(np.mean(np.square(e)))) if len(e) else float("nan")


def _where(f: dict, n_own: int) -> str:
    camp, novel, out = f["campaign"], f["novel"], f["out"]
    lines, onsets, false_first = [], [], 0
    for c in np.unique(camp):
        k = np.flatnonzero(camp == c)
        nv, ou = novel[k], out[k]
        first_after = next((i - Q3_ON for i in range(Q3_ON, len(k)) if nv[i]), None)
        false_first += int(nv[:Q3_ON].sum() + (ou[:Q3_ON] > 0).sum())
        if c >= n_own:
            onsets.append(first_after)
        lines.append(f"    campaign {c:2d}: new state rows first half {int(nv[:Q3_ON].sum()):4d}, Q3 on "
                     f"{int(nv[Q3_ON:Q3_OFF].sum()):4d}/{Q3_OFF - Q3_ON}, after {int(nv[Q3_OFF:].sum()):4d}; "
                     f"first after onset +{first_after}; excluded rows {int((ou > 0).sum())} "
                     f"(first half {int((ou[:Q3_ON] > 0).sum())})")
    return "\n".join(lines), onsets, false_first


def trace(work: str, store22: str, store_one: str, *records: str) -> None:
    import bench_auto106 as a106

    rows = [r for r in a106._rows(store22, store_one) if r["table"] == "22"]
    summary, halves = {}, {}
    for name in records or RECORDS:
        f = dict(np.load(Path(work) / f"{name}.flags.npz"))
        n_own = int(f.get("own", 1))
        novel = f["novel"].astype(bool)
        new = f["campaign"] >= n_own
        camps = [int(np.unique(f["campaign"][m]).size) for m in (new & novel, new)]
        print(f"{name}: new-state rows {int(novel[new].sum())} of {int(new.sum())} new-campaign rows "
              f"({camps[0]} of {camps[1]} campaigns); rows with a sensor excluded "
              f"{int((f['out'][new] > 0).sum())}")
        if name.startswith("col"):
            text, onsets, false_first = _where(f, n_own)
            print(f"  new-state onset after Q3 (samples of 100 s) per new campaign {onsets}; "
                  f"flagged rows before Q3 (new state + excluded) {false_first}")
            print(text)
        got = {}
        for r in (r for r in rows if r["record"] == name):
            a = r["a"]
            y = np.asarray(a["y"], float)
            assert len(novel) == len(y), (name, len(novel), len(y))
            keep = (a["campaign"] >= n_own) & np.isfinite(y)
            dep = sum(v * a[f"pred_{n}"] for n, v in r["dep"].items())
            probe = np.where(novel, a["pred_mlr"], dep)
            members = [n for n in r["dep"] if n != "mlr" and r["dep"][n] > 0]
            got[r["target"]] = (_rmse((y - dep)[keep]), _rmse((y - probe)[keep]),
                                _rmse((y - a["pred_mlr"])[keep]))
            if name.startswith("col"):
                h = keep & _second(a["campaign"])
                halves.setdefault(name, []).append(
                    [_rmse((y - p)[h]) for p in (dep, probe, a["pred_mlr"])])
            if not members:
                continue
            parts = []
            split = (("flagged", keep & novel), ("not", keep & ~novel))
            if name.startswith("col"):
                split += (("not, 2nd half", keep & ~novel & _second(a["campaign"])),)
            for label, m in split:
                if not m.any():
                    continue
                base = _rmse((y - a["pred_mlr"])[m])
                each = " ".join(f"{n} {_rmse((y - a[f'pred_{n}'])[m]) / base:.3f}" for n in members)
                parts.append(f"{label} ({int(m.sum())} rows): W {_rmse((y - dep)[m]) / base:.3f} [{each}]")
            w = " ".join(f"{n} {v:.2f}" for n, v in r["dep"].items() if v > 0)
            print(f"  {r['target']:8s} ({w}) / MLR: " + "; ".join(parts))
        fig = [np.mean([g[k] for g in got.values()]) / np.mean([g[2] for g in got.values()]) for k in (0, 1)]
        summary[name] = fig
        print(f"  record auto / MLR {fig[0]:.3f}; MLR while the new state is raised {fig[1]:.3f}")
        if name in halves:
            h = np.mean(halves[name], axis=0)
            print(f"  second halves (Q3 on from their start): auto / MLR {h[0] / h[2]:.3f}, "
                  f"MLR while raised {h[1] / h[2]:.3f}")
    print(json.dumps({k: [round(x, 4) for x in v] for k, v in summary.items()}))


def _second(campaign: np.ndarray) -> np.ndarray:
    half = np.zeros(len(campaign), bool)
    for c in np.unique(campaign):
        k = np.flatnonzero(campaign == c)
        half[k[Q3_ON:]] = True
    return half


def rooms(*records: str) -> None:
    """The probe on climate rooms (bench_auto91's ``room``: auto and MLR fitted on the train campaigns,
    each test campaign as ``run`` scores it), the flags of MLR deployed on the same record."""
    import bench_auto88b as auto88b
    import bench_auto91 as a91

    for name in records:
        ds, ids, _, _, series = a91.room(name)
        adaptive, ds2 = _deployed(list(auto88b.RECORDS[name]))
        assert ds2.ids("test") == ids, name
        novel = np.concatenate([_stream(adaptive, ds2.campaigns[c])["novel"] for c in ids])
        fig = {"auto": [], "probe": [], "mlr": []}
        for t in series["auto"]:
            y = np.concatenate([series["auto"][t][0][c] for c in ids])
            r_auto, r_mlr = (np.concatenate([series[k][t][1][c] for c in ids]) for k in ("auto", "mlr"))
            keep = np.isfinite(y)
            for key, r in (("auto", r_auto), ("probe", np.where(novel, r_mlr, r_auto)), ("mlr", r_mlr)):
                fig[key].append(_rmse(r[keep]))
        a, p, m = (float(np.mean(fig[k])) for k in ("auto", "probe", "mlr"))
        print(f"  {name}: new-state rows {int(novel.sum())} of {len(novel)} ({len(ids)} test campaigns); "
              f"auto / MLR {a / m:.3f} -> MLR while raised {p / m:.3f}", flush=True)


def _column(seed: str):
    """``(test ids, series)`` of the column record at ``seed``: auto and MLR fitted on its train
    campaign, its test cycle as ``run`` scores it (bench_auto91's ``room``, the column)."""
    import bench_auto_rank as rank
    from sklearn.base import clone

    from thermocomp.core.scoring.evaluation import split_residuals
    from thermocomp.shell.builders import build_compensator

    overrides = ["sim=column_moving_source", f"seed={seed}"]
    sys.argv[2:] = overrides              # bench_auto_rank simulates when sim= is asked
    cfg, ds, train = rank.setup(overrides)
    auto = build_compensator(cfg, ds=ds).fit(train)
    mlr = clone(auto).set_params(estimator=rank._mlr()).fit(train)
    ids = ds.ids("test")
    weights = {t: {n: round(float(w), 2) for n, w in e.weights_.items() if w > 0}
               for t, e in auto.estimators_.items()}
    series = {k: split_residuals(m, ds, ids, "simulation")[2] for k, m in (("auto", auto), ("mlr", mlr))}
    return ids, series, weights


def fresh(*seeds: str) -> None:
    """The bar's fresh records (module doc): F1-F3's figures per seed."""
    for seed in seeds:
        ids, series, weights = _column(seed)
        adaptive, ds = _deployed(["sim=column_moving_source", f"seed={seed}"])
        assert ds.ids("test") == ids, seed
        novel = np.concatenate([_stream(adaptive, ds.campaigns[c])["novel"] for c in ids])
        rows = np.concatenate([np.arange(len(ds.campaigns[c])) for c in ids])
        onset = next((int(r) - Q3_ON for r, v in zip(rows, novel) if v and r >= Q3_ON), None)
        print(f"column s{seed}: new state before Q3 {int(novel[rows < Q3_ON].sum())} rows, on "
              f"{int(novel[(rows >= Q3_ON) & (rows < Q3_OFF)].sum())} of Q3's {Q3_OFF - Q3_ON}, after it "
              f"{int(novel[rows >= Q3_OFF].sum())}; first +{onset} samples after Q3's onset")
        fig = {k: [] for k in ("auto", "probe", "mlr", "auto2", "probe2", "mlr2")}
        for t in series["auto"]:
            y = np.concatenate([series["auto"][t][0][c] for c in ids])
            r_auto, r_mlr = (np.concatenate([series[k][t][1][c] for c in ids]) for k in ("auto", "mlr"))
            keep = np.isfinite(y)
            h = keep & (rows >= Q3_ON)
            for key, r in (("auto", r_auto), ("probe", np.where(novel, r_mlr, r_auto)), ("mlr", r_mlr)):
                fig[key].append(_rmse(r[keep]))
                fig[key + "2"].append(_rmse(r[h]))
            blend = weights.get(t, {})
            if blend != {"mlr": 1.0}:
                on, off = keep & novel, keep & ~novel
                print(f"  {t:8s} {blend}: flagged / MLR {_rmse(r_auto[on]) / _rmse(r_mlr[on]):.3f}, "
                      f"not {_rmse(r_auto[off]) / _rmse(r_mlr[off]):.3f}")
        m = {k: float(np.mean(v)) for k, v in fig.items()}
        print(f"  record auto / MLR {m['auto'] / m['mlr']:.3f} -> MLR while raised "
              f"{m['probe'] / m['mlr']:.3f} "
              f"(probe / auto {m['probe'] / m['auto']:.3f}); second half {m['auto2'] / m['mlr2']:.3f} -> "
              f"{m['probe2'] / m['mlr2']:.3f}", flush=True)
        adaptive, ds = _deployed(["sim=column_moving_source", f"seed={seed}", "sim.generator.q3=false"])
        for c in ds.ids("test"):
            r = _stream(adaptive, ds.campaigns[c])
            print(f"  without Q3 {c}: new state {int(r['novel'].sum())} rows, excluded "
                  f"{int((r['out'] > 0).sum())} rows", flush=True)


def main(argv: list[str]) -> int:
    return run_commands(__doc__, {"flags": flags, "trace": trace, "healthy": healthy, "rooms": rooms,
                                  "fresh": fresh},
                        argv, cpu=sys.stderr)


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
