"""`thermocomp diagnose` on a probe-cycle record: the error measured on 1 row in N (diagsparse61).

The residual, its screening, the CV errors and the acceptance test's blocks read the measured
rows only; the candidates' features (lags, products, ambient laws) run over every row; the test
blocks are as long as the measured series, at its own spacing, takes to decorrelate.  The
records: 12 year-round campaigns of 3-4 h at 1 min (8 train), one with the undeclared door
planted, one clean; on the dense door record ``diagnose`` accepts the door's lag too, on the dense
clean one nothing (``benchmarks/bench_diagsparse61.py``, seed 1).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from conftest import FAST, PLAIN_DIAGNOSE, UNTRACKED, thermocomp
from thermocomp.apps.sim.probe import probe_cycle_copy
from thermocomp.core.io.read import read_dataset
from thermocomp.core.model_selection.blocks import cut_blocks, decorrelation_length

pytestmark = pytest.mark.slow

RECORD = ("seed=1", "sim.generator.n_campaigns=12", "sim.generator.duration_h=[3.0,4.0]",
          "sim.generator.sample_period_s=60.0")


@pytest.fixture(scope="module")
def records(tmp_path_factory):
    root = tmp_path_factory.mktemp("diagsparse61")
    out = {}
    for name, extra in (("door", ["sim.generator.effects=[door]"]), ("clean", [])):
        thermocomp("simulate", f"data.path={root / name}", *UNTRACKED, *RECORD, *extra)
        out[name] = root / name
    return out


def diagnosed(data, out):
    proc = thermocomp("diagnose", f"data.path={data}", f"out={out}", *UNTRACKED, "plots=none",
                      "diagnose.targets=[E_Y]", *PLAIN_DIAGNOSE, check=False)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return json.loads((out / "diagnosis.json").read_text()), proc


@pytest.mark.parametrize("every", [10, 30])
def test_the_planted_door_is_accepted_on_a_probe_cycle(records, every, tmp_path):
    """The door's lag is accepted from 1 measurement in 10 or 30 rows (18-24 or 6-8 in each
    3-4 h campaign); the test error on the measured rows falls by half at least."""
    data = probe_cycle_copy(records["door"], tmp_path / "data", every)
    j, proc = diagnosed(data, tmp_path / "out")
    accepted = [(e["kind"], e["column"]) for e in j["effects"] if e["accepted"]]
    assert ("signal", "S_door") in accepted
    assert j["after"]["test_rmse"] < 0.5 * j["before"]["test_rmse"]
    cv = j["cv"]
    assert cv["min_p"] <= j["bar"]["alpha"]
    # the blocks count measured samples, and every scored row is a measured one
    assert 0 < cv["measured_rows"]["E_Y"] and "measured samples" in proc.stdout
    # the written config, run on the same record, scores the same "after" on the measured rows
    conf = tmp_path / "out" / "diagnosis" / "conf"
    thermocomp("run", f"hydra.searchpath=[file://{conf}]", "experiment=diagnosed",
               f"data.path={data}", f"out={tmp_path / 'rerun'}", *FAST)
    metrics = json.loads((tmp_path / "rerun" / "metrics.json").read_text())["targets"]["E_Y"]["test"]
    assert metrics["rmse"] == pytest.approx(j["after"]["test_rmse_as_run"], rel=1e-9)
    ds, _ = read_dataset(data)
    assert metrics["measured_rows"] == sum(int(ds.campaigns[c]["E_Y"].notna().sum())
                                           for c in ds.ids("test")) < metrics["rows"] / 2


def test_a_clean_probe_cycle_accepts_nothing(records, tmp_path):
    """No effect on a clean record at 1 in 10, where the test could reach alpha (min_p)."""
    j, _ = diagnosed(probe_cycle_copy(records["clean"], tmp_path / "data", 10), tmp_path / "out")
    assert j["cv"]["min_p"] <= j["bar"]["alpha"]
    assert not [e for e in j["effects"] if e["accepted"]]
    assert j["after"]["test_rmse"] == j["before"]["test_rmse"]


def test_blocks_of_a_probe_cycle_hold_measurements_at_its_own_spacing():
    """An AR(1) residual measured on 1 row in 5: its runs are the campaigns, not each lone
    measurement (which gave one-sample blocks and a length of 1 whatever its memory); the
    length is in measured samples and each test block holds that many."""
    rng = np.random.default_rng(0)
    n, every, phi = 4000, 5, 0.98                  # memory of ~80 rows: ~16 measured samples
    r = np.zeros(n)
    for i in range(1, n):
        r[i] = phi * r[i - 1] + rng.normal()
    measured = np.arange(n) % every == 0
    campaigns = np.repeat(["a", "b"], n // 2)
    dense = decorrelation_length(r, campaigns, np.ones(n, bool))
    sparse_r = np.where(measured, r, np.nan)
    length = decorrelation_length(sparse_r, campaigns, measured, np.ones(n, bool))
    assert length > 1 and abs(length * every - dense) <= every
    blocks = cut_blocks(np.zeros(n, int), campaigns, length, scored=measured)
    assert (blocks[~measured] == -1).all() and (blocks[measured] >= 0).all()
    counts = np.bincount(blocks[measured])
    assert counts.min() >= length and counts.max() < 2 * length
