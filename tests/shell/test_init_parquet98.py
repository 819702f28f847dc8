"""``thermocomp init`` on a Parquet record says what it is and writes no separators (lead98).

A Parquet file's columns are typed: it has no delimiter and no decimal mark.  audit97 found
init printing ``delimiter 'auto', decimal 'auto'`` for one and writing both keys into the data
config, as if they had been detected (noise a user then reads as a setting).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import yaml

from thermocomp.shell.cli import main


def _record(path, rows: int = 120):
    rng = np.random.default_rng(98)
    spindle = 20 + np.cumsum(rng.normal(0, 0.05, rows))
    pd.DataFrame({"time_s": np.arange(rows) * 60.0, "T_spindle": spindle,
                  "T_bed": 21 + rng.normal(0, 0.02, rows),
                  "E_X": 3 * (spindle - 20) + rng.normal(0, 0.3, rows)}).to_parquet(path)


def _init(src, tmp_path, capsys) -> tuple[str, dict]:
    out = tmp_path / "init"
    assert main(["init", str(src), f"out={out}"]) == 0, capsys.readouterr().err
    config = yaml.safe_load(next((out / "conf" / "data").glob("*.yaml")).read_text())
    return capsys.readouterr().out, config


def test_parquet_init_names_no_separators(tmp_path, capsys):
    _record(tmp_path / "lab.parquet")
    printed, config = _init(tmp_path / "lab.parquet", tmp_path, capsys)
    assert "a Parquet file" in printed.splitlines()[0]
    assert "delimiter '" not in printed and "delimiter" not in config and "decimal" not in config
    assert config["path"].endswith("lab.parquet")


def test_the_same_record_as_csv_keeps_its_detected_separators(tmp_path, capsys):
    _record(tmp_path / "lab.parquet")
    pd.read_parquet(tmp_path / "lab.parquet").to_csv(tmp_path / "lab.csv", sep=";", decimal=",",
                                                     index=False)
    printed, config = _init(tmp_path / "lab.csv", tmp_path, capsys)
    assert (config["delimiter"], config["decimal"]) == (";", ",")
    assert "delimiter ';', decimal ','" in printed
