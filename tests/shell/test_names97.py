"""One names check for every consumer of a lab's columns (names97, ``bench_names97.py``).

The exported ``stream.c`` took a bare header two columns share but for their unit (``T`` of
``T [°C]`` and ``T [K]``) as its first match, where the served model refuses it naming both;
``monitor.model=`` of another record's model named a campaign's file where ``replay`` says
"fitted on another record", and both named the model's ``T_Spindel``, not the lab's header; a
stream on stdin with a column the record never held was read without a word.  Each case here
fails on b77996ba.
"""

from __future__ import annotations

import io
import subprocess
import sys

import numpy as np
import pandas as pd

from cbuild import compiled
from conftest import FAST, refused
from test_export import _compose, _make_dataset, needs_cc
from thermocomp.shell.cli import main


def _lab_text(rows: int = 48, seed: int = 971, headers=("Zeit", "T", "T", "Temp c", "dX"),
              units=("s", "°C", "K", "°C", "µm")) -> tuple[str, pd.DataFrame]:
    """A lab PC's file (``;``, decimal commas, a unit row) and its rows as written."""
    rng = np.random.default_rng(seed)
    temp = 20 + np.cumsum(rng.normal(0, 0.05, (rows, 3)), axis=0)
    frame = pd.DataFrame({"time": np.arange(rows) * 60.0, "a": temp[:, 0],
                          "b": temp[:, 1] + (273.15 if units[2] == "K" else 0.0), "c": temp[:, 2],
                          "e": 2 * temp[:, 0] - temp[:, 1] + 0.5 * temp[:, 2]}).round(4)
    body = [";".join(f"{v:.4f}".replace(".", ",") for v in r) for r in frame.to_numpy(float)]
    return "".join(f"{ln}\n" for ln in [";".join(headers), ";".join(units), *body]), frame


@needs_cc
def test_stream_c_refuses_a_bare_header_two_columns_share_but_for_their_unit(tmp_path):
    # before: exit 0, the bare 'T' read as its first match, 'T [°C]' (the served model refuses it)
    from omegaconf import OmegaConf

    from thermocomp.apps.deploy.report import plain
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.model_store import save_model
    from thermocomp.shell.source import read_streamed
    from thermocomp.shell.stages.export import export

    text, rows = _lab_text()
    (tmp_path / "lab.csv").write_text(text, encoding="utf-8")
    cfg = _compose(f"data.path={tmp_path / 'lab.csv'}", "data.test_fraction=0.25",
                   "data.delimiter=';'", "data.decimal=','", "data.roles.error=[dX]", "model=mlr",
                   "track=false", "export.format=c", "export.check=false",
                   f"export.model={tmp_path / 'model.pkl'}", f"out={tmp_path / 'code'}")
    OmegaConf.update(cfg, "data.columns", {"T [°C]": "T_a", "T [K]": "T_b"}, force_add=True)
    ds, train, _, _ = read_streamed(cfg, test=False)
    save_model(plain(deployable_model(cfg, ds, train, None, "serve.model")[0]).compensator,
               tmp_path / "model.pkl")
    export(cfg)
    code = tmp_path / "code"
    compiled(code)

    def fed(headers):
        lines = text.splitlines(keepends=True)
        return subprocess.run(["./stream"], cwd=code, capture_output=True,
                              input=(";".join(headers) + "\n" + "".join(lines[2:])).encode())

    joined = fed(["Zeit [s]", "T [°C]", "T [K]", "Temp c [°C]", "dX [µm]"])
    assert joined.returncode == 0 and len(joined.stdout.splitlines()) == 1 + len(rows)
    bare = fed(["Zeit [s]", "T", "T [K]", "Temp c [°C]", "dX [µm]"])
    assert bare.returncode == 2 and not bare.stdout
    assert ("the header (line 1), column 2: 'T' may be 'T [°C]' or 'T [K]': two columns alike "
            "but for their unit") in bare.stderr.decode()


def _other_records_model(tmp_path) -> tuple[str, str]:
    """(data.path of a record, a model.pkl fitted on a lab's file with other headers)."""
    text, _ = _lab_text(headers=("Zeit", "Spindel", "Bett", "Luft", "dX"),
                        units=("s", "°C", "°C", "°C", "µm"))
    (tmp_path / "lab.csv").write_text(text, encoding="utf-8")
    assert main(["run", f"data.path={tmp_path / 'lab.csv'}", "data.test_fraction=0.25",
                 "data.delimiter=;", "data.decimal=,", "data.roles.error=[dX*]", "model=mlr",
                 "plots=none", f"out={tmp_path / 'lab'}", *FAST]) == 0
    return str(_make_dataset(tmp_path / "ds")), str(tmp_path / "lab" / "model.pkl")


def test_monitor_says_another_records_model_as_replay_does_by_the_labs_headers(tmp_path, capsys):
    # before: monitor "file .../K01.csv, column 'T_Spindel': ... 4 of 4 campaigns lack it", replay
    # "the record has none of T_Spindel, ...": the model's names, not the lab's
    data, model = _other_records_model(tmp_path)
    for stage in ("replay", "monitor"):
        refused([stage, f"data.path={data}", f"{stage}.model={model}", f"out={tmp_path / stage}",
                 *FAST], capsys, f"{stage}.model={model} cannot be deployed on data.path={data}",
                "the record has none of 'Spindel [°C]' (read as T_Spindel)",
                "It was fitted on another record")
        assert not (tmp_path / stage).exists()


def test_a_stdin_column_the_record_never_held_is_said_once(tmp_path, capsys, monkeypatch):
    # before: exit 0 without a word of 'Extra [°C]'
    data = _make_dataset(tmp_path / "ds")
    frame = pd.read_csv(data / "K05.csv")
    common = ["monitor", f"data.path={data}", "monitor.input=-", "plots=none", *FAST]
    said = {}
    for name, rows in (("plain", frame), ("extra", frame.assign(**{"Extra [°C]": 21.5}))):
        monkeypatch.setattr(sys, "stdin", io.StringIO(rows.to_csv(index=False)))
        assert main([*common, f"out={tmp_path / name}"]) == 0
        said[name] = [ln for ln in capsys.readouterr().err.splitlines() if "Extra" in ln]
    assert said["plain"] == [] and len(said["extra"]) == 1
    assert "<stdin>: column(s) 'Extra [°C]' not in the data" in said["extra"][0]
    assert "not in the data the model was fitted on: not read" in said["extra"][0]
    assert (tmp_path / "plain" / "monitor.json").read_text() \
        == (tmp_path / "extra" / "monitor.json").read_text()
