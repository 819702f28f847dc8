"""The denoise -> select -> train -> evaluate chain through the command line (in process).

The staged path (files under data/processed and models/) and `thermocomp run` (all in one
process) must give the same model, and train must not reuse files made for other settings.
"""

import json
import pickle

import numpy as np
import pytest

from conftest import LIGHT, UNTRACKED, thermocomp

pytestmark = pytest.mark.slow

FAST = [*UNTRACKED, *LIGHT]   # validation kept


@pytest.fixture(scope="session")
def interim(short_dataset, tmp_path_factory):
    """The short dataset (EMD costs with the length of the records), ingested once for this
    module."""
    path = tmp_path_factory.mktemp("ingested") / "interim"
    thermocomp("ingest", f"data.path={short_dataset}", f"data.interim={path}", "track=false")
    return path


def _common(short_dataset, interim, tmp_path):
    return [f"data.path={short_dataset}", f"data.interim={interim}",
            f"data.processed={tmp_path / 'processed'}", f"model_path={tmp_path / 'm/model.pkl'}",
            f"out={tmp_path / 'rep'}", *FAST]


def _load(path):
    with open(path, "rb") as f:
        return pickle.load(f)


def test_staged_chain_and_run_give_the_same_model(short_dataset, interim, tmp_path):
    common = [*_common(short_dataset, interim, tmp_path), "denoise=emd", "select=pearson",
              "model=pcr"]
    for stage in ("denoise", "select"):       # plots=none draws nothing, in every stage
        thermocomp(stage, *common)
        assert list((tmp_path / "rep" / stage).iterdir()) == []
    for stage in ("denoise", "select", "train", "evaluate"):
        thermocomp(stage, *common, *(["plots=summary"] if stage in ("denoise", "select") else []))
    processed = tmp_path / "processed"
    report = json.loads((processed / "denoise.json").read_text())
    assert (processed / "denoiser.pkl").is_file() and (processed / "campaigns.csv").is_file()
    assert set(report["causal_vs_offline_rms_c"]) == set(report["denoised"])
    assert all(v > 0 for v in report["removed_rms_c"].values())
    figs = sorted(p.name for p in (tmp_path / "rep/denoise").iterdir())
    assert any(f.startswith("imfs_") for f in figs) and any(f.startswith("raw_vs_") for f in figs)
    assert (tmp_path / "rep/select/selection.png").stat().st_size > 10_000
    selection = json.loads((tmp_path / "m/selection.json").read_text())
    for entry in selection["targets"].values():
        assert len(entry["selected"]) == 2
        top = sorted(entry["scores"], key=entry["scores"].get, reverse=True)[:2]
        assert entry["selected"] == top

    proc = thermocomp("run", *common, f"out={tmp_path / 'run'}")
    assert "RMS before" in proc.stdout
    staged, direct = _load(tmp_path / "m/model.pkl"), _load(tmp_path / "run/model.pkl")
    assert staged.selected_ == direct.selected_
    for t in staged.targets_:
        assert staged.selected_[t] == selection["targets"][t]["selected"]
        np.testing.assert_array_equal(staged.estimators_[t].coef_, direct.estimators_[t].coef_)
    np.testing.assert_array_equal(staged.denoiser_.fir_, direct.denoiser_.fir_)
    m_staged = json.loads((tmp_path / "rep/metrics.json").read_text())
    m_run = json.loads((tmp_path / "run/metrics.json").read_text())
    assert m_staged["dataset"] == m_run["dataset"] == short_dataset.name  # not the interim's
    for t in staged.targets_:
        assert m_staged["targets"][t]["test"]["rsd_mean"] == m_run["targets"][t]["test"]["rsd_mean"]
        assert m_run["targets"][t]["test"]["rms_after"] < 0.5 * m_run["targets"][t]["test"]["rms_before"]

    # settings changed without rerunning select / denoise: train ignores the stale files
    proc = thermocomp("train", *common, "select=greedy_residual", "denoise=none")
    assert "selecting again" in proc.stderr and "ignoring it" in proc.stderr
    fresh = _load(tmp_path / "m/model.pkl")
    assert fresh.denoiser_ is None
    assert any(len(v) != 2 for v in fresh.selected_.values())


def test_select_stage_without_denoise_stage_and_bad_config(short_dataset, interim, tmp_path):
    common = _common(short_dataset, interim, tmp_path)
    thermocomp("select", *common, "select=cluster_grey", "denoise=emd")
    sel = json.loads((tmp_path / "m/selection.json").read_text())
    for entry in sel["targets"].values():
        assert entry["criterion"]["name"] == "bicc" and entry["clusters"]
        assert len(entry["selected"]) == len({entry["clusters"][s] for s in entry["selected"]})
    bad = thermocomp("denoise", *common, "denoise=emd", "denoise.denoiser.stopping=never",
                     check=False)
    assert bad.returncode == 2 and "stopping" in bad.stderr
    bad = thermocomp("select", *common, "select=greedy_residual", "select.selector.k=0",
                     check=False)
    assert bad.returncode == 2 and "select.selector.k=0: must be null or an integer >= 1" in bad.stderr
