"""A lab's temperature word at a header's end, ``Tmp``, and stored names (data95).

A temperature's word after a sensor's name (``headstock temp``, ``Spindel Temperatur``, ``bed
temperature [°C]``) was kept after the ``T_`` prefix (``T_headstock_temp``), as was ``Tmp`` /
``Tmp.`` before it (``T_Tmp._headstock``); stop 94 left out only ``Temp``/``Temperatur``/...
before it.  A stored config's ``data.inputs`` or a stored model naming a column by an earlier
rule's name (``T_Temp._headstock``) was fitted without it after a warning, or refused as a
column the campaigns lack, the name now unsaid."""

from __future__ import annotations

import pandas as pd
import pytest

from test_data88b import _record
from thermocomp.core.io.roles import naming
from thermocomp.shell.cli import main


@pytest.mark.parametrize("header, name", [
    ("headstock temp [°C]", "T_headstock"), ("Spindel Temperatur [°C]", "T_Spindel"),
    ("bed temperature [°C]", "T_bed"), ("Coolant Temp. [°C]", "T_Coolant"),
    ("husillo temperatura [°C]", "T_husillo"), ("broche température [°C]", "T_broche"),
    ("spil temperatuur [°C]", "T_spil"), ("motor_tmp [°C]", "T_motor"),
    ("Tmp headstock [°C]", "T_headstock"), ("Tmp. guidebush [°C]", "T_guidebush")])
def test_a_temperature_word_at_the_end_and_tmp_are_not_repeated(header, name):
    # before: T_headstock_temp, T_Spindel_Temperatur, T_Tmp_headstock ...
    named = naming(["Zeit [s]", header, "dX [µm]"], {"error": ["dX"]}, {}).names
    assert named[header] == name


@pytest.mark.parametrize("headers, names", [
    # the word alone, or an ambient's name left: as before
    (["Tmp [°C]", "amb temp [°C]"], ["T_Tmp", "T_amb_temp"]),
    # the short name another header reads as: the long one, as before
    (["bed temp [°C]", "bed [°C]"], ["T_bed_temp", "T_bed"]),
    (["bed temp [°C]", "T_bed [°C]"], ["T_bed_temp", "T_bed"]),
    # a time's word is no temperature's; a lab's own contract name keeps its name
    (["ciclo tempo [°C]", "ciclo temps [°C]", "T_spindle_temp [°C]"],
     ["T_ciclo_tempo", "T_ciclo_temps", "T_spindle_temp"]),
    # a historian's tag path keeps its leaf
    (["MC07.Spindle.Bearing.Temp [°C]"], ["T_MC07.Spindle.Bearing.Temp"])])
def test_names_stay_unique_and_the_word_alone_stays(headers, names):
    named = naming(["Zeit [s]", *headers, "dX [µm]"], {"error": ["dX"]}, {}).names
    assert [named[h] for h in headers] == names


def test_former_names_are_the_earlier_rules_names():
    from thermocomp.core.io.roles import former_names

    column_map = {"Temp. Luft [°C]": "T_Luft", "Temp spindle temp [°C]": "T_spindle",
                  "bed [°C]": "T_bed", "Temp Luft2 [°C]": "T_air"}     # (data.columns: its own)
    assert former_names(column_map) == {
        "T_Temp._Luft": ("T_Luft", "Temp. Luft [°C]"),
        "T_Temp_spindle_temp": ("T_spindle", "Temp spindle temp [°C]"),
        "T_spindle_temp": ("T_spindle", "Temp spindle temp [°C]")}


def _lab(tmp_path) -> str:
    rows = _record(951)
    pd.DataFrame({"Zeit [s]": rows["time"], "Temp. Luft [°C]": rows["T_a"],
                  "headstock temp [°C]": rows["T_b"], "bed [°C]": rows["T_c"],
                  "dX [µm]": rows["E_X"]}).to_csv(tmp_path / "lab.csv", index=False)
    return str(tmp_path / "lab.csv")


def _run(*args: str) -> int:
    return main(["run", *args, "data.roles.error=[dX]", "data.test_fraction=0.25",
                 "track=false", "plots=none"])


def test_stored_inputs_naming_an_earlier_name_are_refused_saying_the_name_now(tmp_path, capsys):
    # before: a warning, "data.inputs names T_Temp._Luft, no column of these data: the model
    # is fitted without it", and a model on T_bed alone
    path = _lab(tmp_path)
    code = _run(f"data.path={path}", "data.inputs=[T_Temp._Luft,T_headstock_temp,T_bed]",
                f"out={tmp_path / 'run'}")
    said = " ".join(capsys.readouterr().err.split())
    assert code == 2 and not (tmp_path / "run" / "model.pkl").exists()
    assert (f"T_Temp._Luft, T_headstock_temp are no columns of {path}, the derived names are "
            "T_Luft ('Temp. Luft [°C]'), T_headstock ('headstock temp [°C]')") in said
    assert ("data.columns={'Temp. Luft [°C]': T_Temp._Luft, 'headstock temp [°C]': "
            "T_headstock_temp}") in said


def test_a_stored_model_naming_an_earlier_name_is_refused_saying_the_name_now(tmp_path, capsys):
    # a model fitted under the name before stop 94 (data.columns keeps it, as the refusal says);
    # before: "1 of 1 campaigns lack it (lab_train)", T_Luft unsaid
    path = _lab(tmp_path)
    conf = tmp_path / "conf" / "data"
    conf.mkdir(parents=True)
    (conf / "old.yaml").write_text(
        f"defaults: [default]\npath: {path}\ncolumns: {{'Temp. Luft [°C]': T_Temp._Luft}}\n",
        encoding="utf-8")
    old = [f"hydra.searchpath=[file://{tmp_path / 'conf'}]", "data=old"]
    assert _run(*old, f"out={tmp_path / 'old'}") == 0
    capsys.readouterr()
    given = [f"replay.model={tmp_path / 'old' / 'model.pkl'}", "data.roles.error=[dX]",
             "data.test_fraction=0.25", "track=false"]
    code = main(["replay", f"data.path={path}", *given, f"out={tmp_path / 'rep'}"])
    said = " ".join(capsys.readouterr().err.split())
    assert code == 2 and "the derived name is T_Luft (header 'Temp. Luft [°C]')" in said
    assert "data.columns={'Temp. Luft [°C]': T_Temp._Luft}" in said
    # (data101) a key beyond ASCII Hydra does not read on the command line: the file's lines
    assert ("in a data config file: myconf/data/mine.yaml with the two lines 'defaults: "
            "[default]' and \"columns: {'Temp. Luft [°C]': T_Temp._Luft}\"") in said
    # the old name kept as said: replayed
    assert main(["replay", *old, *given, f"out={tmp_path / 'kept'}"]) == 0
