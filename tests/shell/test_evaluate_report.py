"""The evaluate/run report (issue 5): every metrics.json key, every figure, MLflow, DVC plots."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT, thermocomp
from test_deploy import mlflow_store

TEST_KEYS = {"rmse", "rsd_mean", "rsd_sd", "rms_before", "rms_after", "p2p_before", "p2p_after",
             "per_campaign", "e_p95",  # CLI.md
             "rms_reduction_pct", "p2p_reduction_pct", "e_max", "e_mean", "iso10791_a3"}
CAMPAIGN_KEYS = {"rmse", "rsd", "p2p_before", "p2p_after",  # CLI.md
                 "rms_before", "rms_after", "rms_reduction_pct", "p2p_reduction_pct"}


def check_report(m: dict, plots: Path, ati: bool, level: str = "summary",
                 train: tuple = ()) -> None:
    """Every key of issue 5 in ``metrics.json``, and under ``plots`` exactly the figures that
    ``plots=level`` asks for (``train``: the train campaigns, whose residuals ``all`` draws)."""
    targets = list(m["targets"])
    expected = set()
    assert targets and {"model", "mode", "targets", "anova", "ati", "mutual_prediction"} <= set(m)
    for t in targets:
        te = m["targets"][t]["test"]
        assert TEST_KEYS <= set(te), TEST_KEYS - set(te)
        for pc in te["per_campaign"].values():
            assert CAMPAIGN_KEYS <= set(pc)
            assert pc["rms_reduction_pct"] == pytest.approx(100 * (1 - pc["rms_after"] / pc["rms_before"]))
        for key in ("e_p95", "e_max", "e_mean"):
            e = te[key]
            assert len(e["window_s"]) == len(e["before"]) == len(e["after"]) > 0
        # E_mean <= E_P95 <= E_max at every window length
        for side in ("before", "after"):
            lo, mid, hi = (np.array(te[k][side], float) for k in ("e_mean", "e_p95", "e_max"))
            assert np.all(lo <= mid + 1e-9) and np.all(mid <= hi + 1e-9)
        iso = te["iso10791_a3"]
        assert iso["n_slots"] == 16 and set(iso["per_campaign"]) == set(te["per_campaign"])
        # the simulated campaigns last 4-8 h, the A.3 test 15 h: said, not invented
        assert iso["summary"] is None and "15 h" in iso["reason"]
        an = m["anova"][t]["error"]
        assert {"F", "p_value", "F_crit", "alpha", "significant"} <= set(an) and an["alpha"] == 0.001
        assert an["F"] > 0 and 0 <= an["p_value"] <= 1
        assert "residual_test" in m["anova"][t]
        mp = m["mutual_prediction"][t]
        n = len(mp["campaigns"])
        rsd = np.array(mp["rsd"], float)
        assert rsd.shape == (n, n) and n == len(mp["ambient_c0"])
        assert mp["ambient_c0"] == sorted(mp["ambient_c0"])  # ordered by initial ambient
        # a campaign's own model fits it better than the others' models do, on average
        assert np.mean(np.diag(rsd)) < np.mean(rsd[~np.eye(n, dtype=bool)])
        at = m["ati"]["targets"][t]
        assert {"coldest", "warmest", "model"} <= set(at["test"])
        assert {"sm_vs_coldest", "sd_vs_coldest", "sm_vs_warmest", "sd_vs_warmest"} <= set(
            at["improvement_pct"])
        assert at["test"]["model"]["rsd_mean"] == pytest.approx(te["rsd_mean"])
        names = ["e_p95", "rsd"] + (["ati_intervals", "ati_elbow"] if ati else [])
        names += ["mutual_prediction"] if level in ("test", "all") else []
        for name in names:
            assert (plots / f"{name}_{t}.png").stat().st_size > 10_000, name
        expected |= {f"{name}_{t}.png" for name in names}
        if level in ("test", "all"):
            expected |= {f"residual_{cid}_{t}.png" for cid in te["per_campaign"]}
        if level == "all":
            expected |= {f"residual_{cid}_{t}.png" for cid in train}
        if ati:
            assert at["n_intervals"] == len(at["intervals"]) == len(at["boundaries_c"]) + 1
            assert at["elbow"]["chosen"] == at["n_intervals"]
            assert "single_model" in at["test"]
    assert m["ati"]["ati_model"] is ati
    expected |= {"e_p95", "residuals"}  # the figures' data for `dvc plots show` (CSV)
    assert {p.name for p in plots.iterdir()} == expected  # nothing else, no temp file left
    assert {p.name for p in (plots / "e_p95").iterdir()} == {f"{t}.csv" for t in m["targets"]}
    assert all(p.stat().st_mode & 0o777 == (0o755 if p.is_dir() else 0o644)
               for p in plots.rglob("*"))


@pytest.fixture(scope="session")
def small_year():
    """Nine simulated campaigns (six train, three test) of the default scenario, in memory."""
    from hydra.utils import instantiate

    from thermocomp.shell.cli import _compose

    ds, _ = instantiate(_compose(["sim.generator.n_campaigns=9"]).sim.generator).generate()
    return ds


@pytest.mark.parametrize("ati, level", [("none", "all"), ("cmeans", "test")])
def test_report_has_every_key_and_figure(small_year, tmp_path, ati, level, capsys):
    from thermocomp.shell.builders import build_compensator
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.stages.modelling import _report
    from thermocomp.shell.tracking import _Null

    # one target with ATI keeps the test fast; the layout does not depend on the target, and two
    # without (not three: plots=all draws every campaign's residual per target) say each has its own
    extra = ["data.targets=[E_Z]"] if ati == "cmeans" else ["data.targets=[E_X,E_Z]"]
    cfg = _compose([f"out={tmp_path / 'out'}", f"ati={ati}", "track=false", f"plots={level}", *extra])
    ds = small_year
    comp = build_compensator(cfg).fit({c: ds.campaigns[c] for c in ds.ids("train")})
    metrics = _report(cfg, comp, ds, _Null())
    on_disk = json.loads((tmp_path / "out" / "metrics.json").read_text())  # strict JSON
    assert on_disk["targets"].keys() == metrics["targets"].keys()
    check_report(on_disk, tmp_path / "out" / "plots", ati=(ati == "cmeans"), level=level,
                 train=tuple(ds.ids("train")))
    assert on_disk["ati"]["name"] == ati
    assert "RMS before" in capsys.readouterr().out


def test_plots_none_writes_no_figure_and_the_same_numbers(small_year, tmp_path):
    """``plots=none``: no plots folder at all; metrics.json as with the default figures."""
    from thermocomp.shell.builders import build_compensator
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.stages.modelling import _report
    from thermocomp.shell.tracking import _Null

    ds = small_year
    light = ["track=false", "data.targets=[E_Z]", "eval.mutual_prediction=false"]
    # one fit for the three reports: ``plots`` is no model setting, and the same compensator
    # makes the equality below one of the figures' alone
    comp = build_compensator(_compose(light)).fit({c: ds.campaigns[c] for c in ds.ids("train")})
    reports = {}
    for level in ("none", "summary"):
        cfg = _compose([f"out={tmp_path / level}", f"plots={level}", *light])
        reports[level] = _report(cfg, comp, ds, _Null())
    assert not (tmp_path / "none" / "plots").exists()
    assert {p.name for p in (tmp_path / "summary" / "plots").iterdir()} == {
        "e_p95_E_Z.png", "rsd_E_Z.png", "e_p95", "residuals"}
    assert reports["none"] == reports["summary"]
    # plots=none into the folder of a run with figures: none of them stay beside its numbers
    cfg = _compose([f"out={tmp_path / 'summary'}", "plots=none", *light])
    _report(cfg, comp, ds, _Null())
    assert not (tmp_path / "summary" / "plots").exists()


@pytest.mark.slow
def test_cli_evaluate_then_dvc_plots_show(tmp_path):
    """simulate -> ingest -> train (ati=cmeans) -> evaluate through the command line in a
    scratch project; figures logged to MLflow; `dvc plots show` renders them."""
    proj = tmp_path / "proj"
    proj.mkdir()
    for item in ("conf", "src", "dvc.yaml", ".dvc"):
        src = ROOT / item
        if src.is_dir():
            shutil.copytree(src, proj / item, ignore=shutil.ignore_patterns("__pycache__", "tmp"))
        elif src.exists():
            shutil.copy2(src, proj / item)
    env = {"THERMOCOMP_ROOT": str(proj),
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    mlflow_store(proj)        # the default store, migrated: its creation is tested in test_tracking
    # one target: the figures of several are test_report_has_every_key_and_figure[none-all]'s
    small = ["sim.generator.n_campaigns=9", "ati=cmeans", "data.targets=[E_Z]"]
    thermocomp("simulate", *small, "track=false", env=env)
    thermocomp("ingest", *small, "track=false", env=env)
    thermocomp("train", *small, "track=false", env=env)
    thermocomp("evaluate", *small, env=env)
    report = proj / "reports" / "default"
    m = json.loads((report / "metrics.json").read_text())
    check_report(m, report / "plots", ati=True)

    import mlflow
    mlflow.set_tracking_uri(f"sqlite:///{proj / 'mlruns' / 'mlflow.db'}")
    run = mlflow.search_runs(experiment_names=["thermocomp"]).iloc[0]
    logged = {a.path for a in mlflow.MlflowClient().list_artifacts(run.run_id, "plots")}
    assert logged == {f"plots/{p.name}" for p in (report / "plots").iterdir()}
    assert {"plots/e_p95_E_Z.png", "plots/rsd_E_Z.png", "plots/ati_elbow_E_Z.png"} <= logged
    assert run["metrics.E_Z.test.rsd_mean"] == pytest.approx(m["targets"]["E_Z"]["test"]["rsd_mean"])

    subprocess.run(["git", "init", "-q"], cwd=proj, check=True)
    proc = subprocess.run([str(Path(sys.executable).parent / "dvc"), "plots", "show"], cwd=proj,
                          env={**os.environ, **env}, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    html = (proj / "dvc_plots" / "index.html").read_text()
    for png in (report / "plots").glob("*.png"):
        assert f"reports_default_plots_{png.name}" in html, png.name
