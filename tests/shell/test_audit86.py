"""A stranger's lab exports off the happy path (audit86; ``benchmarks/bench_audit86.py`` writes
the full record): a German Excel export whose speeds are grouped by a point (``6.000``) beside
decimal commas (``21,18``)."""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest

from test_export import built_stream, needs_cc
from test_stranger68 import linear_run
from thermocomp.shell.cli import main


def german_export(path: Path, seed: int, speeds: list[str]) -> Path:
    """A run of linear_run's rows every 60 s as a German Excel writes it: ``;``, decimal commas,
    a speed column in ``speeds`` (its digits grouped by a point)."""
    values = linear_run(seed, 1)
    lines = ["Zeit [s];T Luft [°C];T Spindel [°C];T Lager [°C];dX [µm];dZ [µm];Spindel [1/min]"]
    for i, row in enumerate(values):
        cells = [str(60 * i), *(f"{v:.2f}".replace(".", ",") for v in row), speeds[i % len(speeds)]]
        lines.append(";".join(cells))
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def test_init_reads_speeds_grouped_by_a_point_beside_decimal_commas(tmp_path, capsys):
    # audit86: refused "the decimal mark is ambiguous (cells with ',' and with '.')" before the
    # thousands separator was looked for: every point groups digits by three, '21,18' and
    # '0,51' show the comma as the decimal mark (init's rule, own-data.md, initone65)
    path = german_export(tmp_path / "lauf.csv", 9011, ["6.000", "12.000", "1.500"])
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 0, capsys.readouterr().err
    conf = (tmp_path / "init" / "conf" / "data" / "lauf.yaml").read_text()
    assert "decimal: ','" in conf and "thousands: ." in conf, conf
    assert "data.thousands='.'" in capsys.readouterr().out
    # a point that does not group by three still leaves the decimal mark to the user
    german_export(path, 9011, ["6.000", "12.5"])
    assert main(["init", str(path), f"out={tmp_path / 'init2'}"]) == 2
    assert "the decimal mark is ambiguous" in capsys.readouterr().err



def test_init_reads_a_folder_whose_runs_two_pcs_exported_each_with_its_own_separators(tmp_path,
                                                                                      capsys):
    # audit86: init read every file with the first's separators (`;`, decimal commas) and
    # refused the UTF-16 TAB file, "set data.delimiter='\t'", which refuses the others; `run`
    # with data.delimiter=auto reads each file by its own
    folder = tmp_path / "runs"
    folder.mkdir()
    for run in (1, 2):
        german_export(folder / f"run{run}.csv", 9012 + run, ["6000"])
    text = german_export(tmp_path / "run3.csv", 9015, ["6000"]).read_text(encoding="utf-8")
    (folder / "run3.csv").write_text(text.replace(",", ".").replace(";", "\t"), encoding="utf-16")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}"]) == 0, capsys.readouterr().err
    assert "each read with its own, data.delimiter=auto" in capsys.readouterr().out
    conf = (tmp_path / "init" / "conf" / "data" / "runs.yaml").read_text()
    assert "delimiter: auto" in conf and "decimal: auto" in conf, conf
    assert main(["run", f"hydra.searchpath=[file://{tmp_path / 'init' / 'conf'}]", "data=runs",
                 "track=false", "plots=none", f"out={tmp_path / 'out'}"]) == 0


def test_a_manifest_saved_by_excel_with_empty_rows_under_its_campaigns_reads(tmp_path, caplog):
    # audit86: a manifest kept in Excel (`;`, a BOM) whose rows under the table were touched:
    # Excel writes them `;;;` and the read refused "campaign id '' is empty" at that row; a
    # campaign file's row of empty cells is left out, said
    from thermocomp.core.io import read_dataset
    from thermocomp.core.io.contract import ContractError

    folder = tmp_path / "runs"
    folder.mkdir()
    rows = []
    for run, split in ((1, "train"), (2, "train"), (3, "test")):
        german_export(folder / f"r{run}.csv", 9015 + run, ["6000"])
        rows.append(f"r{run};r{run}.csv;{split}")
    manifest = folder / "campaigns.csv"
    manifest.write_bytes("\ufeffcampaign;file;split\r\n".encode() + "\r\n".join(
        [*rows, ";;", ";;", ""]).encode())
    opts = {"delimiter": ";", "decimal": ",", "roles": {"error": ["dX", "dZ"]}}
    ds, _ = read_dataset(folder, opts)
    assert sorted(ds.campaigns) == ["r1", "r2", "r3"]
    assert "data rows 4-5 of empty cells" in caplog.text
    # an empty row among the campaigns is still refused at its row
    manifest.write_text("campaign;file;split\n" + "\n".join([rows[0], ";;", *rows[1:]]) + "\n")
    with pytest.raises(ContractError, match="campaign id '' is empty") as refused:
        read_dataset(folder, opts)
    assert refused.value.row == 2


@pytest.mark.parametrize("rows, fractions, says", [
    # a train part too short: a larger test fraction leaves it shorter still
    (10, ["data.test_fraction=0.5", "data.val_fraction=0.4"],
     "the train part would have 1 sample(s) of the record's 10: at least 2 (lower "
     "data.val_fraction and data.test_fraction)"),
    (20, ["data.test_fraction=0.05"], "the test part would have 1 sample(s) of the record's 20: "
                                      "at least 2 (raise data.test_fraction)"),
    # no fraction cuts 3 samples into a train and a test part of 2 each
    (3, [], "the record's 3 samples are too few for 2 parts of at least 2 (train, test)"),
    (2, [], "the record's 2 samples are too few for 2 parts of at least 2"),
])
def test_a_part_too_short_names_the_fraction_that_lengthens_it(tmp_path, capsys, rows, fractions,
                                                               says):
    # audit86: a record's train part too short was told "raise data.test_fraction", which
    # shortens it
    path = german_export(tmp_path / "kurz.csv", 9017, ["6000"])
    path.write_text("".join(path.read_text(encoding="utf-8").splitlines(True)[:rows + 1]),
                    encoding="utf-8")
    code = main(["run", f"data.path={path}", "data.delimiter=;", "data.decimal=,",
                 "data.roles.error=[dX, dZ]", "data.test_fraction=0.1", *fractions,
                 "track=false", "plots=none", f"out={tmp_path / 'out'}"])
    err = capsys.readouterr().err
    assert code == 2 and says in err, err


def test_a_header_written_again_is_refused_without_its_names_said_as_marks(tmp_path, capsys):
    # audit86: a second export pasted under the first (its header again, dX now in mm): init
    # said every name of that line a mark for a value not measured, "'dX [mm]' in 1 cell of
    # number column 'dX [µm]': no number, no digit: ... read as missing", before its read
    # refused the line as the header written again
    path = german_export(tmp_path / "lauf.csv", 9018, ["6000"])
    lines = path.read_text(encoding="utf-8").splitlines()
    path.write_text("\n".join([*lines, lines[0].replace("dX [µm]", "dX [mm]"), *lines[1:]]) + "\n",
                    encoding="utf-8")
    assert main(["init", str(path), f"out={tmp_path / 'init'}"]) == 2
    said = capsys.readouterr()
    assert "the file's header written again under its data" in said.err
    assert "a mark for a value not measured" not in said.out, said.out
    # a mark in a row of numbers is still found
    path.write_text("\n".join([*lines[:5], lines[5].replace(";6000", ";---"), *lines[6:]]) + "\n",
                    encoding="utf-8")
    assert main(["init", str(path), f"out={tmp_path / 'init2'}"]) == 0
    assert "'---' in 1 cell of number column 'Spindel [1/min]'" in capsys.readouterr().out


def test_a_bad_cell_piped_in_with_decimal_commas_is_named_at_its_row(tmp_path):
    # audit86: a stream with decimal commas read a column holding a bad cell as text, its
    # commas unread: "column 'T_amb', data row 1: non-numeric value" for a '2x,5' at row 30
    from dataclasses import replace

    from thermocomp.core.io import ReadOptions
    from thermocomp.core.io.contract import ContractError
    from thermocomp.core.io.stdin import stream_campaigns

    lines = german_export(tmp_path / "lauf.csv", 9019, ["6000"]).read_text(
        encoding="utf-8").splitlines()
    cells = lines[30].split(";")
    lines[30] = ";".join([cells[0], "2x,5", *cells[2:]])
    opts = replace(ReadOptions(), delimiter=";", decimal=",",
                   roles={"error": ["dX", "dZ"], "ambient": ["T Luft"]})
    with pytest.raises(ContractError, match="'2x,5' is not a number") as refused:
        stream_campaigns("\n".join(lines) + "\n", ["T_amb", "T_Spindel"], opts)
    assert (refused.value.column, refused.value.row) == ("T_amb", 30)
    # a line of text under the header (a second export's header, another width) too; it was
    # "'T Spindel [°C]' is not numeric ('20,43')", no row
    lines[30] = "Zeit [s];T Luft [°C];oops"
    with pytest.raises(ContractError, match="'T Luft \\[°C\\]' is not a number") as refused:
        stream_campaigns("\n".join(lines) + "\n", ["T_amb", "T_Spindel"],
                         replace(opts, roles={"error": ["dX", "dZ"], "ambient": ["T Luft"]}))
    assert refused.value.row == 30
    # the rows without it read, the commas as decimal marks
    lines[30] = ";".join(cells)
    frames, _ = stream_campaigns("\n".join(lines) + "\n", ["T_amb", "T_Spindel"], opts)
    assert frames["stdin"]["T_amb"].iloc[29] == float(cells[1].replace(",", "."))


@needs_cc
def test_the_compiled_stream_reads_a_header_written_twice_as_the_reader_does(tmp_path, capsys):
    # audit86: a lab's file with 'T Lager [°C]' twice (different values) is read by run,
    # replay and monitor as 'T Lager#2 [°C]' (init74), which the model reads; the exported
    # stream.c refused it, "the header names input T_Lager twice (columns 4 and 5)"
    path = german_export(tmp_path / "lauf.csv", 9020, ["6000"])
    lines = path.read_text(encoding="utf-8").splitlines()
    rows = [ln.split(";") for ln in lines]
    rows[0].insert(4, rows[0][3])
    for k, row in enumerate(rows[1:]):
        row.insert(4, f"{20 + 0.01 * k:.2f}".replace(".", ","))
    path.write_text("\n".join(";".join(r) for r in rows) + "\n", encoding="utf-8")
    keys = [f"data.path={path}", "data.delimiter=;", "data.decimal=,", "data.test_fraction=0.2",
            "data.roles.error=[dX, dZ]", "data.roles.ambient=[T Luft]", "track=false"]
    assert main(["run", *keys, "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *keys, f"export.model={tmp_path / 'run' / 'model.pkl'}",
                 "export.format=c", f"out={tmp_path / 'code'}"]) == 0
    stream = built_stream(tmp_path / "code")
    streamed = subprocess.run([str(stream)], input=path.read_text(encoding="utf-8"), text=True,
                              capture_output=True)
    assert streamed.returncode == 0, streamed.stderr
    # the same rows under the name the reader gives the second column
    named = path.read_text(encoding="utf-8").replace("T Lager [°C];T Lager [°C]",
                                                     "T Lager [°C];T Lager#2 [°C]", 1)
    renamed = subprocess.run([str(stream)], input=named, text=True, capture_output=True)
    assert renamed.returncode == 0, renamed.stderr
    assert streamed.stdout == renamed.stdout and len(streamed.stdout.splitlines()) == len(rows)
