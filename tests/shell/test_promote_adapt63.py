"""A run promoted with ``adapt.method`` (sweepdvc63): the version's test figures "as deployed"
are those of the model that is served, which learns from the probe, as ``replay`` scores it.
They were the frozen stream's: ``adapt.method=bias`` and ``rls`` versions of one run were
tagged with the figures of ``adapt.method=none``."""

from __future__ import annotations

import json

import numpy as np
import pytest

from conftest import thermocomp
from test_deploy import LIGHT_EVAL, mlflow_store

pytestmark = pytest.mark.slow


def test_promote_scores_the_adaptation_it_deploys(tmp_path):
    data = tmp_path / "lathe"      # 80 h of train, 24 h of test, the probe every 5 min
    thermocomp("simulate", "sim=swiss_lathe_door", "seed=6321", f"data.path={data}", "track=false")
    uri, sweep = mlflow_store(tmp_path), tmp_path / "sweep"
    thermocomp("run", "-m", "model=mlr", f"data.path={data}", f"tracking_uri={uri}", *LIGHT_EVAL,
               f"hydra.sweep.dir={sweep}")
    thermocomp("promote", f"data.path={data}", f"tracking_uri={uri}", f"compare.sweep={sweep}",
               "adapt.method=bias", f"out={tmp_path / 'promoted'}")
    promoted = json.loads((tmp_path / "promoted/promote.json").read_text())
    thermocomp("replay", f"replay.model={sweep / '0/model.pkl'}", f"data.path={data}",
               "adapt.method=bias", "track=false", f"out={tmp_path / 'replayed'}")
    replayed = json.loads((tmp_path / "replayed/replay.json").read_text())["targets"]
    adapted = np.mean([r["rmse"] for r in replayed.values()])
    frozen = np.mean([r["adapt"]["rmse_frozen"] for r in replayed.values()])
    assert abs(adapted - frozen) > 1e-3, replayed          # the adaptation moves the figure ...
    # ... and the version is tagged with the adapted one (was the frozen one)
    assert promoted["candidate"]["test_reported"]["rmse"] == pytest.approx(adapted, rel=1e-9)
