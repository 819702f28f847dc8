"""audit96b: a run's model.pkl deployed on a record it was not fitted on.

``thermocomp serve serve.model=reports/fl_thermal/model.pkl`` (the README's measured record's
model, served as the README serves ``make run``'s) read the default dataset, whose columns it
has none of, and said "column 'T_t1': 16 of 16 campaigns lack it ...; give it to all of them or
leave it out of data.inputs": advice for a faulty record, where the data config was missing.
"""

from __future__ import annotations

import pandas as pd

from conftest import FAST
from test_choose_by_simulation import drift_and_fast
from thermocomp.shell.cli import main


def test_a_model_pkl_deployed_on_another_record_says_it_was_fitted_on_another(tmp_path, capsys):
    """Fails on 324eb8b2 (the message advised leaving ``T_1`` out of data.inputs)."""
    fitted = drift_and_fast(tmp_path / "fitted")
    other = tmp_path / "other"
    other.mkdir()
    for csv in fitted.glob("*.csv"):
        frame = pd.read_csv(csv)
        frame.rename(columns={"T_1": "T_a", "T_2": "T_b"}).to_csv(other / csv.name, index=False)
    run = tmp_path / "run"
    assert main(["run", f"data.path={fitted}", f"out={run}", *FAST]) == 0
    capsys.readouterr()
    for stage, key in (("replay", "replay.model"), ("export", "export.model")):
        assert main([stage, f"{key}={run / 'model.pkl'}", f"data.path={other}",
                     f"out={tmp_path / stage}", "track=false"]) == 2
        said = capsys.readouterr().err
        assert "none of T_1, T_2" in said and "fitted on another record" in said, said
        assert "data.inputs" not in said
        assert not (tmp_path / stage).exists() or not any((tmp_path / stage).iterdir())
    # the record it was fitted on deploys
    assert main(["replay", f"replay.model={run / 'model.pkl'}", f"data.path={fitted}",
                 f"out={tmp_path / 'ok'}", "track=false"]) == 0
