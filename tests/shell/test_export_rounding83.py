"""The logger's last digit across the band in the compiled C (ctest83, issue 34): the exported
monitor's ``mon_within_rounding`` holds a healthy offset the served monitor holds (mon83), and
an export without the rounding bound excludes it where the served monitor without the rule does.

test_monitor_rounding83's machine (eight sensors on a 0.1 K logger, its two training records)
with an error ``E_X`` the sensors make, deployed as replay does (adaptive MLR); its test
campaign is that module's ``offset`` record: ``T_0`` settles at a healthy offset whose error the
last digit of its most weighty predictor flips across the band.  Compiled with gcc -Wall -Wextra
-Werror, the C gives the served corrections on every row, says nothing (``T_0`` never excluded,
no ``not in the code``); with ``monitor.rounding`` zeros (an export before mon83) it excludes
``T_0`` at the served monitor's row without the rule and gives that model's corrections."""

from __future__ import annotations

import copy
import re

import numpy as np
import pandas as pd
import pytest

import test_export
from conftest import deployed_as_replay
from test_export import built_stream, needs_cc
from test_export_cmon80 import _streamed
from test_monitor_rounding83 import NAMES, PERIOD, TRAIN, _monitor, _record
from thermocomp.apps.deploy.export import exported_files, state_space
from thermocomp.apps.deploy.export.pack import corrections
from thermocomp.apps.deploy.report import stream_rows

WEIGHTS = np.array([1.5, -0.5, 0.8, 0.0, 0.3, -0.2, 2.0, -1.0])   # µm per °C: E_X's sensors
SAID = re.compile(r"line (\d+): monitor: (\S+): (.*)")


def _campaign(x: np.ndarray) -> pd.DataFrame:
    frame = pd.DataFrame(x, columns=NAMES)
    frame.insert(0, "time", PERIOD * np.arange(len(x)))
    frame["E_X"] = (x - x[0]) @ WEIGHTS
    return frame


@pytest.fixture(scope="module")
def served(tmp_path_factory):
    """``(adaptive MLR as replay deploys it, the offset record)``."""
    root = tmp_path_factory.mktemp("rounding83") / "data"
    root.mkdir()
    split = {"K01": ("train", TRAIN["a"]), "K02": ("train", TRAIN["b"]),
             "K03": ("test", _record(_monitor(), "offset"))}
    for cid, (_, x) in split.items():
        _campaign(x).to_csv(root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, (s, _) in split.items()],
                 columns=["campaign", "file", "split", "notes"]).to_csv(root / "campaigns.csv",
                                                                        index=False)
    cfg = test_export._compose(f"data.path={root}", "track=false", "monitor.adaptive=true",
                               "model=mlr")
    deployed, ds, test_ids = deployed_as_replay(cfg)
    return deployed, ds.campaigns[test_ids[0]].reset_index(drop=True)


def _c_run(deployed, frame, folder) -> tuple[np.ndarray, np.ndarray, list[tuple[int, str, str]]]:
    """``deployed``'s served corrections, its C's (compiled in ``folder``) and the C's monitor
    messages ``(CSV line, sensor, what)``."""
    ss = state_space(deployed, monitor=True)
    want = corrections(ss, stream_rows(deployed, frame, "K03").y)
    got, said = _streamed(built_stream(folder, exported_files(deployed, "c")), frame, ss.inputs)
    assert got.shape == want.shape
    return want, got, [(int(m[1]), m[2], m[3]) for m in map(SAID.search, said.splitlines()) if m]


def _served_out(deployed, frame) -> list[tuple[int, str]]:
    """The served exclusions ``(CSV line: row + 2, sensor)``."""
    times = frame["time"].to_numpy(float)
    return [(int(np.searchsorted(times, e["time"])) + 2, e["sensor"])
            for e in stream_rows(deployed, frame, "K03").events if e.get("to") == "excluded"]


@needs_cc
def test_the_compiled_monitor_holds_the_offset_the_last_digit_flips_as_served(served, tmp_path):
    deployed, frame = served
    mon = deployed.monitor
    # the deployed monitor meets the rounding case (_record asserts it on the monitor it is given)
    assert np.array_equal(frame[NAMES].to_numpy(float), _record(mon, "offset"))
    assert mon.rounding_c[0] > 0 and state_space(deployed, monitor=True).monitor["rounding"] == \
        pytest.approx(mon.rounding_c)
    before = copy.deepcopy(deployed)         # an export before mon83: monitor.rounding zeros
    before.monitor.rounding_c = np.zeros(len(NAMES))
    assert state_space(before, monitor=True).monitor["rounding"] == [0.0] * len(NAMES)
    shipped = _served_out(before, frame)
    assert [s for _, s in shipped] == ["T_0"]
    warned = [e["time"] for e in stream_rows(deployed, frame, "K03").events
              if e.get("sensor") == "T_0" and e["to"] == "warning"]
    assert not _served_out(deployed, frame) and warned                  # served: warned, held

    (tmp_path / "rule").mkdir()
    want, got, said = _c_run(deployed, frame, tmp_path / "rule")
    assert np.max(np.abs(got - want)) < 1e-9                            # every row
    assert said == []                  # T_0 never excluded, nothing flagged not in the code

    (tmp_path / "before").mkdir()
    want0, got0, said0 = _c_run(before, frame, tmp_path / "before")
    assert np.max(np.abs(got0 - want0)) < 1e-9
    assert [(line, sensor) for line, sensor, what in said0 if "excluded" in what] == shipped
    assert not [what for *_, what in said0 if "not in the code" in what]
    # the exclusion moves the correction (the model reads T_0 rebuilt): the rule is seen
    assert np.max(np.abs(want0 - want)) > 0.1
