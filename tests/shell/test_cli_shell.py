"""The command shell: --version, typo suggestions, per-stage help, log levels and log file,
lenient overrides for the README's values, progress bars, the DVC launcher."""

import json
import os
import re
import shutil
import subprocess
from importlib.metadata import version
from pathlib import Path

import pandas as pd
import pytest

from conftest import FAST, ROOT
from test_deploy import mlflow_store
from thermocomp.base import log
from thermocomp.base.progress import bar
from thermocomp.shell.callbacks import sweep_size
from thermocomp.shell.cli import _compose, lenient, main


def _errors(capsys) -> list[str]:
    return [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("thermocomp: error")]


@pytest.mark.parametrize("flag", ["--version", "-V"])
def test_version(flag, capsys):
    assert main([flag]) == 0
    assert capsys.readouterr().out.strip() == f"thermocomp {version('thermocomp')}"


@pytest.mark.parametrize("args, needle", [
    (["evalute"], "did you mean 'evaluate'?"),
    (["run", "modle=mlr"], "did you mean 'model'?"),
    (["run", "data.delimitr=;"], "did you mean 'data.delimiter'?"),
    (["run", "modle.estimator.alpha=1"], "did you mean 'model.estimator.alpha'?"),
    (["run", "data.split_overides={K01:test}"], "did you mean 'data.split_overrides'?"),
])
def test_typos_get_a_suggestion_and_exit_2(args, needle, capsys):
    assert main(args) == 2
    errors = _errors(capsys)
    assert len(errors) == 1 and needle in errors[0], errors


def test_unknown_group_option_lists_the_options_closest_first(capsys):
    assert main(["run", "model=mlp"]) == 2
    (line,) = _errors(capsys)
    options = line.split("closest first: ")[1].split(", ")
    assert options[0] == "mlr" and set(options) >= {"mlr", "pcr", "arx", "lstm"}


def test_stage_help_is_short_and_hydra_flags_still_work(capsys):
    assert main(["run", "--help"]) == 0
    text = capsys.readouterr().out
    assert len(text.splitlines()) < 20 and "--cfg job" in text and "writes:" in text
    assert main(["run", "--cfg", "job", "--package", "data"]) == 0
    assert "delimiter" in capsys.readouterr().out
    assert main(["run", "--hydra-help"]) == 0
    assert "Hydra" in capsys.readouterr().out


def test_lenient_rewrites_only_what_hydra_rejects():
    assert lenient(["data.delimiter=;", "data.decimal=,"]) == ["data.delimiter=';'", "data.decimal=','"]
    assert lenient(["data.split_overrides={K01:test}", "data.columns={T0:T_0,dL:E_L}"]) == [
        "++data.split_overrides={K01:test}", "++data.columns={T0:T_0,dL:E_L}"]
    untouched = ["data.inputs=[T_1", "model=mlr", "-m", "data.split_overides={K01:test}",
                 "sim.generator.effects=[door]"]
    assert lenient(untouched) == untouched


def test_a_plus_on_a_plain_key_is_dropped_so_a_key_the_config_lacks_is_refused():
    # `+` adds keys only where thermocomp reads new ones: a free map, an object's arguments,
    # the defaults list, Hydra's node; elsewhere Hydra itself says a key is unknown
    kept = ["+model.estimator.foo=1", "++data.columns.T0=T_0", "++data.columns={T0:T_0}",
            "+hydra.callbacks.p._target_=x",
            "+experiment=fl", "~model.estimator.alpha"]
    assert lenient(["+eval.foo=1", "++eval.mode=one_step", *kept]) == [
        "eval.foo=1", "eval.mode=one_step", *kept]
    assert _compose(lenient(["+eval.mode=one_step"]), "run").eval.mode == "one_step"


def _run(capsys, dataset, out, *extra):
    code = main(["run", f"data.path={dataset}", f"out={out}", *FAST, *extra])
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def test_log_levels_stderr_stdout_and_log_file(default_dataset, tmp_path, capsys):
    code, out, err = _run(capsys, default_dataset, tmp_path / "normal")
    assert code == 0
    assert "RMS before" in out and "[thermocomp]" not in out  # the table alone on stdout
    assert "[thermocomp] reading" in err and "[thermocomp] thermocomp " not in err  # no debug
    logged = (tmp_path / "normal" / "thermocomp.log").read_text()
    assert "INFO" in logged and "reading" in logged and "DEBUG" in logged  # the file keeps debug

    code, out, err = _run(capsys, default_dataset, tmp_path / "quiet", "-q")
    assert code == 0 and "RMS before" in out and "[thermocomp]" not in err
    code, out, err = main(["-v", "run", f"data.path={default_dataset}", f"out={tmp_path / 'v'}",
                           *FAST]), *capsys.readouterr()
    assert code == 0 and f"[thermocomp] thermocomp {version('thermocomp')}: run" in err
    log.configure("INFO")


def test_refused_run_leaves_no_log_file(tmp_path, capsys):
    assert main(["run", "data.path=/nonexistent/dataset", f"out={tmp_path / 'o'}", *FAST]) == 2
    assert len(_errors(capsys)) == 1
    assert not (tmp_path / "o").exists()


def test_log_file_is_an_mlflow_artifact(default_dataset, tmp_path, capsys):
    uri = mlflow_store(tmp_path)     # an empty store (the session's migrated copy)
    args = [a for a in FAST if a != "track=false"]
    assert main(["run", f"data.path={default_dataset}", f"out={tmp_path / 'o'}",
                 f"tracking_uri={uri}", *args]) == 0
    import mlflow

    client = mlflow.MlflowClient(uri)
    (run,) = client.search_runs([client.get_experiment_by_name("thermocomp").experiment_id])
    local = client.download_artifacts(run.info.run_id, "thermocomp.log", str(tmp_path / "dl"))
    assert "fitting mlr" in Path(local).read_text()


def _semicolon_copy(src: Path, dest: Path, rename: dict | None = None) -> Path:
    """The dataset's campaign files written as many European exports do: `;` separators,
    decimal commas (the manifest stays as it is)."""
    dest.mkdir()
    shutil.copy2(src / "campaigns.csv", dest / "campaigns.csv")
    for f in src.glob("*.csv"):
        if f.name == "campaigns.csv":
            continue
        df = pd.read_csv(f).rename(columns=rename or {})
        df.to_csv(dest / f.name, sep=";", decimal=",", index=False)
    return dest


def test_readme_values_semicolons_decimal_commas_maps(default_dataset, tmp_path, capsys):
    """`data.delimiter=";" data.decimal=","`, `data.columns={...}` and
    `data.split_overrides={...}` as bash passes them: the same numbers as the plain dataset."""
    assert _run(capsys, default_dataset, tmp_path / "plain")[0] == 0
    plain = json.loads((tmp_path / "plain" / "metrics.json").read_text())

    euro = _semicolon_copy(default_dataset, tmp_path / "euro", rename={"T_amb": "ambient"})
    code, _, err = _run(capsys, euro, tmp_path / "euro_out", "data.delimiter=;", "data.decimal=,",
                        "data.columns={ambient:T_amb}")
    assert code == 0, err
    got = json.loads((tmp_path / "euro_out" / "metrics.json").read_text())
    for t, m in plain["targets"].items():
        assert got["targets"][t]["test"]["rmse"] == pytest.approx(m["test"]["rmse"], rel=1e-9)

    train = pd.read_csv(default_dataset / "campaigns.csv").query("split == 'train'")["campaign"]
    moved = str(train.iloc[0])
    assert _run(capsys, default_dataset, tmp_path / "split",
                f"data.split_overrides={{{moved}:test}}")[0] == 0
    split = json.loads((tmp_path / "split" / "metrics.json").read_text())
    assert moved in split["targets"]["E_X"]["test"]["per_campaign"]
    assert moved not in plain["targets"]["E_X"]["test"]["per_campaign"]


def test_progress_bars_follow_the_level(monkeypatch):
    monkeypatch.setenv(log.LEVEL_ENV, "WARNING")
    assert bar(range(3)).disable
    monkeypatch.setenv(log.LEVEL_ENV, "DEBUG")
    assert not bar(range(3)).disable
    assert bar(range(3), disable=True).disable


def test_sweep_size_counts_the_jobs():
    assert sweep_size(["model=mlr,pcr,arx", "select=all,pearson", "seed=0"]) == 6
    assert sweep_size(["model=mlr"]) == 1


def test_no_bare_print_for_progress_in_src():
    """Progress goes through the logger; a `print(..., file=sys.stderr)` is a regression."""
    offenders = [f"{p.relative_to(ROOT)}:{i}" for p in (ROOT / "src").rglob("*.py")
                 for i, line in enumerate(p.read_text().splitlines(), 1)
                 if re.search(r"\bprint\(.*file=sys\.stderr", line) and "thermocomp: error" not in line]
    assert offenders == []


def test_launcher_without_venv_fails_clearly_before_anything(tmp_path):
    root = tmp_path / "proj"
    (root / "pipelines").mkdir(parents=True)
    shutil.copy2(ROOT / "pipelines" / "thermocomp", root / "pipelines" / "thermocomp")
    env = {"PATH": "/usr/bin:/bin", "HOME": str(tmp_path)}
    proc = subprocess.run([str(root / "pipelines" / "thermocomp"), "simulate"], env=env,
                          capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 127
    assert "not installed" in proc.stderr and str(root / ".venv/bin/thermocomp") in proc.stderr
    assert list(root.iterdir()) == [root / "pipelines"]  # nothing written

    os.symlink(ROOT / ".venv", root / ".venv")
    proc = subprocess.run([str(root / "pipelines" / "thermocomp"), "--version"], env=env,
                          capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 0 and proc.stdout.strip() == f"thermocomp {version('thermocomp')}"


def test_validation_folds_beyond_the_train_campaigns_are_said(default_dataset, tmp_path, capsys):
    fast = [a for a in FAST if a != "eval.validation=false"]
    code = main(["run", f"data.path={default_dataset}", f"out={tmp_path}", *fast,
                 "eval.validation_folds=50"])
    err = capsys.readouterr().err
    assert code == 0
    entry = json.loads((tmp_path / "metrics.json").read_text())["targets"]["E_Z"]["validation"]
    assert entry["n_folds"] < 50
    assert f"eval.validation_folds=50: {entry['n_folds']} fold(s), {entry['method']}" in err
