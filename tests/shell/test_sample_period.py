"""Campaigns logged at different rates have one sample period, the one the lag bank keeps: the
median step over every training row (:func:`thermocomp.core.timerule.median_step`), not the
median of each campaign's own."""

from __future__ import annotations

import numpy as np
import pandas as pd

from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.monitor import AdaptiveCompensator
from thermocomp.core.compensator import Compensator
from thermocomp.core.models.lagbank import LagBank
from thermocomp.shell.cli import main

# one long campaign every 60 s, two short ones every 300 s: 39 steps of 60 s, 10 of 300 s
RATES = {"c0": (40, 60.0), "c1": (6, 300.0), "c2": (6, 300.0)}


def _campaign(rows: int, period: float, seed: int) -> pd.DataFrame:
    rng = np.random.default_rng(seed)
    t1 = 20 + np.cumsum(rng.normal(0, 0.05, rows))
    return pd.DataFrame({"time": np.arange(rows) * period, "T_1": t1,
                         "T_2": t1 + rng.normal(0, 0.02, rows), "E_X": 3 * (t1 - t1[0])})


def _campaigns() -> dict[str, pd.DataFrame]:
    return {c: _campaign(rows, period, k) for k, (c, (rows, period)) in enumerate(RATES.items())}


def test_the_adaptive_stream_substitutes_the_plain_streams_step():
    # before: the guard's period (the adaptive stream's clock) was the median of the campaigns'
    # medians, 300 s, where the plain stream's clock steps the lag bank's 60 s: a sample
    # without time moved the lags 60 s in one stream, 300 s in the other
    train = _campaigns()
    streaming = StreamingCompensator.from_training(Compensator(LagBank(n_taus=3)).fit(train), train)
    adaptive = AdaptiveCompensator.from_training(streaming, train)
    assert streaming._clock.period_s == 60.0
    assert adaptive.period_s == streaming._clock.period_s


def test_init_says_the_period_every_row_is_sampled_at(tmp_path, capsys):
    # before: 'sample period: 300 s' (two short campaigns of three outvoting the long one)
    folder = tmp_path / "lab"
    folder.mkdir()
    for cid, frame in _campaigns().items():
        frame.to_csv(folder / f"{cid}.csv", index=False)
    (folder / "campaigns.csv").write_text("campaign,file,split\nc0,c0.csv,train\n"
                                          "c1,c1.csv,train\nc2,c2.csv,test\n")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    assert "sample period: 60 s," in capsys.readouterr().out
