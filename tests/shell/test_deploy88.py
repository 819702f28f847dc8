"""Deployed as scored, warm and cold (deploy88): ``promote`` reports a cold start beside the
figures "as deployed" (extension); replay's ``rmse_batch`` covers a gapped test campaign as
``run`` scores it; the onnx refusal names every family that exports.

A test campaign that continues the record is scored, replayed and deployed warmed on the
campaigns before it; a controller powered on at its first row (after a power-off, or the
compiled ``stream`` fed the test file, as docs/to-the-machine.md shows) starts cold.  deploy87
gave ``replay`` that figure (``replay.cold_start=true``); ``promote.json``, what a user reads when
a model is registered, had only the warm one.  Here test_deployed_as_scored's cut spindle record
(B continues A), a lag bank: the cold figure is replay's ``rmse_cold_start`` and the warm one is
unchanged.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_deployed_as_scored import _stage, promoted, record  # noqa: F401  (the fixtures)


def test_promote_reports_the_cold_start_beside_the_continued_figures(promoted, record, tmp_path):  # noqa: F811
    _, report, _ = promoted
    cand = report["candidate"]
    replayed = _stage("replay", record, tmp_path / "replay", "model=lagbank", "replay.cold_start=true")
    warm = np.mean([r["rmse"] for r in replayed["targets"].values()])
    cold = np.mean([r["rmse_cold_start"] for r in replayed["targets"].values()])
    assert cand["cold_start_campaigns"] == ["B"] == replayed["cold_start_campaigns"]
    assert cand["test_reported"]["rmse"] == pytest.approx(warm, rel=1e-9)       # unchanged
    assert cand["test_reported_cold_start"]["rmse"] == pytest.approx(cold, rel=1e-9)
    assert abs(cold - warm) > 1e-3 * warm                                       # the lags' restart
    # the other test figures of the cold stream too, none of the validation ones
    assert set(cand["test_reported_cold_start"]) == set(cand["test_reported"])


def test_promote_prints_what_the_cold_start_costs(promoted):  # noqa: F811
    from thermocomp.apps.deploy.promotion import Candidate
    from thermocomp.shell.stages.promote import deployed_lines

    _, report, _ = promoted
    figures = report["candidate"]
    cand = Candidate("r", {}, "d", 0.0, "simulation", "simulation", {}, {},
                     test_figures=figures["test_reported"],
                     test_figures_cold=figures["test_reported_cold_start"],
                     cold_start_campaigns=figures["cold_start_campaigns"])
    line = deployed_lines(cand, "off")[0]
    assert line == (f"cold start (each test campaign from a reset at its first row; B): RMSE mean "
                    f"{figures['test_reported_cold_start']['rmse']:.3f} against "
                    f"{figures['test_reported']['rmse']:.3f} continued")
    # nothing continues: the two figures are one stream's, no line
    cand.cold_start_campaigns = []
    assert not any(x.startswith("cold start") for x in deployed_lines(cand, "off"))


def test_replays_batch_figure_covers_a_gapped_campaign_as_run_scores_it(record, tmp_path):  # noqa: F811
    """``rmse_batch`` stopped at a test campaign's first missing value (audit86b: one NaN row
    mid-campaign, 1.14 µm against run's 2.19 over half the rows); with a gap ``run`` reads
    (``data.max_gap_samples``) it is ``run``'s test RMSE, the gap filled as run fills it."""
    import json
    import shutil

    import pandas as pd

    from test_deployed_as_scored import COLUMNS, FAST
    from thermocomp.shell.cli import main

    gapped = tmp_path / "gapped"
    shutil.copytree(record, gapped)
    b = pd.read_csv(gapped / "B.csv")
    b.loc[100, "T3"] = np.nan            # one missing reading a third into the test file
    b.to_csv(gapped / "B.csv", index=False)
    common = [f"data.path={gapped}", "data.reference=none", "data.max_gap_samples=1", COLUMNS, *FAST]
    assert main(["run", f"out={tmp_path / 'run'}", "model=lagbank", *common]) == 0
    run = json.loads((tmp_path / "run" / "metrics.json").read_text())["targets"]
    assert main(["replay", f"out={tmp_path / 'replay'}", f"replay.model={tmp_path / 'run' / 'model.pkl'}",
                 *common]) == 0
    replayed = json.loads((tmp_path / "replay" / "replay.json").read_text())
    assert replayed["missing"] == {"B": {"T_3": 1}}      # streamed as recorded
    for t, r in replayed["targets"].items():
        assert r["rmse_batch"] == pytest.approx(run[t]["test"]["rmse"], rel=1e-9)
        assert r["max_abs_stream_minus_batch"] < 1e-6    # the rows before the gap, as before


def test_the_onnx_refusal_names_every_family_that_exports():
    """bench_deploy88's every family x wrapper: onnx is refused (exit 2) for each, and the
    message sent a user of arx_rf or lstm away ("the linear families ... export to json, c and
    st"), where both export to all three (their arrays)."""
    from thermocomp.apps.deploy.export import NotExportable, check_exportable

    with pytest.raises(NotExportable, match="no ONNX export is implemented yet") as info:
        check_exportable(None, "onnx")
    for family in ("mlr", "pcr", "arx", "lagbank", "hammerstein", "ATI", "model=auto", "arx_rf", "lstm"):
        assert family in str(info.value)


def test_replay_says_what_the_monitor_did_on_a_lead_in(record, tmp_path, capsys):  # noqa: F811
    """bench_deploy88's dl9213 (a logger's day files, R1b continuing D1..D4): a lag bank's
    deployed RMSE 0.5526 against run's 0.5514 with no event, clamp or guarded row: the sensor
    monitor had acted on a spike in D1 while the stream was warmed (24 events, unreported), and
    the state it left decays into R1b.  Here the cut spindle record with a third part: C
    continues the test part B, which holds a one-sample -4 °C spike on T3."""
    import json

    from test_deployed_as_scored import COLUMNS, FAST
    from thermocomp.shell.cli import main

    chain = spiked_chain(record, tmp_path / "chain")
    common = [f"data.path={chain}", "data.reference=none", COLUMNS, *FAST]
    assert main(["run", f"out={tmp_path / 'run'}", "model=lagbank", *common]) == 0
    capsys.readouterr()
    assert main(["replay", f"out={tmp_path / 'replay'}", f"replay.model={tmp_path / 'run' / 'model.pkl'}",
                 *common]) == 0
    said = capsys.readouterr().out
    replayed = json.loads((tmp_path / "replay" / "replay.json").read_text())
    in_b = [e for e in replayed["events"] if e["campaign"] == "B" and e.get("sensor") == "T_3"]
    assert in_b and in_b[0]["to"] == "excluded"              # B's own stream: reported as before
    warm = replayed["lead_in_events"]
    assert {e["campaign"] for e in warm} == {"C"}            # C's stream, warmed through B
    first = next(e for e in warm if e.get("sensor") == "T_3")
    assert first["to"] == "excluded" and first["time"] < 0   # before C's first row
    assert first["reason"] == in_b[0]["reason"]              # the same spike, the same judgement
    line = next(x for x in said.splitlines() if x.startswith("warm-up: "))
    assert f"warm-up: {len(warm)} events" in line and "before C" in line


def spiked_chain(cut, chain):
    """``cut`` (the cut record: A train, B test continuing A) with a third part: C continues B, cut from B's
    row 150 on; B holds a one-sample -4 °C spike on T3 (row 51)."""
    import shutil

    import pandas as pd

    shutil.copytree(cut, chain)
    b = pd.read_csv(chain / "B.csv")
    b.iloc[150:].to_csv(chain / "C.csv", index=False)
    b = b.iloc[:150].copy()
    b.loc[50, "T3"] -= 4.0
    b.to_csv(chain / "B.csv", index=False)
    pd.DataFrame({"campaign": ["A", "B", "C"], "file": ["A.csv", "B.csv", "C.csv"],
                  "split": ["train", "test", "test"], "continues": ["", "A", "B"]}
                 ).to_csv(chain / "campaigns.csv", index=False)
    return chain
