"""Issue 35 item 4: the decisions that left the stages, tested as pure functions on hand-made
values (no registry, no dataset, no config)."""

from __future__ import annotations

import pytest

from thermocomp.base.errors import ConfigError
from thermocomp.core.scoring.champion import (
    champion_validation,
    check_criterion,
    check_stream_deviation,
    decide,
    outcome_line,
    same_figures,
    tag_value,
)

CHAMPION = {"dataset_hash": "d1", "criterion_target": "mean", "validation_mode": "simulation",
            "metric.val_rmse": "2.5"}


def test_a_champion_scored_the_same_way_gives_its_score():
    assert champion_validation(CHAMPION, "val_rmse", "mean", "d1", "simulation") == (2.5, None)


@pytest.mark.parametrize("key, value, said", [
    ("dataset_hash", "d2", "another dataset"),
    ("criterion_target", "ch1", "another target than mean"),
    ("validation_mode", "one_step", "another mode than simulation"),
    ("metric.val_rmse", "null", "no validation score val_rmse"),
])
def test_a_champion_scored_otherwise_is_not_comparable(key, value, said):
    score, why = champion_validation({**CHAMPION, key: value}, "val_rmse", "mean", "d1",
                                     "simulation")
    assert score is None and said in why


def test_an_old_champion_is_compared_by_its_eval_mode():
    old = {k: v for k, v in CHAMPION.items() if k != "validation_mode"} | {"eval_mode": "simulation"}
    assert champion_validation(old, "val_rmse", "mean", "d1", "simulation")[0] == 2.5
    assert champion_validation(old, "val_rmse", "mean", "d1", "one_step")[0] is None


def _decide(version="2", score=2.0, champ=("1", 2.5, None), **kw):
    kw = {"criterion": "val_rmse", "min_improvement": 0.0} | kw
    return decide(version, score, *champ, **kw)


def test_no_champion_moves_the_alias():
    assert _decide(champ=(None, None, None)) == (True, "no champion yet")


def test_the_champion_itself_stays():
    moved, why = _decide(version="1", score=1.0)
    assert not moved and why == "already champion: version 1"


def test_a_lower_error_beats_the_champion_and_a_higher_does_not():
    moved, why = _decide(score=2.0)
    assert moved and "beats the champion's 2.5 (version 1)" in why
    moved, why = _decide(score=3.0)
    assert not moved and "does not beat" in why


def test_an_improvement_below_the_margin_does_not_move():
    assert not _decide(score=2.4, min_improvement=0.5)[0]
    assert _decide(score=1.9, min_improvement=0.5)[0]


def test_the_same_score_read_back_from_a_tag_ties():
    # the champion's score comes back from a tag (6 significant digits)
    score = 2.123456789
    assert not _decide(score=score, champ=("1", float(tag_value(score)), None))[0]


def test_an_incomparable_champion_is_replaced_only_when_forced():
    moved, why = _decide(champ=("1", None, "it has no validation score val_rmse"))
    assert not moved and "set promote.force=true" in why and "no validation score" in why
    moved, why = _decide(champ=("1", None, "x"), force=True)
    assert moved and why.endswith("; forced")


def test_only_a_validation_figure_may_choose():
    check_criterion("val_rmse")
    with pytest.raises(ConfigError, match="is a test figure"):
        check_criterion("rmse")
    with pytest.raises(ConfigError, match="is not a figure"):
        check_criterion("accuracy")


def test_the_stream_deviation_gate():
    check_stream_deviation(0.01, 0.05, "r1")
    with pytest.raises(ConfigError, match="run r1: streamed predictions differ"):
        check_stream_deviation(0.5, 0.05, "r1")


def test_same_figures_compares_at_tag_precision():
    tags = {"metric.val_rmse": tag_value(1.23456789), "metric.rmse": "null"}
    assert same_figures(tags, {"val_rmse": 1.234568, "rmse": None})
    assert not same_figures(tags, {"val_rmse": 1.3, "rmse": None})


def test_the_last_line_says_what_happened():
    assert outcome_line("m", "2", "champion", True, "no champion yet", None) \
        == "m v2: promoted to @champion (no champion yet)"
    assert outcome_line("m", "1", "champion", False, "already champion: version 1", "1") \
        == "m v1: already champion: version 1"
    assert outcome_line("m", "3", "champion", False, "x does not beat", "1") \
        == "m v3: not promoted (x does not beat)"


# --- design: the study from its settings (thermocomp.apps.volumetric.design_study) ---------------

def _design_settings(**changes):
    import yaml

    from conftest import ROOT
    d = yaml.safe_load((ROOT / "conf" / "design" / "default.yaml").read_text())
    return d | {"grid": [6, 4, 4], "n_machines": 2, "n_jobs": 1} | changes


def test_the_study_takes_unset_entries_from_the_defaults_and_the_machine_from_c():
    from thermocomp.apps.volumetric.design_study import DEFAULT_ARTEFACT, study_from_settings
    study = study_from_settings(_design_settings(), seed=3)
    assert (study.length_mm, study.probing_um, study.ball_um) == DEFAULT_ARTEFACT
    assert study.family.model.order == study.compensation.order + 2 and study.seed == 3
    study = study_from_settings(_design_settings(length_mm=900.0, compensation_order=1,
                                                 machine={"order": 1, "cross_terms": False}))
    assert study.length_mm == 900.0 and study.family.model.order == study.compensation.order == 1


def test_a_machine_simpler_than_the_compensation_model_is_refused():
    from thermocomp.apps.volumetric.design_study import study_from_settings
    with pytest.raises(ConfigError, match="design.machine.order=1 is below the compensation "
                                          "model's 2"):
        study_from_settings(_design_settings(compensation_order=2,
                                             machine={"order": 1, "cross_terms": True}))


def test_a_bar_longer_than_the_travel_is_unreachable():
    from thermocomp.apps.volumetric.design import strategies
    from thermocomp.apps.volumetric.design_study import study_from_settings, unreachable
    studies = {"balls": {"n_balls": [3], "misalignment_deg": [0.0], "position_sets": ["S2"]}}
    todo = strategies(studies)[0]
    assert unreachable(study_from_settings(_design_settings(length_mm=500.0)), todo) == {}
    missed = unreachable(study_from_settings(_design_settings(length_mm=50_000.0)), todo)
    assert [who for who in missed.values()] == [["3 balls at 0° (S2)"]]


# --- select: one selector fitted per target (thermocomp.core.select.per_target) -----------------

def test_each_target_gets_its_own_selection_and_scores():
    import numpy as np
    import pandas as pd
    from sklearn.base import BaseEstimator

    from thermocomp.core.select.pearson import PearsonSelector
    from thermocomp.core.select.per_target import CORRELATION_LABEL, select_per_target

    rng = np.random.default_rng(0)
    X = pd.DataFrame(rng.normal(size=(200, 3)), columns=["T_a", "T_b", "T_c"])
    Y = pd.DataFrame({"E_x": 2 * X["T_b"] + 0.01 * rng.normal(size=200),
                      "E_y": -X["T_c"] + 0.01 * rng.normal(size=200)})
    result, scores, labels = select_per_target(PearsonSelector(k=1), X, Y, "pearson")
    assert [result[t]["selected"] for t in Y] == [["T_b"], ["T_c"]]
    assert max(scores["E_x"], key=scores["E_x"].get) == "T_b"

    class FirstInput(BaseEstimator):     # a selector that shows no scores of its own
        def fit(self, X, y):
            self.selected_ = [X.columns[0]]
            return self

    result, scores, labels = select_per_target(FirstInput(), X, Y, "first")
    assert result["E_y"] == {"selected": ["T_a"]} and labels == dict.fromkeys(Y, CORRELATION_LABEL)
    assert max(scores["E_y"], key=scores["E_y"].get) == "T_c"     # shown by |r|


# --- monitor: what the stage prints (thermocomp.apps.monitor.report) -----------------------------

def test_the_monitor_summary_names_the_costliest_blind_offset_and_the_first_exclusion():
    from thermocomp.apps.monitor.report import summary_lines
    report = {
        "targets": {"E_x": {"rmse_fixed": 1.5, "rmse_adaptive": None, "max_abs_correction": 12.0,
                            "all_finite": True}},
        "sensors": {"T_a": {"undetected_offset_c": 0.5, "undetected_offset_um": {"E_x": 0.2}},
                    "T_b": {"undetected_offset_c": 0.8,
                            "undetected_offset_um": {"E_x": 3.0, "E_y": None}},
                    "T_c": {}},
        "events": [{"to": "warning", "sensor": "T_a", "campaign": "K1", "time": 60.0},
                   {"to": "excluded", "sensor": "T_b", "campaign": "K2", "time": 5400.0}],
    }
    lines = summary_lines(report)
    assert lines[1].split() == ["E_x", "1.500", "-", "12", "True"]
    assert "costs up to 3 µm (T_b 0.8 °C, E_x;" in lines[2]
    assert lines[3] == "events: 2, exclusions: 1, first: T_b (K2, 1.50 h)"


def test_the_monitor_summary_prices_a_sensor_no_other_predicts_per_degree_not_inside_a_band():
    """A lathe's spindle motor, predicted by no other sensor, has a 60.5 °C 'band' that never
    applies: the summary printed 'an offset inside the exclusion band costs up to 19.3 µm
    (T_nc_spindle_motor 60.4626 °C)'; the bound is now the worst observable sensor's, and the
    unobservable ones are listed apart with their cost per °C."""
    from thermocomp.apps.monitor.report import summary_lines
    report = {
        "targets": {"E_x": {"rmse_fixed": 1.5, "rmse_adaptive": 1.5, "max_abs_correction": 12.0,
                            "all_finite": True}},
        "sensors": {"T_guide": {"observable": True, "undetected_offset_c": 0.94,
                                "undetected_offset_um": {"E_x": 10.4}},
                    "T_motor": {"observable": False, "undetected_offset_c": 60.5,
                                "undetected_offset_um": {"E_x": 19.3}}},
        "events": [],
    }
    lines = summary_lines(report)
    assert "costs up to 10.4 µm (T_guide 0.94 °C, E_x;" in lines[2]
    assert lines[3].startswith("no other sensor predicts T_motor: no band bounds a drift")
    assert lines[3].endswith("T_motor 0.319 µm/°C")
