"""``thermocomp init`` gets a lab's export right in one run (initone65, issue 34 item 1).

stranger65's wire EDM exports (``benchmarks/bench_stranger65.py``, its writers reused here on a
smaller record) took ``init`` 5 runs (day files: ``1.200,0``, ``---``, the header written again
on day 3, a sensor renamed from day 6) and 3 runs (a spreadsheet CSV: ``"1,200.0"``, ``#N/A``,
``Err:502``), each refusal naming what to add.  Now init detects each, says why, writes it into
the config, and the ``run`` it prints reads the files on the first try; a doubt is said, not
guessed.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
import yaml

from conftest import FAST
from thermocomp.shell.cli import main

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"


@pytest.fixture(scope="module")
def bench():
    sys.path.insert(0, str(BENCHMARKS))
    try:
        import bench_stranger65
        from edm65 import Edm65
    finally:
        sys.path.remove(str(BENCHMARKS))
    return bench_stranger65, Edm65


def _frame(Edm65, days: int, period: float, seed: int):
    ds, _ = Edm65(days=days, sample_period_s=period, seed=seed).generate()
    return next(iter(ds.campaigns.values()))


def _init_then_run(src: Path, tmp_path: Path, capsys) -> tuple[str, dict, dict]:
    """``init`` once, then the ``run`` it prints: (what init printed, the config, metrics)."""
    out = tmp_path / "init"
    assert main(["init", str(src), f"out={out}"]) == 0, capsys.readouterr().err
    printed = capsys.readouterr().out
    config = yaml.safe_load(next((out / "conf" / "data").glob("*.yaml")).read_text())
    command = next(ln for ln in printed.splitlines() if ln.startswith("next: thermocomp run"))
    overrides = [a.strip("'") for a in command.split()[3:]]
    assert main(["run", *overrides, "model=mlr", *FAST, f"out={tmp_path / 'run'}"]) == 0, \
        capsys.readouterr().err
    metrics = json.loads((tmp_path / "run" / "metrics.json").read_text())
    return printed, config, metrics


def test_day_files_of_a_logger_are_read_by_the_run_init_prints_first_try(bench, tmp_path,
                                                                         capsys, monkeypatch):
    module, Edm65 = bench
    # eight day files at 300 s (288 rows each): the restart and the dropout moved inside a day
    monkeypatch.setattr(module, "RESTART", (2, 140))
    monkeypatch.setattr(module, "DROPOUT", ("T_table", 1, 100, 105))
    frame = _frame(Edm65, 8, 300.0, 6501)
    folder = tmp_path / "edm_a"
    folder.mkdir()
    for k, part in frame.groupby((frame["time"] // 86400).astype(int)):
        (folder / f"EDM_2027060{7 + int(k)}.csv" if k < 3 else
         folder / f"EDM_202706{7 + int(k)}.csv").write_bytes(
            module.day_file(part, int(k)).encode("cp1252"))
    printed, config, metrics = _init_then_run(folder, tmp_path, capsys)
    # each detection said, with its evidence, and written
    assert "thousands separator '.'" in printed and "decimal mark ','" in printed, printed
    assert config["thousands"] == "."
    assert "'---' in 5 cells" in printed and config["missing_values"] == ["---"], printed
    assert config["max_gap_samples"] == 5
    assert "one sensor renamed, read as T_Dielektrikum" in printed, printed
    assert config["columns"] == {"T Wasser": "T_Dielektrikum"}
    # the header written again on day 3 is left out by the reader (no key needed), said
    assert set(metrics["targets"]) == {"E_dX", "E_dY"}
    assert all(t["test"]["rmse"] > 0 for t in metrics["targets"].values())


def test_a_spreadsheet_export_is_read_by_the_run_init_prints_first_try(bench, tmp_path, capsys):
    module, Edm65 = bench
    frame = _frame(Edm65, 5, 60.0, 6502)          # 7200 rows: the writer's marks at rows 3001, 7000
    path = tmp_path / "edm_b_export.csv"
    path.write_text(module.lab_b(frame), encoding="utf-8")
    printed, config, metrics = _init_then_run(path, tmp_path, capsys)
    assert config["thousands"] == "," and "decimal mark '.' after its groups" in printed, printed
    assert sorted(config["missing_values"]) == ["#N/A", "Err:502"]
    assert "a formula's error" in printed and config["max_gap_samples"] == 3, printed
    assert set(metrics["targets"]) == {"E_dX", "E_dY"}


def _plain(path: Path, power: list[str], status: str | None = None) -> Path:
    head = "time;T1 [°C];P [W];dX [µm]" + (";Operator" if status is not None else "")
    rows = [f"{60 * i};{21 + 0.01 * i:.3f};{power[i % len(power)]};{0.5 * i:.3f}"
            + (f";{status}" if status is not None else "") for i in range(120)]
    path.write_text("\n".join([head, *rows]) + "\n", encoding="utf-8")
    return path


def test_a_grouping_the_cells_leave_in_doubt_is_said_and_not_guessed(tmp_path, capsys):
    # '.' with three digits after it in every cell that has it, integers beside: 1.200 W or
    # 1.2 W? No cell says; read as decimals (as the reader reads it), said, not written
    path = _plain(tmp_path / "lab.csv", ["980", "1.200", "1.350", "995"])
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0
    printed = capsys.readouterr().out
    assert "'P [W]'" in printed and "not guessed" in printed, printed
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "lab.yaml").read_text())
    assert "thousands" not in config and "missing_values" not in config


def test_a_token_filling_a_column_is_text_not_a_mark(tmp_path, capsys):
    # '---' in a few cells of the power: a mark; 'Meier' in every cell of a column: that column
    # is text (left out), no mark to list
    path = _plain(tmp_path / "lab.csv", ["980", "995", "1010"] * 13 + ["---"], status="Meier")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0, capsys.readouterr().err
    printed = capsys.readouterr().out
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "lab.yaml").read_text())
    assert config["missing_values"] == ["---"] and "'---' in 3 cells" in printed, printed
    assert "Meier" not in printed and "Operator" in config["roles"]["ignore"]


def test_the_reader_leaves_a_header_written_again_out_and_names_its_line(tmp_path, caplog):
    from thermocomp.core.io import read_dataset

    head = "Datum;Uhrzeit;T Halle;T Bett;dX\r\n;;°C;°C;mm\r\n"
    lines = [head]
    for i in range(30):
        if i == 12:
            lines.append(head)             # the logger restarted: its two header rows again
        lines.append(f"07.06.2027;00:{i:02d}:00;{20 + 0.01 * i:.2f};{21:.2f};{0.001 * i:.4f}"
                     .replace(".", ",").replace("07,06,2027", "07.06.2027") + "\r\n")
    folder = tmp_path / "lab"
    folder.mkdir()
    (folder / "day1.csv").write_text("".join(lines), encoding="utf-8")
    ds, _ = read_dataset(folder, {"roles": {"time": ["Datum", "Uhrzeit"], "error": ["dX"]}})
    frame = next(iter(ds.campaigns.values()))
    assert len(frame) == 30 and frame["time"].diff().dropna().eq(60).all()
    # the header's line (two lines of header above the data: line 15 held data row 13)
    assert "line 15: the file's header written again" in caplog.text, caplog.text
    # a cell refused below it is named by the line the file shows (the header's two lines
    # counted, not as data rows): row 20 stands on line 2 + 19 + 2 + 1
    bad = "".join(lines).replace("00:19:00;20,19;21,00", "00:19:00;20,19;abc1")
    (folder / "day1.csv").write_text(bad, encoding="utf-8")
    from thermocomp.core.io import ContractError

    with pytest.raises(ContractError, match=r"line 24 \(data row 20\): value 'abc1'"):
        read_dataset(folder, {"roles": {"time": ["Datum", "Uhrzeit"], "error": ["dX"]}})


def test_a_header_written_again_is_said_once_however_often_the_file_is_read(tmp_path, capsys):
    # init reads a file twice (its cells, then the record): the warning stood twice in its output
    path = tmp_path / "again.csv"
    rows = [f"{60 * i},{20 + 0.01 * i:.2f},{21 + 0.02 * i:.2f},{0.1 * i:.2f}" for i in range(40)]
    rows.insert(20, "time,T_a,T_b,E_X")
    path.write_text("time,T_a,T_b,E_X\n" + "\n".join(rows) + "\n", encoding="utf-8")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0, capsys.readouterr().err
    assert capsys.readouterr().err.count("the file's header written again") == 1
