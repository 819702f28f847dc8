"""Where ``promote.envelope.per_target`` loses E_X's gain while the monitor has a sensor out
(dep95, issue 34): the 1.7x added Σ² against ``per_target=false`` on the planted spike / jump /
range / dropout of bench_env94c, traced row by row.

Usage (from the repository root; ``PYTHONPATH=<tree>/src``: the code measured is that tree's)::

    python benchmarks/bench_dep95.py cache ROOT SEEDS
    python benchmarks/bench_dep95.py trace ROOT

``cache``: bench_env92's ``draw ROOT SEEDS`` (``column_moving_source`` seed by seed, mlr / arx /
lagbank fitted; cells drawn already are not redone), then per cell the model deployed as
``replay`` deploys it (``monitor.adaptive=true``) with ``per_target`` off and on, and the true
test campaign and bench_env93b's 10 fault cases streamed from a reset row by row through the
adaptive compensator's ``_step``, recording per row: the guarded correction (what ``replay``
scores; checked equal to ``report.stream_rows`` on the true record), the correction before the
guard, the plain stream's own, the excess the envelope's gate passed (``Envelope.excess``), the
inputs as the model read them (an excluded sensor's stand-in included), the sensors the monitor
had out and the fallback whose correction was taken (none where the sensor has none):
``ROOT/rows/<record>-<family>.npz``.
``trace``: per fault kind and per target, what the faults add to Σ² (µm²) under off and on, split
into the rows before the fault's onset, the rows the monitor has the faulty sensor out, and the
rows after; in the out rows, per target, on's and off's squared error against the truth and the
clean record's, how many of them the white targets stream unclamped (the excess shared, env94's
rule) in the clean and the fault record, the stand-in's excess against the true reading's; and
on paper the mend the brief names (a white target clamped while an input is a stand-in: off's
rows for the white targets in the out rows, exact as in bench_env94's ``composed``).

MEASURED (SEEN: env94c's fresh 9709-9713, spent, x mlr / arx / lagbank = 15 cells; ``cache
/tmp/dep95/seen 9709-9713`` on 34af1fcb's src, CPU 71 + 141 + 163 s under a shared load, then
``trace``; the totals equal env94c's: spike 433 / 734, jump 427 / 730, dropout 427 / 725)::

  kind     added Σ² off / on: before   out rows    after   total   | E_X off / on
  spike                        0 / 0   423 / 724   10 / 10  433 / 734 | 250 / 511
  jump                         0 / 0   421 / 722    6 / 8   427 / 730 | 244 / 506
  range                        0 / 0   428 / 725   10 / 10  437 / 734 | 255 / 512
  dropout                      0 / 0   515 / 812  -87 / -87 427 / 725 | 246 / 503

WHERE: all of on's extra cost (301 / 301 / 297 / 297 µm²) is in the rows the monitor has the
faulty sensor out (~110 rows a case, its window), and E_X's (+261, E_Z +43 on the lag banks).
No fallback is involved: every cell's fallbacks are for T_amb and T_front3 only; T_right3 /
T_left3 are stood in for by the monitor's POD reconstruction, read by the model itself.  The clamp
takes no other decision: the white targets stream unclamped (excess on >= 2 inputs) in 2433 of
3417 out rows clean and 2445 with the spike (dropout 2307 = 2307); the envelope is one per input,
so no target's clamp reads another target's range.  The stand-in misses the true reading by 0.96
°C mean |.| (1.27 dropout); under off the clamp removes the response beyond hi (the true reading
above hi in 1188 out rows, the stand-in in 1440), so the stand-in's error barely reaches E_X (white
targets' correction fault - clean RMS 4.46 µm); unclamped, E_X follows it at its gain (9.33 µm).
IT IS THE GAIN, NOT LOST: in the out rows the white targets' Σ² is off 1028 clean / 1324 fault, on
366 / 963 (spike; dropout 1030 / 1314 against 337 / 919): with the sensor out on is still
1324 - 963 = 361 µm² better than off, the stand-in carrying less of Q3 than the sensor did.  The
mend on paper (clamp a white target while an input is a stand-in) gives off's 1324: Σ² +361 and
an added Σ² of 958 against on's 597 (spike): refused on paper, not built.

VERDICT: TRACED.  Not a clamp defect: the 1.7x added Σ² is part of the key's gain (E_X following
Q3 through T_right3 / T_left3) that a POD stand-in cannot carry while the monitor has the sensor
out; per_target stays below off in those rows.  src untouched; the default stays off.
Left: a stand-in that carries a heat source's local part (the monitor's reconstruction), if any.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE)]
import bench_env93b as env93b  # noqa: E402
import bench_env94 as env94  # noqa: E402
from _cli import run_commands  # noqa: E402

CASES = env94.CASES        # the true test campaign and bench_env93b's 10 fault cases
RULES = ("off", "on")


def _recorded(deployed, frame) -> dict:
    """``frame`` streamed from a reset through ``deployed._step`` (the adaptive compensator), with
    per row what the module doc lists."""
    stream = deployed.streaming
    models, fallen_back, output = stream._models, deployed._fallen_back, deployed._output
    row: dict = {}

    def seen_models(seen, time, first):
        y, n = models(seen, time, first)
        row.update(main=y.copy(), excess=stream.envelope.excess(stream.last_x_),
                   x=stream.last_x_.copy())
        return y, n

    def seen_fallen(read):
        out = fallen_back(read)
        row["fallen"] = out or ""
        return out

    def seen_output(y, *args):
        row["pre"] = np.array(y, float)
        return output(y, *args)

    stream._models, deployed._fallen_back, deployed._output = seen_models, seen_fallen, seen_output
    try:
        X = frame[deployed.columns_].to_numpy(float)
        t = frame["time"].to_numpy(float)
        names = list(deployed.monitor.names)
        keep = {k: [] for k in ("y", "pre", "main", "excess", "x", "out", "fallen")}
        deployed.reset()
        for i in range(len(X)):
            row.clear()
            y, _ = deployed._step(X[i], t[i])
            keep["y"].append(y.copy())
            for k in ("pre", "main", "excess", "x"):
                keep[k].append(row.get(k, np.full(len(keep[k][-1]) if keep[k] else 0, np.nan)))
            keep["out"].append([s in deployed.excluded_inputs for s in names])
            keep["fallen"].append(row.get("fallen", ""))
    finally:
        del stream._models, deployed._fallen_back, deployed._output
    return {k: np.array(v) if k != "fallen" else np.array(v, dtype=str) for k, v in keep.items()}


def cache(root: str, seeds: str) -> None:
    """Per cell the recorded rows off / on of the true test campaign and each fault case:
    ``ROOT/rows/<cell>.npz`` (the cells and their deployed models: bench_env94's
    ``deployed_cells``)."""
    from thermocomp.apps.deploy.report import stream_rows

    for record, fam, path, deployed_with in env94.deployed_cells(root, seeds):
        out = {}
        for rule in RULES:
            deployed, ds, _, tid = deployed_with(rule == "on")
            true = ds.campaigns[tid]
            for case in CASES:
                frame = true if case == "true" else env93b.planted(true, *case.split(":"))
                for k, v in _recorded(deployed, frame).items():
                    out[f"{rule}|{case}|{k}"] = v
            gap = np.abs(stream_rows(deployed, true, tid).y - out[f"{rule}|true|y"]).max()
            assert gap < 1e-9, f"{record}-{fam} {rule}: recorded rows differ from replay's by {gap}"
            out[f"{rule}|unclamped"] = np.array(deployed.streaming.unclamped_, dtype=str)
            out[f"{rule}|fallbacks"] = np.array(sorted(deployed.fallbacks_), dtype=str)
        targets = list(deployed.targets_)
        comp = deployed.streaming.compensator
        out["targets"] = np.array(targets, dtype=str)
        out["inputs"] = np.array(comp.inputs_, dtype=str)
        out["monitored"] = np.array(deployed.monitor.names, dtype=str)
        out["measured"] = comp.measured({tid: true})[tid][targets].to_numpy(float)
        out["lo"], out["hi"] = deployed.envelope.lo, deployed.envelope.hi
        out["true_x"] = out["off|true|x"]
        np.savez(path, **out)
        print(record, fam, "unclamped", list(out["on|unclamped"]), "fallbacks",
              list(out["on|fallbacks"]), flush=True)


def _cells(root: str) -> dict:
    out = {}
    for p in sorted((Path(root) / "rows").glob("*.npz")):
        d = np.load(p)
        out[p.stem] = {k: d[k] for k in d.files}
    return out


def _windows(cell: dict, case: str) -> dict:
    """Row masks of ``case``: before the fault's onset, while the monitor has the faulty sensor
    out (under off or on), after."""
    n = len(cell["measured"])
    sensor = case.split(":")[1]
    j = list(cell["monitored"]).index(sensor)
    out = cell[f"off|{case}|out"][:, j] | cell[f"on|{case}|out"][:, j]
    before = np.arange(n) < 3 * n // 4
    return {"before": before & ~out, "out": out, "after": ~before & ~out}


def _sq(cell: dict, rule: str, case: str) -> np.ndarray:
    """Per row and target the squared deployed error (µm²) over the row count (sums to Σ²)."""
    r = cell["measured"] - cell[f"{rule}|{case}|y"]
    return np.where(np.isfinite(r), r ** 2, 0.0) / len(r)


def trace(root: str) -> None:
    """The module doc's split of the added Σ², per fault kind and target, and what the rows the
    sensor is out show: the stand-in, the clamp's gate, E_X's error under each rule."""
    cells = _cells(root)
    for kind in ("spike", "jump", "range", "dropout", "drift"):
        add = {r: {w: 0.0 for w in ("before", "out", "after")} for r in RULES}
        per_t: dict = {}
        n_out, free = 0, {"clean": 0, "fault": 0}
        stand, err = [], {k: 0.0 for k in ("off|true", "off|fault", "on|true", "on|fault", "mend")}
        above = {"true": 0, "stand-in": 0}
        depart: list = []
        for cell in cells.values():
            targets = list(cell["targets"])
            white = [targets.index(t) for t in cell["on|unclamped"]]
            for sensor in env93b.SENSORS:
                case = f"{kind}:{sensor}"
                win = _windows(cell, case)
                for r in RULES:
                    d = _sq(cell, r, case) - _sq(cell, r, "true")
                    for w, m in win.items():
                        add[r][w] += float(d[m].sum())
                    for k, t in enumerate(targets):
                        per_t.setdefault(t, {q: 0.0 for q in RULES})[r] += float(d[:, k].sum())
                m = win["out"]
                n_out += int(m.sum())
                for name, key in (("true", "clean"), (case, "fault")):
                    free[key] += int(((cell[f"on|{name}|excess"][m] != 0).sum(axis=1) >= 2).sum())
                ji = list(cell["inputs"]).index(sensor)
                stand += list(cell[f"on|{case}|x"][m, ji] - cell["true_x"][m, ji])
                above["true"] += int((cell["true_x"][m, ji] > cell["hi"][ji]).sum())
                above["stand-in"] += int((cell[f"on|{case}|x"][m, ji] > cell["hi"][ji]).sum())
                for r in RULES:
                    for c, name in (("true", "true"), ("fault", case)):
                        err[f"{r}|{c}"] += float(_sq(cell, r, name)[m][:, white].sum())
                dep = [cell[f"{r}|{case}|y"][m][:, white] - cell[f"{r}|true|y"][m][:, white] for r in RULES]
                depart.append(np.column_stack([x.ravel() for x in dep]))
                # the mend tried on paper: white targets clamped (off's rows) while the sensor is out
                mend = cell[f"on|{case}|y"].copy()
                mend[np.ix_(m, white)] = cell[f"off|{case}|y"][np.ix_(m, white)]
                r = cell["measured"] - mend
                err["mend"] += float((np.where(np.isfinite(r), r ** 2, 0.0) / len(r))[m][:, white].sum())
        print(f"{kind}: added Σ² pooled over {2 * len(cells)} cases, off / on: "
              + "  ".join(f"{w} {add['off'][w]:.0f} / {add['on'][w]:.0f}" for w in add["off"])
              + f"  total {sum(add['off'].values()):.0f} / {sum(add['on'].values()):.0f}")
        print("   per target off / on: " + "  ".join(f"{t} {v['off']:.0f} / {v['on']:.0f}"
                                                     for t, v in per_t.items()))
        if n_out:
            print(f"   rows out {n_out}: white targets free (excess on >= 2 inputs) clean {free['clean']},"
                  f" fault {free['fault']}; stand-in - true reading {np.mean(stand):+.2f} °C"
                  f" (|.| {np.mean(np.abs(stand)):.2f}); above hi: true {above['true']},"
                  f" stand-in {above['stand-in']}")
            d = np.vstack(depart)
            h = d.shape[1] // 2
            print(f"   white targets' correction, fault - clean, in the out rows: RMS off"
                  f" {np.sqrt(np.nanmean(d[:, :h] ** 2)):.2f} µm,"
                  f" on {np.sqrt(np.nanmean(d[:, h:] ** 2)):.2f} µm")
            print("   white targets' Σ² share in the out rows (µm²): "
                  + "  ".join(f"{k} {v:.0f}" for k, v in err.items()))


def main(argv: list[str] | None = None) -> int:
    return run_commands(__doc__, {"cache": cache, "trace": trace},
                        sys.argv[1:] if argv is None else argv, cpu=sys.stderr)


if __name__ == "__main__":
    sys.exit(main())
