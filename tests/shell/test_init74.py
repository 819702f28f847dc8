"""init74: a lab's export read as exported (stranger74's travelling-column mill): a header
written twice, an hour of a sensor's cells left empty, the hall's air under a compound name.
``init`` writes a config that reads each file; small files written here."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from conftest import FAST, refused
from thermocomp.core.io import read_dataset
from thermocomp.core.io.detect import proposed_roles
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.stdin import read_stream
from thermocomp.shell.cli import main

ROWS = 40


def _columns():
    """time (s), the hall's air at two places, a spindle's temperature (°C), an error (µm)."""
    rng = np.random.default_rng(7481)
    t = np.arange(ROWS) * 60.0
    left = 20 + 0.5 * np.sin(t / 900) + rng.normal(0, 0.02, ROWS)
    right = left + 0.8 + rng.normal(0, 0.02, ROWS)
    spindle = 22 + 6 * (1 - np.exp(-t / 600))
    return t, left, right, spindle, 3.0 * (spindle - 22) + rng.normal(0, 0.1, ROWS)


def _write(path: Path, header: list[str], columns, blank: dict | None = None) -> Path:
    """``columns`` under ``header`` (tab-delimited, decimal commas); ``blank``: column -> rows
    left empty."""
    cells = [[f"{v:.3f}".replace(".", ",") for v in c] for c in columns]
    for i, rows in (blank or {}).items():
        for r in rows:
            cells[i][r] = ""
    lines = ["\t".join(header), *("\t".join(row) for row in zip(*cells))]
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def _init(path: Path, out: Path, capsys) -> tuple[dict, str]:
    """``thermocomp init``: the data config it writes (as read back) and what it printed."""
    code = main(["init", str(path), f"out={out}"])
    said = capsys.readouterr()
    assert code == 0, said.err
    config = yaml.safe_load((out / "conf" / "data" / f"{path.stem}.yaml").read_text(encoding="utf-8"))
    return config, said.out + said.err


def _read(path: Path, config: dict):
    cfg = {k: v for k, v in config.items() if k not in ("defaults", "path")}
    ds, _ = read_dataset(path, cfg)
    return ds


HEADER = ["Zeit (s)", "Halle (°C)", "Halle (°C)", "Spindel (°C)", "dX (µm)"]


def test_a_header_exported_twice_with_the_same_values_is_read_once_and_said(tmp_path, capsys):
    # before: refused by init and run, "columns 2 and 3 have the same header 'Halle (°C)': no
    # setting tells them apart" (one channel exported twice: the lab edited its file)
    t, left, _, spindle, e = _columns()
    path = _write(tmp_path / "same.txt", HEADER, [t, left, left, spindle, e])
    config, said = _init(path, tmp_path / "init", capsys)
    assert "columns 2 and 3 have the same header and the same values ('Halle (°C)'): column 3 " \
           "left out" in said
    assert config["roles"]["ambient"] == ["Halle"]
    ds = _read(path, config)
    frame = next(iter(ds.campaigns.values()))
    assert [c for c in frame.columns if c.startswith("T_")] == ["T_amb", "T_Spindel"]


def test_a_header_exported_twice_with_other_values_is_addressed_by_its_occurrence(tmp_path, capsys):
    # before: refused, and no data.columns / data.roles key could name the second column
    t, left, right, spindle, e = _columns()
    path = _write(tmp_path / "twice.txt", HEADER, [t, left, right, spindle, e])
    config, said = _init(path, tmp_path / "init", capsys)
    assert "column 3 read as 'Halle#2 (°C)'" in said
    assert config["roles"]["ambient"] == ["Halle", "Halle#2"]
    frame = next(iter(_read(path, config).campaigns.values()))
    n = len(frame)                               # (train; read relative to its first sample)
    np.testing.assert_allclose(np.diff(frame["T_amb_Halle_2"]), np.diff(right[:n]), atol=2e-3)
    np.testing.assert_allclose(np.diff(frame["T_amb_Halle"]), np.diff(left[:n]), atol=2e-3)
    # the same export streamed (monitor's stdin): read as the file is
    stream = read_stream(path.read_text(encoding="utf-8"), ["T_amb_Halle_2"],
                         ReadOptions.from_cfg({"roles": config["roles"], "decimal": ","}))[0]
    np.testing.assert_allclose(stream["T_amb_Halle_2"], right, atol=2e-3)


def test_contract_names_twice_are_refused_naming_the_key_that_mends_it(tmp_path, capsys):
    t, left, right, spindle, e = _columns()
    header = ["time", "T_1", "T_1", "E_X"]
    path = _write(tmp_path / "contract.txt", header, [t, left, right, e])
    refused(["init", str(path), f"out={tmp_path / 'init'}"], capsys, str(path),
            "columns 2 and 3 have the same header 'T_1', different values",
            "data.columns={'T_1#2': T_<name>}")
    frame = next(iter(read_dataset(path, {"columns": {"T_1#2": "T_2"}, "decimal": ","})[0]
                      .campaigns.values()))
    np.testing.assert_allclose(np.diff(frame["T_2"]), np.diff(right[:len(frame)]), atol=2e-3)


def test_a_run_of_empty_cells_is_a_gap_init_proposes_with_its_span(tmp_path, capsys):
    # before: init proposed data.max_gap_samples for a mark's runs ('---') only, and refused
    # the file of 12 empty cells by the config it wrote (gap longer than max_gap_samples=0)
    t, left, _, spindle, e = _columns()
    header = ["Zeit (s)", "Halle (°C)", "Motor X (°C)", "Spindel (°C)", "dX (µm)"]
    path = _write(tmp_path / "gap.txt", header, [t, left, spindle + 1, spindle, e],
                  blank={2: range(10, 22)})
    config, said = _init(path, tmp_path / "init", capsys)
    assert config["max_gap_samples"] == 12
    assert "is 12 samples, 720 s of 'Motor X (°C)': data.max_gap_samples=12" in said
    frame = next(iter(_read(path, config).campaigns.values()))
    ends = spindle[[9, 22]] + 1                  # (read as written: 3 decimals)
    motor = frame["T_Motor_X"].to_numpy() - frame["T_Motor_X"].iloc[0] + spindle[0] + 1
    np.testing.assert_allclose(motor[10:22], np.interp(t[10:22], t[[9, 22]], ends), atol=2e-3)


@pytest.mark.parametrize("header, air", [
    ("Hallenmitte", True), ("Umgebungstemp", True), ("RoomTemp", True), ("ambientLeft", True),
    ("Halle#2", True), ("T Luft", True),
    ("Luftlager", False), ("Air_spindle_housing", False), ("AirSpindleHousing", False),
    ("Hallenboden", False), ("Raumachse", False), ("Hallsensor", False)])
def test_the_airs_compound_names_are_ambient_a_parts_are_not(header, air):
    # before: 'Hallenmitte' (the hall's middle) a temperature beside 'Halle' the ambient, and
    # 'Air_spindle_housing' (an aerostatic spindle's housing) taken as the air
    names = ["Zeit (s)", f"{header} (°C)", "dX (µm)"]
    roles = proposed_roles(names, {h: "1" for h in names}, ReadOptions())
    assert (roles["ambient"] == [header]) is air, roles


@pytest.mark.parametrize("stem", ["2024", "inf", "true"])
def test_a_file_named_like_a_number_gets_a_config_name_hydra_reads_as_a_name(stem, tmp_path, capsys):
    """A lab's file `2024.csv` (a year), `inf.csv`, `true.csv`: `data=2024` is an int to Hydra
    ("Config group override must be a string", a traceback). init names the config
    `data_<stem>`, and the command it prints runs."""
    src = _write(tmp_path / f"{stem}.csv", ["Zeit (s)", "Halle (°C)", "Spindel (°C)", "dX (µm)"],
                 [c for i, c in enumerate(_columns()) if i != 2])
    assert main(["init", str(src), f"out={tmp_path / 'o'}"]) == 0
    said = capsys.readouterr().out
    assert f"data=data_{stem}" in said.split("next: ")[-1]
    assert (tmp_path / "o" / "conf" / "data" / f"data_{stem}.yaml").is_file()
    search = f"hydra.searchpath=[file://{tmp_path / 'o' / 'conf'}]"
    assert main(["run", search, f"data=data_{stem}", "model=mlr", f"out={tmp_path / 'r'}",
                 *FAST]) == 0
    assert (tmp_path / "r" / "metrics.json").is_file()
