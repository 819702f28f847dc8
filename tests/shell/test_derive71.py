"""Derived targets, ``data.derive`` (extension, derive71): an ISO 230-3 rig's tilt from two probes,
``(E_X1 - E_X2) / 0.1`` (µm over 0.1 m: µm/m), computed as each campaign is read and then a
target like a measured one.  Scored by ``run`` it equals the same model on files whose lab
computed the column by hand, ``replay`` equals ``run`` for it, a stream's (stdin's) rows and a
served block's reference measurement give it by the same arithmetic; a bad expression is
refused naming the key, exit 2, nothing written (``benchmarks/bench_derive71.py``: catman70's
rig_a in full, with the C pack)."""

from __future__ import annotations

import copy
import io
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml
from omegaconf import OmegaConf

from conftest import FAST, ROOT, refused
from test_stranger68 import ROWS, linear_run
from thermocomp.apps.deploy import StreamingCompensator
from thermocomp.apps.deploy.adapt import from_config
from thermocomp.apps.deploy.pyfunc import CompensatorModel
from thermocomp.core.compensator import Compensator
from thermocomp.core.io import ReadOptions, read_dataset
from thermocomp.core.io.stdin import read_stream
from thermocomp.core.models.linear import MLR
from thermocomp.shell.cli import main

TILT = "(E_X1 - E_X2) / 0.1"
DERIVE = {"E_tilt_X": TILT}
OVERRIDE = f"data.derive={{E_tilt_X: '{TILT}'}}"


def _folder(root: Path, hand: bool = False, probed: tuple | None = None) -> Path:
    """Three runs of two probes 100 mm apart (three temperatures); ``hand``: with the tilt
    column the lab computed, every digit kept; ``probed``: ``(every, first row)`` of each probe
    measured now and then, a probe cycle (``data.sparse_targets``)."""
    root.mkdir()
    for run in (1, 2, 3):
        temps, dx, dz = np.split(linear_run(7181, run), [3, 4], axis=1)
        frame = pd.DataFrame(np.round(temps, 3), columns=["T_a", "T_b", "T_c"])
        frame.insert(0, "time", 30.0 * np.arange(ROWS))
        frame["E_X1"], frame["E_X2"] = np.round(dx[:, 0], 3), np.round(0.4 * dx[:, 0] + dz[:, 0], 3)
        for probe, (every, first) in zip(["E_X1", "E_X2"], probed or ()):
            frame.loc[np.arange(ROWS) % every != first, probe] = np.nan
        if hand:
            frame["E_tilt_X"] = (frame["E_X1"] - frame["E_X2"]) / 0.1
        frame.to_csv(root / f"run{run}.csv", index=False, float_format="%.17g")
    return root


def _figures(entry, out=None) -> list[float]:
    """The numbers of a metrics.json entry, in order."""
    out = [] if out is None else out
    for value in (entry.values() if isinstance(entry, dict) else entry):
        if isinstance(value, (dict, list)):
            _figures(value, out)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            out.append(float(value))
    return out


def test_a_derived_tilt_scores_as_the_lab_computed_column_and_replay_equals_run(tmp_path):
    """Before: 'unknown config key data.derive' (exit 2): the lab computed it in its logger."""
    data = ["data.test_fraction=0.3", *FAST]
    derived, hand = _folder(tmp_path / "lab"), _folder(tmp_path / "hand", hand=True)
    assert main(["run", f"data.path={derived}", OVERRIDE, *data, f"out={tmp_path / 'a'}"]) == 0
    assert main(["run", f"data.path={hand}", *data, f"out={tmp_path / 'b'}"]) == 0
    a, b = (json.loads((tmp_path / o / "metrics.json").read_text())["targets"] for o in "ab")
    assert list(a) == ["E_X1", "E_X2", "E_tilt_X"] == list(b)
    np.testing.assert_allclose(_figures(a["E_tilt_X"]), _figures(b["E_tilt_X"]), atol=1e-9, rtol=0)
    assert a["E_tilt_X"]["test"]["rms_before"] > 10 * a["E_tilt_X"]["test"]["rmse"]
    assert main(["replay", f"data.path={derived}", OVERRIDE, "data.test_fraction=0.3",
                 f"replay.model={tmp_path / 'a' / 'model.pkl'}", "track=false",
                 "promote.envelope.policy=off",        # (run 3 warms beyond the train runs)
                 f"out={tmp_path / 'replay'}"]) == 0
    replay = json.loads((tmp_path / "replay" / "replay.json").read_text())["targets"]
    assert abs(replay["E_tilt_X"]["rmse"] - a["E_tilt_X"]["test"]["rmse"]) < 1e-9


@pytest.mark.parametrize("expression, says", [
    ("(E_X1 - T_a) / 0.1", "data.derive.E_tilt_X: T_a is a temperature"),
    ("(E_X1 - E_X2 / 0.1", "data.derive.E_tilt_X: '(E_X1 - E_X2 / 0.1' is no expression"),
    ("(E_X1 - E_X2) / (0.1 - 0.1)", "data.derive.E_tilt_X: divides by zero (0.1 - 0.1)"),
    ("E_X1 ** 2", "data.derive.E_tilt_X: only + - * / and parentheses"),
    ("(E_X1 - E_Y2) / 0.1", "run1.csv: data.derive.E_tilt_X: the campaign has no column E_Y2 "
                            "(its error columns, contract names: E_X1, E_X2)")])
def test_a_bad_expression_is_refused_naming_the_key_and_nothing_is_written(tmp_path, capsys,
                                                                           expression, says):
    refused(["run", f"data.path={_folder(tmp_path / 'lab')}",
             f"data.derive={{E_tilt_X: '{expression}'}}", "data.test_fraction=0.3", *FAST,
             f"out={tmp_path / 'out'}"], capsys, says)
    assert not (tmp_path / "out").exists()


def test_a_derived_target_of_probe_cycles_is_one_measured_where_its_probes_both_are(tmp_path,
                                                                                  capsys):
    """small72: X1 probed every 4th row, X2 every 6th: the tilt is measured on every 12th, read
    as a probe cycle (before: not said, not in the report) and scored there; probes never
    measured on one row are refused naming the key (before: 'MLR: the target is measured on no
    row'), nothing written."""
    folder = _folder(tmp_path / "lab", probed=((4, 0), (6, 0)))
    ds, report = read_dataset(folder, {"derive": DERIVE, "test_fraction": 0.3})
    assert report["sparse_targets"]["E_tilt_X"]["every"] == 12
    assert report["campaigns"]["run3"]["sparse_targets"]["E_tilt_X"] == {"measured": 10,
                                                                         "every": 12}
    measured = np.flatnonzero(np.isfinite(ds.campaigns["run3"]["E_tilt_X"].to_numpy()))
    np.testing.assert_array_equal(measured, np.arange(0, ROWS, 12))
    assert main(["run", f"data.path={folder}", OVERRIDE, "data.test_fraction=0.3", *FAST,
                 f"out={tmp_path / 'a'}"]) == 0
    assert "E_tilt_X measured on 1 row in 12 (30 rows): read as a probe cycle" in \
        capsys.readouterr().err
    tilt = json.loads((tmp_path / "a" / "metrics.json").read_text())["targets"]["E_tilt_X"]
    assert tilt["test"]["measured_rows"] == 10
    apart = _folder(tmp_path / "apart", probed=((4, 0), (4, 2)))
    refused(["run", f"data.path={apart}", OVERRIDE, "data.test_fraction=0.3", *FAST,
             f"out={tmp_path / 'b'}"], capsys,
            "run1.csv, column 'E_tilt_X': data.derive.E_tilt_X: (E_X1 - E_X2) / 0.1 is measured "
            "on no row: its error columns are never measured on the same row (E_X1 on 1 row in "
            "4, E_X2 on 1 row in 4)")
    assert not (tmp_path / "b").exists()


def test_a_stream_and_a_served_reference_give_the_derived_target_by_the_same_arithmetic(tmp_path):
    """stdin's rows (monitor.input=-) carry E_X1 and E_X2: E_tilt_X is scored from them; a
    served block whose probe touch measured E_X1 and E_X2 adapts E_tilt_X as one carrying it
    (before: no reference for the tilt, its correction the frozen model's)."""
    ds, _ = read_dataset(_folder(tmp_path / "lab"), {"derive": DERIVE, "test_fraction": 0.3})
    test = ds.campaigns[ds.ids("test")[0]]
    text = test.drop(columns="E_tilt_X").to_csv(index=False)
    streamed, _ = read_stream(text, ["T_a", "T_b", "T_c"], ReadOptions.from_cfg({"derive": DERIVE}))
    np.testing.assert_allclose(streamed["E_tilt_X"], test["E_tilt_X"], atol=1e-12, rtol=0)

    train = {c: ds.campaigns[c] for c in ds.ids("train")}
    streaming = StreamingCompensator.from_training(Compensator(MLR()).fit(train), train)
    adapt = OmegaConf.merge(OmegaConf.load(ROOT / "conf" / "adapt" / "default.yaml"),
                            {"method": "bias"})
    streaming.adapt_ = from_config(adapt, len(streaming.targets_), scheduled=False)
    streaming.derived_ = DERIVE
    touched = test.copy()
    touched.loc[touched.index % 40 != 39, ["E_X1", "E_X2", "E_tilt_X"]] = np.nan   # a touch each 40
    served = {}
    for name, block in (("probes", touched.drop(columns="E_tilt_X")), ("tilt", touched),
                        ("none", test.drop(columns=["E_X1", "E_X2", "E_tilt_X"]))):
        model = CompensatorModel(copy.deepcopy(streaming))     # (each from the promoted state)
        model.load_context(None)
        served[name] = model.predict(None, block, {"session": name, "reset": True})
    np.testing.assert_allclose(served["probes"]["C_tilt_X"], served["tilt"]["C_tilt_X"],
                               atol=1e-12, rtol=0)
    assert np.abs(served["probes"]["C_tilt_X"] - served["none"]["C_tilt_X"]).max() > 0.02


def test_init_proposes_the_probe_pairs_tilts_leaving_the_spacing_to_say(tmp_path, capsys):
    """init sees E_X1 and E_X2 (a nest's two probes): their tilt proposed as a comment of the
    config, the spacing left to the lab; filled in, the config reads it (before: nothing said)."""
    assert main(["init", str(_folder(tmp_path / "lab")), f"out={tmp_path / 'init'}"]) == 0
    assert ("probe pairs E_X1 / E_X2: their tilts as targets, data.derive={E_tilt_X: "
            "'(E_X1 - E_X2) / <spacing in m>'}") in capsys.readouterr().out
    text = (tmp_path / "init" / "conf" / "data" / "lab.yaml").read_text(encoding="utf-8")
    assert "#   E_tilt_X: (E_X1 - E_X2) / <spacing_m>" in text
    filled = yaml.safe_load(text.replace("# derive:", "derive:").replace("#   E_", "  E_")
                            .replace("<spacing_m>", "0.1"))
    assert ReadOptions.from_cfg(filled).derive == DERIVE


def test_the_compiled_stream_learns_from_a_derived_reference_by_the_readers_arithmetic(tmp_path):
    """small72: stream.c (adapt.method=bias) computes the tilt's reference from a row's E_X1 and
    E_X2 as the reader does (TC_DERIVED_REFERENCE, from derived.py's parsed tree): its
    corrections equal those of the same rows carrying the tilt the lab computed (before: no
    reference of the tilt, its corrections those of rows without any error)."""
    import shutil
    import subprocess

    from test_export import checked_pack

    if shutil.which("gcc") is None:
        pytest.skip("no C compiler")
    folder = _folder(tmp_path / "lab")
    data = [f"data.path={folder}", OVERRIDE, "data.test_fraction=0.3"]
    assert main(["run", *data, *FAST, "model=mlr", f"out={tmp_path / 'run'}"]) == 0
    assert main(["export", *data, "track=false", "export.format=c", "adapt.method=bias",
                 f"export.model={tmp_path / 'run' / 'model.pkl'}", f"out={tmp_path / 'code'}"]) == 0
    checked_pack(tmp_path / "code")
    rows = pd.read_csv(folder / "run3.csv").iloc[::3]          # a probe touch on every row
    hand = rows.assign(E_tilt_X=(rows["E_X1"] - rows["E_X2"]) / 0.1)

    def streamed(frame: pd.DataFrame) -> np.ndarray:
        done = subprocess.run([str(tmp_path / "code" / "stream")], capture_output=True,
                              input=frame.to_csv(index=False, float_format="%.17g").encode())
        assert done.returncode == 0, done.stderr
        return pd.read_csv(io.BytesIO(done.stdout))["C_tilt_X"].to_numpy(float)

    derived, by_hand = streamed(rows), streamed(hand)
    unreferenced = streamed(rows.drop(columns=["E_X1", "E_X2"]))
    np.testing.assert_allclose(derived, by_hand, rtol=0, atol=1e-9)
    assert np.abs(derived - unreferenced).max() > 1.0           # it learned (µm/m)
