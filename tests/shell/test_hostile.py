"""Hostile input and faults: every case exits 2 with one line and leaves nothing behind.

Each case runs the real command (``thermocomp.shell.cli.main``) on a small hand-made
dataset and checks the exit status, that the one error line names the file,
column and row where they apply, and that ``out``, ``data.interim`` and the
model file are byte-identical to before (or still absent).
"""

from __future__ import annotations

import os
import re
import shutil
import signal
import subprocess
import sys
from itertools import product
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from conftest import FAST, refused, thermocomp
from covering import covering, kept
from thermocomp.base import files
from thermocomp.core.io import load_interim, read_dataset
from thermocomp.shell.cli import main
from thermocomp.shell.stages import STAGES

CAMPAIGNS = (("K01", "train"), ("K02", "train"), ("K03", "train"), ("K04", "test"))


def make_dataset(root: Path, rows: int = 30, gain: float = 3.0) -> Path:
    """Four campaigns (three train, one test) of a two-sensor machine whose error is linear in
    the sensor rises (``gain`` µm/K on ``T_0``), one sample a minute."""
    root.mkdir(parents=True)
    rng = np.random.default_rng(0)
    t = np.arange(rows) * 60.0
    for i, (cid, _) in enumerate(CAMPAIGNS):
        amb = 18.0 + 2 * i
        t0 = amb + 5 * (1 - np.exp(-t / 900)) + rng.normal(0, 0.05, rows)
        t1 = amb + 2 * (1 - np.exp(-t / 1500)) + rng.normal(0, 0.05, rows)
        e = gain * (t0 - t0[0]) - 1.5 * (t1 - t1[0]) + rng.normal(0, 0.2, rows)
        pd.DataFrame({"time": t, "T_0": t0, "T_amb": t1, "E_X": e}).to_csv(
            root / f"{cid}.csv", index=False)
    pd.DataFrame([(c, f"{c}.csv", s, "") for c, s in CAMPAIGNS],
                 columns=["campaign", "file", "split", "notes"]).to_csv(
        root / "campaigns.csv", index=False)
    return root


def edit_csv(path: Path, fn) -> None:
    df = pd.read_csv(path)
    fn(df)
    df.to_csv(path, index=False)


def replace_line(path: Path, line: int, old: bytes, new: bytes) -> None:
    """Replace ``old`` by ``new`` in line ``line`` (0 = the header) of a file, as bytes."""
    lines = path.read_bytes().split(b"\n")
    assert old in lines[line]
    lines[line] = lines[line].replace(old, new, 1)
    path.write_bytes(b"\n".join(lines))


def snapshot(*paths: Path) -> dict:
    """Every file under ``paths`` (bytes), and every temp entry next to them."""
    state = {}
    for p in paths:
        if p.is_file():
            state[str(p)] = p.read_bytes()
        elif p.is_dir():
            state.update({str(f): f.read_bytes() for f in sorted(p.rglob("*")) if f.is_file()})
        else:
            state[str(p)] = None
        if p.parent.is_dir():
            state[f"{p.parent} entries"] = sorted(q.name for q in p.parent.iterdir())
    return state


# -- refused at read: the matrix ----------------------------------------------------------


def _non_utf8_manifest(ds):
    replace_line(ds / "campaigns.csv", 2, b"train,", b"train,caf\xe9 ")


def _non_utf8_cell(ds):
    lines = (ds / "K02.csv").read_bytes().split(b"\n")
    cells = lines[5].split(b",")
    cells[1] = b"20\xb0"  # a latin-1 degree sign in T_0
    lines[5] = b",".join(cells)
    (ds / "K02.csv").write_bytes(b"\n".join(lines))


def _cell(cid, column, row, value):
    def mutate(ds):
        edit_csv(ds / f"{cid}.csv", lambda df: df.__setitem__(
            column, df[column].where(df.index != row - 1, value)))
    return mutate


def _time_jump(cid, row, seconds):
    def mutate(ds):
        edit_csv(ds / f"{cid}.csv", lambda df: df.__setitem__(
            "time", df["time"] + np.where(df.index >= row - 1, seconds, 0.0)))
    return mutate


def _single_row(ds):
    lines = (ds / "K04.csv").read_text().splitlines()
    (ds / "K04.csv").write_text("\n".join(lines[:2]) + "\n")


def _rename_column(cid, old, new):
    def mutate(ds):
        text = (ds / f"{cid}.csv").read_text().splitlines()
        text[0] = text[0].replace(old, new)
        (ds / f"{cid}.csv").write_text("\n".join(text) + "\n")
    return mutate


def _manifest_file(cid, name_of):
    def mutate(ds):
        outside = ds.parent / "x.csv"
        outside.write_bytes((ds / f"{cid}.csv").read_bytes())
        edit_csv(ds / "campaigns.csv", lambda df: df.__setitem__(
            "file", df["file"].where(df["campaign"] != cid, name_of(outside))))
    return mutate


def _time_scaled(cid, factor, only=False):
    def mutate(ds):
        edit_csv(ds / f"{cid}.csv", lambda df: df.__setitem__("time", df["time"] * factor))
        if only:  # a single-campaign dataset: nothing to compare the sample period with
            edit_csv(ds / "campaigns.csv", lambda df: df.drop(df.index[df["campaign"] != cid],
                                                              inplace=True))
    return mutate


def _fahrenheit(cid):
    def mutate(ds):
        def to_f(df):
            for c in ("T_0", "T_amb"):
                df[c] = df[c] * 9 / 5 + 32
        edit_csv(ds / f"{cid}.csv", to_f)
    return mutate


def _semicolons(ds):
    text = (ds / "campaigns.csv").read_text()
    (ds / "campaigns.csv").write_text(text.replace(",", ";"))


def _campaign_semicolons(ds):
    df = pd.read_csv(ds / "K01.csv")
    df.to_csv(ds / "K01.csv", index=False, sep=";", decimal=",")


def _wide_semicolons(ds):
    # a volumetric record has hundreds of columns: the message showed its whole 8 kB header
    df = pd.read_csv(ds / "K01.csv")
    extra = pd.DataFrame({f"T_extra{k:03d}": df["T_0"] for k in range(200)})
    pd.concat([df, extra], axis=1).to_csv(ds / "K01.csv", index=False, sep=";", decimal=",")


READ_CASES = {
    "non-UTF-8 manifest": (_non_utf8_manifest, [],
                           ["campaigns.csv", "column 'notes'", "line 3:", "0xe9 is not UTF-8"]),
    "non-UTF-8 cell": (_non_utf8_cell, [], ["K02.csv", "column 'T_0'", "line 6:", "0xb0 is not UTF-8"]),
    "1e300 error": (_cell("K03", "E_X", 7, 1e300), [],
                    ["K03.csv", "column 'E_X'", "row 7", "data.max_abs_error"]),
    "1e300 temperature": (_cell("K02", "T_amb", 3, 1e300), [],
                          ["K02.csv", "column 'T_amb'", "row 3", "beyond 10000 °C", "data.missing_values"]),
    "single-row campaign": (_single_row, [], ["K04.csv", "1 complete sample", "at least 2"]),
    "resample to 30 GB": (lambda ds: None, ["data.resample_s=0.0001"],
                          ["K01.csv", "data.resample_s=0.0001 would make 1.74e+07 rows from the file's 30"]),
    "resampled to one sample": (lambda ds: None, ["data.resample_s=100000"],
                                ["K01.csv", "1 (after data.resample_s=100000) sample(s)"]),
    "path in a column name": (_rename_column("K01", "E_X", "E_X/../../x"), [],
                              ["K01.csv", "column 'E_X/../../x'", "identifier-like"]),
    "control character in a column name": (_rename_column("K02", "T_amb", "T_amb\x1b[2J"), [],
                                           ["K02.csv", r"column 'T_amb\x1b[2J'", "identifier-like"]),
    "manifest file outside": (_manifest_file("K02", lambda p: "../x.csv"), [],
                              ["campaigns.csv", "column 'file'", "row 2", "outside the dataset"]),
    "manifest file absolute": (_manifest_file("K03", lambda p: str(p)), [],
                               ["campaigns.csv", "column 'file'", "row 3", "outside the dataset"]),
    "one campaign in ms": (_time_scaled("K02", 1000), [],
                           ["K02.csv", "column 'time'", "60000 s is 1e+03x", "time in ms?"]),
    "one campaign in hours": (_time_scaled("K03", 1 / 3600), [],
                              ["K03.csv", "column 'time'", "time in hours?"]),
    "a lone campaign in ms": (_time_scaled("K01", 1e6, only=True), [],
                              ["K01.csv", "column 'time'", "row 30", "lasts 2.014e+04 days", "ms?"]),
    # one wild time, not a unit: the row of the jump is named, not the last row
    "a first time 1e300 s early": (_cell("K02", "time", 1, -1e300), [],
                                   ["K02.csv", "column 'time'", "row 1", "jumps by 1.157e+295 days"]),
    "a logger 2 years on from row 15": (_time_jump("K03", 15, 6.4e7), [],
                                        ["K03.csv", "column 'time'", "row 15",
                                         "from row 14 to row 15"]),
    "°F": (_fahrenheit("K03"), [], ["K03.csv", "column 'T_", "row 1", "look like °F"]),
    "°F threshold": (lambda ds: None, ["data.fahrenheit_threshold_c=19"],
                     ["K02.csv", "column 'T_", "row 1", "data.fahrenheit_threshold_c=19"]),
    # (data.delimiter/decimal=auto, the default, reads these: set, the wrong one is named)
    ";-separated manifest": (_semicolons, ["data.delimiter=,"],
                             ["campaigns.csv", "looks ';'-separated: set data.delimiter=';'"]),
    ";-separated campaign": (_campaign_semicolons, ["data.delimiter=,"],
                             ["K01.csv", "one column 'time;T_0;T_amb;E_X'",
                              "set data.delimiter=';' data.decimal=','"]),
    # the separator set, the decimal comma forgotten: the setting that reads it is named
    "decimal commas": (_campaign_semicolons, ["data.delimiter=';'", "data.decimal=."],
                       ["K01.csv", "column 'time'", "row 1", "a decimal comma? set data.decimal=','"]),
    ";-separated, 200 columns": (_wide_semicolons, ["data.delimiter=,"],
                                 ["K01.csv", "one column 'time;T_0;T_amb;E_X;T_extra000;",
                                  "... (2218 characters)'", "set data.delimiter=';' data.decimal=','"]),
}


# `monitor` reads its test campaigns as recorded (missing cells kept): same refusals, this one
# worded for all samples rather than complete ones
MONITOR_SAYS = {"single-row campaign": ["K04.csv", "1 sample(s)", "at least 2"]}


@pytest.fixture(scope="module")
def previous_ingest(tmp_path_factory) -> Path:
    """A good ingest of another dataset, made once: each case gets a copy of it as the
    ``data.interim`` that must stay as it was."""
    root = tmp_path_factory.mktemp("previous")
    data = make_dataset(root / "previous")
    assert main(["ingest", f"data.path={data}", f"data.interim={root / 'interim'}", "track=false"]) == 0
    return root / "interim"


# Each command reads through the same checks (run and monitor after ingest's reader): make test
# keeps a Latin pairing of commands and cases, plus monitor's own wording of a single row.
@pytest.mark.parametrize("command, case", covering(
    "the same read checks under another command", keep=[("monitor", "single-row campaign")],
    command=["run", "ingest", "monitor"], case=list(READ_CASES)))
def test_bad_data_is_refused_and_leaves_nothing(paths, capsys, previous_ingest, case, command):
    mutate, extra, says = READ_CASES[case]
    says = MONITOR_SAYS.get(case, says) if command == "monitor" else says
    mutate(paths["ds"])
    shutil.copytree(previous_ingest, paths["interim"])  # an earlier good ingest stays as it was
    capsys.readouterr()
    before = snapshot(paths["out"], paths["interim"], paths["model"], paths["ds"])

    refused([command, *paths["args"], *extra], capsys, *says)

    assert snapshot(paths["out"], paths["interim"], paths["model"], paths["ds"]) == before


def test_a_semicolon_dataset_reads_with_the_suggested_settings(paths):
    _semicolons(paths["ds"])
    for cid, _ in CAMPAIGNS:
        df = pd.read_csv(paths["ds"] / f"{cid}.csv")
        df.to_csv(paths["ds"] / f"{cid}.csv", index=False, sep=";", decimal=",")
    ds, _ = read_dataset(paths["ds"], {"delimiter": ";", "decimal": ","})
    assert ds.ids("test") == ["K04"] and list(ds.campaigns["K01"].columns) == [
        "time", "T_0", "T_amb", "E_X"]


@pytest.mark.parametrize("limit, refused_too", [(None, False), (5.0, True)])
def test_fahrenheit_and_period_checks_can_be_switched_off_or_tightened(tmp_path, limit,
                                                                       refused_too):
    ds = make_dataset(tmp_path / "ds")
    _time_scaled("K02", 10)(ds)  # a 10-min log among 1-min logs: plausible
    read_dataset(ds)
    cfg = {"max_period_ratio": limit, "fahrenheit_threshold_c": None}
    _fahrenheit("K01")(ds)
    if refused_too:
        with pytest.raises(ValueError, match="max_period_ratio=5"):
            read_dataset(ds, cfg)
    else:
        assert read_dataset(ds, cfg)[0].campaigns["K01"]["T_0"].iloc[0] > 45


# -- a declared column in some campaigns only: refused before any fit ----------------------


def _drop_column(cid, column):
    return lambda ds: edit_csv(ds / f"{cid}.csv", lambda df: df.drop(columns=column, inplace=True))


def _extra_sensor(cid):
    return lambda ds: edit_csv(ds / f"{cid}.csv", lambda df: df.__setitem__("T_extra", 20.0))


UNEVEN_CASES = {
    "a test campaign lacks an input": (_drop_column("K04", "T_0"),
                                       ["K04.", "column 'T_0'", "1 of 4 campaigns lack it (K04)"]),
    # the odd one out is the campaign that has the sensor, not the first that lacks it
    "one train campaign has an extra sensor": (_extra_sensor("K02"), [
        "K02.", "column 'T_extra'", "only 1 of 4 campaigns have it (K02)",
        "leave it out of data.inputs"]),
}


@pytest.mark.parametrize("command, case", covering(
    "the same uneven-column check under another command", command=["run", "train", "diagnose"],
    case=list(UNEVEN_CASES)))
def test_a_declared_column_missing_from_some_campaigns_names_the_odd_file(paths, capsys, case,
                                                                          command):
    mutate, says = UNEVEN_CASES[case]
    mutate(paths["ds"])
    if command == "train":   # the campaigns keep the contract: ingest takes them as they are
        assert main(["ingest", *paths["args"]]) == 0
        capsys.readouterr()
    before = snapshot(paths["out"], paths["model"])
    line = refused([command, *paths["args"]], capsys, *says)
    assert (".parquet" if command == "train" else ".csv") in line
    assert snapshot(paths["out"], paths["model"]) == before


def test_ati_without_an_ambient_sensor_says_so(paths, capsys):
    for cid, _ in CAMPAIGNS:
        _rename_column(cid, "T_amb", "T_room")(paths["ds"])
    refused(["run", *paths["args"], "ati=cmeans"], capsys,
            "column 'T_amb'", "no campaign has a valid T_amb / T_amb_* value")


def test_a_sensor_of_one_campaign_left_out_of_the_inputs_runs(paths):
    _extra_sensor("K02")(paths["ds"])
    assert main(["run", *paths["args"], "data.inputs=[T_0,T_amb]"]) == 0


# -- refused config ----------------------------------------------------------------------


CONFIG_CASES = {
    "k=0": (["select=pearson", "select.selector.k=0"],
            ["select.selector.k=0: must be null or an integer >= 1"]),
    "k=-3": (["select=greedy_residual", "select.selector.k=-3"], ["select.selector.k=-3:"]),
    "k=1.5": (["select=pearson", "select.selector.k=1.5"], ["select.selector.k=1.5:"]),
    "k=abc": (["select=cluster_grey", "select.selector.k=abc"], ["select.selector.k='abc':"]),
    "k_max=0": (["select=greedy_residual", "select.selector.k_max=0"],
                ["select.selector.k_max=0: must be an integer >= 1"]),
    "m=1": (["select=cluster_grey", "select.selector.m=1"],
            ["select.selector.m=1: must be a number > 1"]),
    # each of these ran (a traceback, or read as given) until the components were checked
    # against their param_rules before any work
    "rho=5": (["select=cluster_grey", "select.selector.rho=5"],
              ["select.selector.rho=5: must be a number in (0, 1]"]),
    "fit_intercept=maybe": (["model=mlr", "model.estimator.fit_intercept=maybe"],
                            ["model.estimator.fit_intercept='maybe': must be true or false"]),
    "variance=abc": (["model=pcr", "model.estimator.variance=abc"],
                     ["model.estimator.variance='abc': must be a number in (0, 1]"]),
    "learning_rate=-1": (["model=lstm", "model.estimator.learning_rate=-1"],
                         ["model.estimator.learning_rate=-1: must be a number >= 0"]),
    "dropout=2": (["model=lstm", "model.estimator.dropout=2"],
                  ["model.estimator.dropout=2: must be a number in [0, 1)"]),
    "arx.max_inputs=0": (["model=arx_rf", "model.estimator.arx.max_inputs=0"],
                         ["model.estimator.arx.max_inputs=0: must be an integer >= 1"]),
    "forest.n_estimators=0": (["model=arx_rf", "model.estimator.forest.n_estimators=0"],
                              ["model.estimator.forest:", "'n_estimators'"]),
    "n_intervals=knee": (["ati=cmeans", "ati.estimator.n_intervals=knee"],
                         ["ati.estimator.n_intervals='knee': must be elbow or an integer >= 1"]),
    "fuzziness=1": (["ati=cmeans", "ati.estimator.fuzziness=1"],
                    ["ati.estimator.fuzziness=1: must be a number > 1"]),
    "elbow_tolerance=-1": (["ati=cmeans", "ati.estimator.elbow_tolerance=-1"],
                           ["ati.estimator.elbow_tolerance=-1: must be a number >= 0"]),
    "pad=-1": (["denoise=emd", "denoise.denoiser.pad=-1"],
               ["denoise.denoiser.pad=-1: must be an integer >= 0"]),
    "validation_folds=1": (["eval.validation_folds=1"],
                           ["eval.validation_folds=1: must be an integer >= 2"]),
    "anova_alpha=0": (["eval.anova_alpha=0"], ["eval.anova_alpha=0: must be a number in (0, 1)"]),
    "validation=maybe": (["eval.validation=maybe"], ["eval.validation='maybe': must be true or false"]),
    "track=maybe": (["track=maybe"], ["track='maybe': must be null or true or false"]),
    "targets=[]": (["data.targets=[]"], ["data.targets=[]: must be null or a non-empty list"]),
    "out=/dev/null": (["out=/dev/null"], ["out=/dev/null: exists and is not a folder"]),
    "seed=abc": (["seed=abc"], ["seed='abc' is not an integer"]),
    "seed=1.5": (["seed=1.5"], ["seed=1.5 is not an integer"]),
    "max_points=0": (["eval.e_p95.max_points=0"],          # an empty E_P95 curve before
                     ["eval.e_p95.max_points=0: must be null or an integer >= 2"]),
}


@pytest.mark.parametrize("case", CONFIG_CASES)
def test_bad_config_is_refused_before_any_work(paths, capsys, case):
    extra, says = CONFIG_CASES[case]
    before = snapshot(paths["out"], paths["interim"], paths["model"])
    refused(["run", *paths["args"], *extra], capsys, *says)
    assert snapshot(paths["out"], paths["interim"], paths["model"]) == before


def test_out_below_a_file_or_in_a_read_only_place_is_refused(paths, capsys, tmp_path):
    (tmp_path / "a_file").write_text("x")
    refused(["run", *paths["args"], f"out={tmp_path / 'a_file' / 'out'}"], capsys,
            "is not a folder")
    refused(["run", *paths["args"], "out=/proc/thermocomp_out"], capsys,
            "out=/proc/thermocomp_out: cannot write in /proc")
    (tmp_path / "a_folder").mkdir()     # not one holding data.path: that is refused first
    refused(["train", *paths["args"], f"model_path={tmp_path / 'a_folder'}"], capsys,
            f"model_path={tmp_path / 'a_folder'}: exists and is a folder")
    refused(["ingest", *paths["args"], f"data.interim={tmp_path / 'a_file'}"], capsys,
            "exists and is not a folder")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a_file", "a_folder", "ds"]


# Each kind of value Hydra parses a seed into that is no seed: a text, a float, a bool, a negative.
BAD_SEEDS = ("abc", "1.5", "true", "-1")
# every stage once, every kind by several stages: the covering rule's pick of the product
STAGE_SEEDS = kept(list(product(STAGES, BAD_SEEDS)))


@pytest.mark.parametrize("stage, seed", STAGE_SEEDS)
def test_a_non_integer_seed_is_refused_by_every_stage(stage, seed, capsys, tmp_path):
    """Every stage refuses a seed that is no integer, and every kind of bad seed is refused (by
    several stages): one call ``_run`` makes for any stage before any work, so each stage with
    each kind (76 commands composed, ~11 s of CPU) asserted nothing more."""
    refused([stage, f"seed={seed}", "track=false", f"out={tmp_path / 'o'}"], capsys,
            "is not an integer")
    assert not (tmp_path / "o").exists()


def test_every_bad_seed_is_tried_by_several_stages():
    assert sorted(stage for stage, _ in STAGE_SEEDS) == sorted(STAGES)
    tried = [seed for _, seed in STAGE_SEEDS]
    assert all(tried.count(seed) >= 2 for seed in BAD_SEEDS), tried


# -- a run's outputs: all or nothing -------------------------------------------------------


def test_refused_runs_leave_no_model_or_ingest_report(paths, capsys):
    refused(["run", *paths["args"], "+data.split_overrides.K04=train"], capsys,
            "no 'test' campaign", f"file {paths['ds'] / 'campaigns.csv'}")   # the whole path
    edit_csv(paths["ds"] / "K02.csv", lambda df: df.rename(columns={"E_X": "E_Y"}, inplace=True))
    refused(["run", *paths["args"]], capsys, "K0", "column 'E_")
    assert not paths["out"].exists() and not paths["out"].parent.exists()


def test_a_refused_or_killed_run_keeps_the_previous_run_of_the_same_out(paths, capsys, monkeypatch):
    """One previous run (with figures), kept whole by a refused run, then by a run killed by
    SIGTERM and one interrupted by Ctrl-C after its figures were queued: each leaves the out
    folder, and the temp entries beside it, as that previous run wrote them."""
    from thermocomp.core import run_report

    assert main(["run", *paths["args"], "plots=summary"]) == 0
    mlr = snapshot(paths["out"])
    assert {"model.pkl", "ingest_report.json", "metrics.json", "plots"} <= {
        p.name for p in paths["out"].iterdir()}

    refused(["run", *paths["args"], "model=pcr", "plots=summary",
             "+data.split_overrides.K04=train"], capsys, "no 'test' campaign")
    assert snapshot(paths["out"]) == mlr

    for signum, said in ((signal.SIGTERM, "run terminated (SIGTERM)"),
                         (signal.SIGINT, "run interrupted (Ctrl-C)")):
        def killed(*args, signum=signum, **kwargs):
            # to this thread, its handler run before returning (os.kill may hand it to a figure
            # thread, and the main thread then meets it a few bytecodes later: a flaky test)
            signal.raise_signal(signum)
            raise AssertionError("not reached")

        handler = signal.getsignal(signal.SIGTERM)
        monkeypatch.setattr(run_report, "anova", killed)  # after the figures were queued
        # Ctrl-C as in a terminal: an earlier test or library in this worker may have left SIGINT
        # ignored or handled otherwise (the run then goes on, as it should: a flaky test)
        interrupt = signal.signal(signal.SIGINT, signal.default_int_handler)
        try:
            assert main(["run", *paths["args"], "plots=summary", "model=pcr"]) == 1  # CLI.md: 0, 2, 1
        finally:
            signal.signal(signal.SIGINT, interrupt)
        assert snapshot(paths["out"]) == mlr, said
        assert said in capsys.readouterr().err
        assert signal.getsignal(signal.SIGTERM) == handler, said


def test_sigterm_while_reading_ends_the_stage_with_status_1_and_says_so(paths, capsys,
                                                                        monkeypatch):
    # outside any MLflow run or file write (ingest without tracking, still reading): before,
    # the default handler ended the process with 143 and no word
    def stray(signum, frame):
        raise AssertionError("SIGTERM reached the caller's handler")

    def killed(*args, **kwargs):
        signal.raise_signal(signal.SIGTERM)
        raise AssertionError("not reached")

    monkeypatch.setattr("thermocomp.core.io.ingest", killed)
    previous = signal.signal(signal.SIGTERM, stray)
    try:
        assert main(["ingest", *paths["args"]]) == 1
        assert signal.getsignal(signal.SIGTERM) == stray
    finally:
        signal.signal(signal.SIGTERM, previous)
    err = capsys.readouterr().err
    assert "ingest terminated (SIGTERM)" in err and "AssertionError" not in err
    assert not paths["interim"].exists() and not paths["out"].exists()


def test_a_library_warning_is_one_log_line(paths, capsys, monkeypatch):
    import warnings

    from thermocomp.core import run_report

    fit = run_report.anova

    def warns(*args, **kwargs):
        for _ in range(3):          # a library resetting the filters in between: once all the same
            with warnings.catch_warnings():
                pass
            warnings.warn("the solver did not converge\n  within 100 steps", UserWarning)
        return fit(*args, **kwargs)

    monkeypatch.setattr(run_report, "anova", warns)
    assert main(["run", *paths["args"]]) == 0
    err = capsys.readouterr().err
    said = [ln for ln in err.splitlines() if "did not converge" in ln]
    assert said == ["[thermocomp] warning: UserWarning: the solver did not converge within 100 "
                    "steps (test_hostile.py:"
                    f"{warns.__code__.co_firstlineno + 4})"], err
    assert "warnings.warn(" not in err


def test_stale_temp_folders_of_dead_processes_are_swept(paths):
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True, check=True).stdout.strip()
    parent = paths["out"].parent
    stale = [parent / f".out.stage-{dead}-abc", parent / f".out.old-{dead}-abc"]
    live = parent / f".out.stage-{os.getppid()}-abc"  # a run still going on
    for folder in (*stale, live):
        (folder / "plots").mkdir(parents=True)
    assert main(["run", *paths["args"]]) == 0
    assert sorted(p.name for p in parent.iterdir()) == sorted(["out", live.name])


# -- two runs sharing data/interim ---------------------------------------------------------


def test_evaluate_refuses_a_model_trained_on_another_ingest(paths, tmp_path, capsys):
    other = make_dataset(tmp_path / "other", gain=6.0)
    interim = [f"data.interim={paths['interim']}", f"model_path={paths['model']}",
               f"data.processed={tmp_path / 'processed'}", *FAST]
    assert main(["ingest", f"data.path={paths['ds']}", *interim]) == 0
    assert main(["train", f"data.path={paths['ds']}", *interim]) == 0
    interim.append(f"data.path={other}")
    assert main(["ingest", *interim]) == 0  # another run's ingest
    model = paths["model"].read_bytes()

    refused(["evaluate", *interim, f"out={paths['out']}"], capsys, "interim",
            "trained on another ingest", "rerun train")

    assert not paths["out"].exists() and paths["model"].read_bytes() == model
    assert main(["train", *interim]) == 0
    assert main(["evaluate", *interim, f"out={paths['out']}"]) == 0


@pytest.mark.parametrize("change", ["data.path", "data.split_overrides"])
def test_a_stage_refuses_an_ingest_of_other_data_or_settings(paths, tmp_path, capsys, change):
    # before, train and evaluate read whatever data/interim/<name> held: another data.path (or
    # split) scored the stale dataset under this config, exit 0 and no word of it.  One ingest
    # and train, put back as they were before each stage's case.
    interim = [f"data.interim={paths['interim']}", f"model_path={paths['model']}",
               f"data.processed={tmp_path / 'processed'}", f"out={paths['out']}", *FAST]
    ingested = [f"data.path={paths['ds']}", *interim]
    assert main(["ingest", *ingested]) == 0
    assert main(["train", *ingested]) == 0
    model = paths["model"].read_bytes()
    kept = tmp_path / "kept_interim"
    shutil.copytree(paths["interim"], kept)
    other = (f"data.path={make_dataset(tmp_path / 'other', gain=6.0)}" if change == "data.path"
             else "data.split_overrides={K01:test}")
    for stage in ("train", "evaluate", "select", "denoise"):
        for made in (paths["interim"], tmp_path / "processed", paths["out"]):
            shutil.rmtree(made, ignore_errors=True)
        shutil.copytree(kept, paths["interim"])
        paths["model"].write_bytes(model)
        line = refused([stage, *ingested, other], capsys, "ingest_report.json", f"ingested with {change}=",
                       "run `thermocomp ingest` with this config first")
        assert str(paths["ds"]) in line or change != "data.path", stage
        assert paths["model"].read_bytes() == model and not paths["out"].exists(), stage
        assert main(["ingest", *ingested, other]) == 0        # ingested so, it is read
        if stage == "evaluate":                                # (by a model trained on it)
            assert main(["train", *ingested, other]) == 0
        assert main([stage, *ingested, other]) == 0, stage


@pytest.mark.parametrize("fault", ["dead channel", "mm", "minutes"])
def test_a_plausible_but_suspect_campaign_is_said_with_its_file_and_column(paths, capsys, fault):
    # what no unit check can refuse (an idle campaign drifts little; two logging rates may be 60x
    # apart), but a measurement hardly shows: ingested, and said, naming file and column
    ds = paths["ds"]
    f = ds / "K02.csv"
    df = pd.read_csv(f)
    if fault == "dead channel":
        df["E_X"] = 0.0
    elif fault == "mm":
        df["E_X"] = df["E_X"] / 1000
    else:
        df["time"] = df["time"] / 60
    df.to_csv(f, index=False)
    assert main(["ingest", f"data.path={ds}", f"data.interim={paths['interim']}", *FAST]) == 0
    err = [ln for ln in capsys.readouterr().err.splitlines() if "warning" in ln]
    assert len(err) == 1 and str(f) in err[0], err
    assert {"dead channel": "column 'E_X': constant", "mm": "another unit",
            "minutes": "in minutes"}[fault] in err[0]


def test_a_clean_dataset_is_ingested_without_a_warning(paths, capsys):
    assert main(["ingest", f"data.path={paths['ds']}", f"data.interim={paths['interim']}", *FAST]) == 0
    assert "warning" not in capsys.readouterr().err


def test_interleaved_ingests_leave_one_whole_dataset(paths, tmp_path, monkeypatch):
    """A second ingest starts and ends while the first is writing: the folder then holds the
    first one's dataset, whole (the last to finish wins), and no temp folder is left."""
    import pyarrow.parquet as pq  # what ingest writes each campaign with

    other = make_dataset(tmp_path / "other", rows=20, gain=6.0)
    write_table, nested = pq.write_table, []

    def interleaved(*args, **kwargs):
        if not nested:
            nested.append(True)
            thermocomp("ingest", f"data.path={other}", f"data.interim={paths['interim']}",
                       "track=false", subprocess=True)   # another process: truly concurrent
            assert load_interim(paths["interim"]).campaigns["K01"].shape[0] == 20
        return write_table(*args, **kwargs)

    monkeypatch.setattr(pq, "write_table", interleaved)
    assert main(["ingest", f"data.path={paths['ds']}", f"data.interim={paths['interim']}",
                 "track=false"]) == 0
    assert nested, "the second ingest never ran while the first was writing"

    got, want = load_interim(paths["interim"]), read_dataset(paths["ds"])[0]
    for cid in want.ids():
        pd.testing.assert_frame_equal(got.campaigns[cid], want.campaigns[cid])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ds", "interim", "other"]


# -- file names built from data ------------------------------------------------------------


@pytest.mark.parametrize("name", ["E_Z/../../x", "../../etc/x", "..", ".hidden", "a\x00b"])
def test_figure_names_from_data_stay_in_their_folder(tmp_path, name):
    path = files.inside(tmp_path, files.safe_name("residual", "K01", name) + ".png")
    assert path.parent == tmp_path and not path.name.startswith(".")
    assert re.fullmatch(r"[\w.\-]+", path.name) and ".." not in path.name
    with pytest.raises(ValueError, match="leaves"):
        files.inside(tmp_path, "../x.png")


def test_evaluate_refuses_settings_the_model_was_not_trained_with(paths, tmp_path, capsys):
    # model=pcr on an MLR model once printed the MLR's figures labelled pcr; another
    # data.targets was a KeyError traceback
    interim = [f"data.path={paths['ds']}", f"data.interim={paths['interim']}",
               f"model_path={paths['model']}", f"data.processed={tmp_path / 'processed'}", *FAST]
    assert main(["ingest", *interim]) == 0
    assert main(["train", *interim]) == 0
    for bad, says in (("model=pcr", "trained with mlr"),
                      ("data.targets=[E_Z]", "trained with every E_ column"),
                      ("data.inputs=[T_0]", "trained with ['T_*']")):
        refused(["evaluate", *interim, f"out={paths['out']}", bad], capsys, bad.split("=")[0], says)
        assert not paths["out"].exists()
    assert main(["evaluate", *interim, f"out={paths['out']}"]) == 0


def test_a_data_path_that_links_to_itself_is_refused(tmp_path, capsys):
    # ingest crashed with pathlib's RuntimeError (exit 1); run, monitor and replay said it
    loop = tmp_path / "ds"
    loop.symlink_to(loop)
    refused(["ingest", f"data.path={loop}", f"data.interim={tmp_path / 'interim'}", *FAST], capsys,
            "Symlink loop", str(loop))


def test_an_unreadable_file_is_one_line_and_exit_2(tmp_path, capsys):
    # root reads a chmod-000 file anyway, so the error is raised as a read would raise it
    from thermocomp.shell.cli import _guarded

    def read():
        raise PermissionError(13, "Permission denied", str(tmp_path / "K01.csv"))

    with pytest.raises(SystemExit) as info:
        _guarded(read)
    err = capsys.readouterr().err.strip().splitlines()
    assert info.value.code == 2 and len(err) == 1
    assert f"file {tmp_path / 'K01.csv'}" in err[0] and "Permission denied" in err[0]
