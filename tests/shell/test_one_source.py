"""One dataset source, one path (issue 35, item 2): ``run`` is the DVC stages' functions chained
in memory, the stages' hand-offs carry one fingerprint (the dataset digest and a config hash),
and every stage opens its data through ``shell/source.open_source``."""

from __future__ import annotations

import json

import pytest

from conftest import LIGHT, UNTRACKED, cli

CHAIN = ("ingest", "denoise", "select", "train", "evaluate")
TIMING = ("fit_time_s",)      # what only differs by the clock


def _without_timing(metrics: dict) -> dict:
    return {k: v for k, v in metrics.items() if k not in TIMING}


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """The hostile matrix's four campaigns (three train, one test), an hour each: the chain
    and ``run`` agree whatever the size (on the simulated short dataset, whose EMD and
    validation refits cost ~3x more, this test took 20 of the module's 28 s of CPU); one
    validation fold still refits the denoiser."""
    from test_hostile import make_dataset

    return make_dataset(tmp_path_factory.mktemp("one_source") / "ds", rows=60)


@pytest.mark.parametrize("settings", [("denoise=emd", "select=pearson", "model=pcr"),
                                      ("select=greedy_residual", "model=arx")])
def test_run_scores_what_the_dvc_chain_scores(small, tmp_path, settings):
    common = [f"data.path={small}", f"data.interim={tmp_path / 'interim'}",
              f"data.processed={tmp_path / 'processed'}", f"model_path={tmp_path / 'm/model.pkl'}",
              *UNTRACKED, *LIGHT, *settings]
    for stage in CHAIN:
        cli(stage, *common, f"out={tmp_path / 'staged'}")
    cli("run", *common, f"out={tmp_path / 'run'}")
    staged = json.loads((tmp_path / "staged/metrics.json").read_text())
    run = json.loads((tmp_path / "run/metrics.json").read_text())
    assert _without_timing(run) == _without_timing(staged)
    assert all(t["validation"]["n_folds"] >= 1 for t in run["targets"].values())


def test_run_is_the_chain_of_the_stages_functions(paths, monkeypatch):
    # a behaviour added to the denoise, select or train stage is in `run` too: it calls them
    from thermocomp.shell import chain
    from thermocomp.shell.cli import main

    called = []
    for step in ("denoise_step", "select_step", "train_step"):
        real = getattr(chain, step)
        monkeypatch.setattr(chain, step, lambda *a, _real=real, _step=step, **k:
                            called.append(_step) or _real(*a, **k))
    assert main(["run", *paths["args"]]) == 0
    assert called == ["denoise_step", "select_step", "train_step"]


def _fingerprints(tmp_path, ds, *overrides) -> dict:
    """``ingested_with``, the denoise.json and selection.json fingerprints of a chain run with
    ``overrides``."""
    common = [f"data.path={ds}", f"data.interim={tmp_path / 'interim'}",
              f"data.processed={tmp_path / 'processed'}", f"model_path={tmp_path / 'm/model.pkl'}",
              f"out={tmp_path / 'out'}", *UNTRACKED, *LIGHT, *overrides]
    for stage in CHAIN[:3]:
        cli(stage, *common)
    return {"ingest": json.loads((tmp_path / "interim/ingest_report.json").read_text())["ingested_with"],
            "denoise": json.loads((tmp_path / "processed/denoise.json").read_text())["fingerprint"],
            "select": json.loads((tmp_path / "m/selection.json").read_text())["fingerprint"]}


def test_every_handoff_is_the_dataset_digest_and_a_config_hash(paths, tmp_path):
    from thermocomp.core.io import load_interim
    from thermocomp.core.io.source import open_dataset

    first = _fingerprints(tmp_path / "a", paths["ds"], "model=pcr")
    interim = load_interim(tmp_path / "a/interim").meta["digest"]
    assert first["ingest"]["digest"] == open_dataset(paths["ds"]).meta["digest"]
    assert first["denoise"]["digest"] == first["select"]["digest"] == interim
    for made in first.values():
        assert len(made["config"]) == 64 and {"digest", "config"} <= set(made)
    # the model is no setting of the hand-offs; the targets are select's, not denoise's
    assert _fingerprints(tmp_path / "b", paths["ds"], "model=mlr") == first
    other = _fingerprints(tmp_path / "c", paths["ds"], "model=pcr", "data.targets=[E_X]")
    assert other["ingest"] == first["ingest"] and other["denoise"] == first["denoise"]
    assert other["select"]["digest"] == interim and other["select"]["config"] != first["select"]["config"]


def test_no_stage_reads_data_but_through_the_source():
    # diagnose, promote, fleet and init read data.path by io.read_dataset of their own, and the
    # dataset hash was taken in three places: one door (shell/source.py), one digest
    import ast
    from pathlib import Path

    import thermocomp.shell as shell

    doors = {"read_dataset", "open_dataset", "load_interim", "open_volumetric", "folder_digest"}
    root = Path(shell.__file__).parent
    found = []
    for path in sorted(root.rglob("*.py")):
        if path.name == "source.py" and path.parent == root:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call):
                name = getattr(node.func, "attr", None) or getattr(node.func, "id", None)
                if name in doors:
                    found.append(f"{path.relative_to(root)}:{node.lineno} {name}")
    assert not found, found


def test_an_ingest_recorded_before_the_config_hash_is_refused_saying_so(paths, capsys):
    from conftest import refused
    from thermocomp.shell.cli import main

    assert main(["ingest", *paths["args"]]) == 0
    report = paths["interim"] / "ingest_report.json"
    doc = json.loads(report.read_text())
    settings = doc["ingested_with"]["settings"]
    doc["ingested_with"] = {"path": settings["data.path"], "digest": doc["ingested_with"]["digest"]}
    report.write_text(json.dumps(doc))
    refused(["train", *paths["args"]], capsys, "ingest_report.json", "earlier version",
            "run `thermocomp ingest` with this config first")


def test_an_ingest_recorded_before_a_reading_option_existed_is_refused_naming_it(paths, capsys):
    from conftest import refused
    from thermocomp.shell.cli import main
    from thermocomp.shell.fingerprint import CONFIG, json_hash

    assert main(["ingest", *paths["args"]]) == 0
    report = paths["interim"] / "ingest_report.json"
    doc = json.loads(report.read_text())
    made = doc["ingested_with"]
    del made["settings"]["data.missing_values"]     # as the code before that option wrote it
    made[CONFIG] = json_hash({k: v for k, v in made["settings"].items() if k != "data.path"})
    report.write_text(json.dumps(doc))
    refused(["train", *paths["args"]], capsys, "ingest_report.json",
            "ingested by an earlier version, which had no data.missing_values",
            "run `thermocomp ingest` with this config first")
