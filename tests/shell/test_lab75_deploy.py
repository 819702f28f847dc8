"""An infinite reading (lab75: a Campbell Scientific logger's ``INF`` for an overflow or an open
input) where a deployed model reads cells: the served model and the exported ``stream.c`` read
it as the file reader does, a missing value (the served model: before, ``inf`` reached the
compensator as a reading; the model of ``tests/data/lab75/halle_toa5.dat`` could not be built,
``run`` refused its ``INF``)."""

from __future__ import annotations

import copy
import subprocess

import numpy as np

from test_export import _compose, needs_cc
from test_lab75 import HALLE
from test_nines_deploy74 import built_stream
from thermocomp.core.io.options import ReadOptions
from thermocomp.core.io.stdin import read_stream

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


@needs_cc
def test_the_exported_stream_reads_an_infinity_as_an_empty_cell(tmp_path):
    """``stream.c`` fed the raw TOA5 file: its rows until the first ``INF`` (line 9), then what
    it says of an empty cell there (a missing input the plain stream refuses, exit 2)."""
    built_stream(tmp_path, COMMON)
    lines = HALLE.read_text().splitlines()

    def fed(cell: str) -> subprocess.CompletedProcess:
        cells = lines[8].split(",")
        cells[2] = cell
        text = "\n".join([*lines[:8], ",".join(cells), *lines[9:]]) + "\n"
        return subprocess.run([str(tmp_path / "code" / "stream")], input=text.encode(),
                              capture_output=True)

    empty = fed("")
    assert empty.returncode == 2 and b"line 9: input T_spindle_Avg has no finite value" in empty.stderr
    for cell in ('"INF"', '"-INF"', "inf", "Infinity"):
        got = fed(cell)
        assert (got.returncode, got.stdout, got.stderr) == (2, empty.stdout, empty.stderr), cell
    assert len(empty.stdout.splitlines()) == 5        # the header and rows 1-4
