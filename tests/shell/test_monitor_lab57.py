"""``monitor`` on a lab's one-file record, as docs/monitoring.md shows it (monstr57): the lab's
own headers with units, ``;`` and decimal commas, its runs numbered in a ``Lauf`` column."""

from __future__ import annotations

import io
import json
import re

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused
from thermocomp.shell.cli import main

HEADERS = ["Spindel [°C]", "Bett [°C]", "Ständer [°C]", "Schlitten [°C]"]
ROLES = ("data.delimiter=;", "data.decimal=,", "data.roles.error=[dX]",
         "data.roles.campaign=Lauf", "data.test_fraction=0.5", "monitor.window=5")


def _run(rng, rows: int) -> pd.DataFrame:
    """One run: four temperatures driven by two sources (the POD has a field to predict), the
    error a weighted sum of them."""
    t = np.arange(rows) * 60.0
    heat = 4 * (1 - np.exp(-t / 3000.0))
    wave = 0.6 * np.sin(t / 1500.0 + rng.uniform(0, 3))
    temps = [20 + a * heat + b * wave + rng.normal(0, 0.02, rows)
             for a, b in ((1.0, 0.2), (0.3, 1.0), (0.6, 0.5), (0.8, 0.7))]
    error = 3.0 * (temps[0] - 20) - 2.0 * (temps[1] - 20) + rng.normal(0, 0.1, rows)
    df = pd.DataFrame({"Zeit [s]": t, **dict(zip(HEADERS, (x.round(3) for x in temps))),
                       "dX [µm]": error.round(2)})
    return df


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    """``messung.csv`` (two runs, the second held out) and the second run's rows as its logger
    writes them on their own (``lauf2.csv``, no run column)."""
    rng = np.random.default_rng(5711)
    runs = [_run(rng, 240), _run(rng, 180)]
    root = tmp_path_factory.mktemp("monlab")
    whole = pd.concat([r.assign(Lauf=i + 1) for i, r in enumerate(runs)])
    whole.to_csv(root / "messung.csv", sep=";", decimal=",", index=False)
    runs[1].to_csv(root / "lauf2.csv", sep=";", decimal=",", index=False)
    return root


def _monitor(lab, out, monkeypatch, stdin: str | None = None, *extra: str) -> dict:
    args = ["monitor", f"data.path={lab / 'messung.csv'}", f"out={out}", *ROLES, *FAST, *extra]
    if stdin is not None:
        monkeypatch.setattr("sys.stdin", io.StringIO((lab / stdin).read_text()))
        args.append("monitor.input=-")
    assert main(args) == 0
    return json.loads((out / "monitor.json").read_text())


def test_a_runs_own_logger_file_streams_as_the_held_out_run(lab, tmp_path, monkeypatch, capsys):
    """The model is fitted on the long file (its config needs ``data.roles.campaign``); the
    logger's file of one run has no ``Lauf`` column.  It was refused ("1 column(s) not read:
    data.roles.campaign='Lauf' names no header"), with no key the lab could give."""
    from_file = _monitor(lab, tmp_path / "file", monkeypatch)
    streamed = _monitor(lab, tmp_path / "stdin", monkeypatch, "lauf2.csv")
    assert "the rows stream as one campaign 'stdin'" in capsys.readouterr().err
    for target, scores in from_file["targets"].items():
        assert streamed["targets"][target]["rmse_adaptive"] == pytest.approx(
            scores["rmse_adaptive"], rel=1e-9)
    assert list(streamed["sensors"]) == list(from_file["sensors"])


@pytest.fixture(scope="module")
def lathe(tmp_path_factory):
    """A short Swiss-lathe record (16 h calibration, 6 h production): its healthy
    ``T_toolholder1`` is self-predicted at up to 0.9 of its warning band."""
    raw = tmp_path_factory.mktemp("lathe57") / "raw"
    assert main(["simulate", "sim=swiss_lathe_door", "seed=5811", f"data.path={raw}",
                 "sim.generator.calibration_hours=16", "sim.generator.production_hours=6",
                 "track=false"]) == 0
    return raw


def test_one_empty_logger_row_costs_the_adaptive_stream_next_to_nothing(lathe, tmp_path,
                                                                       monkeypatch):
    """Every temperature of one row missing (the logger missed a sample): every sensor is out
    for the dropout and comes back.  A healthy sensor whose error sits between half its band and
    its band was held out until it passed half the band (an hour here), and the adaptive stream
    ended 1.14x (E_X) and 1.17x (E_Y) the fixed one's RMSE."""
    rows = pd.read_csv(lathe / "production.csv")
    rows.loc[150, [c for c in rows.columns if c.startswith("T_")]] = np.nan
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(index=False)))
    out = tmp_path / "out"
    assert main(["monitor", f"data.path={lathe}", f"out={out}", "monitor.input=-", *FAST]) == 0
    report = json.loads((out / "monitor.json").read_text())
    back = {e["sensor"]: e["time"] for e in report["events"] if e["to"] == "ok"}
    lost = {e["sensor"] for e in report["events"] if e["to"] == "excluded"}
    assert lost == {c for c in rows.columns if c.startswith("T_")}      # the dropout, seen
    # back together: within one window (10 samples of 60 s) of the first
    assert set(back) == lost and max(back.values()) - min(back.values()) <= 600.0, back
    # each says the band it came back within: its whole warning band (the message said half) of
    # the set it came back in (mon86: the whole set's or wider, some still out); one no other
    # sensor predicts, that no band judged it (stranger80: it said its band too)
    warning = dict(zip((n for n in report["sensors"]), report["bands"]["warning_c"]))
    for e in (e for e in report["events"] if e["to"] == "ok"):
        if report["sensors"][e["sensor"]]["observable"]:
            assert e["reason"].startswith("re-admitted: within ±"), e
            said = float(e["reason"].split("±")[1].split()[0])
            assert said >= float(f"{warning[e['sensor']]:.3g}"), e
        else:
            assert e["reason"].startswith("re-admitted: no detector fired for "), e
    for target, r in report["targets"].items():
        assert r["rmse_adaptive"] <= 1.02 * r["rmse_fixed"], (target, r)


def test_a_renamed_column_in_the_stream_is_named_with_its_own_header(lab, tmp_path,
                                                                     monkeypatch, capsys):
    """The logger's channel renamed ('Bett2' for 'Bett'): the refusal named only the contract
    name the model wants ('T_Bett'), not the stream's header that is likely it."""
    rows = pd.read_csv(lab / "lauf2.csv", sep=";", decimal=",")
    rows = rows.rename(columns={"Bett [°C]": "Bett2 [°C]"})
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(sep=";", decimal=",", index=False)))
    refused(["monitor", f"data.path={lab / 'messung.csv'}", f"out={tmp_path / 'o'}", *ROLES,
             *FAST, "monitor.input=-"], capsys,
            "'T_Bett'", "stdin lacks a column", "'Bett2 [°C]' (read as T_Bett2)", "renamed?",
            "'Bett [°C]' (read as T_Bett)")   # (stranger74) the lacking one by its own header too


def test_a_stream_said_to_continue_a_run_it_does_not_continue_is_refused(lab, tmp_path,
                                                                         monkeypatch, capsys):
    """Run 2 starts cold; said to continue run 1 (which ended warm), the stream was warmed on
    run 1 and its first row read as the logger's common step: every sensor re-referenced by it
    for good (on the lathe: adaptive 27.4 µm against the fixed 1.85)."""
    monkeypatch.setattr("sys.stdin", io.StringIO((lab / "lauf2.csv").read_text()))
    out = tmp_path / "o"
    refused(["monitor", f"data.path={lab / 'messung.csv'}", f"out={out}", *ROLES, *FAST,
             "data.reference=none", "monitor.input=-", "monitor.continues=Lauf_1"], capsys,
            "monitor.continues=Lauf_1", "not where Lauf_1 ended", "4 of 4 temperatures",
            "leave monitor.continues out")
    assert not out.exists()


def test_a_stream_logged_at_another_period_than_training_is_said(lab, tmp_path, monkeypatch,
                                                                 capsys):
    """Run 2 logged every 120 s against 60 s in training: streamed without a word before."""
    rows = pd.read_csv(lab / "lauf2.csv", sep=";", decimal=",")
    (lab / "lauf2_120s.csv").write_text(rows.iloc[::2].to_csv(sep=";", decimal=",", index=False))
    _monitor(lab, tmp_path / "slow", monkeypatch, "lauf2_120s.csv")
    assert "campaign stdin: samples 120 s apart, the training's 60 s" in capsys.readouterr().err
    _monitor(lab, tmp_path / "same", monkeypatch, "lauf2.csv")
    assert "apart, the training's" not in capsys.readouterr().err


def test_a_labs_header_word_beyond_ascii_in_an_override_is_shown_quoted(tmp_path, capsys):
    """``data.roles.state=[Spindel,Tür]`` (the lathe's door, 'Tür [-]'): Hydra's lexer error
    named only its grammar page."""
    refused(["monitor", "data.roles.state=[Spindel,Tür]", f"out={tmp_path / 'o'}", *FAST],
            capsys, "LexerNoViableAltException", "\"data.roles.state=[Spindel,'Tür']\"")


def test_the_figures_bands_are_those_of_the_sensors_they_show(lathe, tmp_path, monkeypatch):
    """The lathe's NC spindle motor, which no other sensor predicts (no error to show), has a
    band of tens of °C from its loose training spread; drawn as the band of every sensor it
    set the scale, and every self-prediction error read as a flat line at 0."""
    import thermocomp.apps.monitor.figures as figures

    drawn = {}

    def keep(fig, path):
        drawn[path.name] = [abs(line.get_ydata()[0]) for line in fig.axes[0].lines
                            if line.get_linestyle() == "--"]
        return path

    monkeypatch.setattr(figures, "save_figure", keep)
    monkeypatch.setattr("sys.stdin", io.StringIO((lathe / "production.csv").read_text()))
    out = tmp_path / "out"
    args = [a for a in FAST if not a.startswith("plots=")]
    assert main(["monitor", f"data.path={lathe}", f"out={out}", "monitor.input=-", *args]) == 0
    report = json.loads((out / "monitor.json").read_text())
    shown = [j for j, s in enumerate(report["sensors"].values()) if s["observable"]]
    blind = [j for j, s in enumerate(report["sensors"].values()) if s["observable"] is False]
    alarm = report["bands"]["alarm_c"]
    assert blind and max(alarm[j] for j in blind) > 10 * max(alarm[j] for j in shown)
    assert max(drawn["self_prediction.png"]) == pytest.approx(max(alarm[j] for j in shown))


def test_a_missing_training_value_of_a_one_file_record_names_the_file_and_header(
        lab, tmp_path, capsys):
    """The refusal named 'messung.csv/messung.csv' (the record's path joined to its own name)
    and the contract name alone, where `run` names the file and the lab's header."""
    whole = pd.read_csv(lab / "messung.csv", sep=";", decimal=",")
    whole.loc[100, "Bett [°C]"] = np.nan
    path = tmp_path / "messung.csv"
    whole.to_csv(path, sep=";", decimal=",", index=False)
    line = refused(["monitor", f"data.path={path}", f"out={tmp_path / 'o'}", *ROLES, *FAST],
                   capsys, f"file {path},", "'T_Bett'", "data row 101", "train campaign Lauf_1",
                   "its header in the file: 'Bett [°C]'")
    assert "messung.csv/messung.csv" not in line


def test_a_state_change_says_how_the_last_errors_stand_against_the_band(tmp_path):
    """A mill trained on 24 h of March, tested in June: its sensors cross the warning band
    and return hundreds of times; a return to ok said only the errors' mean, as often beyond
    the band as not ('-0.52 °C' against 0.509), the same words as the crossing."""
    raw = tmp_path / "raw"
    assert main(["simulate", "sim=large_mill_week", "seed=5812", f"data.path={raw}",
                 "sim.generator.train_hours=24", "sim.generator.test_hours=12",
                 "track=false"]) == 0
    assert main(["monitor", f"data.path={raw}", f"out={tmp_path / 'o'}", *FAST]) == 0
    events = json.loads((tmp_path / "o" / "monitor.json").read_text())["events"]
    back = [e for e in events if e["from"] == "warning" and e["to"] == "ok"]
    out = [e for e in events if e["from"] == "ok" and e["to"] == "warning"]
    assert back and out
    number = r"([0-9.]+(?:e-?\d+)?)"
    for e in back:
        smallest, band = map(float, re.search(rf"the smallest {number} within ±{number} °C",
                                              e["reason"]).groups())
        assert smallest <= band, e        # (3 digits: equal where they round alike)
    for e in out:
        band, smallest = map(float, re.search(rf"all beyond ±{number} °C \(the smallest "
                                              rf"{number}\)", e["reason"]).groups())
        assert smallest >= band, e


@pytest.mark.parametrize("override, fixed", [
    ("compare.target=Verlagerung X [um]", "\"compare.target='Verlagerung X [um]'\""),
    ("data.roles.error=[Verlagerung X [um],E_Z]", "\"data.roles.error=['Verlagerung X [um]',E_Z]\""),
])
def test_a_labs_header_with_spaces_and_brackets_in_an_override_is_shown_quoted(tmp_path, capsys,
                                                                                override, fixed):
    """An ASCII header with spaces and units (``Verlagerung X [um]``) as a value: Hydra said
    only ``mismatched input '['`` and its grammar page (lead58)."""
    refused(["compare", override, f"out={tmp_path / 'o'}", "track=false"], capsys,
            "is read only quoted", fixed)


@pytest.mark.parametrize("after, said", [(85, True), (1, False), (None, False)])
def test_a_stream_said_to_continue_a_run_from_rows_after_its_end_says_the_gap(
        lab, tmp_path, monkeypatch, capsys, after, said):
    """The stream's first row on run 1's clock, 85 periods after its last (84 rows missing): the
    lead-in was moved to end one period before it and the gap bridged without a word
    (restart58: 84 rows).  Right after its last row, or on a clock that restarts (``None``:
    from 0 s, which tells nothing of a gap): nothing said."""
    whole = pd.read_csv(lab / "messung.csv", sep=";", decimal=",")
    run1 = whole[whole["Lauf"] == 1].drop(columns="Lauf")
    period = float(run1["Zeit [s]"].diff().median())
    end = float(run1["Zeit [s]"].iloc[-1])
    rows = pd.concat([run1.iloc[-1:]] * 30, ignore_index=True)     # the machine as run 1 left it
    start = end + after * period if after is not None else 0.0
    rows["Zeit [s]"] = start + np.arange(len(rows)) * period
    monkeypatch.setattr("sys.stdin", io.StringIO(rows.to_csv(sep=";", decimal=",", index=False)))
    assert main(["monitor", f"data.path={lab / 'messung.csv'}", f"out={tmp_path / 'o'}", *ROLES,
                 *FAST, "data.reference=none", "monitor.input=-",
                 "monitor.continues=Lauf_1"]) == 0
    err = capsys.readouterr().err
    assert ("after Lauf_1's last" in err) is said, err
    if said:
        assert f"is {after - 1} sample(s) ({(after - 1) * period / 60:.3g} min) after" in err
        assert "stream from the row after Lauf_1's last" in err
