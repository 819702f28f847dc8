"""``stream.c`` fed a lab's file as it is (session 60, benchmarks/bench_new_machines60.py: the
jig grinder's fixed-width report, the lathe's JSON Lines): "stream: the header lacks input column
T_SPINDLE_MOT" -- the report's title line read as the header, and nothing said what the stream
reads.  Now the refusal says it (CSV, line 1 the header, the model's names in °C, another form
or unit converted first), one line, still ending with the column."""

from __future__ import annotations

import subprocess

from test_export import needs_cc
from test_lab_stream52 import compiled
from test_run_column52 import _long, _runs


@needs_cc
def test_a_file_the_stream_does_not_read_is_refused_saying_what_it_reads(tmp_path):
    binary = compiled(tmp_path, _long(tmp_path / "alle.csv", _runs()))
    report = "        THERMAL DRIFT TEST - JG-400\n    TIME    T0    T1\n     0.0  20.0  20.1\n"
    run = subprocess.run([str(binary)], input=report.encode(), capture_output=True)
    said = run.stderr.decode().strip()
    assert run.returncode == 2 and len(said.splitlines()) == 1
    assert "line 1: CSV naming the inputs as TC_INPUT_NAMES" in said and "converted first" in said
    assert "check/<campaign>/rows.csv" in said      # where the export wrote the converted rows
    assert said.endswith("lacks input column T_T0 (the lab's header 'T0 [°C]')")   # stranger74
