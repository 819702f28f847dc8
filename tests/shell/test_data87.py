"""A lab's files in (data87): a unit changed under an unchanged header is refused on stdin
(``monitor.input=-``) as on the file, at the same column and row; a folder whose files differ in
encoding or thousands separator (one re-saved by Excel) read each file by its own
(``data.encoding=auto``, ``data.thousands=auto``), a file ambiguous on its own refused naming
its column and row."""

from __future__ import annotations

import io
import json
import shutil
from types import SimpleNamespace

import pandas as pd
import pytest
import yaml

from conftest import LIGHT, refused
from test_audit86 import german_export
from test_data86b import _gb_folder
from test_hostile_units import FAHRENHEIT, MILLIMETRES, from_row
from test_stranger69 import ROWS
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.stdin import stdin_text
from thermocomp.shell.cli import main

KELVIN = lambda c: (c + 273.15).round(2)  # noqa: E731 -- as a logger writes it

# (column prefix, conversion from row 15 on); the error column the one of the largest level
# (mm of a 0.3 µm reading is within the noise of zero: no step to judge, on the file too)
CHANGES = {"°F": ("T_", FAHRENHEIT), "K": ("T_", KELVIN), "mm": ("E_", MILLIMETRES),
           "none": ("T_", lambda c: c)}


def _error_line(err: str) -> str | None:
    return next((ln for ln in err.splitlines() if ln.startswith("thermocomp: error")), None)


@pytest.mark.parametrize("change", CHANGES)
def test_a_unit_changed_under_its_header_is_refused_on_stdin_as_on_the_file(
        short_dataset, tmp_path, capsys, monkeypatch, change):
    # data87: the file was refused naming column and row; the same rows piped in were
    # monitored with exit 0 (a °F or kelvin sensor an exclusion event, a mm probe a worse
    # RMSE), the data in another unit scored as the machine's
    folder = shutil.copytree(short_dataset, tmp_path / "ds")
    index = pd.read_csv(folder / "campaigns.csv")
    name = index.loc[index["split"] == "test", "file"].iloc[0]
    rows = pd.read_csv(folder / name)
    prefix, convert = CHANGES[change]
    columns = [c for c in rows.columns if c.startswith(prefix)]
    column = max(columns, key=lambda c: rows[c].abs().median())
    from_row(column, 15, convert)(rows)
    args = ["monitor", f"data.path={folder}", "track=false", "plots=none"]
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(index=False)))
    piped = main([*args, "monitor.input=-", f"out={tmp_path / 'stdin'}"])
    said = _error_line(capsys.readouterr().err)
    rows.to_csv(folder / name, index=False)
    on_file = main([*args, f"out={tmp_path / 'file'}"])
    file_said = _error_line(capsys.readouterr().err)
    assert piped == on_file == (0 if change == "none" else 2), (said, file_said)
    if change == "none":
        return
    assert f"file <stdin>, column '{column}', data row 15: " in said, said
    assert f"{name}, column '{column}', line 16 (data row 15): " in file_said, file_said
    assert said.split("data row 15: ", 1)[1] == file_said.split("data row 15): ", 1)[1]
    # the file's words said the change, a kelvin one too (it was "no temperature, in °C or
    # kelvin ...: another quantity? give its column a role")
    assert "the unit changes inside the file, convert it" in said, said


# -- (b) a folder whose files were saved by different programs -------------------------------

def _lab_folder(root, script_like: bool):
    """Three runs a logger's PC wrote as UTF-8 (``script_like``: ``,`` and decimal points; else
    ``;`` and decimal commas, as the fourth) and a fourth re-saved by a German Excel: cp1252,
    ``;``, decimal commas, its speeds grouped by a point (``6.000``); seeds 9141-9144."""
    root.mkdir()
    for run in (1, 2, 3):
        path = german_export(root / f"run{run}.csv", 9141 + run, ["6000", "12000", "1500"])
        if script_like:
            text = path.read_text(encoding="utf-8").replace(",", ".").replace(";", ",")
            path.write_text(text, encoding="utf-8")
    path = german_export(root / "run4.csv", 9141, ["6.000", "12.000", "1.500"])
    path.write_bytes(path.read_text(encoding="utf-8").encode("cp1252"))
    return root


@pytest.mark.parametrize("script_like", [False, True], ids=["semicolons", "commas"])
def test_a_folder_with_a_file_excel_saved_again_is_read_each_file_by_its_own(tmp_path, capsys,
                                                                            script_like):
    # data87: init refused "byte 0xb0 is not UTF-8 text ... set data.encoding=cp1252", which
    # refuses the UTF-8 files ("save it as the others"); and a folder-wide data.thousands='.'
    # refuses the UTF-8 files' decimal points
    folder = _lab_folder(tmp_path / "runs", script_like)
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0, capsys.readouterr().err
    said = capsys.readouterr().out
    assert "encoding each file's own (UTF-8 and cp1252 files)" in said, said
    conf = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text(
        encoding="utf-8"))
    assert conf["encoding"] == "auto"
    assert conf["thousands"] == ("auto" if script_like else ".")
    ds, _ = read_dataset(folder, conf)
    speeds = {cid: sorted(set(df["S_Spindel"])) for cid, df in ds.campaigns.items()}
    assert speeds["run4"] == speeds["run1"] == [1500.0, 6000.0, 12000.0], speeds
    temps = {cid: df["T_Spindel"].iloc[0] for cid, df in ds.campaigns.items()}
    assert all(19.0 < t < 23.0 for t in temps.values()), temps


def test_a_file_whose_decimal_mark_is_ambiguous_is_refused_naming_its_column_and_row(tmp_path,
                                                                                   capsys):
    folder = _lab_folder(tmp_path / "runs", False)
    text = (folder / "run4.csv").read_bytes().decode("cp1252").splitlines()
    cells = text[4].split(";")
    cells[-1] = "6.5"                 # neither a thousand nor a decimal comma's neighbour
    text[4] = ";".join(cells)
    (folder / "run4.csv").write_bytes(("\n".join(text) + "\n").encode("cp1252"))
    refused(["run", f"data.path={folder}", "data.encoding=auto", "data.thousands=auto",
             "data.roles.error=[d*]", "data.test_fraction=0.25", "track=false", "plots=none",
             f"out={tmp_path / 'out'}"], capsys, "run4.csv", "column 'Spindel [1/min]'",
            "data row 4", "the decimal mark is ambiguous ('6.5' here")


def test_a_number_written_otherwise_beside_grouped_speeds_is_named_where_it_is(tmp_path, capsys):
    # audit112: a US-written '1,234.5' among run4's decimal commas and grouped speeds ('6.000')
    # slipped past the decimal sniff (it holds both marks), so data.thousands=auto read no
    # separator and the read refused '6.000' at row 1, advising a data.thousands='.' the other
    # files refuse; init said "groups digits by three in '1,234.5' but not in '1,234.5'"
    folder = _lab_folder(tmp_path / "runs", False)
    text = (folder / "run4.csv").read_bytes().decode("cp1252").splitlines()
    cells = text[10].split(";")
    cells[5] = "1,234.5"              # dZ, data row 10
    text[10] = ";".join(cells)
    (folder / "run4.csv").write_bytes(("\n".join(text) + "\n").encode("cp1252"))
    refused(["run", f"data.path={folder}", "data.encoding=auto", "data.thousands=auto",
             "data.roles.error=[d*]", "data.test_fraction=0.25", "track=false", "plots=none",
             f"out={tmp_path / 'out'}"], capsys, "run4.csv", "column 'dZ [µm]'", "data row 10",
            "value '1,234.5' does not group its digits by three with '.'")
    assert not (tmp_path / "out").exists()
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 2
    said = capsys.readouterr()
    assert "'.' groups digits by three in '6.000' but not in '1,234.5'" in said.out + said.err, said

def test_a_stream_in_either_encoding_reads_with_data_encoding_auto():
    text = "Zeit [s];T Luft [°C];dX [µm]\n0;20,5;1,5\n"
    for code in ("utf-8", "cp1252"):
        stream = SimpleNamespace(buffer=io.BytesIO(text.encode(code)))
        assert stdin_text(stream, "auto") == text
    with pytest.raises(ContractError, match="byte 0x81 is not UTF-8 or cp1252 text"):
        stdin_text(SimpleNamespace(buffer=io.BytesIO(b"a\n\x81\n")), "auto")


# -- (c) a LabVIEW file of several sessions piped in -----------------------------------------

def test_a_labview_stream_of_two_sessions_is_monitored_as_two_runs(tmp_path, capsys,
                                                                  monkeypatch):
    # data87: "the LabVIEW Measurement File streamed holds 2 sessions ...: stream one run"
    # (exit 2); a session begins with its own 'LabVIEW Measurement' header, no gap taken for
    # one: each is a campaign, from a reset, as the file's runs are
    folder = _gb_folder(tmp_path / "runs")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0
    common = [f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=runs",
              "model=lagbank", *LIGHT, "track=false"]
    assert main(["run", *common, f"out={tmp_path / 'run'}"]) == 0
    one = (folder / "ZP1200_Lauf_03.lvm").read_bytes().decode("cp1252")
    scored = {}
    for label, text in (("one", one), ("two", one + "\r\n" + one)):
        monkeypatch.setattr("sys.stdin", io.StringIO(text))
        out = tmp_path / f"monitor-{label}"
        assert main(["monitor", *common, f"monitor.model={tmp_path / 'run' / 'model.pkl'}",
                     "monitor.input=-", f"out={out}"]) == 0, capsys.readouterr().err
        report = json.loads((out / "monitor.json").read_text())
        scored[label] = report["targets"]["E_dX"]
    assert list(report["campaigns"]) == ["stdin_1", "stdin_2"]
    assert scored["two"]["n_samples"] == 2 * scored["one"]["n_samples"] == 2 * ROWS
    assert scored["two"]["rmse_fixed"] == pytest.approx(scored["one"]["rmse_fixed"], rel=1e-9)
