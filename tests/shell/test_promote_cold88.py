"""``promote`` reports a cold start beside the figures "as deployed" (extension, deploy88).

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
