"""A sample period in a file's NAME (``spindle_60s.csv``) is mentioned by the refusal of a file
without a time column, as a question, and never adopted (audit98 finding 4: the name went
unmentioned; a name like ``lathe_48h.csv`` states a test's length, not its period)."""

from __future__ import annotations

from pathlib import Path

import pytest

from thermocomp.core.io import read_dataset
from thermocomp.core.io.contract import ContractError
from thermocomp.core.io.period_line import named_period
from thermocomp.shell.cli import main

ROWS = "".join(f"{20 + 0.01 * k:.2f};{20.5 + 0.02 * k:.2f};{0.1 * k:.1f}\n".replace(".", ",")
               for k in range(40))


def lab_file(tmp_path, name: str, preamble: str = ""):
    path = tmp_path / name
    path.write_text(preamble + "Halle [°C];Spindel [°C];dZ [µm]\n" + ROWS, encoding="utf-8")
    return path


@pytest.mark.parametrize("name, named", [
    ("spindle_60s.csv", ("60s", 60.0)),
    ("rig-10Hz.csv", ("10Hz", 0.1)),
    ("log 1,5min.csv", ("1,5min", 90.0)),
    ("vgm_500ms.parquet", ("500ms", 0.5)),
    ("lathe_48h.csv", None),            # hours: a test's length far more often
    ("run_2s_3s.csv", None),            # two periods: no hint
    ("run60s.csv", None),               # not a token of its own
])
def test_a_period_token_of_the_stem(name, named):
    assert named_period(Path(name)) == named


def test_the_refusal_asks_about_the_name_and_nothing_is_adopted(tmp_path, capsys):
    src = lab_file(tmp_path, "spindle_60s.csv")
    with pytest.raises(ContractError, match=r"set data.sample_period_s \(the seconds between rows\); "
                                            r"the file name says '60s': if that is the time "
                                            r"between rows, data.sample_period_s=60$"):
        read_dataset(src, {"delimiter": ";", "decimal": ",", "roles": {"error": ["dZ"]}})
    out = tmp_path / "init"
    assert main(["init", str(src), f"out={out}", "track=false"]) == 2
    assert "the file name says '60s'" in capsys.readouterr().err
    assert not out.exists()


def test_a_preamble_line_outranks_the_name(tmp_path):
    src = lab_file(tmp_path, "spindle_60s.csv", "Abtastrate 15 s\n")
    with pytest.raises(ContractError, match=r"line 1 says 'Abtastrate 15 s': "
                                            r"data.sample_period_s=15$"):
        read_dataset(src, {"delimiter": ";", "decimal": ",", "roles": {"error": ["dZ"]}})
