"""A lab's folder of many runs, messy as real loggers make them (messy58), through ``init``,
``run`` and the command line: a channel renamed from some run on, a sensor missing in some runs,
an ATI model without an ambient, a map key beyond ASCII."""

from __future__ import annotations

import numpy as np
import pandas as pd
import yaml

from conftest import FAST, refused
from thermocomp.core.io import read_dataset
from thermocomp.shell.cli import main


def lab_folder(root, runs: int = 6, rename_from: int | None = None, drop: tuple = (),
               probe_mm_from: int | None = None):
    """Runs as a lab's logger writes them (``;``, decimal commas, its own headers): ``T3`` is
    written ``T03`` from run ``rename_from`` on, ``T4`` is not logged in the runs ``drop``, the
    error is ``dX1 [mm]`` from run ``probe_mm_from`` on (another probe)."""
    root.mkdir()
    rng = np.random.default_rng(58)
    for k in range(1, runs + 1):
        t = np.arange(40) * 60.0
        heat = 20 + (2 + k) * (1 - np.exp(-t / 1500)) + rng.normal(0, 0.02, t.size)
        frame = pd.DataFrame({"Zeit [s]": t, "Spindel [°C]": heat,
                              "T3": 20 + 0.3 * np.sin(t / 900 + k), "T4": 20 + 0.001 * t,
                              "dX [µm]": 3 * (heat - 20) + rng.normal(0, 0.05, t.size)})
        if rename_from is not None and k >= rename_from:
            frame = frame.rename(columns={"T3": "T03"})
        if probe_mm_from is not None and k >= probe_mm_from:
            frame["dX [µm]"] /= 1000.0
            frame = frame.rename(columns={"dX [µm]": "dX1 [mm]"})
        if k in drop:
            frame = frame.drop(columns=["T4"])
        frame.to_csv(root / f"run_{k:02d}.csv", sep=";", decimal=",", index=False)
    return root


def test_a_channel_renamed_from_some_run_on_is_named_as_one_with_the_mapping(tmp_path, capsys):
    # it was refused as 'T_T3': 3 of 6 campaigns lack it ... leave it out of data.inputs:
    # a sensor every run logged, dropped, or read as two with each missing in half the runs
    folder = lab_folder(tmp_path / "lab", rename_from=4)
    line = refused(["run", f"data.path={folder}", "data.test_fraction=0.2", *FAST,
                    f"out={tmp_path / 'init'}", "data.roles.error=[dX]"], capsys, "run_04.csv",
                   "'T_T3' is in 3 of 6",
                   "'T_T03' (its header in the file: 'T03') in the other 3, from run_04 on",
                   "data.columns={T03: T_T3}")
    assert "leave it out" not in line
    assert not (tmp_path / "init").exists()
    # the mapping it names reads the folder, and init (initone65) writes it itself
    assert main(["init", str(folder), f"out={tmp_path / 'init'}", "data.roles.error=[dX]",
                 "data.columns={T03: T_T3}"]) == 0
    assert main(["init", str(folder), f"out={tmp_path / 'init2'}", "data.roles.error=[dX]"]) == 0
    written = yaml.safe_load(next((tmp_path / "init2" / "conf" / "data").glob("*.yaml")).read_text())
    assert written["columns"] == {"T03": "T_T3"}


def test_a_sensor_missing_in_some_runs_names_the_pattern_that_leaves_it_out(tmp_path, capsys):
    # 'leave it out of data.inputs': a list of globs over contract names, none of which leaves
    # one sensor out; a pattern over the file's own header does
    folder = lab_folder(tmp_path / "lab", drop=(2, 5))
    refused(["init", str(folder), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"], capsys,
            "run_02.csv", "'T_T4': 2 of 6 campaigns lack it", "data.roles.ignore=['T4']")
    assert main(["init", str(folder), f"out={tmp_path / 'init'}", "data.roles.error=[dX]",
                 "data.roles.ignore=['T4']"]) == 0


def test_an_ati_model_on_runs_without_an_ambient_names_where_to_give_it(tmp_path, capsys):
    # the runs' names held their level (run_25C_03.csv) and the message named a manifest
    # ambient_c alone: not how to give one to a folder without a manifest
    folder = lab_folder(tmp_path / "lab")
    args = ["run", f"data.path={folder}", "data.roles.error=[dX]", "data.test_fraction=0.2",
            "model=mlr", "ati=cmeans", *FAST]
    refused([*args, f"out={tmp_path / 'run'}"], capsys, "data.roles.ambient=[<its header>]",
            "ambient_c in campaigns.csv (columns campaign, file, ambient_c")
    assert not (tmp_path / "run").exists()
    # the manifest it names reads the folder (no split: data.test_fraction holds out)
    pd.DataFrame({"campaign": [f"run_{k:02d}" for k in range(1, 7)],
                  "file": [f"run_{k:02d}.csv" for k in range(1, 7)],
                  "ambient_c": [15, 20, 25, 30, 18, 27]}).to_csv(folder / "campaigns.csv",
                                                                  index=False)
    assert main([*args, f"out={tmp_path / 'run'}"]) == 0


def test_a_map_key_beyond_ascii_on_the_command_line_names_the_config_file(tmp_path, capsys):
    # the hint said to quote the override, "++data.columns='{Spindelkopf [°C]: T_Spindel}'",
    # which Hydra reads as a string: refused again as "data.columns must be a mapping"
    folder = lab_folder(tmp_path / "lab")
    line = refused(["ingest", f"data.path={folder}", "data.columns={Spindelkopf [°C]: T_Spindel}",
                    f"data.interim={tmp_path / 'interim'}"], capsys,
                   "a map's key beyond ASCII is not read on the command line",
                   "\"columns: {'Spindelkopf [°C]': T_Spindel}\"")
    assert "read only quoted" not in line
    # notes100: a form that works where init refused the file, so wrote no config
    assert "'defaults: [default]'" in line and "hydra.searchpath=[file://$PWD/myconf]" in line


def test_init_says_each_sample_period_of_runs_logged_at_two(tmp_path, capsys):
    # it said "sample period: 10 s" alone, the median step of every row, for 2 runs at 10 s
    # and 4 at 60 s (a 10 s run has six times the rows)
    folder = lab_folder(tmp_path / "lab")
    for k in (2, 5):
        frame = pd.read_csv(folder / f"run_{k:02d}.csv", sep=";", decimal=",")
        fine = np.arange(0, frame["Zeit [s]"].iloc[-1] + 1, 10.0)
        pd.DataFrame({c: np.interp(fine, frame["Zeit [s]"], frame[c]) for c in frame}).to_csv(
            folder / f"run_{k:02d}.csv", sep=";", decimal=",", index=False)
    assert main(["init", str(folder), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"]) == 0
    out = capsys.readouterr()
    assert ("rows (the median step of every row; campaigns logged at 10 s: 2, 60 s: 4)"
            in out.out)
    assert "data.resample_s=60 puts them on one grid" in out.err


def test_a_renamed_channel_in_another_unit_is_mapped_and_converted(tmp_path, capsys):
    # stranger65: data.columns now converts a mapped header's unit as a role does, and reads
    # the header without its unit: the refusal names the entry that reads 'dX1 [mm]' in µm
    # (it said to rename the files: data.columns read mm as µm, 1000x too small)
    folder = lab_folder(tmp_path / "lab", probe_mm_from=4)
    refused(["run", f"data.path={folder}", "data.test_fraction=0.2", *FAST,
             f"out={tmp_path / 'run'}", "data.roles.error=[dX*]"],
            capsys, "'E_dX1' (its header in the file: 'dX1 [mm]') in the other 3",
            "data.columns={dX1: E_dX} reads it under one name")
    # (initone65) init writes that entry itself, said
    assert main(["init", str(folder), f"out={tmp_path / 'init'}", "data.roles.error=[dX*]"]) == 0
    assert "one sensor renamed, read as E_dX" in capsys.readouterr().out
    written = yaml.safe_load(next((tmp_path / "init" / "conf" / "data").glob("*.yaml")).read_text())
    assert written["columns"] == {"dX1": "E_dX"}
    ds, _ = read_dataset(folder, {"roles": {"error": ["dX*"]}, "columns": {"dX1": "E_dX"}})
    spans = [np.ptp(df["E_dX"].to_numpy(float)) for df in ds.campaigns.values()]
    assert min(spans) > 0.2 * max(spans)        # every run in µm, none 1000x smaller


def test_a_run_not_recorded_is_refused_before_any_run_is_said_held_out(tmp_path, capsys):
    # a header-only file has no start: the folder was held out in name order, said ("held out
    # in the order listed (no start time for each): test ['run_06']"), and then refused
    folder = lab_folder(tmp_path / "lab")
    header = (folder / "run_03.csv").read_text().splitlines()[0]
    (folder / "run_03.csv").write_text(header + "\n")
    code = main(["init", str(folder), f"out={tmp_path / 'init'}", "data.roles.error=[dX]"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert "run_03.csv: file has a header but no data rows: a run not recorded?" in err
    assert "held out" not in err and "name order" not in err, err
    assert not (tmp_path / "init").exists()


def test_a_channel_renamed_is_named_from_the_first_run_in_time_not_in_file_names(tmp_path,
                                                                              capsys):
    # runs timestamped, their files named otherwise than in time: 'T03' (runs 4-6, the last
    # three days) was said to be the earlier name and 'T3' the rename "from lauf_b on"
    folder = lab_folder(tmp_path / "lab", rename_from=4)
    names = dict(zip(range(1, 7), "bdface"))          # run 4, the first under 'T03', is lauf_a
    for k, name in names.items():
        frame = pd.read_csv(folder / f"run_{k:02d}.csv", sep=";", decimal=",")
        began = pd.Timestamp(f"2026-11-{k + 1:02d} 08:00")
        frame["Zeit [s]"] = (began + pd.to_timedelta(frame["Zeit [s]"], unit="s")).dt.strftime(
            "%Y-%m-%dT%H:%M:%S")
        frame.rename(columns={"Zeit [s]": "Zeit"}).to_csv(
            folder / f"lauf_{name}.csv", sep=";", decimal=",", index=False)
        (folder / f"run_{k:02d}.csv").unlink()
    refused(["run", f"data.path={folder}", "data.test_fraction=0.2", *FAST,
             f"out={tmp_path / 'init'}", "data.roles.error=[dX]"], capsys, "lauf_a.csv",
            "'T_T3' is in 3 of 6 campaigns (lauf_b, lauf_d, lauf_f)",
            "'T_T03' (its header in the file: 'T03') in the other 3, from lauf_a on",
            "data.columns={T03: T_T3}")
