"""The exported ``stream.c`` reads a lab's time of seconds since midnight as the reader does
(lead91): a day added where the clock passes midnight, so a run after a pause across midnight
starts a campaign of its own (``data.runs_at_pauses``), as the record was scored.  Before, the
step back was taken for a clock set back (one period on, said) and the third run streamed as
the second's continuation: its corrections off by up to 31 µm on a simulated record
(``benchmarks/bench_data90.py``'s 9381 ``longpause``)."""

from __future__ import annotations

import io
import json
import pickle
import shutil
import subprocess

import numpy as np
import pandas as pd
import pytest

from cbuild import compiled
from thermocomp.shell.cli import main

ROWS, PERIOD_S, DAY_S = 120, 60, 86400
LIGHT = ["model=mlr", "plots=none", "track=false", "eval.mutual_prediction=false",
         "eval.ati_baselines=false", "eval.iso10791_a3=false"]


def _runs(path, starts_h):
    """Runs of ``ROWS`` rows each starting at ``starts_h`` hours, under ``Seconds of day``; each
    run's error follows its own rise from its first sample (data.reference=first_sample)."""
    rng = np.random.default_rng(91)
    frames = []
    for start in starts_h:
        t = start * 3600 + np.arange(ROWS) * PERIOD_S
        rise = np.cumsum(rng.normal(0.02, 0.05, (ROWS, 2)), axis=0)
        temp = 20 + rng.normal(0, 1) + rise
        frames.append(pd.DataFrame({"Seconds of day": t % DAY_S, "T_a": temp[:, 0],
                                    "T_b": temp[:, 1], "E_X": 3 * rise[:, 0] - rise[:, 1]}))
    pd.concat(frames, ignore_index=True).to_csv(path, index=False)
    return path


def _built(root, data: list[str]):
    """``data``'s record run (mlr), exported as C and built: the folder."""
    if shutil.which("gcc") is None:
        pytest.skip("no C compiler")
    assert main(["run", *data, *LIGHT, f"out={root / 'run'}"]) == 0
    out = root / "c"
    assert main(["export", *data, f"export.model={root / 'run' / 'model.pkl'}",
                 "export.format=c", "export.check=false", f"out={out}"]) == 0
    compiled(out)
    return out


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    root = tmp_path_factory.mktemp("day91")
    # 20:00; 01:00 the next day (a pause across midnight); 10:30
    record = _runs(root / "week.csv", [20, 25, 34.5])
    data = [f"data.path={record}", "data.runs_at_pauses=true", "data.test_fraction=0.34"]
    return {"root": root, "data": data, "out": _built(root, data), "record": record}


def _stream(out, text: str) -> subprocess.CompletedProcess:
    return subprocess.run(["./stream"], cwd=out, input=text, capture_output=True, text=True)


def _raw_and_rows(out, data: list[str], record, capsys) -> tuple[pd.Series, pd.Series]:
    """The C's corrections fed the raw record, and fed its campaigns as ``thermocomp rows``
    writes them (a blank line between: where the stream starts one)."""
    capsys.readouterr()
    assert main(["rows", *data]) == 0
    want = _stream(out, capsys.readouterr().out)
    raw = _stream(out, record.read_text())
    assert want.returncode == 0 and raw.returncode == 0, raw.stderr
    assert "not after the last read" not in raw.stderr
    return (pd.read_csv(io.StringIO(fed.stdout))["C_X"] for fed in (raw, want))


def test_the_raw_record_streams_as_its_campaigns(exported, capsys):
    got, expected = _raw_and_rows(exported["out"], exported["data"], exported["record"], capsys)
    assert len(got) == 3 * ROWS and np.abs(expected).max() > 0.1
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-9)


def test_a_step_of_half_a_day_forward_is_refused_as_the_reader_refuses_it(exported):
    record = pd.read_csv(exported["record"]).iloc[:20]
    record["Seconds of day"] = 3600 + np.arange(20) * PERIOD_S     # 01:00 ...
    record.loc[10:, "Seconds of day"] += 13 * 3600                  # ... 14:10: 11 h back?
    fed = _stream(exported["out"], record.to_csv(index=False))
    assert fed.returncode == 2
    assert "stream: line 12: the time of day (51000 s, seconds since midnight) steps 13 h" \
        " forward: as well 11 h back" in fed.stderr


@pytest.mark.parametrize("written, starts_h", [("seconds", [20, 25, 34.5]), ("h:mm:ss", [23])])
def test_data_time_of_day_exports_and_streams_the_raw_record(tmp_path, capsys, written, starts_h):
    """data.time=of_day (data91) under a header that does not say it (``t``), as seconds or
    ``h:mm:ss`` of the day: exported (data91 refused the key for the C) and the raw record
    streamed as its campaigns (lead91): three runs split at their pauses, or one run from 23:00
    cut in two by data.test_fraction (runs_at_pauses cannot split a time written as text)."""
    record = pd.read_csv(_runs(tmp_path / "week.csv", starts_h))
    seconds = record.pop("Seconds of day").astype(int)
    record.insert(0, "t", seconds if written == "seconds" else [
        f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}" for s in seconds])
    record.to_csv(tmp_path / "week.csv", index=False)
    data = [f"data.path={tmp_path / 'week.csv'}", "data.time=of_day", "data.test_fraction=0.34",
            *(["data.runs_at_pauses=true"] if len(starts_h) > 1 else [])]
    got, expected = _raw_and_rows(_built(tmp_path, data), data, tmp_path / "week.csv", capsys)
    assert len(got) == len(starts_h) * ROWS
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-9)


def test_the_served_session_and_stdin_read_seconds_of_day_past_midnight_as_the_c(exported):
    """dep108d: the served session fed the raw record's plain ``Seconds of day`` (blocks of 90
    rows, one across midnight) carries the day past midnight as stream.c (TC_DAY_SECONDS) and the
    file reader do, so the run after the pause across midnight is a campaign of its own; stdin
    reads its three runs too.  Before, both read midnight's step back as the clock going back:
    the served 2.16 um off the C on the second run, stdin's campaigns 240 + 120 rows."""
    from omegaconf import OmegaConf

    from thermocomp.apps.deploy.pyfunc import CompensatorModel
    from thermocomp.core.io import ReadOptions
    from thermocomp.core.io.stdin import stream_campaigns
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.source import read_streamed

    pkl = exported["root"] / "run" / "model.pkl"
    cfg = _compose([*exported["data"], f"connect.model={pkl}", "track=false",
                    "monitor.adaptive=false"], "connect")
    ds, train = read_streamed(cfg, test=False)[:2]
    deployed = deployable_model(cfg, ds, train, str(pkl), "connect.model")[0]
    text = exported["record"].read_text()
    want = pd.read_csv(io.StringIO(_stream(exported["out"], text).stdout))["C_X"].to_numpy()
    frame, served = pd.read_csv(io.StringIO(text)).drop(columns="E_X"), CompensatorModel(deployed)
    got = pd.concat([served.predict(None, frame.iloc[k:k + 90].reset_index(drop=True),
                                    {"session": "d", "reset": k == 0})
                     for k in range(0, len(frame), 90)], ignore_index=True)["C_X"]
    assert np.abs(want).max() > 0.1
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)
    parts, _ = stream_campaigns(text, list(deployed.columns_),
                                ReadOptions.from_cfg(OmegaConf.to_container(cfg.data, resolve=True)))
    assert [len(p) for p in parts.values()] == [ROWS] * 3


def _deployed_of_day(root, header: str):
    """The mlr deployed (plain stream) on three runs over midnight of plain seconds of the day
    under ``header``, read with ``data.time=of_day``; and the record's rows as served."""
    from thermocomp.shell.builders import deployable_model
    from thermocomp.shell.cli import _compose
    from thermocomp.shell.source import read_streamed

    record = pd.read_csv(_runs(root / f"{header}.csv", [20, 25, 34.5]))
    record.rename(columns={"Seconds of day": header}).to_csv(root / f"{header}.csv", index=False)
    cfg = _compose([f"data.path={root / f'{header}.csv'}", "data.time=of_day", "data.runs_at_pauses=true",
                    "data.test_fraction=0.34", "model=mlr", "track=false", "monitor.adaptive=false"],
                   "connect")
    ds, train = read_streamed(cfg, test=False)[:2]
    return (deployable_model(cfg, ds, train, None, "connect.model")[0],
            pd.read_csv(root / f"{header}.csv").drop(columns="E_X"))


def _served(deployed, frame: pd.DataFrame) -> np.ndarray:
    """``deployed``'s corrections of ``frame`` served in blocks of 90 rows, one session."""
    from thermocomp.apps.deploy.pyfunc import CompensatorModel

    served = CompensatorModel(deployed)
    return pd.concat([served.predict(None, frame.iloc[k:k + 90].reset_index(drop=True),
                                     {"session": "d", "reset": k == 0})
                      for k in range(0, len(frame), 90)], ignore_index=True)["C_X"].to_numpy()


def _exported_day_seconds(deployed, root, name: str) -> bool:
    """``TC_DAY_SECONDS`` of ``deployed``'s pyfunc folder exported (json) without data.time."""
    from thermocomp.apps.deploy.pyfunc import save_compensator

    folder = save_compensator(deployed, root / f"{name}_pyfunc")
    assert main(["export", f"export.model={folder}", "export.format=json", f"out={root / name}",
                 "track=false"]) == 0
    return json.loads((root / name / "compensator.json").read_text())["provenance"]["day_seconds"]


def test_the_export_and_the_served_model_read_the_time_as_the_deployed_model_holds(tmp_path):
    """rev109: the exported ``TC_DAY_SECONDS`` is what the deployed model serves by, its
    ``day_seconds_``: deployed with ``data.time=of_day`` under ``t``, its pyfunc folder exported
    without the key says 1 (0 before: the C read midnight as a clock set back, 8.69 um off the
    served model on rev109's record).  A model pickled before dep108d carries none: the export
    and the served model read its lab's headers by one rule, a lone ``Uhrzeit`` saying seconds
    of the day, so it is served over midnight as the model deployed now is (before: as plain
    seconds, 2.16 um off it here)."""
    assert _exported_day_seconds(_deployed_of_day(tmp_path, "t")[0], tmp_path, "t") is True
    now, frame = _deployed_of_day(tmp_path, "Uhrzeit")
    old = pickle.loads(pickle.dumps(now))
    del old.day_seconds_                    # as a model pickled before dep108d
    assert _exported_day_seconds(old, tmp_path, "old") is True
    want = _served(now, frame)
    assert np.abs(want).max() > 0.1
    np.testing.assert_allclose(_served(old, frame), want, rtol=0, atol=1e-9)


def test_a_blank_line_in_a_file_is_said_and_read_as_run_reads_it(exported):
    """audit103: a logger's stray blank line restarted the stream there (the state reset, the
    next row the reference) where run and replay read the file as one campaign; it was silent
    (8.5 µm off at once on a large mill's MLR: bench_audit103's ``faults``), then said.  dep107b:
    within a run, its time going on, it is nothing, as run, replay and the served stream read it
    (the corrections those of the file without it; a lab's mlr was 35.7 µm off at once); where
    the next row's time is not after the last (the campaigns thermocomp rows writes, each from
    its time 0) it starts a campaign, as before; blank lines at the end say nothing."""
    lines = exported["record"].read_text().splitlines()
    whole = _stream(exported["out"], "\n".join(lines) + "\n")
    stray = [*lines[:61], "", *lines[61:]]                 # line 62, above data row 61
    fed = _stream(exported["out"], "\n".join(stray) + "\n\n\n")
    assert fed.returncode == 0, fed.stderr
    assert [ln for ln in fed.stderr.splitlines() if "blank line" in ln] == [
        "stream: line 62: a blank line: read as nothing, the time going on at line 63 (a stray "
        "blank line within a run), as run, replay and the served stream read it"]
    assert fed.stdout == whole.stdout
    again = [*lines[:61], "", lines[1], *lines[62:]]       # the next row the run's first again
    fed = _stream(exported["out"], "\n".join(again) + "\n")
    assert "line 62: a blank line: a new campaign starts at line 63 (the state reset" in fed.stderr
    assert fed.stdout.splitlines()[61] == whole.stdout.splitlines()[1]   # from a reset


def test_a_blank_line_without_a_time_column_is_left_out_by_every_reader(exported, tmp_path, caplog):
    """dep108b: rows without a time column (data.sample_period_s) and a stray blank line under
    data row 61: the data contract's file reader leaves it out and says it (the rows after it one
    period on); stream.c started a campaign there (the state reset: the mlr's corrections from
    row 62 off), stdin left it out unsaid.  Now each leaves it out and says it, naming row 61, the
    C's corrections those of the rows without it."""
    import logging

    from thermocomp.core.io import ReadOptions, read_dataset
    from thermocomp.core.io.stdin import stream_campaigns

    lines = [ln.split(",", 1)[1] for ln in exported["record"].read_text().splitlines()[:121]]
    stray = [*lines[:62], "", *lines[62:]]                 # line 63, under data row 61 (2 in its run)
    whole, fed = (_stream(exported["out"], "\n".join(rows) + "\n") for rows in (lines, stray))
    assert fed.returncode == 0 and fed.stdout == whole.stdout, fed.stderr
    assert "stream: line 63: a blank line: left out, no time column: the rows from line 64 read one " \
        "period after the row above it" in fed.stderr
    (tmp_path / "stray.csv").write_text("\n".join(stray) + "\n")
    with caplog.at_level(logging.WARNING, logger="thermocomp"):
        read_dataset(tmp_path / "stray.csv", {"sample_period_s": 60})
        parts, _ = stream_campaigns("\n".join(stray) + "\n", ["T_a"], ReadOptions.from_cfg(
            {"sample_period_s": 60}))
    said = [r.getMessage() for r in caplog.records if "a blank line under it is left out" in r.getMessage()]
    assert len(said) == 2 and all("data row 61" in m for m in said), said
    assert list(parts) == ["stdin"] and len(parts["stdin"]) == 120


def _cut(out, state, header: str, first: list[str], then: list[str]) -> str:
    """The C fed ``first`` then, a fresh process from ``state``, ``then``: the second's stdout."""
    one = subprocess.run(["./stream", "--state", str(state)], cwd=out, capture_output=True, text=True,
                         input="\n".join([header, *first]) + "\n")
    two = subprocess.run(["./stream", "--state", str(state)], cwd=out, capture_output=True, text=True,
                         input="\n".join([header, *then]) + "\n")
    assert one.returncode == two.returncode == 0, one.stderr + two.stderr
    return two.stdout


def test_a_stream_cut_at_a_blank_line_goes_on_from_its_state_as_the_whole(exported, capsys, tmp_path):
    """dep107b: the blank line is decided by the next row's time, so a stream cut just after it
    (``--state``) carries it to the next process: a stray one within a run read as nothing, the
    one between the campaigns ``thermocomp rows`` writes a campaign, as the whole stream reads
    them.  Without it in the state a stray blank line restarted the cut stream alone; without a
    time of day's days, the days read back counted as the clock passing midnight there."""
    lines = exported["record"].read_text().splitlines()
    header, body = lines[0], lines[1:]
    whole = _stream(exported["out"], "\n".join(lines) + "\n").stdout.splitlines()
    for k in (60, 150):                # in the first run; in the second, past midnight (its days)
        got = _cut(exported["out"], tmp_path / f"stray{k}.state", header, [*body[:k], ""], body[k:])
        assert got.splitlines()[1:] == whole[k + 1:], k
    capsys.readouterr()
    assert main(["rows", *exported["data"]]) == 0
    rows = capsys.readouterr().out.rstrip("\n").split("\n")
    at = rows.index("")
    assert float(rows[at + 1].split(",")[0]) == 0.0 < float(rows[at - 1].split(",")[0])
    fed = _stream(exported["out"], "\n".join(rows) + "\n").stdout.splitlines()
    got = _cut(exported["out"], tmp_path / "rows.state", rows[0], rows[1:at + 1], rows[at + 1:])
    assert got.splitlines()[1:] == fed[at:] and fed[at] == _stream(
        exported["out"], "\n".join([rows[0], *rows[at + 1:]]) + "\n").stdout.splitlines()[1]


def test_an_inputs_column_written_twice_apart_is_refused_as_the_reader_refuses_it(exported):
    """cin103 (audit103's finding 2): a contract-named file writing input ``T_a`` twice, the copy
    5 °C apart from row 10: the reader (run, replay) refuses the file, the stream read the first
    column on (exit 0).  Now refused at the first row apart in replay's words; a copy equal to
    the first is left out, as the reader leaves it out."""
    record = pd.read_csv(exported["record"], dtype=str).iloc[:20]
    plain = _stream(exported["out"], record.to_csv(index=False))
    copied = pd.concat([record, record[["T_a"]]], axis=1)
    same = _stream(exported["out"], copied.to_csv(index=False))
    assert same.returncode == 0 and same.stdout == plain.stdout, same.stderr
    copied.iloc[10:, -1] = [f"{float(v) + 5:.6f}" for v in record["T_a"].iloc[10:]]
    apart = _stream(exported["out"], copied.to_csv(index=False))
    assert apart.returncode == 2 and apart.stdout.splitlines() == plain.stdout.splitlines()[:11]
    assert apart.stderr.startswith("stream: line 12: columns 2 and 5 have the same header 'T_a', "
                                   "different values ("), apart.stderr
    assert "name the second, data.columns={'T_a#2': T_<name>}" in apart.stderr


def test_a_header_with_a_column_renamed_mid_stream_is_said_for_what_it_is(exported):
    """audit105: a header written again under the rows with input ``T_a`` renamed (``T_a_new``: a
    logger reconfigured, two files joined) was refused as "input T_a: 'T_a_new' is no number (a
    mark for a value not measured?)"; replay refuses the file as a header written again.  Now
    said as the other header it is, the renamed column named, at the same line (exit 2)."""
    lines = pd.read_csv(exported["record"]).iloc[:20].to_csv(index=False).splitlines()
    lines.insert(11, lines[0].replace("T_a", "T_a_new"))          # line 12, above data row 11
    fed = _stream(exported["out"], "\n".join(lines) + "\n")
    assert fed.returncode == 2 and len(fed.stdout.splitlines()) == 1 + 10
    assert fed.stderr == (
        "stream: line 12 is a header other than the first (another file's: a column renamed?): "
        "column 2 reads 'T_a_new' where the header named input T_a: stream each file by itself, "
        "--state FILE carries the campaign from one to the next\n")
