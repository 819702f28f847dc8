"""An infinite reading (lab75: a Campbell Scientific logger's ``INF`` for an overflow or an open
input) where a deployed model reads cells: the served model and the exported ``stream.c`` read
it as the file reader does, a missing value (the served model: before, ``inf`` reached the
compensator as a reading; the model of ``tests/data/lab75/halle_toa5.dat`` could not be built,
``run`` refused its ``INF``)."""

from __future__ import annotations

import copy
import io
import subprocess

import numpy as np
import pandas as pd
import pytest

from test_export import _compose, needs_cc, own_expected
from test_lab75 import HALLE
from test_nines_deploy74 import built_stream
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.stdin import read_stream
from thermocomp.shell.cli import main

COMMON = [f"data.path={HALLE}", "data.roles.error=[d*]", "data.roles.ignore=[SW_in_Avg,WS_ms]",
          "data.max_gap_samples=2", "data.test_fraction=0.25"]


def test_the_served_model_reads_an_infinity_as_a_missing_value():
    """A block with ``inf`` / ``-inf`` in an input is served as the same block with NaN there
    (the adaptive model's event for a missing sensor)."""
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = _compose(*COMMON, "track=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, train, None, "serve.model")[0]
    block = read_stream(HALLE.read_text(), ["T_spindle_Avg"], ReadOptions.from_cfg(
        {"roles": {"error": ["d*"], "ignore": ["SW_in_Avg", "WS_ms"]}}))[0].iloc[12:]
    block = block.reset_index(drop=True).ffill()          # (every input read: no gap of its own)
    infinite, missing = block.copy(), block.copy()
    infinite.loc[3, "T_spindle_Avg"], missing.loc[3, "T_spindle_Avg"] = np.inf, np.nan
    infinite.loc[5, "T_air_Avg"], missing.loc[5, "T_air_Avg"] = -np.inf, np.nan
    served, want = (CompensatorModel(copy.deepcopy(deployed)).predict(None, b, {"reset": True})
                    for b in (infinite, missing))
    assert served.equals(want)
    assert "T_spindle_Avg" in served["events"].iloc[3]
    assert np.isfinite(served.filter(like="C_").to_numpy()).all()


@pytest.fixture(scope="module")
def halle_code(tmp_path_factory):
    """The folder ``code/`` of the model of the TOA5 file, exported as C (its pack) and built."""
    root = tmp_path_factory.mktemp("halle")
    built_stream(root, COMMON)
    return root / "code"


@needs_cc
def test_the_exported_stream_reads_an_infinity_as_an_empty_cell(halle_code):
    """``stream.c`` fed the raw TOA5 file: an ``INF`` cell (line 9) is what an empty cell there
    is (since cmon84 the code's monitor takes the sensor out as a dropout and goes on, since
    dep101 a second one too; since dep105b the third, which leaves none in, too: the last field
    read as served, to the end of the file, the served corrections on every row)."""
    lines = HALLE.read_text().splitlines()

    def fed(cell: str) -> subprocess.CompletedProcess:
        cells = lines[8].split(",")
        cells[2] = cell
        text = "\n".join([*lines[:8], ",".join(cells), *lines[9:]]) + "\n"
        return subprocess.run([str(halle_code / "stream")], input=text.encode(),
                              capture_output=True)

    empty = fed("")
    assert empty.returncode == 0, empty.stderr
    assert b"line 9: monitor: T_spindle_Avg: dropout: no finite value, excluded" in empty.stderr
    for cell in ('"INF"', '"-INF"', "inf", "Infinity"):
        got = fed(cell)
        assert (got.returncode, got.stdout, got.stderr) == (0, empty.stdout, empty.stderr), cell
    # (dep101) a second sensor missing beside the first is held too, as served; (dep105b) the
    # third, none left in, too (before: 'line 15: input T_air_Avg has no finite value', exit 2)
    assert b"line 12: monitor: T_column_Avg: dropout: no finite value, excluded" in empty.stderr
    assert b"line 15: monitor: T_air_Avg: dropout: no finite value, excluded" in empty.stderr
    got = pd.read_csv(io.BytesIO(empty.stdout))
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = _compose(*COMMON, "track=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, train, None, "serve.model")[0]
    lines[8] = lines[8].replace('"INF"', "", 1)
    frame = read_stream("\n".join(lines) + "\n", ["T_spindle_Avg"], ReadOptions.from_cfg(
        {"roles": {"error": ["d*"], "ignore": ["SW_in_Avg", "WS_ms"]}}))[0]
    served = CompensatorModel(deployed).predict(None, frame, {"reset": True})
    assert len(got) == len(served) == 24 and "T_air_Avg" in served["events"].iloc[10]
    np.testing.assert_allclose(got.to_numpy(float), served[list(got.columns)].to_numpy(float),
                               rtol=0, atol=1e-9)


@needs_cc
def test_thermocomp_rows_writes_the_toa5_file_as_the_stream_reads_it(halle_code, capsys):
    """(lab78) ``thermocomp rows`` with the model's data config: the file's rows under the
    model's names, its infinities read (and the train part's filled) as the reader does, the
    test part after the train part it continues in one block (the state carried over); streamed
    through the compiled code, the pack's corrections (before: no such command, and the raw
    file's infinities stopped the stream at line 9)."""
    assert main(["rows", str(HALLE), *COMMON[1:]]) == 0
    rows = capsys.readouterr().out
    assert rows.splitlines()[0].startswith("time,T_spindle_Avg,T_column_Avg,T_air_Avg,")
    assert "\n\n" not in rows and "E_" not in rows.splitlines()[0]
    streamed = subprocess.run([str(halle_code / "stream")], capture_output=True,
                              input=rows.encode(), check=True).stdout
    got = pd.read_csv(io.BytesIO(streamed))
    want = pd.read_csv(own_expected(halle_code)[0])
    assert list(got.columns) == list(want.columns) and len(got) == len(want) == 24
    np.testing.assert_allclose(got.to_numpy(float), want.to_numpy(float), rtol=0, atol=1e-9)
    # the same rows as one served block, from a reset: the same corrections
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = _compose(f"data.path={HALLE}", *COMMON[1:], "track=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, train, None, "serve.model")[0]
    served = CompensatorModel(deployed).predict(None, pd.read_csv(io.StringIO(rows)),
                                                {"reset": True})
    np.testing.assert_allclose(served[list(want.columns)].to_numpy(float), want.to_numpy(float),
                               rtol=0, atol=1e-9)
