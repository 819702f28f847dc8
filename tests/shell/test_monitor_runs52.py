"""A lab's long file with a run column streamed through ``monitor`` on stdin (session 52): each
run a campaign from a reset, as ``monitor``/``replay`` read the file with ``data.roles.campaign``,
not one campaign jumping at every run boundary."""

from __future__ import annotations

import io
import json

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from thermocomp.core.io import ContractError, ReadOptions
from thermocomp.core.io.stdin import stream_campaigns
from thermocomp.shell.cli import main

HEAT = (2, 5, 3, 4)      # °C each run warms by: the held-out runs 3 and 4 within the train's


def _long(path, clock: bool | None):
    """Four 30-min runs in one ``;`` file with decimal commas, ``Lauf`` numbering them; the
    time restarting at 0 s in each, or wall-clock times a day apart, or (None) no time column,
    the rows a minute apart (``data.sample_period_s=60``)."""
    rng = np.random.default_rng(52)
    runs = []
    for k, heat in enumerate(HEAT, 1):
        t = np.arange(30) * 60.0
        fast = heat * (1 - np.exp(-t / 900)) + rng.normal(0, 0.02, t.size)
        slow = heat * (1 - np.exp(-t / 2400))
        run = pd.DataFrame({"Lauf": k, "Zeit [s]": t, "T0 [°C]": 20 + fast,
                            "T1 [°C]": 20 + slow + rng.normal(0, 0.02, t.size),
                            "T2 [°C]": 20 + 0.5 * fast + rng.normal(0, 0.02, t.size),
                            "dX [µm]": 3 * slow + 0.5 * fast + rng.normal(0, 0.05, t.size)})
        if clock:
            start = pd.Timestamp("2023-03-01 08:00") + pd.Timedelta(days=k)
            run.insert(1, "Zeit", (start + pd.to_timedelta(run.pop("Zeit [s]"), unit="s"))
                       .dt.strftime("%d.%m.%Y %H:%M:%S"))
        if clock is None:
            run = run.drop(columns="Zeit [s]")
        runs.append(run)
    pd.concat(runs).to_csv(path, sep=";", decimal=",", index=False)
    return path


@pytest.mark.parametrize("clock", [False, True, None], ids=["seconds", "wall-clock", "untimed"])
def test_a_long_file_on_stdin_is_monitored_run_by_run_as_the_file_is(tmp_path, monkeypatch, clock):
    # before: one campaign 'stdin'; at run 4's first row (30 min in) the time went back to 0 s
    # and every sensor fell a few °C in one sample: 9 events, 3 exclusions, the fixed RMSE 1e12 µm,
    # the adaptive 1.80 µm where the file's runs gave 0.104 and no event (wall-clock: the time
    # jumped a day, 8 events, 3 exclusions, the adaptive 1.87 µm); untimed (stranger73): the
    # file read, the stream crashed, KeyError 'time' (exit 1)
    path = _long(tmp_path / "alle.csv", clock)
    common = [f"data.path={path}", "data.roles.error=[dX]", "data.roles.campaign=Lauf",
              "data.test_fraction=0.5", "model=lagbank", *FAST,
              *(["data.sample_period_s=60"] if clock is None else [])]
    assert main(["monitor", f"out={tmp_path / 'file'}", *common]) == 0
    lines = path.read_text(encoding="utf-8").splitlines()
    monkeypatch.setattr("sys.stdin", io.StringIO("\n".join(
        [lines[0], *(line for line in lines[1:] if line[0] in "34")]) + "\n"))
    assert main(["monitor", f"out={tmp_path / 'stdin'}", *common, "monitor.input=-"]) == 0
    want, got = (json.loads((tmp_path / k / "monitor.json").read_text()) for k in ("file", "stdin"))
    assert want["campaigns"] == got["campaigns"] == ["Lauf_3", "Lauf_4"]
    assert want["events"] == got["events"] == []            # a healthy record stays quiet
    assert got["targets"]["E_dX"]["n_samples"] == 60
    for key, value in want["targets"]["E_dX"].items():
        assert got["targets"]["E_dX"][key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
    assert got["targets"]["E_dX"]["rmse_fixed"] < 0.2


def test_a_stream_whose_run_comes_back_is_refused_naming_its_row(tmp_path):
    text = _long(tmp_path / "alle.csv", clock=True).read_text(encoding="utf-8")
    opts = ReadOptions.from_cfg({"roles": {"error": ["dX"], "campaign": "Lauf"}})
    runs, missing = stream_campaigns(text, ["T_T0"], opts)
    assert list(runs) == ["Lauf_1", "Lauf_2", "Lauf_3", "Lauf_4"] and not missing
    assert [r["time"].iloc[0] for r in runs.values()] == [0.0] * 4     # from each run's start
    assert runs["Lauf_2"]["time"].iloc[-1] == 29 * 60.0
    lines = text.splitlines()
    cells = lines[100].split(";")                  # data row 100: run 4's tenth
    gap = "\n".join([*lines[:100], ";".join([*cells[:2], "", *cells[3:]]), *lines[101:]])
    assert stream_campaigns(gap, ["T_T0"], opts)[1] == {"Lauf_4": {"T_T0": 1}}   # per run
    back = "\n".join([*lines[:62], lines[1], *lines[62:]])     # a row of run 1 within run 3
    with pytest.raises(ContractError, match=r"column 'Lauf', .*row 62.*run '1' comes back"):
        stream_campaigns(back, ["T_T0"], opts)


def test_untimed_rows_on_stdin_are_a_period_apart_from_each_runs_start(tmp_path):
    # stranger73: the monitor crashed (KeyError 'time') on a lab's export without a time column
    text = _long(tmp_path / "alle.csv", clock=None).read_text(encoding="utf-8")
    roles = {"error": ["dX"], "campaign": "Lauf"}
    runs, _ = stream_campaigns(text, ["T_T0"], ReadOptions.from_cfg(
        {"roles": roles, "sample_period_s": 60}))
    assert [r["time"].iloc[0] for r in runs.values()] == [0.0] * 4
    assert runs["Lauf_2"]["time"].iloc[-1] == 29 * 60.0
    with pytest.raises(ContractError, match=r"file <stdin>: no 'time' column .*set "
                                            r"data.sample_period_s"):
        stream_campaigns(text, ["T_T0"], ReadOptions.from_cfg({"roles": roles}))


def test_a_long_file_on_stdin_is_split_at_its_pauses_as_the_file_is(tmp_path, monkeypatch):
    # audit106: with data.runs_at_pauses (which `init` writes for a file that pauses), the file
    # and stream.c start a campaign at each pause, the stream on stdin went on as one campaign
    # 'stdin' without a word (a lab export's 3 h gap: monitor 1.494 um where its runs give 1.685)
    path = _long(tmp_path / "alle.csv", clock=True)
    frame = pd.read_csv(path, sep=";", decimal=",").drop(columns="Lauf")
    frame.to_csv(path, sep=";", decimal=",", index=False)          # the runs a day apart, no counter
    common = [f"data.path={path}", "data.roles.error=[dX]", "data.runs_at_pauses=true",
              "data.test_fraction=0.5", "model=lagbank", *FAST]
    assert main(["monitor", f"out={tmp_path / 'file'}", *common]) == 0
    lines = path.read_text(encoding="utf-8").splitlines()
    monkeypatch.setattr("sys.stdin", io.StringIO("\n".join([lines[0], *lines[61:]]) + "\n"))
    assert main(["monitor", f"out={tmp_path / 'stdin'}", *common, "monitor.input=-"]) == 0
    want, got = (json.loads((tmp_path / k / "monitor.json").read_text()) for k in ("file", "stdin"))
    assert want["campaigns"] == ["alle_3", "alle_4"] and got["campaigns"] == ["stdin_1", "stdin_2"]
    assert want["events"] == got["events"] == []
    for key, value in want["targets"]["E_dX"].items():
        assert got["targets"]["E_dX"][key] == pytest.approx(value, rel=1e-9, abs=1e-12), key
    one, _ = stream_campaigns("\n".join(lines[:31]) + "\n", ["T_T0"], ReadOptions.from_cfg(
        {"roles": {"error": ["dX"]}, "runs_at_pauses": True}))
    assert list(one) == ["stdin"]                    # a stream of one run: no pause, one campaign


def test_the_campaigns_thermocomp_rows_writes_stream_a_campaign_each_as_stream_c_reads_them(tmp_path):
    # dep107: `thermocomp rows` writes each campaign from its time 0, a blank line between (where
    # stream.c starts one); on stdin they were one campaign 'stdin', each start read as a clock
    # set back and a common step of every sensor (the fixture's 4 runs: 23 events, 3 exclusions)
    lines = _long(tmp_path / "alle.csv", clock=False).read_text(encoding="utf-8").splitlines()
    runs = [[ln.split(";", 1)[1] for ln in lines[1:] if ln.split(";")[0] == k] for k in "1234"]
    header = lines[0].split(";", 1)[1]
    opts = ReadOptions.from_cfg({"roles": {"error": ["dX"]}})
    text = "\n".join([header, *runs[0], "", *runs[1], "", *runs[2]]) + "\n\n"
    parts, _ = stream_campaigns(text, ["T_T0"], opts)
    assert list(parts) == ["stdin_1", "stdin_2", "stdin_3"]
    assert [len(p) for p in parts.values()] == [30] * 3
    assert [p["time"].iloc[0] for p in parts.values()] == [0.0] * 3
    # a stray blank line within a run (its time going on) stays nothing, as the file's read
    stray = "\n".join([header, *runs[0][:10], "", *runs[0][10:]]) + "\n"
    parts, _ = stream_campaigns(stray, ["T_T0"], opts)
    assert list(parts) == ["stdin"] and len(parts["stdin"]) == 30


def test_rows_of_runs_under_one_clock_start_each_block_at_0_so_stdin_parts_them(tmp_path, capsys):
    # dep107b: a run column's runs under one clock went on across `thermocomp rows`' blank line
    # (1740 s, then 1800 s: one period on), which no reader tells from a stray blank line within
    # a run (stdin read them as one campaign); each block now starts at 0, as the rows' contract
    path = _long(tmp_path / "alle.csv", clock=False)
    frame = pd.read_csv(path, sep=";", decimal=",")
    frame["Zeit [s]"] = np.arange(len(frame)) * 60.0                       # one clock
    frame.to_csv(path, sep=";", decimal=",", index=False)
    capsys.readouterr()
    assert main(["rows", f"data.path={path}", "data.roles.error=[dX]", "data.roles.campaign=Lauf"]) == 0
    text = capsys.readouterr().out
    lines = text.splitlines()
    assert [float(lines[k + 1].split(",")[0]) for k, ln in enumerate(lines) if not ln] == [0.0] * 3
    parts, _ = stream_campaigns(text, ["T_T0"], ReadOptions.from_cfg({}))
    assert list(parts) == ["stdin_1", "stdin_2", "stdin_3", "stdin_4"]
