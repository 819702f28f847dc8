"""A machine state beyond its training range: extrapolate (today) or clamp it to its training edge?

The deployed stream clamps each temperature to its training envelope but passes a machine state
(``S_*``, read by ``model=hammerstein`` through the static powers of w = s / max|s| on train)
as measured: its exported ``lo``/``hi`` are the largest double.  Here the state is clamped in
front of the model (``clamped``: to its training range widened by ``promote.envelope.margin`` of
its width, as ``Envelope.from_data`` derives a temperature's bounds; ``clamped_edge``: to the
training range itself) and the deployed stream (``replay``, plain and adaptive, warmed on the
campaigns it continues) is scored against the TRUE error, as it is today (``unclamped``).
The clamp of a state is its clip before the powers: a power is static, so the model on the
clipped state is what the temperatures' clamp gives a static model (the whole response to the
excess taken out); the stream's two-channel bound (``clamp_gain``) is linear in the excess,
which a power is not (not measured here).

Run (simulates and caches under ``--root``, default ``/tmp/stateenv55-bench``)::

    PYTHONPATH=src .venv/bin/python benchmarks/bench_state_envelope.py [--runs year7717 long7717]
    PYTHONPATH=src .venv/bin/python benchmarks/bench_state_envelope.py --table

The records, written down before measuring (``FACTORS``, ``RUNS``), made by the scenario's own
physics (the programme's speed drives the heat, the temperatures and the errors; the state
column is never edited): ``year<seed>``: ``yearround_spindle`` (speeds 2000/4000/6000 rpm),
its 8 test campaigns in date order at 1, 1.25, 1.5, 2 x the training maximum in their middle
third (own speed before and after; factor 1: as made); ``long<seed>``: ``long_record``
(speeds up to 8000 rpm, ``data.reference=none``), the jobs at the top speed in its test part
R1b at 1, 1.25, 1.5, 2 x in turn (long7717 has three such jobs: up to 1.5 x; long4253 up to
2 x).  The truth: the same seed with the probes' noise, quantum and error spikes 0 (the same
draws: the temperatures are checked equal), in the model's frame (``Compensator.measured``).
Families: ``hammerstein`` (as configured; chosen powers: year7717 w for every target; year4253
none / w / w^2 for E_X / E_Y / E_Z; long7717 w^2; long4253 w and w^2), ``hammerstein_w2`` (both
powers in, no CV between them: the stop-54 record's model), ``lagbank``, ``mlr``.

Measured 2026-11-30 (defaults; seeds 7717, 4253; CPU 16 s user for the year runs, the
year7717 hammerstein lines cached from a first run, 109 s for both long runs, simulation
included).  Σ² = sum over the targets of the mean squared error vs truth (µm²), the campaigns
with an overspeed pooled (row-weighted), over the whole campaigns; ``gm``: geometric mean over
them of clamped / unclamped Σ², ``wins``: campaigns the clamp wins::

  run       family          mode      unclamped  clamped   edge    gm  wins
  year7717  hammerstein     plain        300.1    234.2   237.4  1.48  2/6
                            adaptive     301.1    230.7   229.7  1.36  2/6
            hammerstein_w2  plain        666.2    235.8   231.9  0.69  5/6
                            adaptive     639.5    239.0   229.3  0.68  5/6
  year4253  hammerstein     plain         54.8     80.4    86.6  1.17  3/6
                            adaptive      77.4     98.8   103.1  1.18  3/6
            hammerstein_w2  plain         76.5     95.1   101.6  1.08  3/6
                            adaptive      96.5    106.1   109.6  1.06  3/6
  long7717  hammerstein     plain        0.190    0.392   0.492  2.06  0/1
                            adaptive     0.604    0.815   0.907  1.35  0/1
            hammerstein_w2  plain        0.136    0.375   0.524  2.76  0/1
                            adaptive     0.562    0.819   0.953  1.46  0/1
  long4253  hammerstein     plain        1.397    6.616   8.996  4.74  0/1
  (= _w2)                   adaptive     4.439   12.755  15.675  2.87  0/1

From each campaign's first sample beyond the training speed on the picture is the same (year7717
hammerstein plain 441.9 / 344.0, long4253 1.970 / 9.380).  ``lagbank`` and ``mlr`` read no
state: clamped = unclamped to the last digit on every line (year7717 plain 142.0 and 169.5,
long4253 plain 0.648 and 3.991).  In range (K03 and K15 of each year run, year4253's K03 at
4000 rpm at most, x 4 families x 2 modes: 32 lines) nothing changes: |clamped - unclamped| 0.
year7717's pooled gain with the configured model is one campaign (K24, 2 x in December: Σ²
1324 -> 819; the other five pooled: 47.7 -> 90.1); on 4 of its 6 overspeed campaigns the clamp
is worse (K12, 2 x: E_Z RMS 11.8 -> 18.4 µm).

CONCLUSION.  Holding the state at its training edge is NOT clearly better: it is worse on both
long records (1.35-4.7 x Σ², plain and adaptive, both models), worse on year4253 (+47 % plain,
+28 % adaptive), and better only on year7717 (-22 %, from one campaign; -65 % for the forced
w^2 model, which extrapolates worst there).  The simulated machines' heat grows with the speed
(motor losses q0 + a n + b n², bearing friction), so a fitted w or w^2 term carried beyond the
training range follows the truth's direction, while a clamped state holds the heat at its
training maximum and misses the rest.  Nothing in src changed: the exported ``lo``/``hi`` of a
state stay the largest double (docs/cli.md), the clamp stays the temperatures'.  The training
edge without the margin (``clamped_edge``) is worse still on every line the clamp loses.
(Aside, not this question: on the long records the adaptive compensator's Σ² is 1.2-6.8 x the
plain stream's for every family, lagbank and mlr too: long4253 lagbank 4.40 against 0.648.
Stop 56, ``bench_excursion56.py``: the correction guard's bound makes 82-100 % of it (mlr
long7717: more), not the sensor monitor.)
"""

from __future__ import annotations

import argparse
import json
import resource
from pathlib import Path

import numpy as np
import pandas as pd
from hydra import compose, initialize_config_dir

from thermocomp.apps.deploy.streaming import replay
from thermocomp.apps.sim.campaign import Programme
from thermocomp.apps.sim.long_record import LongRecord
from thermocomp.apps.sim.yearround import YearRoundSpindle
from thermocomp.base.paths import conf_dir
from thermocomp.core.continuation import lead_ins
from thermocomp.core.io.contract import write_dataset
from thermocomp.shell.builders import build_compensator, deploy_stream, deployable
from thermocomp.shell.source import read_streamed

STATE = "S_spindle_rpm"
# written down before measuring: the factors on the training maximum speed, taken in turn by
# the test campaigns (yearround) or the test part's top-speed jobs (long record); 1.0: as made
FACTORS = (1.0, 1.25, 1.5, 2.0)
# family -> model overrides; hammerstein_w2: both powers w, w^2 in, no CV between them (the
# stop-54 record's model: the w^2 term is what extrapolates fastest)
FAMILIES = {"hammerstein": ["model=hammerstein"],
            "hammerstein_w2": ["model=hammerstein", "+model.estimator.choose_exponents=false"],
            "lagbank": ["model=lagbank"], "mlr": ["model=mlr"]}
VARIANTS = ("unclamped", "clamped", "clamped_edge")    # edge: no margin, the training range itself
RUNS = {"year7717": ("year", 7717), "year4253": ("year", 4253), "long7717": ("long", 7717),
        "long4253": ("long", 4253)}


class OverspeedYear(YearRoundSpindle):
    """``yearround_spindle`` whose test campaigns (FACTORS in turn, by date) run, in their middle
    third, at ``factor`` x the training maximum speed, their own speed before and after: the
    scenario's physics (heat, temperatures, errors) responds to the speed it is given."""

    def plans(self, rng):
        plans = super().plans(rng)
        top = max(float(s) for s in self.speeds_rpm)
        for k, plan in enumerate(p for p in plans if p.split == "test"):
            factor = FACTORS[k % len(FACTORS)]
            plan.manifest = {**plan.manifest, "overspeed": factor}
            if factor == 1.0:
                continue
            base = float(plan.programme.steps[0][1]) or top
            a, b = self._on_grid(plan.duration_s / 3), self._on_grid(2 * plan.duration_s / 3)
            plan.programme = Programme(((0.0, base), (a, factor * top), (b, base)))
            plan.notes = f"overspeed {factor}: {plan.programme.describe()}"
        return plans


class OverspeedLong(LongRecord):
    """``long_record`` whose jobs at the top speed in the test part (the last ``test_fraction``)
    run at FACTORS x that speed in turn; the record before is as made."""

    def plans(self, rng):
        (plan,) = super().plans(rng)
        top = max(float(s) for s in self.speeds_rpm)
        cut_s = plan.duration_s * (1.0 - float(self.test_fraction))
        steps, k = [], 0
        for start, rpm in plan.programme.steps:
            if start >= cut_s and rpm == top:
                rpm, k = FACTORS[k % len(FACTORS)] * top, k + 1
            steps.append((start, rpm))
        plan.programme = Programme(tuple(steps))
        return [plan]


SCENARIOS = {"year": (OverspeedYear, {"error_noise_um": 0.0, "error_quantum_um": 0.0}, []),
             "long": (OverspeedLong, {"error_noise_um": 0.0, "error_quantum_um": 0.0,
                                      "n_error_outliers": 0}, ["data.reference=none"])}


def simulate(root: Path, run: str) -> tuple[Path, Path]:
    """``(noisy data set, its noise-free twin)``: the same seed, the probes' noise, quantum and
    spikes 0 (the same draws: the temperatures are the same, the errors the truth)."""
    kind, seed = RUNS[run]
    scenario, quiet, _ = SCENARIOS[kind]
    out = []
    for name, params in (("noisy", {}), ("truth", quiet)):
        path = root / f"{run}_{name}"
        if not (path / "campaigns.csv").is_file():
            ds, _ = scenario(seed=seed, **params).generate()
            write_dataset(ds, path, "csv")
        out.append(path)
    return tuple(out)


def _compose(*overrides):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return compose(config_name="config", overrides=list(overrides))


def _clamped(df: pd.DataFrame | None, lo: float, hi: float) -> pd.DataFrame | None:
    return None if df is None else df.assign(**{STATE: df[STATE].clip(lo, hi)})


def measure(run: str, noisy: Path, truth: Path, family: str, adaptive: bool) -> list[dict]:
    """One line per test campaign and variant: RMS (µm) of truth - deployed prediction over the
    campaign (``all``) and from its first sample beyond the training speed on (``beyond``)."""
    data = SCENARIOS[RUNS[run][0]][2]
    cfg = _compose(f"data.path={noisy}", "track=false", f"monitor.adaptive={str(adaptive).lower()}",
                   *data, *FAMILIES[family])
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds).fit(train)
    deployed = deployable(cfg, deploy_stream(cfg, comp, train), train, ds)
    warm = lead_ins(comp, ds, test_ids)
    powers = {t: list(getattr(est, "exponents_", ())) for t, est in comp.estimators_.items()}
    # the state's envelope derived as the temperatures' is (Envelope.from_data): train rows, margin
    s = pd.concat([train[c][STATE] for c in train_ids]).to_numpy(float)
    lo, hi = float(s.min()), float(s.max())
    margin = float(cfg.promote.envelope.margin)
    bounds = {"unclamped": (-np.inf, np.inf), "clamped_edge": (lo, hi),
              "clamped": (lo - margin * (hi - lo), hi + margin * (hi - lo))}
    ds_t, _, _, _ = read_streamed(_compose(f"data.path={truth}", "track=false", *data))
    lines = []
    for cid in test_ids:
        df = ds.campaigns[cid].reset_index(drop=True)
        clean = ds_t.campaigns[cid].reset_index(drop=True)
        temps = [c for c in df.columns if c.startswith("T_")]
        assert np.array_equal(df[temps].to_numpy(), clean[temps].to_numpy()), cid
        true = comp.measured({cid: clean})[cid][comp.targets_].to_numpy(float)
        beyond = df[STATE].to_numpy(float) > hi
        first = int(np.argmax(beyond)) if beyond.any() else len(df)
        for variant in VARIANTS:
            pred = replay(deployed, _clamped(df, *bounds[variant]),
                          lead_in=_clamped(warm.get(cid), *bounds[variant]))
            r = true - pred[comp.targets_].to_numpy(float)
            lines.append({"run": run, "family": family, "adaptive": adaptive, "campaign": cid,
                          "factor": float(df[STATE].max() / hi), "variant": variant, "n": len(df),
                          "n_beyond": int(beyond.sum()), "first_beyond": first,
                          "all": dict(zip(comp.targets_, np.sqrt(np.mean(r ** 2, 0)).tolist())),
                          "beyond": dict(zip(comp.targets_, np.sqrt(np.mean(r[first:] ** 2, 0)).tolist()))
                          if first < len(df) else None,
                          "powers": powers, "state_hi": hi})
    return lines


def table(root: Path) -> pd.DataFrame:
    """Per run, family and mode (plain, adaptive) and scope (``all``: the whole campaigns;
    ``beyond``: from each one's first sample beyond the training speed on), the campaigns with an
    overspeed pooled: Σ² (sum over the targets of the mean squared error vs truth, µm²) per
    variant, the geometric mean over the campaigns of clamped / unclamped and the campaigns the
    clamp wins; ``in_range``: the largest |clamped - unclamped| Σ² of a campaign in range."""
    rows = []
    for f in sorted(root.glob("*_plain.json")) + sorted(root.glob("*_adaptive.json")):
        for line in json.loads(f.read_text()):
            for scope in ("all", "beyond"):
                if line[scope] is not None:
                    rows.append({**{k: line[k] for k in ("run", "family", "adaptive", "campaign",
                                                         "factor", "variant")}, "scope": scope,
                                 "w": line["n"] - (line["first_beyond"] if scope == "beyond" else 0),
                                 "s2": sum(v ** 2 for v in line[scope].values())})
    d = pd.DataFrame(rows)
    inside = d[(d.factor <= 1.0) & (d.scope == "all")].pivot_table(
        index=["run", "family", "adaptive", "campaign"], columns="variant", values="s2")
    in_range = (inside[["clamped", "clamped_edge"]].sub(inside["unclamped"], axis=0)).abs()
    out = []
    for (run, family, adaptive, scope), g in d[d.factor > 1.0].groupby(
            ["run", "family", "adaptive", "scope"]):
        piv = g.pivot_table(index="campaign", columns="variant", values="s2")
        w = g.groupby("campaign").w.first()
        pooled = piv.mul(w, axis=0).sum() / w.sum()
        out.append({"run": run, "family": family, "mode": "adaptive" if adaptive else "plain",
                    "scope": scope, "campaigns": len(piv), **pooled[list(VARIANTS)].to_dict(),
                    "gm_ratio": float(np.exp(np.log(piv["clamped"] / piv["unclamped"]).mean())),
                    "clamp_wins": int((piv["clamped"] < piv["unclamped"]).sum())})
    print(f"in range: {len(inside)} campaign lines, largest |clamped - unclamped| Σ² "
          f"{float(in_range.to_numpy().max()) if len(inside) else float('nan'):.3g}")
    return pd.DataFrame(out)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", default="/tmp/stateenv55-bench")
    ap.add_argument("--runs", nargs="+", default=list(RUNS))
    ap.add_argument("--families", nargs="+", default=list(FAMILIES))
    ap.add_argument("--table", action="store_true", help="print the table of the cached results")
    args = ap.parse_args(argv)
    root = Path(args.root)
    if args.table:
        with pd.option_context("display.width", 200, "display.max_rows", 500):
            print(table(root).round(3).to_string(index=False))
        return
    root.mkdir(parents=True, exist_ok=True)
    for run in args.runs:
        noisy, truth = simulate(root, run)
        for family in args.families:
            for adaptive in (False, True):
                out = root / f"{run}_{family}_{'adaptive' if adaptive else 'plain'}.json"
                if not out.is_file():
                    out.write_text(json.dumps(measure(run, noisy, truth, family, adaptive)))
                print(run, family, adaptive, "CPU s",
                      round(resource.getrusage(resource.RUSAGE_SELF).ru_utime, 1), flush=True)


if __name__ == "__main__":
    main()
