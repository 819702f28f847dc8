"""`thermocomp init` proposes a text column naming a lab's runs, as it proposes one numbering them
(deploy57).

A lab's long file whose run column holds labels (``Versuch`` K01, K02 ...) rather than numbers
was written into the config as ``ignore``: `run` then read the runs as one record (warning
"runs joined in one file?") and cut its test part inside the last run, where the same runs
numbered 1, 2 ... were proposed as ``data.roles.campaign`` and read one campaign each.
"""

from __future__ import annotations

import pandas as pd
import yaml

from test_run_column52 import _runs
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main


def _labelled(path, runs, labels, header="Versuch"):
    pd.concat([r.assign(**{header: lab})[[header, *r.columns]] for lab, r in zip(labels, runs)]
              ).to_csv(path, sep=";", decimal=",", index=False)
    return path


def _init(tmp_path, path) -> dict:
    assert main(["init", str(path), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"]) == 0
    return yaml.safe_load((tmp_path / "init" / "conf" / "data" / f"{path.stem}.yaml").read_text())


def test_init_proposes_a_column_of_run_labels_and_its_config_reads_the_runs(tmp_path, capsys):
    runs = _runs()
    path = _labelled(tmp_path / "alle.csv", runs, ["V-01", "V-02", "V-03", "V-04"])
    config = _init(tmp_path, path)
    assert config["roles"]["campaign"] == "Versuch" and "Versuch" not in config["roles"]["ignore"]
    assert "campaign V-04: test" in capsys.readouterr().out
    ds, _ = read_dataset(path, {"roles": config["roles"], "test_fraction": 0.25})
    assert list(ds.campaigns) == ["V-01", "V-02", "V-03", "V-04"]
    assert [len(ds.campaigns[c]) for c in ds.campaigns] == [len(r) for r in runs]


def test_a_comment_or_a_label_that_comes_back_is_left_out_as_before(tmp_path):
    # one clock over the runs: read as one record, as before (no run column to split them)
    runs = [r.assign(**{"Zeit [s]": r["Zeit [s]"] + k * 86400.0}) for k, r in enumerate(_runs())]
    notes = _labelled(tmp_path / "notes.csv", runs, ["warm", "kalt", "warm2", "kalt2"],
                      header="Bemerkung")
    assert _init(tmp_path / "a", notes)["roles"].get("campaign") is None
    back = _labelled(tmp_path / "back.csv", runs, ["K1", "K2", "K1", "K3"])
    assert _init(tmp_path / "b", back)["roles"].get("campaign") is None


def test_the_rule_reads_the_header_and_the_labels():
    from thermocomp.core.io.runs import looks_like_run_labels

    rows = ["K01"] * 12 + ["K02"] * 12
    assert looks_like_run_labels(rows, "Versuch")
    assert looks_like_run_labels(rows, "Run ID [-]")
    assert not looks_like_run_labels(rows, "Bemerkung")            # no run word
    assert not looks_like_run_labels(["K01"] * 24, "Versuch")     # one run
    assert not looks_like_run_labels(["K01", "K02"] * 12, "Versuch")   # labels coming back
    assert not looks_like_run_labels(["K01"] * 5 + ["K02"] * 5, "Versuch")  # too few rows a run
    assert not looks_like_run_labels(rows[:-1] + [None], "Versuch")    # a row without its run
