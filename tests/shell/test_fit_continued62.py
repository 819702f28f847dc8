"""Train files that continue one another are fitted as the one record they are, as they are
predicted (lagbank62).

``run`` predicts a test file that continues the train files joined to them (the state carried
over, :mod:`thermocomp.core.continuation`), but fitted the train files apart, every lag restarted
at each file's first sample: the model was scored in a frame it was not fitted in (probe61's
grinder, three weekly files of one record: the lag bank tested E_Z 5.04 µm against MLR's 1.69,
9.7 in the test week's first sixth; fitted on the two train weeks joined 0.70).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from hydra import compose, initialize_config_dir

from thermocomp.base.paths import conf_dir
from thermocomp.core.continuation import predict
from thermocomp.shell.chain import fit_chain
from thermocomp.shell.source import open_source

PERIOD = 60.0


def _record(n: int = 2400, seed: int = 0) -> pd.DataFrame:
    """A machine whose error follows a heater's power through a 3 h thermal lag (µm) while its
    sensor follows it through 20 min: the error is a slow lag of the sensor, a state that a
    restart at a file's first sample forgets."""
    rng = np.random.default_rng(seed)
    power = np.repeat(rng.uniform(0, 4, n // 60 + 1), 60)[:n]
    a_s, a_e = np.exp(-PERIOD / 1200.0), np.exp(-PERIOD / 10800.0)
    sensor, slow = np.zeros(n), np.zeros(n)
    for i in range(1, n):
        sensor[i] = a_s * sensor[i - 1] + (1 - a_s) * power[i]
        slow[i] = a_e * slow[i - 1] + (1 - a_e) * sensor[i]
    return pd.DataFrame({"time": np.arange(n) * PERIOD, "T_heater": 20 + sensor + rng.normal(0, 0.01, n),
                         "T_amb": 20 + rng.normal(0, 0.01, n),
                         "E_X": 6.0 * slow + rng.normal(0, 0.05, n)})


def _folder(root, parts: dict[str, tuple[slice, str, str]]):
    """``parts``: campaign -> (its rows of the record, split, the campaign it continues)."""
    root.mkdir()
    record = _record()
    rows = []
    for cid, (cut, split, before) in parts.items():
        part = record.iloc[cut].reset_index(drop=True)
        part.assign(time=part["time"] - part["time"].iloc[0]).to_csv(root / f"{cid}.csv", index=False)
        rows.append((cid, f"{cid}.csv", split, before))
    pd.DataFrame(rows, columns=["campaign", "file", "split", "continues"]).to_csv(
        root / "campaigns.csv", index=False)
    return root


def _test_prediction(root):
    with initialize_config_dir(config_dir=str(conf_dir()), version_base="1.3"):
        cfg = compose(config_name="config", overrides=[
            "track=false", "plots=none", "model=lagbank", "model.estimator.n_taus=4",
            f"data.path={root}"])
    ds = open_source(cfg)
    assert cfg.data.reference == "none"        # the test continues the train: state carried over
    comp = fit_chain(cfg, ds)
    return predict(comp, ds, ["test"])[0]["test"]["E_X"].to_numpy()


def test_a_record_cut_into_train_files_is_fitted_as_the_uncut_record(tmp_path):
    whole = _folder(tmp_path / "whole", {"train": (slice(0, 1800), "train", ""),
                                         "test": (slice(1800, None), "test", "train")})
    cut = _folder(tmp_path / "cut", {"first": (slice(0, 900), "train", ""),
                                     "train": (slice(900, 1800), "train", "first"),
                                     "test": (slice(1800, None), "test", "train")})
    assert _test_prediction(cut) == pytest.approx(_test_prediction(whole), abs=1e-6)
