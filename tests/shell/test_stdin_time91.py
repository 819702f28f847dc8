"""A stream on stdin (``monitor.input=-``) finds its time column as the file reader does
(lead91): a lab's ``t`` (or ``Zeit``) with no ``data.roles`` set.  Before, stdin read only
``data.columns`` unless a role or a unit was given, and refused the record's own test file,
"no 'time' column ... set data.sample_period_s" (data91's "left")."""

from __future__ import annotations

import io
import json
import sys

import numpy as np
import pandas as pd
import pytest

from thermocomp.shell.cli import main


@pytest.fixture(scope="module")
def fitted(tmp_path_factory):
    root = tmp_path_factory.mktemp("stdin91")
    (root / "runs").mkdir()
    rng = np.random.default_rng(91)
    for k in range(4):
        rise = np.cumsum(rng.normal(0.02, 0.05, (150, 4)), axis=0)
        pd.DataFrame({"t": np.arange(150) * 60.0, "T_a": 20 + rise[:, 0], "T_b": 20 + rise[:, 1],
                      "T_c": 20 + 0.5 * rise[:, 0] + rise[:, 2], "T_d": 20 + rise[:, 3],
                      "E_X": 3 * rise[:, 0] - rise[:, 1]}).to_csv(root / "runs" / f"r{k}.csv", index=False)
    data = [f"data.path={root / 'runs'}", "data.test_fraction=0.25"]
    light = ["plots=none", "track=false"]
    assert main(["run", *data, "model=mlr", *light, f"out={root / 'run'}"]) == 0
    return root, [*data, f"monitor.model={root / 'run' / 'model.pkl'}", *light]


def _monitored(root, args, name: str, *more: str) -> dict:
    assert main(["monitor", *args, *more, f"out={root / name}"]) == 0
    return json.loads((root / name / "monitor.json").read_text())["targets"]["E_X"]


def test_a_stream_of_the_test_file_finds_its_t_column(fitted, monkeypatch):
    root, args = fitted
    monkeypatch.setattr(sys, "stdin", io.StringIO((root / "runs" / "r3.csv").read_text()))
    piped = _monitored(root, args, "piped", "monitor.input=-")
    read = _monitored(root, args, "read")
    assert piped["rmse_fixed"] == pytest.approx(read["rmse_fixed"], rel=1e-9)
