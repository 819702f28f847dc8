"""A lab's own export, three leftovers of stop 93 (data94).

An hour past 24 among decimal hours read under ``data.units={Hora: h}`` was refused naming the
value in seconds (``90900 s``), the unit it was converted to, not as the lab wrote it
(``25.25 h``).  A temperature's word before a sensor's name (``Temp. headstock``) was kept after
the ``T_`` prefix (``T_Temp._headstock``).  A served block carrying the date and its time of day
in two columns (``Datum;Uhrzeit``), as the file reader and ``stream.c`` read them, was refused,
"a date without a time of day"."""

from __future__ import annotations

import copy

import numpy as np
import pandas as pd
import pytest

from test_data88b import START, _record
from test_decimal_hours93 import _raw_hours
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.roles import naming

HOURS = {"roles": {"error": ["dX"]}, "delimiter": ";", "decimal": ",", "units": {"Hora": "h"},
         "time": "of_day"}


def test_an_hour_past_24_is_refused_naming_it_as_written(tmp_path):
    # before: "value 90900 s is no second of a day" (the hours converted to seconds)
    text = _raw_hours(_record(941)).split("\r\n")
    text[20] = "25,25" + text[20][text[20].index(";"):]      # data row 20
    (tmp_path / "bad.csv").write_bytes("\r\n".join(text).encode("utf-8"))
    with pytest.raises(ContractError) as caught:
        read_dataset(tmp_path / "bad.csv", HOURS)
    said = str(caught.value)
    assert caught.value.row == 20 and caught.value.column == "time" and "bad.csv" in said
    assert "value 25.25 h is no hour of a day, [0, 24) h" in said and "90900 s" in said
    assert "data.units={'Hora': h}" in said


def test_seconds_past_a_day_are_still_named_in_seconds(tmp_path):
    # a guard: a time of day in seconds (no unit) names its value as before
    rows = _record(942)
    seconds = ((rows["time"] + 77400.0) % 86400.0).to_numpy().copy()    # (past midnight)
    seconds[12] = 86460.0
    rows.assign(time=seconds).to_csv(tmp_path / "s.csv", index=False)
    with pytest.raises(ContractError, match=r"value 86460 s is no second of a day") as caught:
        read_dataset(tmp_path / "s.csv", {"time": "of_day"})
    assert caught.value.row == 13


@pytest.mark.parametrize("header, name", [
    ("Temp. headstock [°C]", "T_headstock"), ("Temp._headstock [°C]", "T_headstock"),
    ("Temperatur Spindel [°C]", "T_Spindel"), ("Temperatura husillo [°C]", "T_husillo"),
    ("Temperature bed [°C]", "T_bed"), ("Température broche [°C]", "T_broche"),
    ("temp-1 [°C]", "T_1")])
def test_a_temperature_word_is_not_repeated_after_the_prefix(header, name):
    # before: T_Temp._headstock, T_Temperatur_Spindel ...
    named = naming(["Zeit [s]", header, "dX [µm]"], {"error": ["dX"]}, {}).names
    assert named[header] == name


@pytest.mark.parametrize("headers, names", [
    # the word alone, or an ambient's name left: as before
    (["Temp [°C]", "Temp amb [°C]"], ["T_Temp", "T_Temp_amb"]),
    # the short name another header reads as: both kept apart, the long one as before
    (["Temp. headstock [°C]", "headstock [°C]"], ["T_Temp._headstock", "T_headstock"]),
    (["Temp bed [°C]", "T_bed [°C]"], ["T_Temp_bed", "T_bed"]),
    # a time's word is no temperature's (French 'temps', Italian 'tempo')
    (["tempo_ciclo [°C]"], ["T_tempo_ciclo"])])
def test_names_stay_unique_and_the_word_alone_stays(headers, names):
    named = naming(["Zeit [s]", *headers, "dX [µm]"], {"error": ["dX"]}, {}).names
    assert [named[h] for h in headers] == names


def test_init_writes_a_config_that_reads_the_short_names(tmp_path, capsys):
    from thermocomp.shell.cli import main

    rows = _record(943)
    lab = pd.DataFrame({"Zeit [s]": rows["time"], "Temp. a [°C]": rows["T_a"],
                        "Temp. b [°C]": rows["T_b"], "Temp. c [°C]": rows["T_c"],
                        "dX [µm]": rows["E_X"]})
    lab.to_csv(tmp_path / "lab.csv", index=False)
    assert main(["init", str(tmp_path / "lab.csv"), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    assert "T_a" in said and "T_Temp" not in said
    ds, _ = read_dataset(tmp_path / "lab.csv", {"roles": {"error": ["dX"]}})
    assert list(ds.campaigns["lab"].columns) == ["time", "T_a", "T_b", "T_c", "E_dX"]


def _pair(rows: pd.DataFrame) -> pd.DataFrame:
    """``rows`` as a lab's logger writes them: ``Datum;Uhrzeit`` (from 21:30, past midnight)."""
    stamps = [START + pd.Timedelta(seconds=float(t)) for t in rows["time"]]
    return pd.DataFrame({"Datum": [f"{s:%d.%m.%Y}" for s in stamps],
                         "Uhrzeit": [f"{s:%H:%M:%S}" for s in stamps],
                         "Temp. a [°C]": rows["T_a"], "Temp. b [°C]": rows["T_b"],
                         "Temp. c [°C]": rows["T_c"], "dX [µm]": rows["E_X"]})


def _served(tmp_path):
    """A lag bank (it reads the time) fitted on the pair file, deployed as served."""
    from test_export import _compose
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    _pair(_record(944)).to_csv(tmp_path / "pair.csv", index=False)
    cfg = _compose(f"data.path={tmp_path / 'pair.csv'}", "data.test_fraction=0.25",
                   "data.roles.error=[dX]", "model=lagbank", "track=false",
                   "monitor.adaptive=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    return deployable_model(cfg, ds, train, None, "serve.model")[0]


def test_a_served_block_reads_a_date_and_its_time_of_day_as_the_file_does(tmp_path):
    # before: refused, "value '05.03.2027' is a date without a time of day"
    from thermocomp.apps.deploy.pyfunc import CompensatorModel, signature

    deployed = _served(tmp_path)
    assert "Uhrzeit" in signature(deployed).inputs.input_names()    # (MLflow keeps it)
    rows = _record(945)
    pair = _pair(rows)
    stamped = pair.drop(columns=["Datum", "Uhrzeit"]).assign(
        time=[(START + pd.Timedelta(seconds=float(t))).isoformat() for t in rows["time"]])
    served = {}
    for label, frame in (("pair", pair), ("stamped", stamped)):
        model = CompensatorModel(copy.deepcopy(deployed))
        served[label] = pd.concat([model.predict(None, frame.iloc[a:a + 10].reset_index(drop=True),
                                                 {"reset": a == 0})
                                   for a in range(0, len(frame), 10)], ignore_index=True)
    assert np.isfinite(served["pair"]["C_dX"]).all()
    np.testing.assert_array_equal(served["pair"]["C_dX"], served["stamped"]["C_dX"])
    # a time of day without its date column: the time's own rule, as before (a lag bank reads
    # the time: refused naming the date)
    lone = pair.drop(columns="Datum").iloc[:10]
    with pytest.raises(Exception, match=r"lacks column\(s\) \['Datum' \(read as time\)\]"):
        CompensatorModel(copy.deepcopy(deployed)).predict(None, lone, {"reset": True})
