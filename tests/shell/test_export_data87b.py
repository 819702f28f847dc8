"""The compiled stream of a model trained with ``data.encoding=auto`` (data87b): exported as
cp1252 (``TC_ENCODING`` 1), ``stream.c`` reads a Windows Excel's cp1252 file and a logger's
UTF-8 one, each line as the reader decodes its file, and refuses a header byte neither reads.

Run (2026-12-04, fix/data87b from main b9c94b3b, gcc -std=c99 -Wall -Wextra -Werror)::

    PYTHONPATH=src python -m pytest -p no:xdist -q tests/shell/test_export_data87b.py

passed on main as it is (no defect; 3.7 s user + 0.4 s sys): each test run's rows (run3 UTF-8,
run4 cp1252 with ``6.000``) through ``stream`` within 1e-9 µm of the check pack's served
corrections, the header byte 0x81 refused (exit 2, ``line 1``).  Can fail: with ``auto``
exported as ``utf-8`` (``TC_ENCODING`` 0) the cp1252 run is refused, "lacks input column T_Luft
(the lab's header 'T Luft [\xc2\xb0C]')".  Not covered: a cp1252 line that happens to be valid
UTF-8 (``Ã°``), which ``stream.c`` reads as UTF-8 line by line where the reader decodes the
whole file as cp1252.
"""

from __future__ import annotations

import io
import subprocess
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from conftest import FAST
from test_audit86 import german_export
from test_export import checked_pack, needs_cc, own_expected
from thermocomp.core.io import ContractError
from thermocomp.core.io.stdin import stdin_text
from thermocomp.shell.cli import main


def _folder(root):
    """Four runs of test_audit86's German export (seeds 9172-9175), ``°C`` / ``µm`` headers: a
    logger's PC wrote runs 1-3 as UTF-8, a German Excel saved run 4 again as cp1252 (its speeds
    grouped by a point, ``6.000``); runs 3 and 4 are the test half."""
    root.mkdir()
    for run in (1, 2, 3, 4):
        speeds = ["6.000", "12.000", "1.500"] if run == 4 else ["6000", "12000", "1500"]
        path = german_export(root / f"run{run}.csv", 9171 + run, speeds)
    path.write_bytes(path.read_text(encoding="utf-8").encode("cp1252"))
    return root


@needs_cc
def test_the_c_of_an_auto_encoded_model_reads_cp1252_and_utf8_files_as_served(tmp_path, capsys):
    runs = _folder(tmp_path / "runs")
    common = [f"data.path={runs}", "data.encoding=auto", "data.thousands=.",
              "data.roles.error=[d*]", "data.test_fraction=0.5"]
    assert main(["run", *common, *FAST, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    code = tmp_path / "code"
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={code}"]) == 0, \
        capsys.readouterr().err
    checked_pack(code)                      # built with -Werror, its own pack passed
    served = {p.parent.name: pd.read_csv(p).to_numpy(float) for p in own_expected(code)}
    assert sorted(served) == ["run3", "run4"], sorted(served)
    raw = {name: (runs / f"{name}.csv").read_bytes() for name in served}
    assert b"\xb0C" in raw["run4"] and "°C".encode() in raw["run3"]
    for name, want in served.items():
        done = subprocess.run([str(code / "stream")], input=raw[name], capture_output=True)
        assert done.returncode == 0, (name, done.stderr)
        got = pd.read_csv(io.BytesIO(done.stdout)).to_numpy(float)
        assert got.shape == want.shape, (name, got.shape, want.shape)
        assert np.abs(got - want).max() <= 1e-9, name
    # a header byte that is neither UTF-8 nor cp1252 (0x81) is refused by the code as by the
    # reader, naming its line (data-format.md, data.encoding)
    bad = raw["run4"].replace(b"\xb0C", b"\x81C", 1)
    done = subprocess.run([str(code / "stream")], input=bad, capture_output=True)
    assert done.returncode == 2 and not done.stdout.strip(), done.stdout
    assert "stream: line 1: a byte cp1252 does not read" in done.stderr.decode(), done.stderr
    with pytest.raises(ContractError, match="byte 0x81 is not UTF-8 or cp1252 text"):
        stdin_text(SimpleNamespace(buffer=io.BytesIO(bad)), "auto")
