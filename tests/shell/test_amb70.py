"""``init`` on a lab's catman exports (amb70, catman70's leftovers): the air thermocouple (``T
Luft [°C]``, ``T air [°C]``) named the ambient sensor by its word, so that ``auto`` may try ATI
without a ``data.roles.ambient`` by hand (an air bearing's ``Luftlager`` / ``air_bearing`` and
an ``Airbag`` not), and one file of tests appended with the logger silent between them read
with ``data.runs_at_pauses: true`` written by ``init``, saying why (the files are
test_catman70's)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import yaml

from conftest import FAST
from test_catman70 import _easy_folder, _values, _week
from test_stranger68 import ROWS
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main


def _written(out, name: str) -> dict:
    return yaml.safe_load((out / "conf" / "data" / f"{name}.yaml").read_text(encoding="utf-8"))


def test_init_names_the_air_thermocouple_of_a_catman_folder_the_ambient_sensor(tmp_path, capsys):
    """Before: 'T Luft [°C]' proposed a temperature (T_Luft): ``auto`` skipped ATI, and the
    user had to add data.roles.ambient."""
    assert main(["init", str(_easy_folder(tmp_path / "rig")), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "ambient: 'T Luft [°C]' (its name" in said
    assert "  T Luft [°C]                     ambient      T_amb" in said
    config = _written(tmp_path / "init", "rig")
    assert config["roles"]["ambient"] == ["T Luft"]
    config.pop("defaults")
    ds, _ = read_dataset(config["path"], config)
    frame = ds.campaigns["Spindeltest_02"]
    assert "T_amb" in frame.columns and "T_Luft" not in frame.columns
    np.testing.assert_allclose(frame["T_amb"].to_numpy(), _values(2)[:, 0])


def _table(path, headers: list[str]) -> None:
    """A minute's samples of the errors and temperatures under ``headers`` (an error dX first)."""
    rng = np.random.default_rng(70)
    t = np.arange(ROWS) * 60.0
    columns = {"time [s]": t, "dX [µm]": np.cumsum(rng.normal(0, 0.3, ROWS))}
    for k, h in enumerate(headers):
        columns[h] = 20 + 0.01 * k + np.cumsum(rng.normal(0, 0.01, ROWS))
    pd.DataFrame(columns).to_csv(path, index=False, float_format="%.4f")


def test_two_air_columns_are_both_ambient_and_an_air_bearing_or_an_airbag_is_not(tmp_path,
                                                                                 capsys):
    """'air' and 'Luft' as whole words only, and not where another word says whose air it is
    (before: every one of them a temperature)."""
    _table(tmp_path / "hall.csv", ["T Luft vorn [°C]", "T air rear [°C]", "T Luftlager [°C]",
                                   "T air_bearing [°C]", "Airbag [°C]", "T cooling air [°C]"])
    assert main(["init", str(tmp_path / "hall.csv"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "ambient: 'T Luft vorn [°C]', 'T air rear [°C]' (their names" in said
    config = _written(tmp_path / "init", "hall")
    assert config["roles"]["ambient"] == ["T Luft vorn", "T air rear"]
    config.pop("defaults")
    ds, _ = read_dataset(config["path"], config)
    columns = set(next(iter(ds.campaigns.values())).columns)
    assert columns == {"time", "E_dX", "T_amb_T_Luft_vorn", "T_amb_T_air_rear", "T_Luftlager",
                       "T_air_bearing", "T_Airbag", "T_cooling_air"}


def test_init_writes_runs_at_pauses_for_a_week_of_tests_appended_in_one_file(tmp_path, capsys):
    """Before: init read the week as one record cut 90/10 (its warning named
    data.runs_at_pauses): a second try to read the three tests as campaigns."""
    path = _week(tmp_path / "week17.txt")
    assert main(["init", str(path), "data.roles.error=['MCS*']", f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert ("week17.txt: its time pauses 2 time(s) for more than 100 sample periods (the "
            "longest 47 h)") in said
    assert "campaign week17_3: test, 120 rows" in said
    config = _written(tmp_path / "init", "week17")
    assert config["runs_at_pauses"] is True
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=week17",
                 "model=mlr", *FAST, f"out={tmp_path / 'out'}"]) == 0
    metrics = json.loads((tmp_path / "out" / "metrics.json").read_text())
    assert metrics["targets"]["E_MCS_X1"]["test"]["rmse"] < 0.2     # (the map is linear)
    # one test alone in its file: no pause, nothing proposed
    one = tmp_path / "one"
    one.mkdir()
    _table(one / "test01.csv", ["T Ständer [°C]"])
    assert main(["init", str(one / "test01.csv"), f"out={tmp_path / 'init1'}"]) == 0
    assert "runs_at_pauses" not in _written(tmp_path / "init1", "test01")


def test_a_keysight_label_in_angle_brackets_names_the_air(tmp_path, capsys):
    """A Keysight DAQ's header puts the channel's label in angle brackets (``101 <Air> (C)``);
    before, ``<air>`` was one word and the air a plain temperature (small71's check)."""
    _table(tmp_path / "daq.csv", ["101 <Air> [°C]", "102 <Bed> [°C]", "103 <Luft Lager> [°C]"])
    assert main(["init", str(tmp_path / "daq.csv"), f"out={tmp_path / 'init'}"]) == 0
    assert "ambient: '101 <Air> [°C]' (its name" in capsys.readouterr().out
    assert _written(tmp_path / "init", "daq")["roles"]["ambient"] == ["101 <Air>"]
