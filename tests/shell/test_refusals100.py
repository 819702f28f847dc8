"""A lab file's independent refusals in one message (refusals100; audit100's finding 2).

``init`` of an Excel-like export (local stamps over the hour daylight saving time repeats, an
empty column) refused one thing per try: the clock, then the empty column, then read it.  Now
one message names both, each with file, column, row and its key, and one command line holding
every key, which then reads the file; nothing is written by the refusal.  A refusal that names
no key (no data rows) is said alone, as before.  The first test fails on 063630e6 (its refusal
names the clock alone).
"""

from __future__ import annotations

import re
import shlex

import numpy as np
import pandas as pd

from thermocomp.shell.cli import main

ROWS = 240      # 4 h at 60 s, over 02:00-03:00 of 2026-10-25, which Europe/Berlin's clock repeats


def _excel_like(path) -> None:
    """Local stamps without an offset over the repeated hour, decimal commas, an empty column."""
    utc = pd.date_range("2026-10-24 23:00", periods=ROWS, freq="60s", tz="UTC")
    local = utc.tz_convert("Europe/Berlin")
    t = np.arange(ROWS) / ROWS
    cells = {"Zeit": [f"{w:%Y-%m-%d %H:%M:%S}" for w in local],
             "Spindel (°C)": 20 + 3 * t, "Bett (°C)": 20 + np.sin(6 * t),
             "Umgebung (°C)": 20 + 0.5 * np.cos(3 * t), "Weg X (um)": 4 * t + np.sin(9 * t),
             "Reserve (leer)": [""] * ROWS}
    frame = pd.DataFrame(cells)
    text = frame.to_csv(sep=";", index=False, decimal=",", float_format="%.4f")
    path.write_bytes(("\ufeff" + text).encode("utf-8"))


def test_the_clock_and_an_empty_column_are_refused_at_once_and_the_line_given_reads_it(
        tmp_path, capsys):
    lab = tmp_path / "excel.csv"
    _excel_like(lab)
    out = tmp_path / "init"
    assert main(["init", str(lab), f"out={out}"]) == 2
    err = capsys.readouterr().err
    assert not out.exists()                                   # nothing half-written
    said = next(ln for ln in err.splitlines() if ln.startswith("thermocomp: error:"))
    assert "2 refusals of the file at once" in said
    assert re.search(r"\(1\) file \S+excel\.csv, column 'time', line \d+ \(data row 121\)", said)
    assert "data.timezone=Europe/Berlin" in said
    assert re.search(r"\(2\) file \S+excel\.csv, column 'T_Reserve_leer'.*data\.roles\.ignore", said)
    line = said.split("all the keys together, with which it reads the file: ")[1]
    words = shlex.split(line)
    assert words[:3] == ["thermocomp", "init", str(lab)]
    assert "data.timezone=Europe/Berlin" in words and "data.roles.ignore=['Reserve']" in words
    assert main(words[1:]) == 0                               # the line as given reads the file
    printed = capsys.readouterr().out
    assert re.search(r"Reserve \(leer\)\s+ignore \(left out\)", printed)
    assert (out / "conf" / "data" / "excel.yaml").exists()


def test_a_refusal_no_key_settles_stays_alone_and_the_keys_are_read_as_hydra_reads_them(
        tmp_path, capsys):
    from thermocomp.shell.stages.gathered import named_keys, override  # (new: not on 063630e6)

    empty = tmp_path / "empty.csv"
    empty.write_text("Zeit;Spindel (°C);Weg X (um)\n")
    assert main(["init", str(empty), f"out={tmp_path / 'init'}"]) == 2
    err = capsys.readouterr().err
    assert "refusals of the file at once" not in err and "thermocomp: error:" in err
    assert named_keys("leave it out (data.roles.ignore=['Reserve', T1])") == {
        "data.roles.ignore": ["Reserve", "T1"]}
    assert named_keys("(e.g. data.timezone=Europe/Berlin)") == {"data.timezone": "Europe/Berlin"}
    assert named_keys("data.columns={'a b': T_x}") is None          # not a key followed
    assert named_keys("data.dayfirst=true or data.dayfirst=false") is None   # the lab's choice
    assert override("data.roles.ignore", ["Motor Spindel"]) == "\"data.roles.ignore=['Motor Spindel']\""


def test_the_line_keeps_the_users_own_entries_of_a_list_key(tmp_path, capsys):
    lab = tmp_path / "excel.csv"
    _excel_like(lab)
    assert main(["init", str(lab), "data.roles.ignore=[Bett]", f"out={tmp_path / 'init'}"]) == 2
    said = next(ln for ln in capsys.readouterr().err.splitlines() if "all the keys together" in ln)
    words = shlex.split(said.split("with which it reads the file: ")[1])
    assert "data.roles.ignore=['Bett','Reserve']" in words, words


def test_no_time_column_and_an_empty_column_are_refused_at_once(tmp_path, capsys):
    """(data103) a refusal no key settles (no time column: the period is the lab's to give) no
    longer hides the empty column after it: one message, then the line with the others' keys
    and the period read the file.  Fails on 4a21da2b: the missing time column alone."""
    lab = tmp_path / "logger.csv"
    t = np.arange(60) / 60
    frame = pd.DataFrame({"T1 (front)": 20 + 3 * t, "Spindel (Gehäuse)": 21 + np.sin(6 * t),
                          "dX [µm]": 4 * t + np.sin(9 * t), "Reserve (frei)": [""] * 60})
    lab.write_text(frame.to_csv(sep="\t", index=False, float_format="%.4f"), encoding="utf-8")
    out = tmp_path / "init"
    assert main(["init", str(lab), f"out={out}"]) == 2
    said = next(ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("thermocomp: error:"))
    assert not out.exists()                                   # nothing half-written
    assert "2 refusals of the file at once ((1): yours to settle" in said
    assert re.search(r"\(1\) file \S+logger\.csv: no 'time' column.*data\.sample_period_s", said)
    assert re.search(r"\(2\) file \S+logger\.csv, column 'T_Reserve_frei'.*data\.roles\.ignore", said)
    words = shlex.split(said.split("with (1) settled too: ")[1])
    assert "data.roles.ignore=['Reserve']" in words
    assert main([*words[1:], "data.sample_period_s=60"]) == 0
    assert (out / "conf" / "data" / "logger.yaml").exists()
