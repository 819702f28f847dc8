"""An old measuring program's fixed-width report through `init` and the reader (session 60,
benchmarks/bench_new_machines60.py, the jig grinder).

The report has a title block, a header of names padded with spaces (a name may hold one), a line
of units (``MIN``, ``DEG F``, ``MM``, ``KRPM``), a dashed rule and right-aligned columns with no
delimiter: `init` said "no column reads as a measured error ... the numeric columns: none" (the
file read as one column).  Read now through its CSV text (:mod:`thermocomp.core.io.fixedwidth`).
"""

from __future__ import annotations

import numpy as np
import pytest
import yaml

from thermocomp.core.io import read_dataset
from thermocomp.core.io.fixedwidth import is_fixed_width, layout
from thermocomp.core.io.layout import is_unit_row
from thermocomp.shell.cli import main

TITLE = ["        THERMAL DRIFT TEST - JG-400 JIG GRINDER     PROGRAM TDM 3.2",
         "        SERIAL 40117    DATE 10/05/2026    START 07:42", ""]
COLUMNS = [("TIME", "MIN"), ("SPINDLE MOT", "DEG F"), ("ROOM AIR", "DEG F"), ("DISP Y", "MM"),
           ("SPINDLE", "KRPM")]


def report(path, rows=30, first_f=68.0):
    """The program's report: ``DEG F`` from ``first_f``, ``DISP Y`` 0.3 µm a row (in mm)."""
    cells = [[f"{i:.1f}", f"{first_f + 0.09 * i:.3f}", f"{68.0 + 0.018 * (i % 3):.3f}",
              f"{0.0003 * i - 0.002:.5f}", f"{45 if i % 10 < 5 else 0}"] for i in range(rows)]
    widths = [max(len(n), len(u), *(len(r[j]) for r in cells)) + 2
              for j, (n, u) in enumerate(COLUMNS)]
    lines = [*TITLE, "".join(n.rjust(w) for (n, _), w in zip(COLUMNS, widths)),
             "".join(u.rjust(w) for (_, u), w in zip(COLUMNS, widths)), "-" * sum(widths)]
    lines += ["".join(c.rjust(w) for c, w in zip(r, widths)) for r in cells]
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\r\n".join(lines) + "\r\n", encoding="ascii")
    return path


def test_the_columns_of_a_fixed_width_table_are_told_by_its_numbers(tmp_path):
    path = report(tmp_path / "JG400_S01.TXT")
    lines = path.read_text().splitlines()
    found = layout(lines)
    assert found.header == (3, 4) and found.first_data == 6
    assert [found.cells(lines[6])[j] for j in (0, 3)] == ["0.0", "-0.00200"]
    assert is_fixed_width(path)
    # a CSV file, a line of numbers parted by single spaces (no columns) are no such table
    csv = tmp_path / "a.csv"
    csv.write_text("time,T1\n" + "".join(f"{i},{20 + i}\n" for i in range(10)))
    assert not is_fixed_width(csv)
    ragged = tmp_path / "b.txt"
    ragged.write_text("t T1\n" + "".join(f"{10 ** (i % 4)} {i}.5\n" for i in range(10)))
    assert not is_fixed_width(ragged)


def test_a_unit_row_may_give_a_speed_in_thousands_of_rpm():
    assert is_unit_row(["MIN", "DEG F", "MM", "KRPM"])


def test_a_fixed_width_report_is_read_in_the_contracts_units(tmp_path):
    path = report(tmp_path / "JG400_S01.TXT")
    ds, _ = read_dataset(path, {"roles": {"error": ["DISP*"], "state": ["SPINDLE"],
                                          "ambient": ["ROOM*"]}})
    (cid,) = ds.ids()
    df = ds.campaigns[cid]
    assert list(df.columns) == ["time", "T_SPINDLE_MOT", "T_amb", "E_DISP_Y", "S_SPINDLE"]
    assert df["time"].iloc[1] == 60.0                                 # minutes
    assert df["T_SPINDLE_MOT"].iloc[0] == pytest.approx(20.0)         # 68 °F
    assert df["E_DISP_Y"].to_numpy()[:3] == pytest.approx([-2.0, -1.7, -1.4])   # mm -> µm
    assert np.array_equal(df["S_SPINDLE"].to_numpy()[:6], [45, 45, 45, 45, 45, 0])


def test_init_reads_a_folder_of_fixed_width_reports(tmp_path, capsys):
    for s in (1, 2, 3, 4):
        report(tmp_path / "jig" / f"JG400_S{s:02d}.TXT", first_f=66.0 + s)
    out = tmp_path / "init"
    assert main(["init", str(tmp_path / "jig"), "data.test_fraction=0.25", f"out={out}"]) == 0
    said = capsys.readouterr().out
    assert "a fixed-width table" in said and "units from line 5" in said
    config = yaml.safe_load((out / "conf" / "data" / "jig.yaml").read_text())
    assert config["roles"]["error"] == ["DISP Y"]
    assert config["roles"]["state"] == ["SPINDLE"]
