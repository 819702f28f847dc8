"""A historian's long export through the CLI (historian60): ``init`` proposes the grid's period
(the fastest error tag's median interval, written with a comment) and the roles over the TAG
names, ``run`` with that config scores it, ``run`` without the period and a file with a bad
sample exit 2 naming the key, or the file, column and row.  Before, ``init`` found no measured
error ("the numeric columns: 'Value'") and ``run`` refused 'TagName', 'Value' and 'Quality' as
columns without a role."""

from __future__ import annotations

import json

import pandas as pd
import yaml

from conftest import FAST, refused, thermocomp
from test_historian60 import BEARING, PROBE, samples, write


def test_init_proposes_the_period_and_run_scores_the_long_file(tmp_path):
    write(samples(), tmp_path / "pi.csv")
    out = tmp_path / "out"
    said = thermocomp("init", f"data.path={tmp_path / 'pi.csv'}", f"out={out}").stdout
    assert f"data.resample_s=10 s, the median interval of the fastest error tag {PROBE!r}" in said
    assert "a historian's long file ('TagName' the tag, 'Value' the value, 'Quality'" in said
    text = (out / "conf" / "data" / "pi.yaml").read_text()
    config = yaml.safe_load(text)
    assert config["resample_s"] == 10.0 and config["roles"]["error"] == ["MC07.Probe.Z"]
    assert "# the grid a historian's tags are held onto" in text.split("resample_s:")[0]
    thermocomp("run", f"hydra.searchpath=[file://{out / 'conf'}]", "data=pi", f"out={out}",
               "model=mlr", *FAST)
    metrics = json.loads((out / "metrics.json").read_text())
    assert "E_MC07.Probe.Z" in json.dumps(metrics)


def test_run_without_the_period_is_refused_naming_the_key(tmp_path, capsys):
    write(samples(), tmp_path / "pi.csv")
    refused(["run", f"data.path={tmp_path / 'pi.csv'}", "data.roles.error=[MC07.Probe.Z]",
             f"out={tmp_path / 'out'}", *FAST], capsys,
            "data.resample_s", f"{PROBE} 10 s", "thermocomp init")
    assert not (tmp_path / "out" / "metrics.json").exists()


def test_a_repeated_stamp_with_another_value_exits_2_naming_file_column_row(tmp_path, capsys):
    frame = samples()
    at = int(frame.index[frame["TagName"] == BEARING][3])
    extra = frame.loc[[at]].assign(Value=frame.loc[at, "Value"] + 1)
    write(pd.concat([frame.loc[:at], extra, frame.loc[at + 1:]], ignore_index=True),
          tmp_path / "pi.csv")
    refused(["run", f"data.path={tmp_path / 'pi.csv'}", "data.roles.error=[MC07.Probe.Z]",
             "data.resample_s=10", f"out={tmp_path / 'out'}", *FAST], capsys,
            f"file {tmp_path / 'pi.csv'}, column 'Value', data row {at + 2}",
            f"tag {BEARING!r} has two samples at")
    assert not (tmp_path / "out" / "metrics.json").exists()


def test_init_proposes_a_column_of_0_and_1_as_a_state(tmp_path):
    """A flag under a header that does not say so (``Part.Loaded``, ``Hall.Door``) was proposed a
    temperature, or the hall's air by its word, and read as one (historian60's lathe)."""
    import numpy as np

    t = np.arange(200) * 60.0
    door = (np.arange(200) // 25 % 2).astype(float)
    frame = pd.DataFrame({"time": t, "Hall.Door": door,
                          "Spindle.Temp": 20 + t / 3600 + 0.1 * door,
                          "dX [um]": 2 * t / 3600 + np.sin(t / 900)})
    frame.to_csv(tmp_path / "lab.csv", index=False)
    out = tmp_path / "out"
    said = thermocomp("init", f"data.path={tmp_path / 'lab.csv'}", f"out={out}").stdout
    assert "'Hall.Door': only two values one apart (0 / 1) over the record" in said
    config = yaml.safe_load((out / "conf" / "data" / "lab.yaml").read_text())
    assert config["roles"]["state"] == ["Hall.Door"] and config["roles"]["ambient"] == []
