"""The diagnosed effects export still refused at stop 59, to the machine's code (exportrest60).

A simulated year-round spindle with a door (``thermocomp simulate sim=yearround_spindle
"sim.generator.effects=[door]" seed=6002``: 24 campaigns, initial ambients 3.7-31.7 °C, the door
``S_door`` no declared input) gets, per case, a diagnosed model built as diagnose's written
config builds it (:class:`~thermocomp.apps.diagnose.AugmentedRegressor` around ``model=mlr`` or a
lag bank, fitted on the train campaigns, deployed as ``replay`` deploys it) with the effects:
a lag's initial-state transient (one learned direction over the field temperatures and the door,
one per sensor), ``ambient_step`` (two thresholds, beside the ambient law) and a lag bank's lag
of a diagnosed lag (a cascade), and effects around an ATI model (three intervals; two with the
ambient interaction).  Its model.pkl goes through ``thermocomp export`` (C, ST, JSON);
``stream.c`` (``cc``) streams the test campaigns one after the other (a blank row: a campaign
restart), whole and stopped half-way and resumed with ``--state``; the ST runs through the
tests' transpiler and the JSON through the numpy reference.  Each is compared with ``replay`` of
the same deployed object.  The test campaigns are edited: the door missing at the first test
campaign's first two rows (a transient's sensor missing at its first row), a missing time, a
3 h gap, one sensor pushed out of the envelope half-way (the clamp acting).  Everything in a
scratch root, never the checkout's.

    PYTHONPATH=$PWD/src .venv/bin/python benchmarks/bench_diagnosed_to_code60.py [case ...]

Measured (gain61, 2026-12-01; 618 test rows, 311 clamped): every case's C, restarted C, ST and
JSON = replay to <= 4.5e-12 µm; the low-pass copies around the ATI interaction and over an ARX
model (``lowpass-on-arx``) clamped by their gains (``outright`` 0; 3, every target, before).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from compiled_stream import compile_stream, whole_and_resumed

ROOT = Path(os.environ.get("BENCH_ROOT", "/tmp/exportrest60-root"))
REPO = Path(__file__).resolve().parents[1]
PY = str(REPO / ".venv" / "bin" / "python")
DATA = "data/raw/year6002"          # a seed no test or benchmark uses (grep 6002)
SIM = ["sim=yearround_spindle", "seed=6002", "sim.generator.effects=[door]"]

FIELD = ["T_bearing_f1", "T_bearing_f2", "T_bearing_f3", "T_nose", "T_bearing_r"]
DOOR_LAG = {"kind": "signal", "transform": "first_order_lag", "column": "S_door", "tau_s": 1800.0}
CASES = {
    "transient-direction": ([{**DOOR_LAG, "initial_state": [*FIELD, "S_door"],
                              "initial_directions": 2}], "mlr"),
    "transient-per-sensor": ([{"kind": "dynamics", "transform": "first_order_lag",
                               "column": "T_nose", "tau_s": 3600.0,
                               "initial_state": ["T_nose", "S_door"]}], "mlr"),
    "lowpass-transient": ([{"kind": "dynamics", "transform": "lowpass_inputs", "tau_s": 3600.0,
                            "initial_state": FIELD, "initial_directions": 1}], "mlr"),
    "ambient-steps": ([{"kind": "ambient_interval", "transform": "ambient_step", "threshold_c": 18.0},
                       {"kind": "ambient_interval", "transform": "ambient_step", "threshold_c": 9.0},
                       {"kind": "ambient_interval", "transform": "ambient_linear"}], "mlr"),
    "lag-of-lag": ([DOOR_LAG], "lagbank"),
    "all-on-lagbank": ([{**DOOR_LAG, "initial_state": [*FIELD, "S_door"], "initial_directions": 1},
                        {"kind": "ambient_interval", "transform": "ambient_step", "threshold_c": 18.0},
                        {"kind": "interaction", "transform": "product", "column": "S_door",
                         "other": "T_nose"}], "lagbank"),
    # around an ATI model (diagnose ati=cmeans): each interval's laws on the features, and with
    # the ambient interaction times A0 - 20 too
    "around-ati": ([{**DOOR_LAG, "initial_state": [*FIELD, "S_door"], "initial_directions": 1},
                    {"kind": "ambient_interval", "transform": "ambient_step", "threshold_c": 18.0},
                    {"kind": "interaction", "transform": "product", "column": "S_door",
                     "other": "T_nose"}], "ati"),
    "around-ati-interaction": ([{**DOOR_LAG, "initial_state": [*FIELD, "S_door"],
                                 "initial_directions": 1},
                                {"kind": "dynamics", "transform": "lowpass_inputs", "tau_s": 3600.0}],
                               "ati+interaction"),
    # gain61: a low-pass copy over an ARX model (its feedback on the copy's lag), clamped by
    # its gain (outright before, as around the ATI model above)
    "lowpass-on-arx": ([{"kind": "dynamics", "transform": "lowpass_inputs", "tau_s": 3600.0}], "arx"),
}
PUSH_C = 30.0


def tc(*args: str) -> str:
    env = dict(os.environ, THERMOCOMP_ROOT=str(ROOT), PYTHONPATH=str(REPO / "src"))
    p = subprocess.run([PY, "-m", "thermocomp", *args], cwd=ROOT, env=env, capture_output=True,
                       text=True)
    if p.returncode:
        raise RuntimeError(f"thermocomp {' '.join(args)}: exit {p.returncode}\n{p.stderr[-2000:]}")
    return p.stdout + p.stderr


def compose(*overrides):
    from hydra import compose as hydra_compose
    from hydra import initialize_config_dir

    from thermocomp.base.paths import conf_dir
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        return hydra_compose(config_name="config", overrides=list(overrides))


def edited(tests: list[pd.DataFrame], first: str) -> list[pd.DataFrame]:
    """The test campaigns as the bench streams them (module doc)."""
    out = [df.reset_index(drop=True).copy() for df in tests]
    out[0].loc[[0, 1], "S_door"] = np.nan          # a transient's sensor missing at its first row
    out[0].loc[7, "time"] = np.nan                 # one period after the previous sample
    out[1].loc[len(out[1]) // 3:, "time"] += 3 * 3600.0     # a gap: nothing restarts
    for df in out:
        df.loc[len(df) // 2:, first] += PUSH_C     # out of the envelope: the clamp acts
    return out


def case(name: str) -> dict:
    from sklearn.base import clone

    from thermocomp.apps.deploy.export import Simulator
    from thermocomp.apps.deploy.export.statespace import StateSpace
    from thermocomp.apps.deploy.streaming import replay
    from thermocomp.apps.diagnose import AugmentedRegressor
    from thermocomp.apps.diagnose.features import as_effect
    from thermocomp.core.models import ARX, MLR, LagBank
    from thermocomp.core.models.ati import ATIRegressor
    from thermocomp.shell.builders import build_compensator, deploy_stream
    from thermocomp.shell.model_store import save_model
    from thermocomp.shell.source import read_streamed
    sys.path[:0] = [str(REPO / "tests" / "shell"), str(REPO / "tests")]
    from test_export import StructuredText

    effects, base = CASES[name]
    cfg = compose(f"data.path={ROOT / DATA}", "track=false", "monitor.adaptive=false",
                  "promote.envelope.pattern=false", "model=mlr")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    comp = build_compensator(cfg, ds=ds)
    inner = {"lagbank": LagBank(n_taus=2), "mlr": None, "arx": ARX(ar=True),
             "ati": ATIRegressor(MLR(), n_intervals=3),
             "ati+interaction": ATIRegressor(MLR(), n_intervals=2, ambient_interaction=True)}[base]
    est = AugmentedRegressor(inner, effects={t: effects for t in ("E_X", "E_Y", "E_Z")})
    comp = clone(comp).set_params(estimator=est).fit(train)
    stream = deploy_stream(cfg, comp, train)
    folder = ROOT / "reports" / f"code60-{name}"
    (folder / "model").mkdir(parents=True, exist_ok=True)
    pkl = save_model(comp, folder / "model" / "model.pkl")
    for fmt in ("c", "st"):
        msg = tc("export", f"data.path={DATA}", f"export.model={pkl}", f"export.format={fmt}",
                 f"out={folder / 'code'}", "track=false", "monitor.adaptive=false",
                 "promote.envelope.pattern=false")
    folder = folder / "code"
    binary = compile_stream(folder)
    tests = edited([ds.campaigns[c] for c in test_ids], stream.columns_[0])
    cols = ["time", *stream.columns_]
    parts = [df[cols].to_csv(index=False, float_format="%.17g") for df in tests]
    text = parts[0] + "".join("\n" + p.split("\n", 1)[1] for p in parts[1:])
    targets = list(stream.targets_)
    replayed = [replay(stream, df) for df in tests]
    expected = np.vstack([-r[targets].to_numpy(float) for r in replayed])
    got, restarted = whole_and_resumed(binary, text)
    outs = [f"C_{t[2:]}" for t in targets]
    ss = StateSpace.from_dict(json.loads((folder / "compensator.json").read_text()))
    sim, fb = Simulator(ss), StructuredText((folder / "compensator.st").read_text())
    js, st = [], []
    for df in tests:
        sim.reset()
        for k, (u, t) in enumerate(zip(df[stream.columns_].to_numpy(float), df["time"])):
            js.append(sim.step(u, t))
            st.append(fb(u, t, k == 0))
    banner = (folder / "compensator.c").read_text().split("*/")[0]
    laws = banner.split("per target: ")[1].split("\n *  inputs")[0] if "per target" in banner else ""
    return {"case": name, "base": base, "rows": len(expected),
            "clamped": int(sum(int(r["n_clamped"].gt(0).sum()) for r in replayed)),
            "initial": len(ss.initial), "laws": len(ss.law_lo),
            "ambient laws": sum(ss.law_ambient or [0]),
            "cascades": sum(k >= 0 for k in ss.lag_of),
            "outright": sum(ss.clamp_outright or [0]),
            "C-replay": float(np.max(np.abs(got[outs].to_numpy(float) - expected))),
            "restart-replay": float(np.max(np.abs(restarted[outs].to_numpy(float) - expected))),
            "ST-replay": float(np.max(np.abs(np.array(st) - expected))),
            "json-replay": float(np.max(np.abs(np.array(js) - expected))),
            "named": all(as_effect(e).title.replace("°C", " degC") in laws for e in effects),
            "export": msg.strip().splitlines()[-1][:80]}


def main(names: list[str]) -> None:
    ROOT.mkdir(parents=True, exist_ok=True)
    if not (ROOT / "conf").exists():
        (ROOT / "conf").symlink_to(REPO / "conf")
    if not (ROOT / DATA).exists():
        tc("simulate", *SIM, f"data.path={DATA}")
    rows = [case(n) for n in names or list(CASES)]
    table = pd.DataFrame(rows)
    with pd.option_context("display.float_format", "{:.1e}".format, "display.width", 200):
        print(table.drop(columns=["export"]).to_string(index=False))


if __name__ == "__main__":
    main(sys.argv[1:])
