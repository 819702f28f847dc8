"""``data.bits`` (lab83): a PLC status word declared is read as its bits' 0/1 states, the word
itself no input; a bad declaration or word is refused naming the key, or the file, column and
row; ``init`` proposes the key for a word and never decodes it undeclared."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
import yaml

from conftest import refused, thermocomp
from thermocomp.core.io import ContractError, read_dataset
from thermocomp.core.io.bits import looks_like_bits

BITS = {0: "machine_on", 1: "spindle_on", 7: "probe_ready"}


def _record(path, status: np.ndarray | None = None):
    rng = np.random.default_rng(8571)
    n = 240
    on = (np.arange(n) // 30) % 2
    spin = on * ((np.arange(n) // 10) % 2)
    word = 128 + on + 2 * spin if status is None else status
    t = np.arange(n) * 10.0
    frame = pd.DataFrame({"time": t, "Spindel [°C]": 20 + np.cumsum(spin) / 50,
                          "Status": word, "dX [um]": 3 * np.cumsum(spin) / 50
                          + rng.normal(0, 0.1, n)})
    frame.to_csv(path, index=False)
    return frame


CFG = {"roles": {"error": ["dX*"], "state": ["Status"]}, "test_fraction": 0.25}


def test_declared_bits_are_read_as_states_and_the_word_is_no_column(tmp_path):
    frame = _record(tmp_path / "lab.csv")
    ds, report = read_dataset(tmp_path / "lab.csv", {**CFG, "bits": {"Status": BITS}})
    df = pd.concat(ds.campaigns.values(), ignore_index=True)
    assert "S_Status" not in df.columns
    word = frame["Status"].to_numpy()
    for bit, name in BITS.items():     # the bit as the word's binary text says it
        expected = [float(format(int(w), "064b")[-1 - bit]) for w in word]
        assert df[f"S_{name}"].tolist() == expected
    plain, _ = read_dataset(tmp_path / "lab.csv", CFG)
    assert "S_Status" in pd.concat(plain.campaigns.values()).columns


@pytest.mark.parametrize(("bits", "says"), [
    ({"Status": {64: "x"}}, "bit 64 is no bit"),
    ({"Status": {0: "two words"}}, "no state name"),
    ({"Status": {0: "a", 1: "a"}}, "'a' names two bits"),
    ({"Status": "on"}, "must map bit numbers"),
])
def test_a_bad_declaration_is_refused_naming_the_key(tmp_path, bits, says):
    _record(tmp_path / "lab.csv")
    with pytest.raises(ContractError, match="data.bits") as exc:
        read_dataset(tmp_path / "lab.csv", {**CFG, "bits": bits})
    assert says in str(exc.value)


def test_a_word_not_read_or_a_name_taken_is_refused_naming_file_and_column(tmp_path):
    _record(tmp_path / "lab.csv").assign(Tuer=0.0).to_csv(tmp_path / "lab.csv", index=False)
    cfg = {**CFG, "roles": {**CFG["roles"], "state": ["Status", "Tuer"]}}
    for bits, says in (({"Zustand": {0: "on"}}, "column 'Zustand'"),
                       ({"Status": {0: "Tuer"}}, "the state 'Tuer' (S_Tuer) is a column's")):
        with pytest.raises(ContractError) as exc:
            read_dataset(tmp_path / "lab.csv", {**cfg, "bits": bits})
        assert f"file {tmp_path / 'lab.csv'}" in str(exc.value) and says in str(exc.value)


def test_a_word_that_is_no_whole_number_exits_2_naming_file_column_row(tmp_path, capsys):
    word = 128.0 + np.zeros(240)
    word[57] = 129.5
    _record(tmp_path / "lab.csv", word)
    refused(["run", f"data.path={tmp_path / 'lab.csv'}", "data.roles.error=[dX*]",
             "data.roles.state=[Status]", "data.test_fraction=0.25", "++data.bits.Status.0=on",
             f"out={tmp_path / 'out'}"], capsys,
            f"file {tmp_path / 'lab.csv'}, column 'Status', line 59 (data row 58)",
            "129.5 is no whole number")


def test_the_rule_tells_a_word_from_a_count_and_a_temperature():
    assert looks_like_bits(np.array([129, 131, 133, 135, 129.0])) == [0, 1, 2, 7]
    assert looks_like_bits(np.arange(6.0)) is None                   # a count 0-5
    assert looks_like_bits(np.array([20.5, 21.0, 22.0])) is None     # not whole
    assert looks_like_bits(np.array([1.0, 2.0, 4.0, 8.0])) is None   # one bit at a time


def test_init_proposes_the_key_and_never_decodes_a_word_undeclared(tmp_path):
    frame = _record(tmp_path / "lab.csv")
    words = sorted(set(frame["Status"]))
    # a position at three stops (0 / 100 / 200 mm: sums of three powers of two): no word
    frame.assign(**{"Pos [mm]": 100.0 * (np.arange(len(frame)) // 80)}).to_csv(
        tmp_path / "lab.csv", index=False)
    out = tmp_path / "out"
    said = thermocomp("init", f"data.path={tmp_path / 'lab.csv'}",
                      "data.roles.state=[Status, Pos*]", f"out={out}").stdout
    assert "'Pos [mm]' holds" not in said
    assert f"'Status' holds {len(words)} whole numbers ({', '.join(map(str, words))})" in said
    assert "data.bits={Status: {0: <name>, 1: <name>, 7: <name>}}" in said
    config = yaml.safe_load((out / "conf" / "data" / "lab.yaml").read_text())
    assert "bits" not in config
    declared = thermocomp("init", f"data.path={tmp_path / 'lab.csv'}",
                          "data.roles.state=[Status, Pos*]",
                          "++data.bits.Status.0=machine_on", f"out={out}").stdout
    assert "a PLC's status word?" not in declared
    config = yaml.safe_load((out / "conf" / "data" / "lab.yaml").read_text())
    assert {int(b): n for b, n in config["bits"]["Status"].items()} == {0: "machine_on"}


def _folder(tmp_path):
    """Four runs of three sensors, the status word and dX (the last held out)."""
    folder = tmp_path / "runs"
    folder.mkdir()
    for k in range(4):
        frame = _record(folder / f"run{k}.csv")
        rng = np.random.default_rng(8572 + k)
        frame["dX [um]"] += rng.normal(0, 0.2, len(frame))
        frame["Bett [°C]"] = 20 + np.cumsum(rng.normal(0, 0.02, len(frame)))
        frame["Ständer [°C]"] = 20.5 + np.cumsum(rng.normal(0, 0.02, len(frame)))
        frame.to_csv(folder / f"run{k}.csv", index=False)
    return folder, ["data.roles.error=[dX*]", "data.roles.state=[Status]",
                    "data.test_fraction=0.25", "model=hammerstein", "track=false", "plots=none",
                    *(f"++data.bits.Status.{b}={n}" for b, n in BITS.items())]


def test_a_stream_on_stdin_decodes_the_declared_word_as_the_file_reader(tmp_path, monkeypatch):
    """Before, a hammerstein monitor on stdin refused 'stdin lacks S_machine_on'."""
    import io
    import json

    from thermocomp.shell.cli import main

    folder, keys = _folder(tmp_path)
    monitor = ["monitor", f"data.path={folder}", *keys]
    assert main([*monitor, f"out={tmp_path / 'file'}"]) == 0
    monkeypatch.setattr("sys.stdin", io.StringIO((folder / "run3.csv").read_text()))
    assert main([*monitor, "monitor.input=-", f"out={tmp_path / 'piped'}"]) == 0
    from_file, piped = (json.loads((tmp_path / name / "monitor.json").read_text())["targets"]
                        for name in ("file", "piped"))
    assert piped["E_dX"]["rmse_fixed"] == pytest.approx(from_file["E_dX"]["rmse_fixed"],
                                                        rel=1e-9)


def test_export_says_the_code_reads_each_bit_as_its_own_column(tmp_path, capsys):
    from thermocomp.shell.cli import main

    folder, keys = _folder(tmp_path)
    out = tmp_path / "out"
    assert main(["run", f"data.path={folder}", *keys, f"out={out}"]) == 0
    assert main(["export", f"data.path={folder}", *keys, f"export.model={out / 'model.pkl'}",
                 "export.format=c", "export.check=false", f"out={tmp_path / 'c'}"]) == 0
    header = (tmp_path / "c" / "compensator.h").read_text()
    read = [n for n in BITS.values() if f'"S_{n}"' in header]
    assert read, header[:2000]
    said = capsys.readouterr().err
    assert ", ".join(f"S_{n} (bit {b} of 'Status')" for b, n in BITS.items() if n in read) in said
    assert "or from the word in their place, decoded as the reader decodes it" in said
