"""A lab's raw export, round 3 (issue 34, item 1; the guide's "bad input" rule): a message's row
is the line the lab opens in its editor, an elapsed time over 24 h reads, and a folder's runs are
held out alike read whole or in groups."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import refused
from test_raw_exports44 import ROWS, _record
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.stdin import stream_seconds
from thermocomp.shell.cli import main

ROLES = {"error": ["dX"]}
SEPARATORS = {"delimiter": ";", "decimal": ","}     # (a row cut short: no separator detected)


def _messy(path: Path, edit, *, time: bool = True, preamble: bool = True) -> tuple[Path, int]:
    """The record as a logger writes it: a BOM, CRLF, a preamble with a blank line, a unit row,
    blank lines among the rows, an Excel row of empty cells (``;;``, with a time column); and
    ``edit(cells, k)`` on the cells of data row ``k`` (0-based, a row of values) that it edits,
    returning ``k``.  Returns the file and the 1-based line of that row."""
    t, t1, t2, e = _record()
    rows = [[f"{v:.4f}".replace(".", ",") for v in values] for values in zip(t, t1, e)]
    k = edit(rows)
    head = ["Logger: XY-200", "", "Start: 28.11.2026"] * preamble + [
        ("Zeit;" if time else "") + "T1;dX", ("s;" if time else "") + "°C;µm"]
    lines, target = list(head), None
    for i, cells in enumerate(rows):
        if i in (4, 9):
            lines.append("")
        if i == 7 and time:
            lines.append(";;")
        if i == k:
            target = len(lines) + 1
        lines.append(";".join(cells if time else cells[1:]))
    path.write_bytes(b"\xef\xbb\xbf" + ("\r\n".join(lines) + "\r\n").encode())
    return path, target


def _cell(column: int, value: str, k: int = 20):
    def edit(rows):
        rows[k][column] = value
        return k
    return edit


def _short(rows):
    rows[20] = rows[20][:2]
    return 20


def _gap(rows):
    rows[20][1] = ""
    return 20


def _fahrenheit(rows):      # T1 in °F from data row 20 on
    for cells in rows[20:]:
        cells[1] = f"{float(cells[1].replace(',', '.')) * 1.8 + 32:.4f}".replace(".", ",")
    return 20


CASES = {   # what is wrong at data row 20 (0-based), what the message says of it, its line
    "a cell no number": (_cell(1, "oops"), "'oops' is not a number", 29),
    # (a row cut short under a preamble: no table found there, the lines differ in width)
    "a row cut short": (_short, "expected 3 fields, got 2", 26),
    "a time going back": (_cell(0, "60"), "time decreases", 29),
    "an error beyond its limit": (_cell(2, "2e6"), "data.max_abs_error", 29),
    "a gap": (_gap, "data.max_gap_samples=0", 29),
    "a unit changing": (_fahrenheit, "the unit changes inside the file", 29),
}


@pytest.mark.parametrize("case", CASES)
def test_a_refused_row_is_named_by_its_line_in_the_file(tmp_path, case):
    # before: 'row 21' (or 20, without the row of empty cells), the data rows counted without
    # the preamble, header, unit row, blank lines: line 29 in the lab's editor
    edit, says, line = CASES[case]
    path, edited = _messy(tmp_path / "lab.csv", edit, preamble=line == 29)
    with pytest.raises(ContractError, match=re.escape(says)) as refusal:
        read_dataset(path, {"roles": ROLES, **SEPARATORS})
    assert refusal.value.line == edited == line
    assert f"line {line} (data row {refusal.value.row})" in str(refusal.value)


def test_a_row_without_a_time_column_or_a_joined_time_is_named_by_its_line(tmp_path):
    path, line = _messy(tmp_path / "untimed.csv", _cell(1, "oops"), time=False)
    with pytest.raises(ContractError) as refusal:
        read_dataset(path, {"roles": ROLES, "sample_period_s": 60})
    assert (refusal.value.line, refusal.value.row) == (line, 21)
    # a date and a time of day joined, read after the row of empty cells is left out
    path = tmp_path / "joined.csv"
    lines = ["Datum;Uhrzeit;T1;dX"] + [f"28.11.2026;10:{i:02d}:00;20,{i};{i}" for i in range(30)]
    lines[20] = "28.11.2026;10:99:00;20,5;1"
    path.write_text("\n".join([lines[0], ";;;", "", *lines[1:]]) + "\n", encoding="utf-8")
    with pytest.raises(ContractError, match="the date and the time of day joined") as refusal:
        read_dataset(path, {"roles": {**ROLES, "time": ["Datum", "Uhrzeit"]}})
    assert (refusal.value.line, refusal.value.row) == (23, 20)


def test_a_said_row_is_named_by_its_line_too(tmp_path, caplog):
    path, _ = _messy(tmp_path / "lab.csv", lambda rows: None)
    read_dataset(path, {"roles": ROLES})
    assert f"{path}, line 14 (data row 8): 1 row(s) of empty cells" in caplog.text
    path, _ = _messy(tmp_path / "untimed.csv", lambda rows: None, time=False)
    read_dataset(path, {"roles": ROLES, "sample_period_s": 60})
    assert f"{path}, line 9 (data row 4): a blank line under it" in caplog.text
    assert len(read_dataset(path, {"roles": ROLES, "sample_period_s": 60})[0].campaigns[
        "untimed"]) == ROWS


def _elapsed(path: Path, header: str, hours: float = 25.5, fraction: str = "") -> Path:
    """A logger's elapsed time ``h:mm:ss`` every 30 min up to ``hours``, the record's values."""
    t = np.arange(0, hours * 3600 + 1, 1800.0)
    t1 = 20 + 5 * (1 - np.exp(-t / 20000))
    clock = [f"{int(s // 3600)}:{int(s % 3600 // 60):02d}:{int(s % 60):02d}{fraction}" for s in t]
    rows = [f"{c};{a:.4f};{4 * (a - 20):.4f}" for c, a in zip(clock, t1)]
    path.write_text("\n".join([f"{header};T1 [°C];dX [µm]", *rows]) + "\n", encoding="utf-8")
    return path


def test_an_elapsed_time_past_24_hours_is_read_as_seconds(tmp_path, capsys):
    # before: refused, "value '0:00:00' is a time of day without its date"
    path = _elapsed(tmp_path / "run.csv", "Zeit")
    ds, report = read_dataset(path, {"roles": ROLES})
    frame = ds.campaigns["run"]
    np.testing.assert_array_equal(frame["time"], np.arange(52) * 1800.0)     # 25:30:00 last
    np.testing.assert_allclose(frame["T_T1"], 20 + 5 * (1 - np.exp(-frame["time"] / 20000)),
                               atol=1e-4)
    assert report["campaigns"]["run"]["time"] == "elapsed"
    out = tmp_path / "init"
    assert main(["init", str(path), f"out={out}"]) == 0                      # roles proposed
    assert "time: 'Zeit', elapsed h:mm:ss" in capsys.readouterr().out


def test_an_elapsed_time_within_a_day_reads_where_its_header_or_data_time_says_so(
        tmp_path, capsys):
    # a header saying so (init proposed 'ignore' for it), or data.time=elapsed
    path = _elapsed(tmp_path / "dauer.csv", "Dauer", hours=20, fraction=",5")
    frame = read_dataset(path, {"roles": ROLES})[0].campaigns["dauer"]
    np.testing.assert_array_equal(frame["time"], np.arange(41) * 1800.0 + 0.5)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0, capsys.readouterr().err
    path = _elapsed(tmp_path / "zeit.csv", "Zeit", hours=5)        # a time of day? never guessed
    out = tmp_path / "refused"
    refused(["init", str(path), f"out={out}"], capsys, str(path), "line 2 (data row 1)",
            "time of day without its date", "data.time=elapsed")
    assert not out.exists()
    frame = read_dataset(path, {"roles": ROLES, "time": "elapsed"})[0].campaigns["zeit"]
    np.testing.assert_array_equal(frame["time"], np.arange(11) * 1800.0)
    df = stream_seconds(pd.Series(["0:00:00", "0:30:00", "26:00:00"]), "elapsed")
    np.testing.assert_array_equal(df, [0.0, 1800.0, 93600.0])


def test_a_cell_of_an_elapsed_time_that_is_no_h_mm_ss_is_refused_with_its_line(tmp_path):
    path = _elapsed(tmp_path / "run.csv", "Zeit")
    lines = path.read_text(encoding="utf-8").splitlines()
    lines[7] = lines[7].replace(":00:00", ":0:00", 1)
    path.write_text("\n".join([lines[0], "", *lines[1:]]) + "\n", encoding="utf-8")
    with pytest.raises(ContractError, match="is not an elapsed time h:mm:ss") as refusal:
        read_dataset(path, {"roles": ROLES})
    assert (refusal.value.line, refusal.value.row) == (9, 7)


def _fleet(root: Path, stamp: str = "%Y-%m-%dT%H:%M:%S") -> Path:
    """Two machines' runs named by operator (name order is not time order), a manifest with
    the machine and no start: the files' first timestamps (``stamp``) say which came last."""
    root.mkdir()
    t, t1, t2, e = _record()
    days = {"mueller": 0, "abel": 1, "zander": 2, "klein": 5, "berg": 3, "adler": 4}
    rows = []
    for k, (name, day) in enumerate(days.items()):
        stamps = (pd.Timestamp("2026-03-02 07:00") + pd.to_timedelta(day, unit="D")
                  + pd.to_timedelta(t, unit="s")).strftime(stamp)
        pd.DataFrame({"time": stamps, "T_1": t1 + day, "E_X": e}).to_csv(root / f"{name}.csv",
                                                                         index=False)
        rows.append((name, f"{name}.csv", "train", "A" if k < 3 or name == "klein" else "B"))
    pd.DataFrame(rows, columns=["campaign", "file", "split", "machine"]).to_csv(
        root / "campaigns.csv", index=False)
    return root


@pytest.mark.parametrize("stamp, cfg", [("%Y-%m-%dT%H:%M:%S", {}),
                                        ("%d.%m.%Y %H:%M:%S", {"timezone": "Europe/Berlin"})])
def test_a_group_of_a_folder_holds_out_the_runs_a_whole_read_holds_out(tmp_path, stamp, cfg):
    # before: a whole read held out by the files' first timestamps (klein, the last run), a
    # group read (a fleet's machine) by manifest order (zander of machine A, adler of B)
    root = _fleet(tmp_path / "fleet", stamp)
    cfg = {**cfg, "test_fraction": 0.34}
    whole, _ = read_dataset(root, cfg)
    assert set(whole.ids("test")) == {"adler", "klein"}          # days 4 and 5 of six
    for machine, ids in (("A", ["mueller", "abel", "zander", "klein"]),
                         ("B", ["berg", "adler"])):
        group, _ = read_dataset(root, cfg, campaigns=ids)
        assert dict(group.manifest["split"]) == dict(whole.manifest.loc[ids, "split"]), machine


def test_a_files_footer_and_inits_manifest_are_read_once(tmp_path, monkeypatch, capsys):
    # before: the 16 KB tail read twice a file (the footer looked for, then again for Arrow);
    # init read a folder's manifest three times before the read that checks its config
    import thermocomp.core.io.manifest as manifest
    import thermocomp.core.io.tables as tables

    reads = {"footer": 0, "manifest": 0}

    def counted(name, function):
        def call(*args, **kwargs):
            reads[name] += 1
            return function(*args, **kwargs)
        return call

    monkeypatch.setattr(tables, "footer", counted("footer", tables.footer))
    monkeypatch.setattr(manifest, "_load_manifest", counted("manifest", manifest._load_manifest))
    root = _fleet(tmp_path / "lab")
    path = root / "klein.csv"
    path.write_text(path.read_text() + "End of data\n")
    assert main(["init", str(root), f"out={tmp_path / 'init'}"]) == 0
    assert "footer left out" in capsys.readouterr().err
    assert reads == {"footer": 6, "manifest": 2}       # one a file; init's, and the read's


def test_a_temperatures_one_letter_unit_is_read_where_its_first_value_is_in_it(tmp_path):
    # before: 'T1 K' named T_T1_K (under data.roles the name part is taken whole) and refused
    # as kelvin, 'Probe F' refused as °F; a name's last letter ('Sensor K' at 20 °C, 'T K',
    # 'Zone C', an error 'T m') is still a name
    t, t1, t2, e = _record()
    path = tmp_path / "lab.csv"
    pd.DataFrame({"time": t, "T1 K": t1 + 273.15, "Probe F": t2 * 1.8 + 32, "Sensor K": t1,
                  "Zone C": t2, "dX": e, "T m": e}).to_csv(path, index=False, float_format="%.6f")
    frame = read_dataset(path, {"roles": {"error": ["dX", "T m"]}})[0].campaigns["lab"]
    assert list(frame.columns) == ["time", "T_T1", "T_Probe", "T_Sensor_K", "T_Zone_C", "E_dX",
                                   "E_T_m"]
    np.testing.assert_allclose(frame[["T_T1", "T_Probe", "T_Sensor_K", "T_Zone_C"]],
                               np.c_[t1, t2, t1, t2], atol=1e-4)
    np.testing.assert_allclose(frame["E_T_m"], e, atol=1e-5)
    pd.DataFrame({"time": t, "T K": t1 + 273.15, "dX": e}).to_csv(path, index=False)
    with pytest.raises(ContractError, match="kelvin"):            # 'T K': a name, in kelvin
        read_dataset(path, {"roles": {"error": ["dX"]}})
