"""The results object (issue 35 item 3): one definition of each score key and headline figure.

``metrics.json`` is read and shown through :mod:`thermocomp.core.scoring.results`: the same figure under
its MLflow, DVC and ``compare`` names is one number, the printed table is its ``summary()``,
the written document its ``to_json()``; the score keys are spelled in two modules only.
"""

from __future__ import annotations

import ast
import json
from pathlib import Path

import pytest

from test_hostile import make_dataset
from thermocomp.core.scoring.results import SCORE_KEYS, EvaluationResult
from thermocomp.shell.cli import main

SRC = Path(__file__).resolve().parents[2] / "src" / "thermocomp"
KEY_MODULES = {"core/metrics.py", "core/scoring/results.py"}     # where a score key may be spelled out
QUICK = ["track=false", "plots=none", "eval.mutual_prediction=false", "eval.ati_baselines=false",
         "eval.validation_folds=3"]


def _string_literals(path: Path) -> set[str]:
    """Every string constant of a module but its docstrings (f-string parts and
    expressions included: ``f"{m['rmse']}"`` holds the constant ``rmse``)."""
    docs, constants = set(), []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):    # one walk, not two
        if isinstance(node, ast.Constant) and isinstance(node.value, str):
            constants.append(node)
        elif isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) \
                and ast.get_docstring(node, clean=False) is not None:
            docs.add(id(node.body[0].value))
    return {n.value for n in constants if id(n) not in docs}


def test_score_keys_are_spelled_out_in_two_modules_only():
    spelled = {}
    for path in sorted(SRC.rglob("*.py")):
        found = _string_literals(path) & set(SCORE_KEYS)
        if found:
            spelled[str(path.relative_to(SRC))] = sorted(found)
    assert set(spelled) <= KEY_MODULES, (
        f"score key literals outside {sorted(KEY_MODULES)} (read them through "
        f"thermocomp.core.scoring.results, or name them with the constants of thermocomp.core.metrics): "
        f"{ {m: k for m, k in spelled.items() if m not in KEY_MODULES} }")
    assert set(spelled) == KEY_MODULES      # the scan sees the keys where they are defined


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """One small run scored in each mode, validation on: ``{mode: (out, stdout)}``."""
    root = tmp_path_factory.mktemp("results")
    data = make_dataset(root / "data", rows=60)
    out = {}
    for mode in ("simulation", "one_step"):
        folder = root / mode
        assert main(["run", f"data.path={data}", f"out={folder}", f"eval.mode={mode}", *QUICK]) == 0
        out[mode] = folder
    return out


def _walk_keys(doc, keys: set) -> set:
    if isinstance(doc, dict):
        keys |= set(doc)
        for v in doc.values():
            _walk_keys(v, keys)
    return keys


def test_every_score_key_is_a_key_a_run_writes_or_a_headline_name(runs):
    written = set()
    for out in runs.values():
        _walk_keys(json.loads((out / "metrics.json").read_text()), written)
        result = EvaluationResult(json.loads((out / "metrics.json").read_text()))
        for style in ("dvc", "compare", "baseline", "fleet"):
            for figures in result.headline(style).values():
                written |= set(figures)
    assert set(SCORE_KEYS) <= written, sorted(set(SCORE_KEYS) - written)


def test_to_json_is_the_written_metrics_json_and_summary_the_printed_table(runs, capsys):
    for out in runs.values():
        text = (out / "metrics.json").read_text()
        assert EvaluationResult(json.loads(text)).to_json() == text
    data = runs["simulation"].parent / "data"
    again = runs["simulation"].parent / "again"
    capsys.readouterr()
    assert main(["run", f"data.path={data}", f"out={again}", *QUICK]) == 0
    result = EvaluationResult(json.loads((again / "metrics.json").read_text()))
    printed = capsys.readouterr().out
    assert result.summary() in printed
    assert printed.count("\n") >= result.summary().count("\n") + 1
    headline = json.loads((again / "headline" / "E_X.json").read_text())
    assert headline == result.headline("dvc")["E_X"]


@pytest.mark.parametrize("mode", ["simulation", "one_step"])
def test_mlflow_dvc_and_compare_read_one_figure_each(runs, mode):
    doc = json.loads((runs[mode] / "metrics.json").read_text())
    result = EvaluationResult(doc)
    dvc, compare = result.headline("dvc")["E_X"], result.headline("compare")["E_X"]
    mlflow = result.headline("mlflow")
    entry = doc["targets"]["E_X"]
    test, val = entry["test"], entry["validation"]
    assert dvc["test_rmse"] == compare["rmse"] == mlflow["E_X.test.rmse"] == test["rmse"]
    assert dvc["test_rsd_mean"] == compare["rsd_mean"] == mlflow["E_X.test.rsd_mean"]
    assert dvc["rms_reduction_pct"] == compare["rms_reduction_pct"] == pytest.approx(
        100 * (1 - test["rms_after"] / test["rms_before"]))
    # the run's own mode for MLflow and DVC; compare and promote choose in the deployed one
    assert dvc["val_rmse"] == mlflow["E_X.val.rmse"] == val["rmse"]
    deployed = entry["validation_simulation"] if mode == "one_step" else val
    assert compare["val_rmse"] == deployed["rmse"]
    other = "one_step" if mode == "simulation" else "simulation"
    assert mlflow[f"E_X.test_{other}.rmse"] == entry[f"test_{other}"]["rmse"]
    assert mlflow["E_X.persistence.rmse"] == entry["persistence"]["rmse"]


def test_the_baseline_row_is_reduced_against_the_measured_error(runs):
    doc = json.loads((runs["simulation"] / "metrics.json").read_text())
    entry = doc["targets"]["E_X"]
    row = EvaluationResult(doc).headline("baseline")["E_X"]
    assert row["rmse"] == entry["persistence"]["rmse"]
    assert row["rms_reduction_pct"] == pytest.approx(
        100 * (1 - entry["persistence"]["rmse"] / entry["test"]["rms_before"]))
    assert row["e_p95_1h"] is None        # not computed for the baseline


def test_the_printed_header_names_ati_and_denoising_where_a_run_uses_them(runs):
    """A sweep's jobs over ``denoise`` (or ``ati``) printed the same header: the run records its
    denoising and the header names both where they are not ``none``."""
    doc = json.loads((runs["simulation"] / "metrics.json").read_text())
    assert doc["denoise"] == "none"
    head = EvaluationResult(doc).summary().splitlines()[0]
    assert "denoise=" not in head and "ati=" not in head
    doc.update(denoise="emd", ati={**doc.get("ati", {}), "name": "cmeans"})
    head = EvaluationResult(doc).summary().splitlines()[0]
    assert "select=all  ati=cmeans  denoise=emd  mode=simulation" in head
