"""The correction guard's bound during a real excursion: widened by what the model's inputs explain?

Stop 56 (``bench_excursion56.py``) found the ADAPTIVE deployed compensator 1.2-6.8 x the PLAIN
stream's Σ² vs truth on the ``long_record`` overspeeds, 82-100 % of it the CorrectionGuard's bound
(``apps/deploy/guard.py``: the training error range widened by ``margin`` 0.2 of its width): the
true error reaches 115.9 µm against a 90.3 µm bound (long4253), 86.6 against 76.7 (long7717).
Here two wider bounds are scored against today's.

Rules, written before scoring them (stop 56, guard56).  ``lo``, ``hi``: today's bound per target
(and ``lo_new``, ``hi_new``, the same here: ``new_state_margin`` is null); ``g_t``: the step gain
of target ``t``'s model at the envelope's horizon over its inputs (``core.context.step_gain(est,
None, envelope.horizon_s)``: what the stream's clamp and the exported ``clamp_gain`` use; a
target without one gets no allowance); ``[a_j, b_j]``: input ``j``'s TRAINING range in the
model's frame (the train campaigns' stacked inputs, before the envelope's margin)::

  G0  today: [lo, hi].
  G1  per sample: [lo - A_t, hi + A_t], A_t = sum_j |g_tj| * d_j, d_j the distance of the input
      the model reads (after the sensor monitor, the reference and the envelope's clamp:
      ``dx - Envelope.excess(dx)``) beyond [a_j, b_j] (0 inside).  A faulty sensor the monitor
      misses is clamped at the envelope's edge when it leaves the training pattern, so its share
      is at most |g_tj| * (envelope hi_j - b_j).
  G2  fixed, at promotion: [lo - A_t, hi + A_t], A_t = sum_j |g_tj| * max(hi_j - b_j, a_j - lo_j)
      (hi_j, lo_j the envelope's): the largest extra response of the linear part to inputs
      inside the envelope box beyond their training range.  Static: the exported forms (C, ST,
      Simulator) carry it as ``guard_lo``/``guard_hi`` with no code change; G1 needs the
      training ranges and the gains in the code.

Added after G1 and G2 were scored (their fault lines below): both let the exported code and a
fault the monitor misses through (a reading in K clamped at the envelope's edge is beyond
training by the envelope's margin, and MLR leans -36 µm/K on that sensor)::

  G3  G1, but only for a sample ON the training pattern (``Envelope.leaves_pattern(dx)`` false:
      the sensors moved together as in training, a machine state the stream passes as measured);
      a sample off it (one sensor leaving the others: the faults) gets today's bound.  Without a
      pattern (``basis`` None) never: G0.

Bars (all to adopt; the brief's): (a) long4253 / long7717 adaptive Σ² closer to plain for every
family (hammerstein, lagbank, mlr); (b) the injected faults of ``bench_deploy_faults.py`` (its
record, models and faults; the adaptive form and the exported code) before / after: any fault
whose correction moves further from the healthy stream is reported; (c) healthy records
unchanged.  Added here, before scoring, because the bound was measured once on records where
the model is WRONG in an excursion (docs/monitoring.md, "A new thermal state": widening it
there lost on 2 of 6 record x model pairs): (d) ``column_moving_source`` seeds 3141 and 5003
(a heat source training never saw; ``bench_new_thermal_state.py``'s records), mlr / arx /
lagbank, Σ² vs the measured error, the envelope as shipped (clamp).

Run (the long records are ``bench_state_envelope.py``'s, cached in ``--root``; the others are
simulated and fitted into ``--work``)::

    PYTHONPATH=src .venv/bin/python benchmarks/bench_guard56.py [--parts a d b] [--out f.json]

Measured 2026-11-30 (stop 56; 100.5 s user + 1.1 s sys for the three parts, the long records
cached, the cms records and the fault fits made).  ``src``: the deployed compensator as src
builds it now (G3, ``monitor.guard.follow_inputs=true``); G0-G3 rebuild the guard of the same
deployment.  Σ² = sum over the targets of the MSE vs truth (long; the test part) or vs the
measured error (cms; the test campaigns pooled), µm²; (n): bound episodes::

  record    family       plain      G0        G1        G2        G3 = src   G2's +A (µm)
  long4253  hammerstein  1.397   4.439 (2)  1.346     1.346     1.346        30.5
            lagbank      0.648   4.397 (2)  2.422     2.422     2.422        20.1
            mlr          3.991   5.811 (1)  2.956     2.956     2.956        36.3
  long7717  hammerstein  0.190   0.604 (1)  0.201     0.201     0.201        16.7
            lagbank      0.238   0.667 (1)  0.237     0.237     0.237        20.9
            mlr          1.193   1.386 (1)  1.094     1.094     1.094        33.6
  cms3141   mlr        787.906 788.130 (1)  788.130   788.151   788.130   9-143 per target
            arx       1336.482 1335.133 (1) 1335.133  1335.134  1335.133   7-124
            lagbank    940.189 942.334 (2)  938.885   939.017   942.334    3-57
  cms5003   mlr       1951.687 1887.124 (1) 1887.124  1887.181  1887.124  10-224
            arx        867.629 843.230 (1)  843.230   843.358   843.230    7-123
            lagbank   1387.754 1331.687 (2) 1331.707  1331.715  1331.687   5-67

Bar (a): every rule takes the whole bound's share out (the adaptive Σ² is then the monitor's
alone, ``bench_excursion56.py``'s ``monitor`` column: below plain but for long4253's lag bank,
3.7 x plain from the monitor's hold of the hot T_motor); G1's and G3's largest allowance 21-78 µm
on the long records (the inputs on the pattern on every overspeed sample: G1 = G3).  Bar (d): the
guard hardly acts on the cms records with the clamp (plain ~ G0): every rule within 0.3 %; G3's
allowance there 3-8 µm against G1's 15-66 (the new source moves the sensors apart: off the pattern).

Bar (b), ``bench_deploy_faults.py``'s 15 cases x mlr / arx / lagbank, max|C| / largest change /
change at the last row (µm) in three forms: ``adaptive`` (monitor + guard), ``no_monitor`` (the
guard alone: a fault the monitor misses), ``code`` (the exported Simulator, G0 / G2 / src).  In
the adaptive form every rule gives G0's line on every fault (the monitor takes the faults out).
Without the monitor and in the code, the lines that move (every other line equal)::

  fault        family   G0 no_monitor    G1 no_monitor    G2 no_monitor / code
  nan_16       mlr      62.0/40.1/0.0    =                64.8/42.9/0.0  / =
  nan_end      mlr      62.0/42.3/36.1   =                85.2/59.2/59.2 / =
               lagbank  62.0/38.5/37.8   =                78.8/54.6/54.6 / =
  nan_first    mlr      10.3/37.8/36.3   55.0/82.5/81.0   150.8/178.2/176.7 / =
               arx      10.3/35.7/35.7   34.0/59.4/59.4   144.7/164.3/132.5 / =
               lagbank  11.3/34.6/34.6   55.8/80.1/80.1   297.6/321.8/321.8 / =
  stuck        mlr      62.0/40.0/36.1   =                79.7/53.8/53.8 (code too)
               lagbank  62.0/38.1/37.8   =                72.4/48.2/48.2 (code too)
  spike50      lagbank  22.8/29.5/1.4    =                22.8/35.6/1.4  (code too)
  kelvin_half  mlr      19.4/37.8/36.3   55.0/82.5/81.0   150.8/178.2/176.7 (code too)
               arx      21.2/35.7/35.7   34.0/59.4/59.4   101.8/126.1/125.9 (code too)
               lagbank  19.1/34.6/34.6   55.8/80.1/80.1   297.6/321.8/321.8 (code too)

(``=``: G0's line; G2's code lines not marked are G0's code lines.)  G3 and ``src`` give G0's line
on all 135 lines (the adaptive form, the guard alone and, for ``src``, the code): a reading in K,
a stuck sensor, a spike take the sample off the training pattern.  G1 widens by the clamped
reading's distance beyond training (the envelope's margin times MLR's 36 µm/K on T_motor2), G2
by every input's margin at once.  Bar (c): the healthy lines are G0's in every form.

CONCLUSION.  G3 adopted (``monitor.guard.follow_inputs``, default true; guard.py, the adaptive
compensator, the exported Simulator / C / ST; ``tests/shell/test_guard_follows_inputs56.py``);
G1 and G2 not (each fails bar (b)).  G3 trusts what the clamp trusts: a sample on the training
pattern.  A fault that moves every sensor along the pattern (a shared reference's offset) is
read as a hotter machine, by the stream's clamp before and by the guard now; its allowance is
not capped (78 µm at most on these records).
"""

from __future__ import annotations

import argparse
import copy
import json
import sys
from pathlib import Path

import numpy as np
import pandas as pd

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_state_envelope import SCENARIOS, _compose, simulate  # noqa: E402
from cpu import print_cpu  # noqa: E402

from thermocomp.apps.deploy.adaptive import AdaptiveCompensator  # noqa: E402
from thermocomp.apps.deploy.guard import CorrectionGuard  # noqa: E402
from thermocomp.apps.deploy.streaming import replay  # noqa: E402
from thermocomp.core.context import step_gain  # noqa: E402
from thermocomp.core.continuation import lead_ins  # noqa: E402
from thermocomp.shell.builders import build_compensator, deploy_stream, deployable  # noqa: E402
from thermocomp.shell.source import read_streamed  # noqa: E402

RULES = ("G0", "G1", "G2", "G3", "src")
LONG = {"long4253": ("hammerstein", "lagbank", "mlr"), "long7717": ("hammerstein", "lagbank", "mlr")}
CMS = {"cms3141": ["sim=column_moving_source", "seed=3141"],
       "cms5003": ["sim=column_moving_source", "seed=5003"]}
CMS_FAMILIES = ("mlr", "arx", "lagbank")


# -- the rules --------------------------------------------------------------------------------
def gains(stream) -> np.ndarray:
    """(targets, inputs) step gains at the envelope's horizon (0 rows: no gain)."""
    n = len(stream.envelope.lo)
    out = np.zeros((len(stream.targets_), n))
    for k, (_, est, idx) in enumerate(stream._plan):
        g = step_gain(est, None, stream.envelope.horizon_s)
        if g is not None:
            out[k, np.arange(n) if idx is None else np.asarray(idx)] = g
    return out


def training_range(comp, train: dict) -> tuple[np.ndarray, np.ndarray]:
    X = comp.stacked(train, targets=[]).X
    return X.min().to_numpy(float), X.max().to_numpy(float)


class WidenedGuard(CorrectionGuard):
    """Today's guard with its bound widened by ``extra`` (µm per target), set before each
    step (G1, G3)."""

    extra: np.ndarray | float = 0.0
    widest = 0.0     # G1: the largest allowance seen (µm)

    def step(self, y, dt, time, new_state=False, allowance=None):
        saved = self.lo, self.hi, self.lo_new, self.hi_new
        a = self.extra
        self.lo, self.hi = self.lo - a, self.hi + a
        if self.lo_new is not None:
            self.lo_new, self.hi_new = self.lo_new - a, self.hi_new + a
        try:
            return super().step(y, dt, time, new_state, allowance)
        finally:
            self.lo, self.hi, self.lo_new, self.hi_new = saved


def with_rule(adaptive: AdaptiveCompensator, rule: str, comp, train: dict) -> AdaptiveCompensator:
    """A copy of the adaptive compensator whose guard follows ``rule`` (module doc)."""
    dep = copy.deepcopy(adaptive)
    if rule == "src":                              # as deployed (guard.py's follow_inputs)
        return dep
    dep.guard.in_gain = None                       # the rules below on today's fixed bound
    if rule == "G0":
        return dep
    stream, env = dep.streaming, dep.streaming.envelope
    G = np.abs(gains(stream))
    a, b = training_range(comp, train)
    guard = dep.guard
    if rule == "G2":                               # a plain guard with wider limits: it exports
        allowance = G @ np.maximum(env.hi - b, a - env.lo)
        guard.lo, guard.hi = guard.lo - allowance, guard.hi + allowance
        if guard.lo_new is not None:
            guard.lo_new, guard.hi_new = guard.lo_new - allowance, guard.hi_new + allowance
        guard.extra = allowance
        return dep
    guard.__class__ = WidenedGuard
    inner = stream._step

    def step(x, t, clocked=False):                 # G1: the inputs as the model reads them
        y, n = inner(x, t, clocked)
        dx = x[:len(a)] - stream._ref
        on = rule == "G1" or not env.leaves_pattern(dx)      # G3: on the training pattern only
        if stream.policy != "off":
            dx = dx - env.excess(dx)
        guard.extra = G @ np.maximum(np.maximum(dx - b, a - dx), 0.0) * on
        guard.widest = max(guard.widest, float(guard.extra.max(initial=0.0)))
        return y, n

    if stream.denoiser is not None:
        raise NotImplementedError("G1 here reads the raw inputs: a denoised model is not scored")
    guard.widest = 0.0
    stream._step = step
    return dep


# -- scoring ----------------------------------------------------------------------------------
def _score(forms: dict, frames: list, targets) -> dict:
    """Σ² (sum over targets of the MSE, rows pooled) and bounded samples per form."""
    out = {}
    for name, dep in forms.items():
        r, bounded, widest = [], 0, 0.0
        for df, lead, true in frames:
            pred = replay(dep, df, lead_in=lead)
            r.append(true - pred[targets].to_numpy(float))
            bounded += sum("correction bounded" in e["reason"]
                           for row in pred.get("events", []) for e in json.loads(row))
            widest = max(widest, float(getattr(getattr(dep, "guard", None), "widest", 0.0)))
        r = np.vstack(r)
        out[name] = {"s2": float((r ** 2).mean(0).sum()), "bounded_events": bounded,
                     "widest_allowance_um": widest}
    return out


def _forms(stream, adaptive, comp, train) -> dict:
    forms = {"plain": stream}
    for rule in RULES:
        forms[rule] = with_rule(adaptive, rule, comp, train)
    return forms


def _static_allowance(adaptive, comp, train) -> list:
    return with_rule(adaptive, "G2", comp, train).guard.extra.tolist()


def long_record(root: Path, run: str, family: str) -> dict:
    noisy, truth = simulate(root, run)
    data = SCENARIOS["long"][2]
    cfg = _compose(f"data.path={noisy}", "track=false", *data, f"model={family}")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).fit(train)
    stream = deploy_stream(cfg, comp, train)
    adaptive = deployable(cfg, copy.deepcopy(stream), train, ds)
    ds_t, _, _, _ = read_streamed(_compose(f"data.path={truth}", "track=false", *data))
    leads = lead_ins(comp, ds, test_ids)
    frames = []
    for cid in test_ids:
        df = ds.campaigns[cid].reset_index(drop=True)
        true = comp.measured({cid: ds_t.campaigns[cid].reset_index(drop=True)})[cid]
        frames.append((df, leads.get(cid), true[comp.targets_].to_numpy(float)))
    return {"record": run, "family": family,
            "forms": _score(_forms(stream, adaptive, comp, train), frames, comp.targets_),
            "bound": [adaptive.guard.lo.tolist(), adaptive.guard.hi.tolist()],
            "g2_allowance": _static_allowance(adaptive, comp, train)}


def cms_record(work: Path, tag: str, family: str) -> dict:
    from thermocomp.shell.cli import main as cli
    data = work / tag
    if not (data / "campaigns.csv").is_file():
        cli(["-q", "simulate", *CMS[tag], f"data.path={data}", "track=false", f"out={work / 'sim'}"])
    cfg = _compose(f"data.path={data}", "track=false", f"model={family}")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).fit(train)
    stream = deploy_stream(cfg, comp, train)
    adaptive = deployable(cfg, copy.deepcopy(stream), train, ds)
    leads = lead_ins(comp, ds, test_ids)
    measured = comp.measured({c: ds.campaigns[c] for c in test_ids})
    frames = [(ds.campaigns[c].reset_index(drop=True), leads.get(c),
               measured[c][comp.targets_].to_numpy(float)) for c in test_ids]
    return {"record": tag, "family": family,
            "forms": _score(_forms(stream, adaptive, comp, train), frames, comp.targets_),
            "g2_allowance": _static_allowance(adaptive, comp, train)}


def fault_lines(root: Path) -> list[dict]:
    """Bar (b): ``bench_deploy_faults.py``'s record, models and faults; per rule the adaptive
    form and (G0, G2: static bounds) the exported code: max|C|, the largest change from the same
    form's healthy stream and the change at the last row (µm)."""
    import bench_deploy_faults as bdf

    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import main as cli

    data = root / "ys"
    if not data.exists():
        cli(["-q", "simulate", "sim=yearround_spindle", "seed=5353", "sim.generator.n_campaigns=9",
             "sim.generator.duration_h=[3.0,5.0]", f"data.path={data}", f"out={root / 'sim'}"])
    raw = pd.read_csv(data / f"{bdf.CAMPAIGN}.csv")
    lines = []
    for family in bdf.FAMILIES:
        model = root / family / "model.pkl"
        if not model.exists():
            cli(["-q", "run", f"data.path={data}", f"model={family}", "track=false", "plots=none",
                 f"out={root / family}"])
        cfg = bdf._cfg(data, "monitor.adaptive=true")
        ds, train_ids, _, _ = read_streamed(cfg)
        adaptive = deployable_model(cfg, ds, train_ids, str(model), "replay.model")[0]
        train = {c: ds.campaigns[c] for c in train_ids}
        # the guard without the monitor: what guards a fault the monitor misses (and the code)
        alone = AdaptiveCompensator(copy.deepcopy(adaptive.streaming), None,
                                    copy.deepcopy(adaptive.guard), adaptive.period_s)
        for rule in RULES:
            dep = with_rule(adaptive, rule, adaptive.compensator, train)
            bare = with_rule(alone, rule, adaptive.compensator, train)
            forms = {"adaptive": lambda df, d=dep: bdf._streamed(d, df)[0],
                     "no_monitor": lambda df, d=bare: bdf._streamed(d, df)[0]}
            if rule in ("G0", "G2", "src"):
                forms["code"] = lambda df, d=dep: bdf._code(d, df)
            for form, fn in forms.items():
                healthy = fn(raw)
                for name, df in {"healthy": raw, **bdf.faults(raw)}.items():
                    y = bdf._aligned(name, fn(df), len(raw) // 2)
                    n = min(len(y), len(healthy))
                    change = np.abs(y[:n] - healthy[:n])
                    lines.append({"family": family, "rule": rule, "form": form, "fault": name,
                                  "max_c": float(np.max(np.abs(y))),
                                  "max_change": float(np.max(change)),
                                  "last_change": float(np.max(change[-1])),
                                  "finite": bool(np.isfinite(y).all())})
    return lines


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default="/tmp/stateenv55-bench")
    ap.add_argument("--work", default="/tmp/guard56-bench")
    ap.add_argument("--parts", nargs="+", default=["a", "d"])
    ap.add_argument("--only", default="")
    ap.add_argument("--out", default=None)
    args = ap.parse_args(argv)
    results = []
    jobs = ([(long_record, Path(args.root), r, f) for r, fams in LONG.items() for f in fams]
            if "a" in args.parts else []) + \
           ([(cms_record, Path(args.work), r, f) for r in CMS for f in CMS_FAMILIES]
            if "d" in args.parts else [])
    for fn, where, rec, fam in jobs:
        if args.only not in f"{rec} {fam}":
            continue
        r = fn(where, rec, fam)
        results.append(r)
        print(f"{rec:9s} {fam:12s} " + "  ".join(
            f"{k} {v['s2']:.3f} ({v['bounded_events']})" for k, v in r["forms"].items())
            + f"  G2 +{np.round(r['g2_allowance'], 1).tolist()} µm", flush=True)
    if "b" in args.parts:
        lines = fault_lines(Path(args.work) / "df")
        results.append({"faults": lines})
        table = pd.DataFrame(lines)
        table["cell"] = table.apply(lambda r: f"{r.max_c:.1f}/{r.max_change:.1f}/{r.last_change:.1f}"
                                    + ("" if r.finite else " NaN!"), axis=1)
        print(table.pivot_table(index=["fault", "family"], columns=["form", "rule"], values="cell",
                                aggfunc="first", sort=False).to_string())
    print_cpu()
    if args.out:
        Path(args.out).write_text(json.dumps(results))


if __name__ == "__main__":
    main()
