"""An MQTT bridge's JSON Lines through `init` and the reader (session 60,
benchmarks/bench_new_machines60.py, the six-spindle lathe).

One nested object a line, ``{"ts": <epoch ms>, "temps": {"drum_K": ...}, "probe": {"dia_nm": ...,
"spindle": 3}, "state": {"speed_rpm": ..., "cycle_s": ..., "flood": true}}``: `init` said "a
record's file is .csv, .txt, ... not .jsonl".  Read now through its CSV text
(:mod:`thermocomp.core.io.jsonlines`, the keys joined with ``.``); then the gateway's tags: the
``_K`` of a temperature in kelvin (refused as "looks like kelvin, convert to °C"), ``state.`` a
machine state (``state.cycle_s`` was proposed as a temperature), ``shop_air`` the ambient, the
epoch milliseconds named in the refusal with their remedy.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
import yaml

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.jsonlines import json_lines_as_csv
from thermocomp.core.io.units import role_by_unit
from thermocomp.shell.cli import main

EPOCH_MS = 1791158400000       # 2026-10-05 00:00 UTC


def bridge_file(path, rows=40, missing=(20, 21, 22)):
    """One message a minute (late by i ms), kelvin, nanometres; the rows ``missing`` lost."""
    lines = []
    for i in range(rows):
        if i in missing:
            continue
        lines.append(json.dumps({
            "ts": EPOCH_MS + 60000 * i + i, "dev": "MS6-02",
            "temps": {"drum_front_K": round(293.15 + 0.05 * i, 2), "shop_air_K": 294.15 + 0.01 * (i % 2)},
            "probe": {"dia_nm": 100 * i, "spindle": i % 6 + 1},
            "state": {"cycle_s": 42, "flood": i % 10 < 5}}))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_a_json_lines_file_is_its_flattened_csv_text(tmp_path):
    path = bridge_file(tmp_path / "ms6.jsonl", rows=3, missing=())
    with json_lines_as_csv(path) as text:
        lines = text.read_text().splitlines()
    assert lines[0] == ("ts,dev,temps.drum_front_K,temps.shop_air_K,probe.dia_nm,probe.spindle,"
                        "state.cycle_s,state.flood")
    assert lines[1].endswith(",42,true") and lines[2].startswith(f"{EPOCH_MS + 60001},MS6-02,")


def test_a_line_that_is_no_json_object_is_refused_with_its_line(tmp_path):
    path = bridge_file(tmp_path / "ms6.jsonl", rows=3, missing=())
    path.write_text(path.read_text() + '{"ts": 1, "temps": \n')
    with pytest.raises(ContractError, match=r"line 4.*one object a line"):
        read_dataset(path, {"units": {"ts": "ms"}})


def test_a_gateways_tags_say_their_roles():
    assert role_by_unit("state.cycle", "s") == "state"        # (a time unit after no time word)
    assert role_by_unit("state.cycle_s", None) == "state"
    assert role_by_unit("Spindle state", None) == "state"
    assert role_by_unit("state.temp_oil", None) is None       # a temperature says so


def test_json_lines_are_read_in_the_contracts_units(tmp_path, caplog):
    path = bridge_file(tmp_path / "ms6.jsonl")
    ds, _ = read_dataset(path, {"units": {"ts": "ms"}, "roles": {"state": ["probe.spindle", "state.*"],
                                                                  "ignore": ["dev"]}})
    (cid,) = ds.ids()
    df = ds.campaigns[cid]
    assert df["T_temps.drum_front"].iloc[0] == pytest.approx(20.0)          # kelvin
    assert df["T_temps.shop_air"].iloc[0] == pytest.approx(21.0)
    assert df["E_probe.dia"].to_numpy()[:3] == pytest.approx([0.0, 0.1, 0.2])  # nm -> µm
    assert {"S_probe.spindle", "S_state.cycle_s", "S_state.flood"} <= set(df.columns)
    assert np.array_equal(df["S_state.flood"].to_numpy()[3:7], [1, 1, 0, 0])
    assert df["time"].iloc[1] - df["time"].iloc[0] == pytest.approx(60.001)
    # the outage named at the file's line (the row after it is on line 21, the CSV's 22)
    assert any("before line 21 " in r.getMessage() for r in caplog.records), caplog.text


def test_epoch_milliseconds_are_refused_with_their_remedy(tmp_path):
    # 10 h of minutes read as seconds: "lasts 417 days ... is time in ms?", now with what says so
    path = bridge_file(tmp_path / "ms6.jsonl", rows=600, missing=())
    with pytest.raises(ContractError, match=r"milliseconds since 1970.*data\.units=\{<its header>: ms\}"):
        read_dataset(path, {"roles": {"state": ["probe.spindle", "state.*"], "ignore": ["dev"]}})


def test_init_reads_an_mqtt_bridges_json_lines(tmp_path, capsys):
    path = bridge_file(tmp_path / "ms6.jsonl")
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.25", "data.units={ts: ms}",
                 f"out={out}"]) == 0
    said = capsys.readouterr().out
    assert "JSON Lines" in said
    config = yaml.safe_load((out / "conf" / "data" / "ms6.yaml").read_text())
    assert config["roles"]["error"] == ["probe.dia"]          # (its unit, nm, read from the tag)
    assert config["roles"]["ambient"] == ["temps.shop_air_K"]
    assert {"state.cycle_s", "state.flood"} <= set(config["roles"]["state"])


def test_a_gateways_csv_tags_say_kelvin_the_shops_air_and_epoch_milliseconds(tmp_path, capsys):
    # the same tags in a CSV export: each mend on its own, without JSON Lines
    lines = ["ts,drum_K,shop_air_K,dia_nm"] + [
        f"{EPOCH_MS + 60000 * i},{293.15 + 0.05 * i:.2f},{294.15 + 0.01 * (i % 2):.2f},{100 * i}"
        for i in range(600)]
    path = tmp_path / "gw.csv"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(ContractError, match=r"milliseconds since 1970.*data\.units=\{<its header>: ms\}"):
        read_dataset(path, {"roles": {"error": ["dia*"]}})
    ds, _ = read_dataset(path, {"units": {"ts": "ms"}, "roles": {"error": ["dia*"]}})
    df = ds.campaigns[ds.ids()[0]]
    assert df["T_drum"].iloc[0] == pytest.approx(20.0)
    out = tmp_path / "init"
    assert main(["init", str(path), "data.units={ts: ms}", f"out={out}"]) == 0
    config = yaml.safe_load((out / "conf" / "data" / "gw.yaml").read_text())
    assert config["roles"]["ambient"] == ["shop_air_K"]


def test_kelvin_without_its_unit_is_refused_with_the_setting_that_reads_it(tmp_path):
    # before: "temperatures look like kelvin, convert to °C": hand work on the lab's file
    path = tmp_path / "gw.csv"
    path.write_text("time,drum,dia [nm]\n" + "".join(f"{60 * i},{293.15 + 0.05 * i:.2f},{100 * i}\n"
                                                  for i in range(20)))
    with pytest.raises(ContractError, match=r"look like kelvin.*data\.units=\{<its header>: K\}.*"
                                            r"its header in the file: 'drum'"):
        read_dataset(path, {"roles": {"error": ["dia*"]}})
    ds, _ = read_dataset(path, {"roles": {"error": ["dia*"]}, "units": {"drum": "K"}})
    assert ds.campaigns[ds.ids()[0]]["T_drum"].iloc[0] == pytest.approx(20.0)


def test_init_reads_a_gateways_epoch_milliseconds_without_being_told(tmp_path, capsys):
    # before: refused (no time column; then "lasts 2.1e+04 days ... is time in ms?"): the
    # stranger added data.units={ts: ms}; init now writes it, said
    path = bridge_file(tmp_path / "ms6.jsonl")
    out = tmp_path / "init"
    assert main(["init", str(path), "data.test_fraction=0.25", f"out={out}"]) == 0
    assert "'ts' from 1791158400000: milliseconds since 1970" in capsys.readouterr().out
    config = yaml.safe_load((out / "conf" / "data" / "ms6.yaml").read_text())
    assert config["units"] == {"ts": "ms"}
    seconds = tmp_path / "s.csv"           # seconds since 1970: left as they are
    seconds.write_text("ts,drum_K,dia_nm\n" + "".join(f"{1791158400 + 60 * i},{293.15 + 0.05 * i:.2f},"
                                                       f"{100 * i}\n" for i in range(20)))
    assert main(["init", str(seconds), "data.test_fraction=0.25", f"out={tmp_path / 'init_s'}"]) == 0
    config = yaml.safe_load((tmp_path / "init_s" / "conf" / "data" / "s.yaml").read_text())
    assert "ts" not in (config.get("units") or {})
