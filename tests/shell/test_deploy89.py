"""Deployed as scored, cold and warm-up (deploy89): the export's conformance pack checks the code
from a cold start too (``<campaign>.cold``, extension of ``check.json``), and ``monitor`` says
what its sensor monitor did while a test campaign's stream was warmed on the campaigns it
continues (``lead_in_events`` and the ``warm-up:`` line, as ``replay`` and ``promote`` do).

A controller restarted mid-campaign starts from a reset, and so does the compiled ``stream`` fed
a test file alone (docs/to-the-machine.md); the pack held the test campaign warmed on the train
part only, so nothing checked the code from that state (bench_deploy88's "Craw" column stood
in).  The record is test_deployed_as_scored's cut spindle record (B continues A), a lag bank:
its long lags make the cold stream far from the warm one.
"""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pandas as pd
import pytest

from test_deploy88 import spiked_chain
from test_deployed_as_scored import COLUMNS, CONTRACT, FAST, LAB, record  # noqa: F401  (the fixture)
from test_export import built_stream, needs_cc
from thermocomp.shell.cli import main

RENAMED = dict(zip(LAB, CONTRACT))


@pytest.fixture(scope="module")
def exported(record, tmp_path_factory):  # noqa: F811
    """``(the export folder, replay.json with the cold start, the run's out)`` of a lag bank."""
    root = tmp_path_factory.mktemp("deploy89")
    common = [f"data.path={record}", "data.reference=none", COLUMNS, *FAST]
    assert main(["run", f"out={root / 'run'}", "model=lagbank", *common]) == 0
    model = root / "run" / "model.pkl"
    assert main(["replay", f"out={root / 'replay'}", f"replay.model={model}", "replay.cold_start=true",
                 *common]) == 0
    assert main(["export", f"out={root / 'code'}", f"export.model={model}", "export.format=c",
                 f"data.path={record}", "data.reference=none", COLUMNS]) == 0
    replayed = json.loads((root / "replay" / "replay.json").read_text())
    return root / "code", replayed


def test_the_pack_holds_a_continuing_campaign_from_a_cold_start_as_replay_scores_it(exported, record):  # noqa: F811
    code, replayed = exported
    pack = json.loads((code / "check" / "check.json").read_text())
    entries = {e["campaign"]: e for e in pack["campaigns"]}
    b = pd.read_csv(record / "B.csv").rename(columns=RENAMED)
    warm, cold = entries["B"], entries["B.cold"]
    assert warm["lead_in_rows"] > 0 and "cold_start" not in warm
    assert cold["lead_in_rows"] == 0 and cold["cold_start"] == "B"
    assert cold["rows"] == len(b) and cold["cut"] is None
    rows = pd.read_csv(code / cold["folder"] / "rows.csv")
    assert np.array_equal(rows["time"].to_numpy(float), b["time"].to_numpy(float))   # B alone
    got = pd.read_csv(code / cold["folder"] / "expected.csv")
    continued = pd.read_csv(code / warm["folder"] / "expected.csv").iloc[warm["lead_in_rows"]:]
    # the cold stream's corrections are replay's cold figure: residual = measured + C
    for t in replayed["targets"]:
        residual = b[t].to_numpy(float) + got[f"C_{t[2:]}"].to_numpy(float)
        assert np.sqrt(np.mean(residual ** 2)) == pytest.approx(
            replayed["targets"][t]["rmse_cold_start"], rel=1e-9)
        # and not the continued stream's: the lag bank restarted
        assert np.abs(got[f"C_{t[2:]}"].to_numpy() - continued[f"C_{t[2:]}"].to_numpy()).max() > 1e-3


@needs_cc
def test_the_compiled_code_passes_the_cold_campaign(exported):
    code, _ = exported
    built_stream(code)
    script = subprocess.run(["sh", "check/check.sh"], cwd=code, capture_output=True, text=True)
    assert script.returncode == 0, script.stderr
    assert "'check/B.cold/expected.csv'" in (code / "check" / "check.sh").read_text()


def test_monitor_says_what_its_monitor_did_on_a_lead_in_as_replay_does(record, tmp_path, capsys):  # noqa: F811
    """test_deploy88's chain (C continues the test part B, which holds a one-sample -4 °C spike on
    T3): ``monitor`` streams C warmed through B as ``replay`` does, and said nothing of the
    exclusion there that moves the state C starts from."""
    chain = spiked_chain(record, tmp_path / "chain")
    common = [f"data.path={chain}", "data.reference=none", COLUMNS, *FAST]
    assert main(["run", f"out={tmp_path / 'run'}", "model=lagbank", *common]) == 0
    model = f"{tmp_path / 'run' / 'model.pkl'}"
    capsys.readouterr()
    assert main(["replay", f"out={tmp_path / 'replay'}", f"replay.model={model}", *common]) == 0
    replay_said = capsys.readouterr().out
    assert main(["monitor", f"out={tmp_path / 'monitor'}", f"monitor.model={model}", "plots=none",
                 *common]) == 0
    said = capsys.readouterr().out
    replayed = json.loads((tmp_path / "replay" / "replay.json").read_text())
    monitored = json.loads((tmp_path / "monitor" / "monitor.json").read_text())
    warm = monitored["lead_in_events"]
    assert warm == replayed["lead_in_events"]                  # the same stream, the same events
    first = next(e for e in warm if e.get("sensor") == "T_3")
    assert first["campaign"] == "C" and first["to"] == "excluded" and first["time"] < 0
    line = next(x for x in said.splitlines() if x.startswith("warm-up: "))
    replay_line = next(x for x in replay_said.splitlines() if x.startswith("warm-up: "))
    # one wording; the figure that saw the lead-in unmonitored is monitor's fixed stream
    assert line == replay_line.replace("RMSE batch (run's)", "RMSE fixed")
