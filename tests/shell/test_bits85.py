"""A model fitted on a record whose states come from a PLC status word (``data.bits``, lab83)
deployed as scored (bits85): the served model takes the lab's own rows, the word in them, and
decodes it as the reader did (the declaration travels with the model, as its column names do);
the exported ``stream.c`` reads each bit as a column of its own, as ``thermocomp rows`` writes
them, or the word in their place, decoded as served decodes it (lead91; bits85 refused it); ``replay`` and
``export`` of the registered model decode the word by its declaration where no data.bits is given
(data86), and refuse one given that is not the model's."""

from __future__ import annotations

import io
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from conftest import refused
from test_deploy import mlflow_store
from thermocomp.shell.cli import main

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
import bench_bits85  # noqa: E402 (the record's writer, shared with its bench)

BITS = {0: "machine_on", 1: "spindle_on", 2: "coolant_on"}


def _runs(folder, seeds=(8931, 8932, 8933, 8934)):
    """Four runs of a machine whose spindle and coolant, logged as bits 1 and 2 of ``Status``
    (bit 7 a ready flag), drive its heat and its error (benchmarks/bench_bits85.py writes them)."""
    bench_bits85.write(folder, list(seeds))
    return folder


@pytest.fixture(scope="module")
def promoted(tmp_path_factory):
    """The record run (hammerstein, the bits declared), promoted from a tracking store."""
    import mlflow

    root = tmp_path_factory.mktemp("bits85")
    folder = _runs(root / "runs")
    data = [f"data.path={folder}", "data.roles.error=[dX*]", "data.roles.state=[Status]",
            "data.test_fraction=0.25", *(f"++data.bits.Status.{b}={n}" for b, n in BITS.items())]
    uri = mlflow_store(root)
    light = ["model=hammerstein", "plots=none", "eval.mutual_prediction=false",
             "eval.ati_baselines=false", "eval.iso10791_a3=false", f"tracking_uri={uri}"]
    assert main(["run", *data, *light, f"out={root / 'run'}"]) == 0
    mlflow.set_tracking_uri(uri)
    run_id = mlflow.search_runs(experiment_names=["thermocomp"])["run_id"].iloc[0]
    assert main(["promote", *data, *light, f"promote.run_id={run_id}",
                 f"out={root / 'promote'}"]) == 0
    report = json.loads((root / "promote" / "promote.json").read_text())
    return {"root": root, "data": data, "uri": uri, "model_uri": report["model_uri"],
            "lab": pd.read_csv(folder / "run3.csv").astype(float)}


def _rows(promoted, capsys) -> pd.DataFrame:
    """run3 as ``thermocomp rows`` writes it: the word decoded by the reader."""
    capsys.readouterr()
    assert main(["rows", *promoted["data"], "rows.campaigns=[run3]"]) == 0
    return pd.read_csv(io.StringIO(capsys.readouterr().out))


def test_the_served_model_decodes_the_labs_word_as_the_reader(promoted, capsys):
    """Before, the lab's rows were refused 'input lacks column(s) ['S_machine_on', ...]' (MLflow
    had dropped ``Status`` as an input the signature lacks)."""
    import mlflow
    from mlflow.exceptions import MlflowException

    mlflow.set_tracking_uri(promoted["uri"])
    model = mlflow.pyfunc.load_model(promoted["model_uri"])
    rows = _rows(promoted, capsys)
    assert "Status" not in rows.columns and "S_spindle_on" in rows.columns
    decoded = model.predict(rows, params={"reset": True})["C_dX"].to_numpy()
    lab = model.predict(promoted["lab"], params={"reset": True})["C_dX"].to_numpy()
    assert np.abs(decoded).max() > 1.0
    np.testing.assert_allclose(lab, decoded, rtol=0, atol=1e-9)
    # a word that is no whole number: refused naming the column and the row of the block
    bad = promoted["lab"].copy()
    bad.loc[7, "Status"] = 130.5
    said = r"^column 'Status', data row 8 of the block: value 130.5 is no whole number"
    with pytest.raises(MlflowException, match=said):
        model.predict(bad, params={"reset": True})
    with pytest.raises(MlflowException, match="gives the status word and its bit S_spindle_on"):
        model.predict(promoted["lab"].assign(S_spindle_on=1.0), params={"reset": True})


@pytest.fixture(scope="module")
def stream_c(promoted, tmp_path_factory):
    """The promoted model exported as C (no pack) and built: the folder."""
    if shutil.which("gcc") is None:
        pytest.skip("no C compiler")
    out = tmp_path_factory.mktemp("c")
    assert main(["export", *promoted["data"], f"export.model={promoted['model_uri']}",
                 f"tracking_uri={promoted['uri']}", "export.format=c", "export.check=false",
                 f"out={out}"]) == 0
    compiled(out)
    return out


def test_the_c_stream_takes_the_rows_as_served_and_the_word_as_served(promoted, stream_c,
                                                                       capsys):
    """The rows as ``thermocomp rows`` writes them (each bit a column) and the lab's own rows (the
    word): both streamed as served (before, lead91: the word refused, "this code does not decode
    the word")."""
    import mlflow

    rows = _rows(promoted, capsys)
    mlflow.set_tracking_uri(promoted["uri"])
    model = mlflow.pyfunc.load_model(promoted["model_uri"])
    lab = promoted["lab"]
    for fed_rows in (rows, lab):
        fed = subprocess.run(["./stream"], cwd=stream_c, input=fed_rows.to_csv(index=False),
                             capture_output=True, text=True)
        assert fed.returncode == 0, fed.stderr
        served = model.predict(fed_rows, params={"reset": True})
        np.testing.assert_allclose(pd.read_csv(io.StringIO(fed.stdout))["C_dX"],
                                   served["C_dX"], rtol=0, atol=1e-9)


def _streamed(stream_c, rows: pd.DataFrame) -> subprocess.CompletedProcess:
    return subprocess.run(["./stream"], cwd=stream_c, input=rows.to_csv(index=False),
                          capture_output=True, text=True)


def test_the_c_stream_refuses_a_word_that_is_none_as_served(promoted, stream_c):
    lab = promoted["lab"].copy()
    column = list(lab.columns).index("Status") + 1
    lab.loc[7, "Status"] = 130.5            # the block's data row 8, the file's line 9
    bad = _streamed(stream_c, lab)
    # (a stream: the rows above it corrected, as for any cell that is no number)
    assert bad.returncode == 2 and len(bad.stdout.splitlines()) == 1 + 7
    assert (f"stream: line 9, column {column} ('Status'): value 130.5 is no whole number >= 0: "
            "no status word (data.bits)") in bad.stderr
    both = _streamed(stream_c, promoted["lab"].assign(S_spindle_on=1.0))
    assert both.returncode == 2 and not both.stdout
    assert "gives the status word 'Status'" in both.stderr and "S_spindle_on" in both.stderr
    neither = _streamed(stream_c, promoted["lab"].drop(columns="Status"))
    assert neither.returncode == 2 and not neither.stdout
    said = re.search(r"lacks input column (S_\w+), bit (\d+) of the PLC status word 'Status' "
                     r"\(data.bits\), and the word", neither.stderr)
    assert said, neither.stderr
    assert said[1] == f"S_{BITS[int(said[2])]}"


def _replayed(promoted, name: str, *data: str) -> float:
    out = promoted["root"] / name
    assert main(["replay", *data, f"replay.model={promoted['model_uri']}",
                 f"tracking_uri={promoted['uri']}", f"out={out}"]) == 0
    return json.loads((out / "replay.json").read_text())["targets"]["E_dX"]["rmse"]


@pytest.fixture(scope="module")
def keyed(promoted) -> float:
    """The registered model replayed with data.bits given: its RMSE (two tests read it)."""
    return _replayed(promoted, "replay-keyed", *promoted["data"])


def test_a_replay_without_the_declaration_decodes_the_word_as_the_model_declares_it(promoted, keyed):
    """The registered model replayed on a data config without data.bits: the word decoded by
    the declaration the model carries, as with the key (data86; before: refused, "lacks 3
    columns the deployed model reads ... give data.bits={Status: ...}")."""
    data = [d for d in promoted["data"] if not d.startswith("++data.bits")]
    assert _replayed(promoted, "replay-bare", *data) == keyed


def _monitored(promoted, name: str, *args: str, model: str | None = None) -> float:
    out = promoted["root"] / name
    assert main(["monitor", *args, f"monitor.model={model or promoted['model_uri']}",
                 "plots=none", f"tracking_uri={promoted['uri']}", f"out={out}"]) == 0
    return json.loads((out / "monitor.json").read_text())["targets"]["E_dX"]["rmse_fixed"]


def test_a_monitor_of_the_registered_model_decodes_the_word_as_the_model_declares_it(
        promoted, keyed, monkeypatch):
    """``monitor monitor.model=models:/...`` (and its pyfunc folder) without data.bits, on the
    record's test run and on the lab's run3.csv piped in: the word decoded by the model's
    declaration, its fixed stream the one replay scores (data86b; before: refused, "a model.pkl
    file ...; a registered model replays through replay.model=...")."""
    import mlflow

    data = [d for d in promoted["data"] if not d.startswith("++data.bits")]
    scored = keyed                  # the replay with data.bits given
    assert _monitored(promoted, "monitor-bare", *data) == pytest.approx(scored, rel=1e-9)
    mlflow.set_tracking_uri(promoted["uri"])
    folder = mlflow.artifacts.download_artifacts(artifact_uri=promoted["model_uri"],
                                                 dst_path=str(promoted["root"] / "pyfunc"))
    assert _monitored(promoted, "monitor-folder", *data, model=folder) == pytest.approx(
        scored, rel=1e-9)
    monkeypatch.setattr(sys, "stdin", io.StringIO((promoted["root"] / "runs" / "run3.csv")
                                                  .read_text()))
    assert _monitored(promoted, "monitor-stdin", *data, "monitor.input=-") == pytest.approx(
        scored, rel=1e-9)


@pytest.mark.parametrize("stage", ["replay", "export", "monitor"])
def test_a_declaration_given_that_is_not_the_models_is_refused_naming_both(promoted, capsys,
                                                                            stage):
    data = [d for d in promoted["data"] if not d.startswith("++data.bits")]
    # its bits 1 and 2 swapped: every state the model reads is there, each the other's (before:
    # read so, the spindle taken for the coolant without a word)
    other = [*data, "++data.bits.Status.0=machine_on", "++data.bits.Status.1=coolant_on",
             "++data.bits.Status.2=spindle_on"]
    extra = ["export.format=c", "export.check=true"] if stage == "export" else []
    refused([stage, *other, f"{stage}.model={promoted['model_uri']}",
             f"tracking_uri={promoted['uri']}", *extra,
             f"out={promoted['root'] / ('other-' + stage)}"], capsys,
            f"data.bits={{Status: {{0: machine_on, 1: coolant_on, 2: spindle_on}}}} is not the "
            f"declaration {stage}.model={promoted['model_uri']} was fitted with, data.bits="
            "{Status: {0: machine_on, 1: spindle_on, 2: coolant_on}}: a status word is read as "
            "the model reads it")


def test_the_check_pack_of_an_export_without_the_declaration_decodes_the_word(promoted):
    """``export export.check=true`` of the registered model, no data.bits: its pack holds the
    test run, the word decoded as the model declares it (before: refused, "lacks 3 columns")."""
    data = [d for d in promoted["data"] if not d.startswith("++data.bits")]
    out = promoted["root"] / "c-bare"
    assert main(["export", *data, f"export.model={promoted['model_uri']}",
                 f"tracking_uri={promoted['uri']}", "export.format=c", "export.check=true",
                 f"out={out}"]) == 0
    pack = json.loads((out / "check" / "check.json").read_text())
    first = pack["campaigns"][0]
    assert (first["campaign"], first["rows"]) == ("run3", len(promoted["lab"]))
