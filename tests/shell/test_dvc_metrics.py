"""`dvc repro` of the default study in a scratch copy of the project, the venv not on PATH, and
what DVC shows of it: headline metrics (narrow), a handful of `exp show` columns, data-driven
plots, the sweep pipeline on the same project, and what a changed model parameter reruns.  One
full repro for the module: its tests run on one xdist worker (`make test` uses `--dist
loadfile`), in file order, the one that changes the study last.  The README's `dvc repro`,
`dvc repro` (nothing runs), `dvc metrics show` are run here, as written."""

import json
import re
import subprocess

import pandas as pd
import pytest

from conftest import SHORT_KEYS, copy_project, dvc, set_keys, thermocomp
from test_deploy import mlflow_store
from thermocomp.core.figures.plotdata import write_compare
from thermocomp.core.figures.plots import FigurePool, residual_plot

pytestmark = pytest.mark.slow
STAGES = ("simulate", "ingest", "denoise", "select", "train", "evaluate", "diagnose")
TRACKED = "ingest"      # the default (track=null) tracks it; the others are told track=false
TARGETS = ("E_X", "E_Y", "E_Z")
# The README's `dvc exp show` (a handful of columns: the test and validation RMSE per target)
EXP_SHOW = ["exp", "show", "--drop", ".*", "--keep",
            "Experiment|Created|.*headline/.*:(test_rmse|val_rmse)$"]


def _ran(log: str) -> set[str]:
    return {s for s in STAGES if f"Running stage '{s}'" in log}


def _tracked(uri: str) -> list[tuple[str, str]]:
    """(stage, status) of every run in the store."""
    from mlflow import MlflowClient

    client = MlflowClient(uri)
    runs = client.search_runs([e.experiment_id for e in client.search_experiments()])
    return [(r.data.tags.get("stage"), r.info.status) for r in runs]


@pytest.fixture(scope="session")
def repro(tmp_path_factory):
    dest, env = copy_project(tmp_path_factory.mktemp("dvcm") / "proj")
    # the default study shortened (SHORT): what DVC runs and shows does not depend on its size
    set_keys(dest / "conf/sim/yearround_spindle.yaml", **SHORT_KEYS)
    # One stage tracked by default shows the study tracks under `dvc repro`; tracking every stage
    # costs ~3 s of MLflow start-up per process and is not what the rest of the module checks,
    # nor are the figures of denoise, select and diagnose (~2 s of CPU each in their workers;
    # tested where they are drawn; evaluate's are the DVC plots asserted here).  With plots=none
    # denoise and select still make their (DVC plots) folders, empty.
    pipeline = dest / "dvc.yaml"
    untracked = "|".join(s for s in STAGES if s not in ("simulate", TRACKED))
    text, n = re.subn(rf"(cmd: pipelines/thermocomp (?:{untracked}))$", r"\1 track=false",
                      pipeline.read_text(), flags=re.M)
    text, m = re.subn(r"(cmd: pipelines/thermocomp (?:denoise|select|diagnose) .*)$", r"\1 plots=none",
                      text, flags=re.M)
    assert n == len(STAGES) - 2 and m == 3
    pipeline.write_text(text)
    # The default store as a copy of a migrated one: creating it (Alembic migrations, seconds of
    # CPU) is tested where it is the point (test_tracking, test_hostile_procs), not under DVC.
    store = mlflow_store(dest)
    first = dvc("repro", cwd=dest, env=env)
    assert _ran(first.stdout + first.stderr) == set(STAGES), first.stdout + first.stderr
    assert (dest / "reports/default/metrics.json").is_file()
    assert _tracked(store) == [(TRACKED, "FINISHED")]
    again = dvc("repro", cwd=dest, env=env)          # the README's second `dvc repro`
    assert _ran(again.stdout + again.stderr) == set() and "up to date" in again.stdout + again.stderr
    (dest / ".gitignore").write_text("/mlruns/\n/reports/\ndvc_plots/\n.venv\n")
    subprocess.run(["git", "add", "-A"], cwd=dest, env=env, check=True, capture_output=True)
    subprocess.run(["git", "commit", "-qm", "study"], cwd=dest, env=env, check=True)
    return dest, env


def test_metrics_show_is_narrow_and_loads_everything(repro):
    dest, env = repro
    proc = dvc("metrics", "show", cwd=dest, env=env)
    text = proc.stdout + proc.stderr
    assert "failed to load" not in text            # not even for pipelines/sweep before a sweep
    assert max(len(line) for line in proc.stdout.splitlines()) <= 200
    for t in TARGETS:
        assert f"reports/default/headline/{t}.json" in text
        assert f"reports/default/diagnosis_headline/{t}.json" in text


def test_headline_numbers_are_the_full_reports_numbers(repro):
    dest, env = repro
    shown = json.loads(dvc("metrics", "show", "--json", cwd=dest, env=env).stdout)[""]["data"]
    metrics = json.loads((dest / "reports/default/metrics.json").read_text())
    for t in TARGETS:
        head = shown[f"reports/default/headline/{t}.json"]["data"]
        full = metrics["targets"][t]
        assert head["test_rmse"] == pytest.approx(full["test"]["rmse"])
        assert head["test_rsd_sd"] == pytest.approx(full["test"]["rsd_sd"])
        assert head["val_rmse"] == pytest.approx(full["validation"]["rmse"])
        assert head["rms_reduction_pct"] == pytest.approx(
            100 * (1 - full["test"]["rms_after"] / full["test"]["rms_before"]))
        diag = json.loads((dest / f"reports/default/diagnosis/diagnosis_{t}.json").read_text())
        dh = shown[f"reports/default/diagnosis_headline/{t}.json"]["data"]
        assert dh == pytest.approx({"test_before": diag["before"]["test_rmse"],
                                    "test_after": diag["after"]["test_rmse"],
                                    "cv_before": diag["before"]["cv_rmse"],
                                    "cv_after": diag["after"]["cv_rmse"]})


def test_exp_show_has_a_handful_of_columns(repro):
    dest, env = repro
    table = pd.read_csv(pd.io.common.StringIO(dvc(*EXP_SHOW, "--csv", cwd=dest, env=env).stdout))
    metric_cols = [c for c in table.columns if "headline" in c]
    assert len(table.columns) <= 8 and len(metric_cols) == 2 * len(TARGETS)
    workspace = table.iloc[0]
    head = json.loads((dest / "reports/default/headline/E_Z.json").read_text())
    assert workspace["reports/default/headline/E_Z.json:test_rmse"] == pytest.approx(head["test_rmse"])


def _plots(dest, env) -> dict:
    return json.loads(dvc("plots", "show", "--json", cwd=dest, env=env).stdout)


def test_plots_show_draws_the_data_and_the_figures(repro):
    dest, env = repro
    shown = _plots(dest, env)
    data = shown["data"]
    for t in TARGETS:
        (e_p95,) = data[f"reports/default/plots/e_p95/{t}.csv"]
        spec = e_p95["content"]
        assert spec["encoding"]["x"]["field"] == "window_h"
        fields = {v["field"] for v in spec["data"]["values"]}
        assert fields == {"before", "after"}
        curve = pd.read_csv(dest / f"reports/default/plots/e_p95/{t}.csv")
        full = json.loads((dest / "reports/default/metrics.json").read_text())["targets"][t]["test"]
        assert curve["window_h"].to_numpy() * 3600 == pytest.approx(full["e_p95"]["window_s"], rel=1e-5)
        assert data[f"reports/default/plots/e_p95_{t}.png"][0]["type"] == "image"
    # the default study draws without errors; only the sweep's plot is missing before a sweep
    assert {e["name"] for e in shown.get("errors", [])} <= {"reports/sweep_compare/compare_plot.csv"}


def test_residual_and_sweep_plots(repro, monkeypatch):
    """plots=test writes one residual CSV per test campaign and target (x hours) and asks for
    its figure; a sweep's comparison (compare_plot.csv) is drawn with the runs ranked on x."""
    dest, env = repro
    # The figures are queued, not drawn: ~20 PNGs, 10 s of CPU, none of them read here (DVC
    # draws the CSVs; residual_plot is drawn in tests/core/test_plots.py)
    asked = []
    monkeypatch.setattr(FigurePool, "submit", lambda pool, plot, *args, **kw: asked.append((plot, args)))
    # in this process: what evaluate writes is the point here, not its process (DVC's are)
    thermocomp("evaluate", "plots=test", "track=false", "eval.mutual_prediction=false", cwd=dest,
               env={"THERMOCOMP_ROOT": str(dest)})
    residual_figures = {(args[4], args[3]) for plot, args in asked if plot is residual_plot}
    table = pd.DataFrame({"run_id": ["a" * 32, "b" * 32, "c" * 32], "model": ["mlr", "pcr", "arx"],
                          "select": ["all", "all", "pearson"], "val_rmse": [1.0, 1.2, 1.5],
                          "rmse": [1.1, 1.3, 1.4]})
    write_compare(dest / "reports/sweep_compare", table)
    shown = _plots(dest, env)
    assert not shown.get("errors")
    data = shown["data"]
    test_ids = pd.read_csv(dest / "data/raw/yearround_spindle/campaigns.csv").query(
        "split == 'test'")["campaign"]
    assert residual_figures == {(cid, t) for cid in test_ids for t in TARGETS}
    for cid in test_ids:
        (res,) = data[f"reports/default/plots/residuals/{cid}_E_Z.csv"]
        assert res["content"]["encoding"]["x"]["field"] == "hours"
        csv = pd.read_csv(dest / f"reports/default/plots/residuals/{cid}_E_Z.csv")
        assert csv["residual"].to_numpy() == pytest.approx(  # 6 significant digits in the CSV
            (csv["measured"] - csv["model"]).to_numpy(), abs=1e-4)
    (cmp,) = data["reports/sweep_compare/compare_plot.csv"]
    assert cmp["content"]["encoding"]["x"]["field"] == "rank"
    assert {v["field"] for v in cmp["content"]["data"]["values"]} == {"val_rmse", "test_rmse"}


SWEEP = "pipelines/sweep/dvc.yaml"


def test_the_sweep_pipeline_runs_every_job_and_the_comparison_then_nothing(repro):
    """`dvc repro pipelines/sweep/dvc.yaml` (the README's DVC sweep) on the study's project: the
    sweep's jobs as committed and the comparison, then nothing; the default study's simulate,
    already run, not again.  (An arx_rf job in its grid failed on this dataset, which has no door
    signal, and with it every `dvc repro` of this pipeline.)  The jobs run as on a one-CPU
    machine (``LOKY_MAX_CPU_COUNT=1``: the launcher's ``n_jobs=-1`` is one job at a time, in the
    stage's process): two loky workers each importing the stack and opening the store cost ~19
    of its 52 s of CPU (in a project of its own then), and a joblib sweep on two workers is
    test_sweep's (one parent, four children, the table).  Not marked ``full``: the only test
    that runs every job of the committed grid on the default data (test_pipeline_commands only
    composes them).  After the residual test (it writes the sweep's plot CSV by hand), before the
    one that changes the study."""
    dest, env = repro
    env = {**env, "LOKY_MAX_CPU_COUNT": "1"}
    proc = dvc("repro", SWEEP, cwd=dest, env=env)
    log = proc.stdout + proc.stderr
    for stage in ("sweep", "compare"):
        assert f"Running stage '{SWEEP}:{stage}'" in log, log
    assert "Running stage 'simulate'" not in log, log
    sweep = json.loads((dest / "reports/sweep/sweep.json").read_text())
    jobs = [p for p in (dest / "reports/sweep").iterdir() if (p / "metrics.json").is_file()]
    assert len(jobs) == 6, sweep                      # 3 models x 2 selections
    ranked = pd.read_csv(dest / "reports/sweep_compare/compare_plot.csv")
    assert len(ranked) == 6 and ranked["val_rmse"].is_monotonic_increasing
    proc = dvc("repro", SWEEP, cwd=dest, env=env)
    again = proc.stdout + proc.stderr
    assert "Running stage" not in again and "up to date" in again


def test_a_model_parameter_reruns_train_evaluate_and_diagnose_only(repro):
    """Last in the module: it changes the study."""
    dest, env = repro
    model_conf = dest / "conf/model/mlr.yaml"
    model_conf.write_text(model_conf.read_text().replace("fit_intercept: true",
                                                         "fit_intercept: false"))
    again = dvc("repro", cwd=dest, env=env)
    assert _ran(again.stdout + again.stderr) == {"train", "evaluate", "diagnose"}, again.stdout
    shown = dvc("metrics", "show", cwd=dest, env=env).stdout
    assert "reports/default/headline/E_Z.json" in shown and "test_rmse" in shown
