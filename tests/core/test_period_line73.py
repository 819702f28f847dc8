"""A sample period stated in a logger's preamble line, for a file without a time column
(stranger73: a lab's `;`/decimal-comma export said `Abtastrate 15 s` on its first line; `init`
and `run` said only "set data.sample_period_s")."""

from __future__ import annotations

import pytest
import yaml

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.period_line import stated_period
from thermocomp.shell.cli import main

ROWS = "".join(f"{20 + 0.01 * k:.2f};{20.5 + 0.02 * k:.2f};{0.1 * k:.1f}\n".replace(".", ",")
               for k in range(40))
HEADER = "Halle [°C];Spindel [°C];dZ [µm]\n"


def lab_file(tmp_path, preamble: str):
    path = tmp_path / "lab.csv"
    path.write_text(preamble + HEADER + ROWS, encoding="utf-8")
    return path


@pytest.mark.parametrize("line, seconds", [
    ("Messung VGM 3;Abtastrate 15 s\n", 15.0),
    ("Sample interval: 500 ms\n", 0.5),
    ("Sampling rate = 2 Hz\n", 0.5),
    ("Messintervall;00:01:00\n", 60.0),
    ("Logging interval 1,5 min\n", 90.0),
])
def test_a_preamble_line_stating_the_period_is_read(tmp_path, line, seconds):
    said = stated_period(lab_file(tmp_path, line), ";", "utf-8")
    assert said is not None and said.seconds == pytest.approx(seconds) and said.line == 1


@pytest.mark.parametrize("preamble", [
    "Messung VGM 3;Abtastrate 15\n",                       # no unit: no evidence
    "Separate run 3 h\n",                                  # no keyword (a word holding 'rate')
    "Abtastrate 15 s\nSample interval: 30 s\n",            # two lines, two periods
    "Sample rate: 10 S/s\n",                                # samples a second (lead73: 10 s)
    "",                                                    # no preamble
])
def test_nothing_is_proposed_without_a_clear_statement(tmp_path, preamble):
    assert stated_period(lab_file(tmp_path, preamble), ";", "utf-8") is None


def test_run_refusal_quotes_the_line(tmp_path):
    opts = {"delimiter": ";", "decimal": ",", "roles": {"error": ["dZ"]}}
    with pytest.raises(ContractError, match=r"set data.sample_period_s \(the seconds between "
                                            r"rows\); line 1 says 'Messung;Abtastrate 15 s': "
                                            r"data.sample_period_s=15$"):
        read_dataset(lab_file(tmp_path, "Messung;Abtastrate 15 s\n"), opts)


def test_init_writes_the_stated_period_and_reads_the_record(tmp_path, capsys):
    src = lab_file(tmp_path, "Messung;Abtastrate 15 s\n")
    assert main(["init", str(src), f"out={tmp_path / 'init'}", "track=false"]) == 0
    out = capsys.readouterr().out
    assert "line 1 says 'Messung;Abtastrate 15 s': data.sample_period_s=15 (written" in out
    assert "sample period: 15 s, 40 rows" in out
    config = yaml.safe_load((tmp_path / "init" / "conf" / "data" / "lab.yaml").read_text())
    assert config["sample_period_s"] == 15.0
