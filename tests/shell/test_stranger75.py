"""What a stranger met on a horizontal boring mill's run files (stranger75, ``bench_stranger75.py``);
each test fails on the code before its mend.  Small files written here: hours, not the bench's days."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import FAST, refused
from thermocomp.core.io import ReadOptions, read_dataset
from thermocomp.core.io.stdin import read_stream
from thermocomp.shell.cli import main


def boring_mill(rows: int = 180, seed: int = 75) -> pd.DataFrame:
    """A boring mill's hours at 60 s: the headstock's height in mm (150-1850, a job at a time),
    two temperatures, the Y error in µm."""
    rng = np.random.default_rng(seed)
    t = np.arange(rows) * 60.0
    heat = 16 + 5 * (1 - np.exp(-t / 2400)) + rng.normal(0, 0.02, rows)
    height = np.repeat(rng.integers(15, 186, rows // 30 + 1) * 10.0, 30)[:rows]
    return pd.DataFrame({"Date/Time": pd.Timestamp("2027-10-27 06:00") + pd.to_timedelta(t, "s"),
                         "Column (°C)": heat, "Air (°C)": 16 + 0.0002 * t,
                         "Y head (mm)": height, "dY (µm)": (4.5 * (heat - 16)).round(2)})


def _config(out) -> dict:
    [path] = (out / "conf" / "data").glob("*.yaml")
    return yaml.safe_load(path.read_text())


def test_init_proposes_an_axis_travel_past_a_metre_as_a_state(tmp_path, capsys):
    # before: 'Y head (mm)' up to 1850 mm, read as an error for a look at its span, was refused
    # as an error of 1.85e6 µm beyond data.max_abs_error before init could propose it a state
    path = tmp_path / "hbm.csv"
    frame = boring_mill()
    frame.to_csv(path, index=False)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    roles = _config(tmp_path / "init")["roles"]
    assert "Y head" in roles["state"] and roles["error"] == ["dY"]
    assert f"'Y head (mm)' spans {np.ptp(frame['Y head (mm)']):.4g} mm" in capsys.readouterr().out
    # an error beyond the bound, no travel (an axis' reading, 1.2 m off), stays refused by
    # init, as `run` refuses it
    frame.assign(**{"dY (µm)": frame["dY (µm)"] + 1.2e6}).to_csv(path, index=False)
    refused(["init", str(path), f"out={tmp_path / 'far'}"], capsys, "data.max_abs_error")


def test_a_null_bound_switches_its_check_off_as_the_docs_say(tmp_path):
    # before: data.max_abs_error=null (own-data.md: "Set a key to null to switch that check
    # off") was read as its default, 1e6 µm
    path = tmp_path / "hbm.csv"
    boring_mill().to_csv(path, index=False)
    roles = {"error": ["dY", "Y head"], "state": [], "ambient": [], "ignore": [], "time": "auto"}
    with pytest.raises(Exception, match="max_abs_error"):
        read_dataset(path, {"roles": roles, "test_fraction": 0.2})
    ds, _ = read_dataset(path, {"roles": roles, "test_fraction": 0.2, "max_abs_error": None})
    top = boring_mill()["Y head (mm)"].iloc[:len(ds.campaigns[ds.ids("train")[0]])].max()
    assert ds.campaigns[ds.ids("train")[0]]["E_Y_head"].max() == pytest.approx(top * 1000.0)


SUMMARY = ("# --- run summary ---\n# start: 2027-10-27 06:00:00\n# stop: 2027-10-27 08:59:00\n"
           "# samples: 180\n# max spindle speed: 3000 rpm\n# operator: M. Keller\n"
           "# note: run 1, test mandrel 300 mm, probe checked\n")


def test_a_block_of_comments_under_the_rows_is_left_out_and_said(tmp_path, caplog):
    # before: "a '#' line among the rows, of other than the header's width: a comment?" -- a
    # logger's seven-line run summary under its rows refused every run file
    path = tmp_path / "hbm.csv"
    frame = boring_mill()
    path.write_text(frame.to_csv(index=False, lineterminator="\r\n") + SUMMARY.replace("\n", "\r\n"),
                    encoding="utf-8")
    roles = {"error": ["dY"], "state": ["Y head"], "ambient": [], "ignore": [], "time": "auto"}
    with caplog.at_level("WARNING"):
        ds, _ = read_dataset(path, {"roles": roles, "test_fraction": 0.2})
    assert sum(len(f) for f in ds.campaigns.values()) == len(frame)
    assert "footer left out (7 line(s) under the data: '# --- run summary ---')" in caplog.text
    # piped in as written, the stream reads it as the file reader does (it refused it)
    roles_cfg = {"roles": roles, "timezone": None}
    text = path.read_text(encoding="utf-8")
    with caplog.at_level("WARNING"):
        streamed, _ = read_stream(text, ["T_Column", "T_Air"], ReadOptions.from_cfg(roles_cfg))
    assert len(streamed) == len(frame) and "<stdin>: footer left out (7 line(s)" in caplog.text
    # a '#' line among the rows of a file that writes no comment is still refused
    body = frame.to_csv(index=False).splitlines()
    path.write_text("\n".join([*body[:50], "# tool change", *body[50:]]) + "\n", encoding="utf-8")
    with pytest.raises(Exception, match="a '#' line among the rows"):
        read_dataset(path, {"roles": roles, "test_fraction": 0.2})


def test_init_leaves_a_loggers_weekday_out_and_says_so(tmp_path, capsys):
    # before: 'Weekday' (ISO 1-7) was proposed the temperature T_Weekday without a word
    path = tmp_path / "hbm.csv"
    frame = boring_mill(rows=2 * 72)                # two days at 20 min, Friday to Sunday
    frame["Date/Time"] = pd.Timestamp("2027-10-29 06:00") + pd.to_timedelta(np.arange(144) * 1200, "s")
    frame.insert(1, "Weekday", frame["Date/Time"].dt.isocalendar().day.astype(int))
    frame.to_csv(path, index=False)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert _config(tmp_path / "init")["roles"]["ignore"] == ["Weekday"]
    assert "'Weekday': the day of the week" in said and "T_Weekday" not in said
    # `run` by roles alone (no init) says it, where it read it silently
    common = ["run", f"data.path={path}", "data.roles.error=[dY]", "data.roles.state=[Y head]",
              "data.test_fraction=0.2", *FAST, "plots=none", "track=false"]
    assert main([*common, f"out={tmp_path / 'run'}"]) == 0
    assert ("'Weekday' (T_Weekday) names the day of the week (whole numbers 0-7): a calendar number "
            "read as a temperature; data.roles.ignore=['Weekday']") in capsys.readouterr().err
    assert main([*common, "data.roles.ignore=[Weekday]", f"out={tmp_path / 'quiet'}"]) == 0
    assert "day of the week" not in capsys.readouterr().err
