"""A lab's data in (data88b): a folder holding ONE run as two loggers' files is cut as a one-file
record is (``data.test_fraction``: its last share a test campaign continuing the rest; it was
refused, "a run of two files is not cut in two"), and a time of day without its date that passes
midnight is unwrapped into a continuing time, the rows a logger skipped still skipped (it was
refused; the fix it gave timed the rows by their period, which closes such gaps)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from conftest import LIGHT
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.shell.cli import main

ROWS = 48
PERIOD_S = 300
START = pd.Timestamp("2027-03-05 21:30:00")     # past midnight at row 30


def _record(seed: int = 0) -> pd.DataFrame:
    """A run's rows (contract names), ``time`` in s from its start."""
    rng = np.random.default_rng(seed)
    temp = 20 + np.cumsum(rng.normal(0, 0.05, (ROWS, 3)), axis=0)
    error = 2 * temp[:, 0] - temp[:, 1] + 0.5 * temp[:, 2] + rng.normal(0, 0.01, ROWS)
    return pd.DataFrame({"time": np.arange(ROWS) * float(PERIOD_S), "T_a": temp[:, 0],
                         "T_b": temp[:, 1], "T_c": temp[:, 2], "E_X": error})


def _stamps(time: pd.Series, form: str) -> list[str]:
    return [(START + pd.Timedelta(seconds=float(t))).strftime(form) for t in time]


def _pair(folder, rows: pd.DataFrame) -> None:
    """``rows`` as two loggers wrote them: ``run01_temp.csv`` and ``run01_disp.csv``."""
    folder.mkdir()
    stamped = rows.assign(time=_stamps(rows["time"], "%Y-%m-%dT%H:%M:%S"))
    stamped[["time", "T_a", "T_b", "T_c"]].to_csv(folder / "run01_temp.csv", index=False)
    stamped[["time", "E_X"]].to_csv(folder / "run01_disp.csv", index=False)


def _test_rmse(out) -> dict:
    metrics = json.loads((out / "metrics.json").read_text())
    return {t: said["test"]["rmse"] for t, said in metrics["targets"].items()}


def test_one_run_of_two_loggers_files_is_cut_as_its_joined_file_is(tmp_path):
    # before: refused, exit 2, "a folder whose one run is two loggers' files (run01_temp.csv,
    # run01_disp.csv: one campaign) has none to hold out ... not cut in two"
    rows = _record()
    _pair(tmp_path / "pair", rows)
    rows.to_csv(tmp_path / "joined.csv", index=False)
    cfg = {"test_fraction": 0.25}
    pair, _ = read_dataset(tmp_path / "pair", cfg)
    joined, _ = read_dataset(tmp_path / "joined.csv", cfg)
    assert list(pair.manifest["split"]) == list(joined.manifest["split"]) == ["train", "test"]
    assert list(pair.manifest["continues"]) == ["", "run01_train"]     # the run's id, its parts
    for part, same in zip(pair.ids(), joined.ids()):
        pd.testing.assert_frame_equal(pair.campaigns[part][list(rows.columns)],
                                      joined.campaigns[same][list(rows.columns)])
    # init proposes it with no key; run scores it as the joined file, replay streams it alike
    assert main(["init", str(tmp_path / "pair"), f"out={tmp_path / 'init'}"]) == 0
    search = f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]"
    scored = {}
    for name, path in (("pair", tmp_path / "pair"), ("joined", tmp_path / "joined.csv")):
        common = [search, "data=pair", f"data.path={path}", "model=mlr",
                  "data.test_fraction=0.25", *LIGHT, "track=false"]
        assert main(["run", *common, f"out={tmp_path / (name + '-run')}"]) == 0
        assert main(["replay", *common, f"replay.model={tmp_path / (name + '-run') / 'model.pkl'}",
                     f"out={tmp_path / (name + '-replay')}"]) == 0
        replayed = json.loads((tmp_path / (name + "-replay") / "replay.json").read_text())
        scored[name] = (_test_rmse(tmp_path / (name + "-run")), replayed)
    assert scored["pair"][0] == pytest.approx(scored["joined"][0], abs=1e-9)
    for target, streamed in scored["joined"][1]["targets"].items():
        for key in ("n_samples", "rmse", "rmse_batch"):      # (not its µs per sample)
            assert scored["pair"][1]["targets"][target][key] == pytest.approx(streamed[key],
                                                                              abs=1e-9)


def _clock(rows: pd.DataFrame) -> pd.DataFrame:
    """``rows`` with ``Time`` the wall clock's ``hh:mm:ss``, no date (past midnight)."""
    return rows.assign(time=_stamps(rows["time"], "%H:%M:%S")).rename(columns={"time": "Time"})


def test_a_time_of_day_past_midnight_reads_as_a_continuing_time_its_skipped_rows_kept(tmp_path):
    # before: refused, "a time of day without its date (it would go back at midnight)"; its
    # fix, the rows timed by the period, closes the gap of every row a logger skipped
    rows = _record(1).drop(index=[5, 6, 29, 30, 41]).reset_index(drop=True)   # (one at midnight)
    _clock(rows).to_csv(tmp_path / "night.csv", index=False)
    rows.to_csv(tmp_path / "contract.csv", index=False)
    night, report = read_dataset(tmp_path / "night.csv")
    contract, _ = read_dataset(tmp_path / "contract.csv")
    clock, time = night.campaigns["night"], contract.campaigns["contract"]
    # the time of day's seconds since the first day's midnight: the contract's from the start
    np.testing.assert_array_equal(clock["time"] - clock["time"].iloc[0], time["time"])
    pd.testing.assert_frame_equal(clock.drop(columns="time"), time.drop(columns="time"))


@pytest.mark.parametrize("back", ["00:10:00", "23:20:00"])
def test_a_time_of_day_going_back_otherwise_stays_refused(tmp_path, back):
    # only a step back of about a day is midnight: one of 10 min (a clock set back) stays
    # refused with its row, past midnight too
    rows = _clock(_record(2))
    rows.loc[40, "Time"] = back        # row 40 is 00:50:00 (after midnight), 39 00:45:00
    rows.to_csv(tmp_path / "back.csv", index=False)
    with pytest.raises(ContractError) as caught:
        read_dataset(tmp_path / "back.csv")
    assert caught.value.row is not None
    assert "decrease" in caught.value.reason or "back" in caught.value.reason
