"""An InfluxDB annotated CSV through the CLI (influx61): ``init`` reads it as a long file (each
table a series, a ``unit`` tag its unit), proposes the grid's period and the roles over the
series' names, ``run`` with that config scores it; a bad sample exits 2 naming the file, the
column and the file's own line.  Before, ``init`` found "no column reads as a measured error
(...) the numeric columns: none"."""

from __future__ import annotations

import json

import yaml

from conftest import FAST, refused, thermocomp
from test_influx61 import annotated, rfc, series


def test_init_reads_the_export_and_run_scores_it(tmp_path):
    (tmp_path / "m1.csv").write_text(annotated(series()), newline="")
    out = tmp_path / "out"
    # ('rpm' alone says no unit: a temperature to init, refused at 8000 °C; the stranger says)
    said = thermocomp("init", f"data.path={tmp_path / 'm1.csv'}", "data.roles.state=[rpm]",
                      f"out={out}").stdout
    assert "an InfluxDB annotated CSV (each table a series" in said
    assert "data.resample_s=30 s, the median interval of the fastest error tag 'dZ [um]'" in said
    config = yaml.safe_load((out / "conf" / "data" / "m1.yaml").read_text())
    assert config["resample_s"] == 30.0 and config["roles"]["error"] == ["dZ"]
    assert config["roles"]["state"] == ["rpm", "door"]
    thermocomp("run", f"hydra.searchpath=[file://{out / 'conf'}]", "data=m1", f"out={out}",
               "model=mlr", *FAST)
    assert "E_dZ" in json.dumps(json.loads((out / "metrics.json").read_text()))


def test_a_bad_value_exits_2_naming_file_column_and_line(tmp_path, capsys):
    lines = annotated(series()).split("\r\n")
    k = next(k for k, ln in enumerate(lines) if ln.endswith(",Bed,degC")
             and f",{rfc([610])[0]}," in ln)
    cells = lines[k].split(",")
    cells[6] = "n/a"
    lines[k] = ",".join(cells)
    (tmp_path / "m1.csv").write_text("\r\n".join(lines), newline="")
    refused(["run", f"data.path={tmp_path / 'm1.csv'}", "data.roles.error=[dZ]",
             "data.roles.state=[rpm,door]", "data.resample_s=30", f"out={tmp_path / 'out'}",
             *FAST], capsys, f"file {tmp_path / 'm1.csv'}, column '_value', line {k + 1}",
            "value 'n/a' of tag 'Bed [degC]' is not a number")
