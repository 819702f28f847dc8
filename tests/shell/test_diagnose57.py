"""`thermocomp diagnose` as a stranger meets it (diagstr57): `model=auto` refused before any
search, and the ATI wrapper named in what the stage prints."""

from __future__ import annotations

import pytest

from conftest import PLAIN_DIAGNOSE

pytestmark = pytest.mark.slow


def test_model_auto_is_refused_before_the_search_naming_what_to_diagnose(short_door_dataset,
                                                                         tmp_path, capsys):
    # before: the whole search ran, then fitting the diagnosed model raised a TypeError
    # (auto's unbuilt candidates could not be cloned): a traceback, exit 1
    from thermocomp.shell.cli import main
    code = main(["diagnose", f"data.path={short_door_dataset}", f"out={tmp_path}", "track=false",
                 "plots=none", "model=auto", "model.candidates=[mlr,pcr]",
                 "diagnose.targets=[E_Y]", "diagnose.max_effects=1"])
    err = capsys.readouterr().err
    assert code == 2
    assert "model=auto is not diagnosed" in err and "model=<family>" in err
    assert "model=<family> ati=cmeans" in err     # an ATI candidate is no model= (diag106c)
    assert "Traceback" not in err and not (tmp_path / "diagnosis.json").exists()


def test_the_ati_wrapper_is_named_in_the_printed_header(short_door_dataset, tmp_path, capsys):
    # before: `ati=cmeans` printed `model=mlr`, as the plain MLR's diagnosis does
    from thermocomp.shell.cli import main
    assert main(["diagnose", f"data.path={short_door_dataset}", f"out={tmp_path}", "track=false",
                 "plots=none", "ati=cmeans", "diagnose.targets=[E_Y]", "diagnose.families=[signal]",
                 "diagnose.max_effects=1", *PLAIN_DIAGNOSE]) == 0
    said = capsys.readouterr()
    assert "model=mlr ati=cmeans  dataset=" in said.out
    assert "diagnosing mlr ati=cmeans (" in said.err
    # and what it writes (diagnosis.json said "model": "mlr" only, as a plain MLR's)
    import json
    written = json.loads((tmp_path / "diagnosis.json").read_text())
    assert (written["model"], written["ati"]) == ("mlr", "cmeans")
    report = (tmp_path / "diagnosis" / "report.md").read_text()
    assert report.startswith("# Residual diagnosis: mlr ati=cmeans on ")
