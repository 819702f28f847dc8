"""effects99 (issue 34): ``metrics.json`` (``targets.<t>.auto.diagnosed``) and the printed
candidates table say which effects ``model.diagnosed``'s search accepted for a target -- named
with the lab's headers, each with its acceptance p, the penalty, the design's smallest p -- or
that it accepted none (benchmarks/bench_effects99.py)."""

from __future__ import annotations

from types import SimpleNamespace

from test_auto_diagnosed99b import _cfg
from test_diagnose_few import few
from thermocomp.apps.diagnose.features import Effect
from thermocomp.core.continuation import fit_joined
from thermocomp.core.models.auto import add_choices
from thermocomp.core.scoring.results import auto_table
from thermocomp.shell.builders import accepted_entry, build_compensator


def test_the_accepted_effect_is_in_the_auto_entry_and_the_table():
    ds, truth = few("axis_position", 0)          # test_diagnose_few: diagnose accepts S_pos_Y
    comp = build_compensator(_cfg("model.diagnosed=true", "diagnose.max_effects=2"), ds=ds)
    fitted = fit_joined(comp, ds, ds.ids("train"))
    targets = add_choices(fitted, {"E_Y": {}})
    entry = targets["E_Y"]["auto"]["diagnosed"]
    first = entry["accepted"][0]
    assert first["effect"].startswith(f"interaction:{truth['undeclared_effects'][0]['column']} ")
    assert first["p"] <= 0.01 and first["p_value"] <= first["p"]
    assert 0 < entry["min_p"] <= first["p"]
    line = [s for s in auto_table({"targets": targets}) if "E_Y diagnosed:" in s]
    assert line and first["effect"] in line[0] and "smallest p" in line[0]


def test_lab_names_and_nothing_accepted_are_said():
    ev = SimpleNamespace(effect=Effect("interaction", "product", column="T_a", other="T_b"),
                         p_family=0.002, p_value=0.001)
    entry = accepted_entry(SimpleNamespace(accepted=[ev], alpha=0.5), 0.0005, {"T_a": ["Temp A"]})
    assert entry["accepted"] == [{"effect": Effect("interaction", "product", column="Temp A",
                                                   other="T_b").title, "p": 0.002, "p_value": 0.001}]
    assert entry["alpha"] == 0.5
    none = accepted_entry(SimpleNamespace(accepted=[], alpha=None), 0.0039, {})
    assert none == {"accepted": [], "alpha": None, "min_p": 0.0039}
    table = auto_table({"targets": {"E_Y": {"auto": {"candidates": {"mlr": 1.0}, "chosen": "mlr",
                                                      "weights": {"mlr": 1.0}, "diagnosed": none}}}})
    assert "  E_Y diagnosed: nothing accepted on the train split (the design's smallest p 0.0039)" in table
