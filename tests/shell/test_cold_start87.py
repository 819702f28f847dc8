"""``replay.cold_start=true`` (extension, deploy87): what a restart of the compensator at a test
campaign that continues the record costs, beside what is scored.

By default ``replay`` streams such a campaign after the campaigns it continues, as ``run`` scores
it; a controller powered on at the test file's first row starts cold.  On audit86b's lr9032 the
cold start moved a lag bank's RMSE 2.66 -> 2.10 µm and auto's 0.632 -> 2.22, and no report said
so.  Here test_deployed_as_scored's cut spindle record (B continues A), the plain stream.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pandas as pd
import pytest

from test_deployed_as_scored import _stage, record  # noqa: F401  (the fixture)


def _cut_chain(cut: Path, dest: Path) -> Path:
    """The record with B on a clock of its own and continuing nothing: a compensator started at
    its first row."""
    shutil.copytree(cut, dest)
    b = pd.read_csv(dest / "B.csv")
    b["secs"] -= b["secs"].iloc[0]
    b.to_csv(dest / "B.csv", index=False)
    manifest = pd.read_csv(dest / "campaigns.csv")
    manifest.drop(columns="continues").to_csv(dest / "campaigns.csv", index=False)
    return dest


def test_the_cold_start_figure_is_the_stream_started_at_the_test_file(record, tmp_path, capsys):  # noqa: F811
    run = _stage("run", record, tmp_path / "run", "model=lagbank")
    assert run["carry_over"] == {"B": ["A", "B"]}
    model = f"replay.model={tmp_path / 'run' / 'model.pkl'}"
    scored = _stage("replay", record, tmp_path / "scored", model)
    capsys.readouterr()
    both = _stage("replay", record, tmp_path / "both", model, "replay.cold_start=true")
    said = capsys.readouterr().out
    alone = _stage("replay", _cut_chain(record, tmp_path / "cut"), tmp_path / "alone", model)
    assert "cold_start_campaigns" not in scored and "rmse_cold_start" not in scored["targets"]["E_ch1"]
    assert both["cold_start_campaigns"] == ["B"]
    for t, r in both["targets"].items():
        assert r["rmse"] == scored["targets"][t]["rmse"]          # what is scored: unchanged
        assert r["rmse_cold_start"] == pytest.approx(alone["targets"][t]["rmse"], rel=1e-9)
        assert abs(r["rmse_cold_start"] - r["rmse"]) > 1e-3 * r["rmse"]   # the lags' restart
    line = next(x for x in said.splitlines() if x.startswith("cold start"))
    assert f"E_ch1 {both['targets']['E_ch1']['rmse_cold_start']:.3f} against" in line
    assert "; B)" in line
