"""Hostile paths and targets: where a stage writes, what a config builds, how long a name is.

Every case runs the real command on a small hand-made dataset, exits 2 with one line naming
the keys, and leaves the raw data byte-identical and nothing created where it was refused.
"""

from __future__ import annotations

import os

import pytest

from conftest import refused
from test_hostile import FAST, make_dataset, snapshot
from thermocomp.shell.cli import main


@pytest.fixture
def ds(tmp_path):
    """The probe's dataset: campaign files in ``<ds>/plots/`` (where a report puts figures)."""
    root = make_dataset(tmp_path / "ds")
    (root / "plots").mkdir()
    for f in sorted(root.glob("K0*.csv")):
        f.rename(root / "plots" / f.name)
    manifest = root / "campaigns.csv"
    manifest.write_text(manifest.read_text().replace(",K0", ",plots/K0"))
    return root


# -- item 1: one output-path policy, every stage that writes ------------------------------

def _overlaps(ds, tmp):
    """``(stage, overrides, output key, input key)``: an output that is, lies inside or holds
    an input."""
    model = tmp / "models" / "model.pkl"
    return [
        ("run", [f"out={ds}"], "out", "data.path"),                  # the probe's two cases
        ("run", [f"out={ds / 'out'}"], "out", "data.path"),
        ("ingest", [f"data.interim={ds}"], "data.interim", "data.path"),
        ("ingest", [f"data.interim={tmp}"], "data.interim", "data.path"),
        ("ingest", [f"out={ds}"], "out", "data.path"),               # its log goes to out
        ("denoise", [f"data.interim={tmp / 'i'}", f"data.processed={tmp / 'i' / 'p'}"],
         "data.processed", "data.interim"),
        ("select", [f"data.interim={tmp / 'i'}", f"model_path={tmp / 'i' / 'm.pkl'}"],
         "model_path", "data.interim"),
        ("train", [f"model_path={ds / 'model.pkl'}"], "model_path", "data.path"),
        ("evaluate", [f"model_path={model}", f"out={model.parent}"], "out", "model_path"),
        ("diagnose", [f"out={ds / 'diagnosis'}"], "out", "data.path"),
        ("replay", [f"replay.model={model}", f"out={model.parent}"], "out", "replay.model"),
        ("monitor", [f"monitor.model={model}", f"out={tmp / 'models'}"], "out", "monitor.model"),
        ("calibrate", [f"calibrate.dataset={ds / 'parameters'}"], "calibrate.dataset", "data.path"),
        ("promote", [f"out={ds}"], "out", "data.path"),
        ("design", [f"out={ds}"], "out", "data.path"),
        ("compare", [f"compare.out={ds}"], "compare.out", "data.path"),
    ]


@pytest.mark.parametrize("case", range(16))
def test_an_output_over_an_input_is_refused_before_any_work(ds, tmp_path, capsys, case):
    stage, overrides, out_key, in_key = _overlaps(ds, tmp_path)[case]
    model = tmp_path / "models" / "model.pkl"
    model.parent.mkdir()
    model.write_bytes(b"not read: refused before")
    before = snapshot(ds, model.parent)
    line = refused([stage, f"data.path={ds}", *overrides, *FAST], capsys,
                   f"{out_key}=", f"{in_key}=", "never writes where it reads")
    assert line.index(f"{out_key}=") < line.index(f"{in_key}=")
    assert snapshot(ds, model.parent) == before
    assert not (tmp_path / "i").exists()


def test_a_tracking_store_in_the_raw_data_is_refused(ds, tmp_path, capsys):
    """A SQLite store writes its file, a lock and the artifacts beside it."""
    before = snapshot(ds)
    refused(["run", f"data.path={ds}", f"out={tmp_path / 'o'}", "track=true", "plots=none",
             f"tracking_uri=sqlite:///{ds / 'mlflow.db'}"], capsys,
            "tracking_uri=sqlite:///", "lies inside data.path=")
    assert snapshot(ds) == before


def test_a_sweep_folder_in_the_raw_data_is_refused_before_hydra_writes_there(ds, capsys):
    before = snapshot(ds)       # Hydra wrote multirun.yaml and <job>/.hydra/ there first
    refused(["run", "-m", f"data.path={ds}", f"hydra.sweep.dir={ds / 'sweep'}", *FAST], capsys,
            f"hydra.sweep.dir={ds / 'sweep'} lies inside data.path={ds}")
    assert snapshot(ds) == before


def test_a_link_to_the_raw_data_is_the_raw_data(ds, tmp_path, capsys):
    link = tmp_path / "link"
    link.symlink_to(ds, target_is_directory=True)
    before = snapshot(ds)
    refused(["run", f"data.path={ds}", f"out={link}", *FAST], capsys, f"out={link} is data.path")
    assert snapshot(ds) == before


def test_outputs_beside_the_inputs_still_run(ds, tmp_path):
    """The layouts of every day: data/raw/<x>, data/interim/<name>, models/<name>/, reports/<name>."""
    where = [f"data.path={ds}", f"data.interim={tmp_path / 'interim'}",
             f"model_path={tmp_path / 'models' / 'model.pkl'}", f"out={tmp_path / 'reports'}", *FAST]
    before = snapshot(ds / "plots")        # and the entries of ds
    for stage in ("ingest", "train", "evaluate"):
        assert main([stage, *where]) == 0
    assert (tmp_path / "reports" / "metrics.json").is_file() and snapshot(ds / "plots") == before


# -- item 2: the instantiation allow-list ---------------------------------------------------

def _writers(tmp, ds):
    """``(target, its arguments)``: callables that write a file, ``tmp / 'made'``."""
    made = tmp / "made"
    return [("builtins.open", [f"+model.estimator.file={made}", "+model.estimator.mode=w"]),
            ("shutil.copyfile", [f"+model.estimator.src={ds / 'campaigns.csv'}",
                                 f"+model.estimator.dst={made}"]),
            ("os.makedirs", [f"+model.estimator.name={made}"]),
            ("numpy.savetxt", [f"+model.estimator.fname={made}", "+model.estimator.X=[1,2]"]),
            # named under thermocomp, but logging's (a file handler opens its file)
            ("thermocomp.base.log.logging.FileHandler", [f"+model.estimator.filename={made}"])]


@pytest.mark.parametrize("case", range(5))
def test_a_target_that_writes_a_file_is_refused_in_one_line(ds, tmp_path, capsys, case):
    target, args = _writers(tmp_path, ds)[case]
    refused(["run", f"data.path={ds}", f"out={tmp_path / 'o'}", *FAST,
             f"model.estimator._target_={target}", "~model.estimator.fit_intercept", *args],
            capsys, f"model.estimator._target_={target}", "built from a config")
    assert not (tmp_path / "made").exists() and not (tmp_path / "o").exists()


@pytest.mark.parametrize("stage, args", [
    ("run", ["model=arx_rf", "model.estimator.forest._target_=os.makedirs",    # nested
             "~model.estimator.forest.n_estimators", "~model.estimator.forest.min_samples_leaf",
             "~model.estimator.forest.random_state", "+model.estimator.forest.name={made}"]),
    ("run", ["ati=cmeans", "ati.estimator._target_=os.makedirs",               # _partial_
             "+ati.estimator.name={made}"]),
    ("train", ["select=pearson", "select.selector._target_=os.makedirs", "+select.selector.name={made}"]),
    ("simulate", ["sim.generator._target_=os.makedirs", "+sim.generator.name={made}"]),
], ids=["nested", "partial", "selector", "generator"])
def test_every_built_node_is_checked(ds, tmp_path, capsys, stage, args):
    made = tmp_path / "made"
    refused([stage, f"data.path={tmp_path / 'sim' if stage == 'simulate' else ds}",
             f"out={tmp_path / 'o'}", *FAST, *(a.format(made=made) for a in args)],
            capsys, "_target_=os.makedirs", "built from a config")
    assert not made.exists()


def test_a_hydra_callback_is_checked_before_hydra_builds_it(ds, tmp_path, capsys):
    made = tmp_path / "made"
    refused(["run", "-m", f"data.path={ds}", f"hydra.sweep.dir={tmp_path / 'sweep'}", *FAST,
             "+hydra.callbacks.evil._target_=builtins.open", f"+hydra.callbacks.evil.file={made}",
             "+hydra.callbacks.evil.mode=w"], capsys, "hydra.callbacks.evil._target_=builtins.open")
    assert not made.exists() and not (tmp_path / "sweep").exists()


def test_a_test_estimator_is_built_only_when_the_environment_allows_it(monkeypatch, tmp_path, ds,
                                                                       capsys):
    args = ["run", f"data.path={ds}", f"out={tmp_path / 'o'}", *FAST, "model.name=ar_stub",
            "~model.estimator.fit_intercept", "model.estimator._target_=test_deploy.ARStub"]
    monkeypatch.delenv("THERMOCOMP_TARGETS", raising=False)
    refused(args, capsys, "model.estimator._target_=test_deploy.ARStub")
    monkeypatch.setenv("THERMOCOMP_TARGETS", "test_deploy.")
    assert main(args) == 0


# -- item 13: a name of 300 characters ---------------------------------------------------

def test_a_name_too_long_for_a_file_name_is_one_line(ds, tmp_path, capsys):
    before = set(os.listdir(tmp_path))
    refused(["run", f"data.path={ds}", f"name={'x' * 300}", f"out={tmp_path}/${{name}}", *FAST],
            capsys, "name=", "at most 100")
    refused(["run", f"data.path={ds}", f"out={tmp_path / ('y' * 300)}", *FAST], capsys,
            "out=", "300 bytes")
    assert set(os.listdir(tmp_path)) == before
