"""A run's ``model.pkl`` served continues a campaign as the registered model does (deploy57).

`thermocomp serve serve.model=<run>/model.pkl` (the README's served route) makes the model
deployable on the train split of ``data.path``, as ``replay`` does, but held no campaign's end
state: a test campaign that continues the train record (``continues``, docs/sweeps.md) was
refused with "the model holds no end state of that campaign (it holds: none)", where the
registered model of the same run continues it as ``run`` scores it.  Now the served model.pkl
holds the end states of ``data.path``'s campaigns, as ``promote`` records them.
"""

from __future__ import annotations

import numpy as np
import pytest

from test_deployed_as_scored import INPUTS, PLAIN, _stage, _test_file, record  # noqa: F401 (fixture)
from thermocomp.apps.deploy.pyfunc import CompensatorModel
from thermocomp.shell.cli import _compose
from thermocomp.shell.config.overrides import lenient
from thermocomp.shell.stages.serve import _deployed


def test_a_served_model_pkl_continues_the_train_record_as_run_scores_it(record, tmp_path):  # noqa: F811
    run = _stage("run", record, tmp_path / "run", "model=lagbank")
    pkl = tmp_path / "run" / "model.pkl"
    cfg = _compose(lenient([f"data.path={record}", *PLAIN, "track=false"]), "serve")
    served = CompensatorModel(_deployed(cfg, str(pkl)))
    assert sorted(served.streaming.end_states_) == ["A", "B"]
    lab = _test_file(record)
    out = served.predict(None, lab[INPUTS], {"session": "machine", "continues": "A"})
    for t, m in run["targets"].items():  # the correction C = -Ê leaves run's test error
        left = lab[t[2:]].to_numpy() + out["C_" + t[2:]].to_numpy()
        assert np.sqrt(np.mean(left ** 2)) == pytest.approx(m["test"]["rmse"], rel=0.01)
