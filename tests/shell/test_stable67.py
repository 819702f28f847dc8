"""stable67: a machine whose errors are at the probe's noise level on some axes.

A model that fits noise makes such an axis worse than no compensation.  ``model=auto`` validates
no correction (``none``) beside its candidates and keeps a zero correction where nothing validates
below it; the run's validation reports the uncompensated error's RMS on the same rows
(``rms_before``), its printed table and ``promote`` say plainly when a model validates worse."""

from __future__ import annotations

import contextlib
import io
import json
import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from thermocomp.shell.cli import main

PERIOD_S = 60.0
ROWS = 240
RUNS = [(f"R{k:02d}", "train" if k <= 7 else "test") for k in range(1, 10)]
BASE = ["track=false", "plots=none", "data.reference=first_sample"]
DEPLOY = ["promote.envelope.policy=off", "monitor.adaptive=false"]   # streamed as run scores


@pytest.fixture(scope="module")
def record(tmp_path_factory):
    """Nine 4 h runs (seven train, two test): three sensors warming and cooling with a duty
    cycle; E_N is the probe's noise alone (0.4 µm), E_G a real 3 µm/K growth of T_a plus noise."""
    root = tmp_path_factory.mktemp("stable67") / "data"
    root.mkdir()
    rng = np.random.default_rng(6711)
    t = np.arange(ROWS) * PERIOD_S
    for cid, _ in RUNS:
        duty = np.repeat(rng.integers(0, 2, ROWS // 30 + 1), 30)[:ROWS].astype(float)
        heat = np.zeros(ROWS)
        for i in range(1, ROWS):
            heat[i] = heat[i - 1] + (duty[i] - heat[i - 1]) * PERIOD_S / 1800.0
        T_a = 20 + 1.5 * heat + rng.normal(0, 0.02, ROWS)
        T_b = 20 + np.cumsum(rng.normal(0, 0.01, ROWS)) + rng.normal(0, 0.02, ROWS)
        T_c = 20 + 0.5 * heat + 0.5 * (T_b - 20) + rng.normal(0, 0.02, ROWS)
        pd.DataFrame({"time": t, "T_a": T_a, "T_b": T_b, "T_c": T_c,
                      "E_N": rng.normal(0, 0.4, ROWS),
                      "E_G": 3.0 * (T_a - T_a[0]) + rng.normal(0, 0.3, ROWS)}
                     ).to_csv(root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s) for c, s in RUNS], columns=["campaign", "file", "split"]
                 ).to_csv(root / "campaigns.csv", index=False)
    return root


def _run(record, out, *args) -> dict:
    assert main(["run", f"data.path={record}", f"out={out}", *BASE, *args]) == 0
    return json.loads((out / "metrics.json").read_text())["targets"]


AUTO = ["model=auto", "model.candidates=[mlr,pcr]"]


@pytest.fixture(scope="module")
def auto_run(record, tmp_path_factory):
    out = tmp_path_factory.mktemp("auto") / "out"
    return out, _run(record, out, *AUTO)


def test_auto_keeps_no_correction_where_nothing_validates_below_it(auto_run):
    _, targets = auto_run
    noise, real = targets["E_N"], targets["E_G"]
    assert noise["auto"]["chosen"] == "none"
    none = noise["auto"]["candidates"]["none"]
    assert all(v > none for n, v in noise["auto"]["candidates"].items()
               if n in ("mlr", "pcr"))
    # the deployed correction is zero: the test error is the uncompensated one, and the run's
    # validation scores the kept zero as no correction on the same rows
    assert noise["test"]["rmse"] == pytest.approx(noise["test"]["rms_before"], rel=1e-12)
    assert noise["validation"]["rmse"] == pytest.approx(none, rel=1e-12)
    assert noise["validation"]["rms_before"] == pytest.approx(none, rel=1e-12)
    # the axis with a real effect keeps its compensation
    assert real["auto"]["chosen"] != "none"
    assert real["validation"]["rmse"] < 0.5 * real["validation"]["rms_before"]
    assert real["test"]["rmse"] < 0.5 * real["test"]["rms_before"]


def test_uncompensated_keep_keeps_the_fitted_model(record, tmp_path):
    targets = _run(record, tmp_path / "out", *AUTO, "model.estimator.uncompensated=keep")
    noise = targets["E_N"]
    assert noise["auto"]["chosen"] != "none"
    assert noise["validation"]["rmse"] > noise["validation"]["rms_before"]


@pytest.fixture(scope="module")
def tracked_mlr(record, tmp_path_factory) -> tuple[str, Path, dict, str]:
    """``(tracking uri, out, targets, what it printed)`` of one tracked ``run model=mlr`` (E_N
    validates worse than no correction): the run test reads its message, the promote test
    promotes it."""
    root = tmp_path_factory.mktemp("tracked_mlr")
    uri = f"sqlite:///{root / 'mlruns.db'}"
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        assert main(["run", f"data.path={record}", f"tracking_uri={uri}", "plots=none",
                     "data.reference=first_sample", "model=mlr", f"out={root / 'run'}"]) == 0
    targets = json.loads((root / "run" / "metrics.json").read_text())["targets"]
    return uri, root / "run", targets, out.getvalue() + err.getvalue()


def test_run_says_plainly_when_a_model_validates_worse_than_no_compensation(tracked_mlr):
    _, _, targets, said = tracked_mlr
    line = next(x for x in said.splitlines() if "WORSE THAN NO COMPENSATION" in x)
    v = targets["E_N"]["validation"]
    assert v["rmse"] > v["rms_before"]
    assert f"E_N {v['rmse']:.3g} > {v['rms_before']:.3g}" in line
    assert "E_G" not in line


def test_the_zero_correction_replays_and_exports_as_zero(record, auto_run, tmp_path):
    out, targets = auto_run
    model = out / "model.pkl"
    assert main(["replay", f"data.path={record}", f"replay.model={model}",
                 f"out={tmp_path / 'replay'}", *BASE, *DEPLOY]) == 0
    replayed = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]
    for t in ("E_N", "E_G"):
        assert replayed[t]["rmse"] == pytest.approx(targets[t]["test"]["rmse"], rel=1e-9)
    if shutil.which("gcc") is None:
        return
    code = tmp_path / "c"
    assert main(["export", f"data.path={record}", f"export.model={model}", "export.format=c",
                 "export.check=true", f"out={code}", *BASE, *DEPLOY]) == 0
    assert "none (no correction" in (code / "compensator.json").read_text()
    compiled(code)
    check = subprocess.run(["sh", "check/check.sh"], cwd=code, capture_output=True, text=True)
    assert check.returncode == 0, check.stdout + check.stderr
    for path in (code / "check").glob("*/expected.csv"):
        expected = pd.read_csv(path)
        assert (expected["C_N"] == 0).all() and (expected["C_G"] != 0).any()


def test_promote_warns_of_a_candidate_worse_than_no_compensation(record, tracked_mlr, tmp_path,
                                                                 capsys):
    uri, _, _, said = tracked_mlr
    args = [f"data.path={record}", f"tracking_uri={uri}", "plots=none",
            "data.reference=first_sample"]
    run_id = re.search(r"MLflow run (\w+)", said).group(1)
    assert main(["promote", *args, f"promote.run_id={run_id}",
                 f"out={tmp_path / 'promote'}"]) == 0
    err = capsys.readouterr().err
    warned = next(x for x in err.splitlines() if "WORSE THAN NO COMPENSATION" in x)
    assert run_id in warned and "E_N" in warned


def test_a_val_split_scores_no_correction_too(record, tmp_path):
    """With val campaigns in the manifest auto scores each candidate on them, and no correction
    on the same rows."""
    data = tmp_path / "data"
    shutil.copytree(record, data)
    manifest = pd.read_csv(data / "campaigns.csv")
    manifest.loc[manifest["campaign"].isin(["R06", "R07"]), "split"] = "val"
    manifest.to_csv(data / "campaigns.csv", index=False)
    targets = _run(data, tmp_path / "out", *AUTO)
    noise, real = targets["E_N"], targets["E_G"]
    assert noise["auto"]["scheme"] == "val split"
    assert noise["auto"]["candidates"]["none"] == pytest.approx(
        noise["validation"]["rms_before"], rel=1e-12)
    assert noise["auto"]["chosen"] == "none"
    assert noise["test"]["rmse"] == pytest.approx(noise["test"]["rms_before"], rel=1e-12)
    assert real["auto"]["chosen"] != "none"


def test_a_derived_target_gets_the_zero_rule_and_its_message(record, tmp_path, capsys):
    """(dates84) A ``data.derive`` target is computed as the campaign is read, before any model:
    fitted, validated and judged against no correction as a measured one is (a tilt of the
    noise probe: auto keeps a zero correction; MLR's table says it validates worse)."""
    derive = "+data.derive={E_tilt_N: 'E_N / 0.1'}"
    tilt = _run(record, tmp_path / "auto", *AUTO, derive)["E_tilt_N"]
    assert tilt["auto"]["chosen"] == "none"
    assert tilt["test"]["rmse"] == pytest.approx(tilt["test"]["rms_before"], rel=1e-12)
    capsys.readouterr()
    v = _run(record, tmp_path / "mlr", "model=mlr", derive)["E_tilt_N"]["validation"]
    said = capsys.readouterr()
    line = next(x for x in (said.out + said.err).splitlines() if "WORSE THAN NO COMPENSATION" in x)
    assert v["rmse"] > v["rms_before"] and f"E_tilt_N {v['rmse']:.3g} > {v['rms_before']:.3g}" in line
