"""AmeriFlux's ``-9999`` as ``data.missing_values`` lists it, where a deployed model reads cells
(lab74): the served model and the exported ``stream.c`` read a cell of that number, however
written, as the reader does, a missing value (before, the mark was refused, so no model read it;
a -9999 cell a temperature of -9999 °C to them)."""

from __future__ import annotations

import copy
import subprocess

import numpy as np
import pandas as pd

from cbuild import compiled
from conftest import FAST
from test_export import _compose, needs_cc
from test_nines74 import FLUX, ROLES, nines
from thermocomp.shell.cli import main

COMMON = [f"data.roles.{k}=[{','.join(v)}]" for k, v in ROLES.items()] + [
    "data.missing_values=[-9999]", "data.max_gap_samples=2", "data.test_fraction=0.25"]


def test_the_served_model_reads_the_mark_as_a_missing_value(tmp_path):
    """A block with ``-9999.0`` in an input is served as the same block with NaN there (the
    adaptive model's event for a missing sensor), not as a reading."""
    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.source import read_streamed

    cfg = _compose(f"data.path={nines(tmp_path / 'flux.dat')}", *COMMON, "track=false")
    ds, train, _, _ = read_streamed(cfg, test=False)
    deployed = deployable_model(cfg, ds, train, None, "serve.model")[0]
    block = pd.read_csv(FLUX)
    marked, missing = block.copy(), block.copy()
    marked.loc[3, "T_1_5_1"], missing.loc[3, "T_1_5_1"] = -9999.0, np.nan
    served, want, read = (CompensatorModel(copy.deepcopy(deployed)).predict(None, b, {"reset": True})
                          for b in (marked, missing, block))
    pd.testing.assert_frame_equal(served, want)
    assert "T_1_5_1" in served["events"].iloc[3]
    assert served["C_T_1_9_1"].iloc[3] != read["C_T_1_9_1"].iloc[3]


def built_stream(tmp_path, common: list[str]) -> None:
    """``tmp_path / 'code' / 'stream'``: the model ``run`` fits with the overrides ``common``,
    exported as C and compiled."""
    assert main(["run", *common, *FAST, "plots=none", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *common, "track=false", "export.format=c",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    compiled(tmp_path / "code")


@needs_cc
def test_the_exported_stream_reads_the_mark_as_an_empty_cell(tmp_path):
    """``stream.c`` fed ``-9999.000`` in an input says and does what it does for an empty cell
    there: (cdrop77) a monitored sensor's missing reading, which the code's sensor monitor
    excludes and rebuilds from the others, said on stderr, every row's corrections printed
    (before cdrop77: refused, exit 2, as the plain stream refuses a missing input)."""
    built_stream(tmp_path, [f"data.path={nines(tmp_path / 'flux.dat')}", *COMMON])
    lines = FLUX.read_text().splitlines()
    column = lines[0].split(",").index('"T_1_5_1"')

    def fed(cell: str) -> subprocess.CompletedProcess:
        cells = lines[4].split(",")
        cells[column] = cell
        text = "\n".join([*lines[:4], ",".join(cells), *lines[5:]]) + "\n"
        return subprocess.run([str(tmp_path / "code" / "stream")], input=text.encode(),
                              capture_output=True)

    marked, empty = fed("-9999.000"), fed("")
    assert marked.returncode == empty.returncode == 0
    assert marked.stderr == empty.stderr
    assert b"line 5: monitor: T_1_5_1: dropout: no finite value, excluded" in marked.stderr
    assert marked.stdout == empty.stdout
    assert len(marked.stdout.splitlines()) == len(lines)     # (the header, then every row)
