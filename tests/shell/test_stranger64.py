"""What a stranger met on a portal mill's lab exports (stranger64, ``bench_stranger64.py``);
each test fails on the code before its mend.  Small files: hours, not the bench's weeks."""

from __future__ import annotations

import subprocess

import numpy as np
import pandas as pd
import yaml

from cbuild import compiled
from conftest import FAST, refused
from test_export import needs_cc
from thermocomp.shell.cli import main

EXCEL_EPOCH = pd.Timestamp("1899-12-30")


def lab_frame(rows: int = 240, seed: int = 64) -> pd.DataFrame:
    """A portal mill's hours at 60 s: two temperatures, the ram's extension in mm (0-800, a job
    at a time), the probe's Z error in mm (a thermal error: a few hundredths)."""
    rng = np.random.default_rng(seed)
    t = np.arange(rows) * 60.0
    heat = 15 + 4 * (1 - np.exp(-t / 3000)) + rng.normal(0, 0.02, rows)
    ram = np.repeat(rng.integers(0, 81, rows // 40 + 1) * 10.0, 40)[:rows]
    return pd.DataFrame({"t [s]": t, "T ram [°C]": heat, "T hall [°C]": 12 + 0.001 * t,
                         "Z ram [mm]": ram,
                         "dZ [mm]": (-0.012 * (heat - 15) * (1 + ram / 800)).round(4)})


def _config(out) -> dict:
    [path] = (out / "conf" / "data").glob("*.yaml")
    return yaml.safe_load(path.read_text())


def test_init_proposes_a_length_that_spans_an_axis_travel_as_a_state(tmp_path, capsys):
    # before: 'Z ram [mm]' (0-800 mm) was proposed the error E_Z_ram, and `run` scored a
    # "thermal error" of 800,000 µm beside the probe's dZ
    path = tmp_path / "pm12.csv"
    lab_frame().to_csv(path, index=False)
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    said = capsys.readouterr().out
    roles = _config(tmp_path / "init")["roles"]
    assert "Z ram" in roles["state"] and "Z ram" not in roles["error"]
    assert roles["error"] == ["dZ"]
    span = np.ptp(lab_frame()["Z ram [mm]"])
    assert f"'Z ram [mm]' spans {span:.4g} mm" in said and "S_Z_ram" in said
    # a length the user names as the error stays one
    assert main(["init", str(path), "data.roles.error=[dZ,Z ram]",
                 f"out={tmp_path / 'named'}"]) == 0
    assert "Z ram" in _config(tmp_path / "named")["roles"]["error"]



def test_run_warns_of_a_length_read_as_an_error_that_spans_an_axis_travel(tmp_path, capsys):
    # before: `run data.roles.error=[dZ]` read 'Z ram [mm]' as the error E_Z_ram by its unit,
    # silently, and scored a thermal error of 0.8 m beside the probe's
    path = tmp_path / "pm12.csv"
    lab_frame().to_csv(path, index=False)
    common = ["run", f"data.path={path}", "data.test_fraction=0.3", *FAST, "plots=none",
              f"out={tmp_path / 'run'}"]
    span = np.ptp(lab_frame()["Z ram [mm]"])
    assert main([*common, "data.roles.error=[dZ]"]) == 0
    err = capsys.readouterr().err
    assert (f"'Z ram [mm]' (E_Z_ram), an error by its unit, spans {span:.4g} mm" in err
            and "data.roles.state=['Z ram']" in err)
    for roles in ("data.roles.error=[dZ,Z ram]", "data.roles.state=[Z ram]"):
        assert main([*common, roles]) == 0
        assert "spans" not in capsys.readouterr().err

def excel_dates(path, rows: int = 240):
    """The record saved from Excel: its time a ``Date`` of serial days, no time column."""
    frame = lab_frame(rows).drop(columns=["Z ram [mm]"])
    start = (pd.Timestamp("2027-03-01") - EXCEL_EPOCH) / pd.Timedelta(days=1)
    days = (start + frame.pop("t [s]") / 86400.0).map(lambda d: f"{d:.10f}")
    frame.insert(0, "Date", days)
    frame.to_csv(path, index=False)
    return path


def test_init_reads_excel_serial_days_as_the_time(tmp_path, capsys):
    # before: refused, "no 'time' column (...): set data.sample_period_s" -- the rows are not a
    # period apart by a setting, they carry their dates as Excel's serial days
    path = excel_dates(tmp_path / "march.csv")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    config = _config(tmp_path / "init")
    assert config["roles"]["time"] == "Date" and config["units"] == {"Date": "d"}
    said = capsys.readouterr().out
    assert "Excel's serial days" in said and "sample period: 60 s, 240 rows" in said


def test_a_read_by_roles_without_a_time_names_the_excel_days_and_their_unit(tmp_path, capsys):
    # before: the same refusal to set data.sample_period_s
    path = excel_dates(tmp_path / "march.csv")
    refused(["ingest", f"data.path={path}", "data.roles.error=[dZ]", "track=false"], capsys,
            "Excel's serial days", "data.units={Date: d}", "data.roles.time='Date'")


def test_files_of_one_clock_whose_readings_restart_are_said(tmp_path, capsys):
    # before: the weekly files joined silently (state carried over across a 2.5 K step of the
    # right column's sensor), while replay's sensor monitor excluded it as a jump
    folder = tmp_path / "weeks"
    folder.mkdir()
    frame = lab_frame(240).drop(columns=["Z ram [mm]"])
    first, second = frame.iloc[:120].copy(), frame.iloc[120:].copy()
    second["T ram [°C]"] -= 2.5                          # restarted, the hours continue
    first.to_csv(folder / "week1.csv", index=False)
    second.to_csv(folder / "week2.csv", index=False)
    common = ["run", f"data.path={folder}", "data.roles.error=[dZ]", "data.test_fraction=0.5",
              *FAST, "plots=none", f"out={tmp_path / 'run'}"]

    def said() -> list[str]:
        return [ln for ln in capsys.readouterr().err.splitlines() if "by its time, but" in ln]

    assert main(common) == 0
    [line] = said()
    assert line.startswith("[thermocomp] warning: week2 continues week1 by its time, but its "
                           "first row steps 1 temperature(s)")
    assert "(T_ram -2.5" in line and "data.reference=first_sample" in line
    assert main([*common, "data.reference=first_sample"]) == 0
    assert not said()
    frame.iloc[120:].to_csv(folder / "week2.csv", index=False)      # one record: not said
    assert main(common) == 0
    assert not said()


def preamble_file(path, rows: int = 240):
    """The PM-12 logger's weekly file: four preamble lines, TAB-separated, decimal commas, the
    time as elapsed hours, the ram's extension a state."""
    frame = lab_frame(rows)
    frame.insert(0, "t [h]", (frame.pop("t [s]") / 3600.0).round(4))
    table = frame.to_csv(sep="\t", index=False, lineterminator="\n").replace(".", ",")
    path.write_text("Machine;PM-12\nOperator: K. Brandt\nProject: thermal drift\n"
                    "Probe: touch probe\n" + table, encoding="utf-8")
    return path


@needs_cc
def test_the_compiled_stream_skips_a_loggers_preamble_as_the_reader_does(tmp_path):
    # before: "stream: the header (line 1 ...) lacks input column T_ram" (exit 2) for the file
    # `run` had read as it is
    path = preamble_file(tmp_path / "PM12_week1.txt")
    common = [f"data.path={path}", "data.roles.error=[dZ]", "data.roles.state=[Z ram]",
              "data.test_fraction=0.3"]
    assert main(["run", *common, *FAST, "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    compiled(tmp_path / "code")
    lines = path.read_text(encoding="utf-8").splitlines(keepends=True)
    out = {}
    for name, text in (("as written", "".join(lines)), ("without it", "".join(lines[4:]))):
        done = subprocess.run([str(tmp_path / "code" / "stream")], input=text.encode(),
                              capture_output=True)
        assert done.returncode == 0, (name, done.stderr)
        out[name] = done.stdout
    assert out["as written"] == out["without it"]
    assert len(out["as written"].splitlines()) == 241
    # a file whose header lacks an input is still refused, naming the header's line and the
    # input it lacks (stranger73: it named line 1, the preamble's, and the first input of all,
    # T_ram, whichever was missing)
    for header, lacking in (("T ram [°C]", b"T_ram"), ("T hall [°C]", b"T_hall")):
        text = "".join(lines).replace(header, "T rim [°C]")
        done = subprocess.run([str(tmp_path / "code" / "stream")], input=text.encode(),
                              capture_output=True)
        assert done.returncode == 2 and b"(line 5" in done.stderr, done.stderr
        # (stranger74: and the lab's own header it reads that input from)
        assert done.stderr.rstrip().endswith(b"lacks input column " + lacking + b" (the lab's header '"
                                             + header.encode() + b"')"), done.stderr
