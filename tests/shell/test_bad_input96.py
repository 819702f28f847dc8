"""Bad input a stranger hands in, as ``benchmarks/bench_badin96.py`` swept it (badin96).

A ``data.roles`` pattern given to ``init`` that matches no header was kept in the config
written, naming nothing, exit 0; a ``model.pkl`` one of whose columns a train campaign lacks was
refused by ``replay`` / ``monitor`` naming the campaign's id alone, not its file."""

from __future__ import annotations

import pandas as pd

from conftest import FAST, refused
from test_hostile import make_dataset
from thermocomp.shell.cli import main


def test_init_refuses_a_role_pattern_that_matches_no_header(tmp_path, capsys):
    # before: exit 0, 'zz*' written into data.roles.error beside the detected dX
    lab = tmp_path / "lab.csv"
    t = [60.0 * i for i in range(40)]
    pd.DataFrame({"Zeit [s]": t, "T1 [°C]": [20 + 0.01 * s / 60 for s in t],
                  "dX [µm]": [0.05 * s / 60 for s in t]}).to_csv(lab, index=False)
    out = tmp_path / "out"
    refused(["init", str(lab), "data.roles.error=[zz*]", f"out={out}"], capsys,
            f"file {lab}", "data.roles.error=['zz*'] matches no column", "dX [µm]")
    assert not out.exists()
    assert main(["init", str(lab), "data.roles.error=[dX*]", f"out={out}"]) == 0


def test_a_model_whose_column_a_train_campaign_lacks_is_refused_naming_its_file(tmp_path, capsys):
    # before: 'replay.model=... cannot be deployed: column 'T_0': 1 of 3 campaigns lack it (K02)'
    ds = make_dataset(tmp_path / "ds")
    run = tmp_path / "run"
    assert main(["run", f"data.path={ds}", f"out={run}", *FAST]) == 0
    frame = pd.read_csv(ds / "K02.csv")
    frame.drop(columns="T_0").to_csv(ds / "K02.csv", index=False)
    for stage in ("replay", "monitor"):
        out = tmp_path / stage
        refused([stage, f"data.path={ds}", f"{stage}.model={run / 'model.pkl'}", f"out={out}",
                 *FAST], capsys, f"file {ds / 'K02.csv'}", "column 'T_0'",
                f"{stage}.model={run / 'model.pkl'} cannot be deployed")
        assert not out.exists()
