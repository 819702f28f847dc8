"""An ATI model that kept one model exports as that model (deploy57).

`ati=cmeans` on train campaigns that all start at one ambient level falls back to one model,
what `ati=none` fits ("one model (the model ati=none fits)"), and streams exactly as it.  A sweep
over `ati=none,cmeans` on such a record (a lab's one file: one campaign, one level) could then
promote a champion that `export` refused: "ati=cmeans switches between one model per ambient
interval ... not one linear system", which it was not.  Now such a model exports the arrays of
its one model (one of several intervals exports too since export57: test_export_ati57.py).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from test_export import _compose
from thermocomp.apps.deploy.export import Simulator, exported_files, state_space
from thermocomp.apps.deploy.streaming import replay
from thermocomp.core.models.ati import ATIRegressor
from thermocomp.shell.builders import build_compensator, deploy_stream
from thermocomp.shell.source import read_streamed

CAMPAIGNS = (("K01", "train"), ("K02", "train"), ("K03", "train"), ("K04", "test"))


def one_level(root, rows: int = 60):
    """Four campaigns of a two-sensor machine, every one started at the same 20 °C."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(57)
    t = np.arange(rows) * 120.0
    for i, (cid, _) in enumerate(CAMPAIGNS):
        a = 20 + (3 + i) * (1 - np.exp(-t / 2000)) + rng.normal(0, 0.03, rows)
        amb = 20 + 0.4 * np.sin(t / 3000 + i) + rng.normal(0, 0.03, rows)
        amb[0] = 20.0
        ex = 2.5 * (a - a[0]) - 1.5 * (amb - amb[0]) + rng.normal(0, 0.1, rows)
        pd.DataFrame({"time": t, "T_a": a, "T_amb": amb, "E_X": ex}).to_csv(root / f"{cid}.csv",
                                                                          index=False)
    pd.DataFrame([(c, f"{c}.csv", s) for c, s in CAMPAIGNS],
                 columns=["campaign", "file", "split"]).to_csv(root / "campaigns.csv", index=False)
    return root


def _deployed(data, ati: str, family: str):
    cfg = _compose(f"model={family}", f"ati={ati}", f"data.path={data}", "track=false",
                   "monitor.adaptive=false")
    ds, train_ids, test_ids, _ = read_streamed(cfg)
    train = {c: ds.campaigns[c] for c in train_ids}
    stream = deploy_stream(cfg, build_compensator(cfg, ds=ds).fit(train), train)
    return stream, [ds.campaigns[c].reset_index(drop=True) for c in test_ids]


def test_an_ati_model_of_one_interval_exports_as_the_model_ati_none_fits(tmp_path):
    data = one_level(tmp_path / "data")
    for family in ("mlr", "lagbank"):
        stream, tests = _deployed(data, "cmeans", family)
        [(_, est, _)] = stream._plan
        assert isinstance(est, ATIRegressor) and est.n_intervals_ == 1
        files = exported_files(stream, "c")          # refused before
        plain, _ = _deployed(data, "none", family)
        assert files["compensator.h"] == exported_files(plain, "c")["compensator.h"]
        sim = Simulator(state_space(stream))
        for df in tests:
            expected = -replay(stream, df)[stream.targets_].to_numpy(float)
            sim.reset()
            got = np.array([sim.step(r, t) for r, t in zip(df[stream.columns_].to_numpy(float),
                                                           df["time"])])
            assert np.max(np.abs(got - expected)) <= 1e-9
