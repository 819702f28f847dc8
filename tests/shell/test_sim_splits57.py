"""`simulate`'s year-round spindle with ``test_every`` outside ``[2, n_campaigns]``: one of its
splits was empty, written with exit 0 (``n_campaigns=2``: no test campaign, which ``run`` then
refused pointing at the manifest's ``split`` column; ``test_every=1``: no train campaign).
Fails on the code before simstr57's rule."""

from __future__ import annotations

import pytest

from conftest import refused


@pytest.mark.parametrize("overrides", [["sim.generator.n_campaigns=2"],
                                       ["sim.generator.n_campaigns=4", "sim.generator.test_every=5"],
                                       ["sim.generator.n_campaigns=3", "sim.generator.test_every=1"]])
def test_a_year_round_calendar_without_a_train_or_a_test_campaign_is_refused(overrides, tmp_path,
                                                                              capsys):
    path = tmp_path / "data"
    refused(["simulate", *overrides, "sim.generator.duration_h=[1,2]", f"data.path={path}",
             "track=false"], capsys, "sim.generator.test_every=", "[2, sim.generator.n_campaigns=")
    assert not path.exists()


def test_the_smallest_calendar_with_both_splits_is_written(tmp_path):
    from thermocomp.shell.cli import main

    path = tmp_path / "data"
    assert main(["simulate", "sim.generator.n_campaigns=2", "sim.generator.test_every=2",
                 "sim.generator.duration_h=[1,2]", f"data.path={path}", "track=false"]) == 0
    splits = (path / "campaigns.csv").read_text().splitlines()[1:]
    assert [line.split(",")[2] for line in splits] == ["train", "test"]
